#pragma once
// The report's rows, one per planned run of every scene (run_plan.hpp), and
// the three stages that fill them: the measured runs, the timing rounds, and
// under MPI the gather of every rank's rows to rank 0.
#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "commands/ensemble_run.hpp"
#include "running/runnable_system.hpp"
#include "report/reference.hpp"
#include "methods/run_plan.hpp"
#include "studies/study.hpp"

namespace sympl::app {

struct report_row {
    const scene* s = nullptr;
    const planned_run* run = nullptr;
    const runnable_system* p = nullptr;
    run_result r{};
    double final_error = -1;
    double loop_area_error = -1;  // only where the scene asks for it
    std::vector<double> times{};  // one per timing round
    const scene_method& method() const { return *run->method; }
};

// Every planned run of every plan, in order.
std::vector<report_row> rows_of(const std::vector<run_plan>& plans, const std::vector<runnable_system>& systems);

// Which rows this process runs (under MPI: round-robin over the ranks).
using row_filter = std::function<bool(std::size_t)>;

// The measured runs: energy, final state, blow-up, loop area where asked;
// `threads` runs side by side (0: OpenMP's default), each with a system of
// its own, so that the rows' numbers are the same for any thread count.
// The tasks `first` (the references) share the threads, started before the rows.
void measure_rows(std::vector<report_row>& rows, const row_filter& mine, const progress& bar, int threads,
                  const std::vector<std::function<void()>>& first = {});

// `rounds` timing rounds over every stable run, interleaved between methods,
// so a slow spell of a shared machine falls on all of them. A run whose
// errors reached order one is no solution at any level (left out of every
// table and figure), so it is not timed: at Kepler e = 0.99 the fixed-step
// runs are such runs, and timing them was a large part of the report's time.
// Its final error is judged against the exact solution or, on the process
// that has it, the reference; without either it is timed. Each round runs
// `threads` timed runs side by side, one per thread.
void time_rows(std::vector<report_row>& rows, const row_filter& mine, int rounds, double least, const progress& bar,
               const std::map<const scene*, reference_state>& references, int threads);

// Rank 0 receives every rank's measured rows (exactly as the rank measured
// them: numbers as shortest round-trip text).
void gather_rows(std::vector<report_row>& rows, const row_filter& mine, const exchange& ranks);

// Final errors against the references, and each row's median, min and max time.
void finish_rows(std::vector<report_row>& rows, const std::map<const scene*, reference_state>& references);

}  // namespace sympl::app
