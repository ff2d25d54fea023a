#pragma once
// What a scene's runs are, worked out once: every (method, dt or tolerance)
// run, the finest physical step, the reference's step and the step counts.
// The size check, the reference, `sympl run` and `sympl report` all read the
// plan; none works the sweeps out again.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "running/runnable_system.hpp"
#include "reading/scene.hpp"

namespace sympl::app {

// `sympl run` takes the first value of each method's sweep; `sympl report` takes them all.
enum class sweep_use { first, whole };

struct planned_run {
    const scene_method* method = nullptr;
    double dt = 0;         // fixed-step methods (logh: the fictitious step); 0 for adaptive ones
    double tolerance = 0;  // adaptive Odeint methods; 0 for the others
    // Steps the run takes (an extrapolated method's inner steps counted);
    // 0 where the method chooses its own (adaptive, LogH).
    double steps = 0;
    double setting() const { return dt > 0 ? dt : tolerance; }  // the sweep's value
    // The request for this run's measured (observed) run.
    run_request request() const;
};

struct run_plan {
    const scene* s = nullptr;
    sweep_use use = sweep_use::first;
    std::vector<planned_run> runs{};  // in the scene's method order, each sweep largest first
    double finest_dt = 0;           // the smallest physical step of the runs (the scene's dt if none has one)
    double reference_dt = 0;        // a quarter of finest_dt; 0 when the system is exact
    double reference_steps = 0;     // of the reference's two runs (reference.hpp), together
    std::size_t degrees_of_freedom = 0;
    std::size_t sweep_length(const scene_method& m) const;  // how many of its values run
};

// The step sizes (or, for adaptive kinds, tolerances) the method is swept over, largest first.
const std::vector<double>& sweep_of(const scene& s, const scene_method& m);

run_plan plan_runs(const scene& s, const runnable_system& p, sweep_use use);

// What one run may hold where the scene sets the size (docs/reliability.md,
// "Memory"): Gauss-Legendre's Newton matrices, the energy series a Python run
// returns (`sympl run` writes its own as it goes, holding none).
inline constexpr double memory_budget_bytes = double(std::uint64_t(4) << 30);

// The bytes a run of m holds that its scene sizes: for Gauss-Legendre the
// Jacobian (2n)^2 and the Newton matrix (2ns)^2 of `real_bytes` numbers; for
// an energy series every k steps, a (t, error) pair per row. A reason beside
// the figure says what they are.
struct memory_estimate {
    double bytes = 0;
    std::string what;
};
memory_estimate run_memory(const method_spec& m, std::size_t degrees_of_freedom, double steps,
                           std::size_t energy_every, double real_bytes = 8);

// Refuses, with the figures, a plan whose runs would take more than
// max_steps steps each: every fixed-step method at every step size it will
// use, an extrapolated method counting its inner steps, and the reference
// run. LogH and adaptive methods choose their own steps and are not counted.
// And a run that would hold more than memory_budget_bytes (run_memory).
void check_run_size(const run_plan& plan, double max_steps);

// The scene's system made runnable, every method checked against it: a method
// it cannot run is a scene_error before anything runs or is written.
runnable_system system_of(const scene& s);

}  // namespace sympl::app
