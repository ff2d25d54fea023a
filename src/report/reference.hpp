#pragma once
// The state a run's final error is measured against: the exact solution where
// the system has one, otherwise Sofroniou-Spaletta 10 in long double (RK4 for
// a system that is not Hamiltonian) at a quarter of the finest step, with its
// own error estimated from the run at twice that step.
#include <filesystem>
#include <string>
#include <vector>

#include "running/runnable_system.hpp"
#include "methods/run_plan.hpp"
#include "reading/scene.hpp"

namespace sympl::app {

struct reference_state {
    std::vector<double> x;
    double error = 0;  // relative; 0 for an exact solution
    std::string kind;  // how it was made
    // Not empty when the reference run itself blew up: what happened, with the
    // reference's own dt. No final errors are measured against it then; the
    // methods still run and report everything else.
    std::string failure;
};

// At the plan's reference step (a quarter of the finest step its runs take).
// With `cache` not empty, a reference is stored there under a key of
// everything it depends on. side_by_side: its two runs (the step and twice
// it) on two threads.
reference_state make_reference(const scene& s, const runnable_system& p, const run_plan& plan,
                               const std::filesystem::path& cache = {}, bool side_by_side = false);

// What the reference will cost before it starts: its steps (both runs) and
// the seconds they take, extrapolated from a timed run of a few of its steps
// (a step's cost grows with the degrees of freedom, which step counts miss).
struct reference_cost {
    double steps = 0;
    double seconds = 0;
};
reference_cost estimate_reference(const scene& s, const runnable_system& p, const run_plan& plan);

// `sympl run` says on stderr what a reference will cost when it is estimated
// above announced_reference_seconds, and refuses one above
// max_reference_seconds (scaled with --max-steps over its default).
inline constexpr double announced_reference_seconds = 10;
inline constexpr double max_reference_seconds = 3600;

}  // namespace sympl::app
