#pragma once
// `sympl report`: the work-precision study (CSV, gnuplot PNGs, summary.md)
// with the stiff and extreme cases (studies/).
#include <iosfwd>
#include <string>
#include <vector>

#include "commands/ensemble_run.hpp"
#include "reading/scene.hpp"

namespace sympl::app {

struct report_options {
    std::string out_dir = "sympl-report";
    bool quick = false;
    bool studies = true;   // stability map, Kepler e = 0.99, long run, extreme scales
    bool plots = true;     // PNGs with gnuplot when it is installed
    double max_steps = default_max_steps;  // per run, checked before anything runs
    // Threads that make references, measure and time runs side by side, each
    // run on one thread (0: OMP_NUM_THREADS, else every core).
    int threads = 0;
};

// The study over `scenes`; writes into options.out_dir and prints a short
// table. Under MPI (`ranks` from process_exchange()) the runs are spread over
// the ranks and rank 0 alone writes and prints.
void run_report(const std::vector<scene>& scenes, const report_options& options, std::ostream& out,
                const exchange& ranks = exchange{});

}  // namespace sympl::app
