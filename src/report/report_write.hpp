#pragma once
// The report's written outputs from its finished rows (report_rows.hpp):
// work_precision.csv, the work-precision figure, and the fastest method per
// accuracy level (summary.md's section, the table printed at the end and
// time_to_accuracy.csv).
#include <filesystem>
#include <map>
#include <ostream>
#include <vector>

#include "report/report_rows.hpp"
#include "reading/scene.hpp"

namespace sympl::app {

// The report's two measures, each with its own table and figure: the final
// phase-space error against the reference (regular motion: in chaotic motion
// it measures the Lyapunov exponent) and the largest relative energy error
// over the run (every Hamiltonian scene).
enum class error_measure { final_error, energy_error };

inline double measured(const report_row& r, error_measure by) {
    return by == error_measure::final_error ? r.final_error : r.r.max_energy_error;
}

// An error this large is no solution at any level the report reads (1e-4 and
// below): such runs are flagged, not drawn or interpolated; the threshold is
// the one `sympl run` flags by (scene.hpp).
inline constexpr double order_one = order_one_error;

// Whether a scene takes part in the work-precision comparison: some method
// runs more than one setting (the chaos map's single run does not).
bool has_sweep(const run_plan& plan);

void write_work_precision_csv(const std::vector<report_row>& rows,
                              const std::map<const scene*, reference_state>& references,
                              const std::filesystem::path& dir);

// One panel per scene with a sweep and the measure, each with its own key
// (sympl's methods solid, Odeint's dashed) and the fastest sympl and Odeint
// method at the tightest level both reach named in its title.
// work_precision.png (final error) or energy_precision.png.
void plot_work_precision(const std::vector<report_row>& rows, const std::vector<run_plan>& plans,
                         const std::filesystem::path& dir, error_measure by);

// summary.md's fastest-method tables, one per measure, with the method to pick
// per scene and level; the table printed at the end; time_to_accuracy.csv.
// Scenes without a sweep and runs whose error reached order one are named.
void fastest_per_level(const std::vector<report_row>& rows, const std::vector<run_plan>& plans, std::ostream& md,
                       std::ostream& table, const std::filesystem::path& dir);

}  // namespace sympl::app
