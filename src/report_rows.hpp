#pragma once
// The report's rows, one per planned run of every scene (run_plan.hpp), and
// the three stages that fill them: the measured runs, the timing rounds, and
// under MPI the gather of every rank's rows to rank 0.
#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "ensemble_run.hpp"
#include "problem.hpp"
#include "reference.hpp"
#include "run_plan.hpp"
#include "studies/study.hpp"

namespace sympl::app {

struct report_row {
    const scene* s = nullptr;
    const planned_run* run = nullptr;
    const problem* p = nullptr;
    run_result r{};
    double final_error = -1;
    double loop_area_error = -1;  // only where the scene asks for it
    std::vector<double> times{};  // one per timing round
    const scene_method& method() const { return *run->method; }
};

// Every planned run of every plan, in order.
std::vector<report_row> rows_of(const std::vector<run_plan>& plans, const std::vector<problem>& problems);

// Which rows this process runs (under MPI: round-robin over the ranks).
using row_filter = std::function<bool(std::size_t)>;

// The measured runs: energy, final state, blow-up, loop area where asked.
void measure_rows(std::vector<report_row>& rows, const row_filter& mine, const progress& bar);

// `rounds` timing rounds over every stable run, interleaved between methods,
// so a slow spell of a shared machine falls on all of them.
void time_rows(std::vector<report_row>& rows, const row_filter& mine, int rounds, double least, const progress& bar);

// Rank 0 receives every rank's measured rows (exactly as the rank measured
// them: numbers as shortest round-trip text).
void gather_rows(std::vector<report_row>& rows, const row_filter& mine, const exchange& ranks);

// Final errors against the references, and each row's median, min and max time.
void finish_rows(std::vector<report_row>& rows, const std::map<const scene*, reference_state>& references);

}  // namespace sympl::app
