#pragma once
// The report's written outputs from its finished rows (report_rows.hpp):
// work_precision.csv, the work-precision figure, and the fastest method per
// accuracy level (summary.md's section, the table printed at the end and
// time_to_accuracy.csv).
#include <filesystem>
#include <map>
#include <ostream>
#include <vector>

#include "report_rows.hpp"

namespace sympl::app {

// Whether a scene takes part in the work-precision comparison: some method
// runs more than one setting (the chaos map's single run does not).
bool has_sweep(const run_plan& plan);

void write_work_precision_csv(const std::vector<report_row>& rows,
                              const std::map<const scene*, reference_state>& references,
                              const std::filesystem::path& dir);

// One panel per scene with a sweep; every method one colour and marker
// throughout the figure, sympl's solid and Odeint's dashed, one legend.
void plot_work_precision(const std::vector<report_row>& rows, const std::vector<run_plan>& plans,
                         const std::filesystem::path& dir);

void fastest_per_level(const std::vector<report_row>& rows, const std::vector<run_plan>& plans, std::ostream& md,
                       std::ostream& table, const std::filesystem::path& dir);

}  // namespace sympl::app
