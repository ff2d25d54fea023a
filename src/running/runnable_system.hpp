#pragma once
// A system made runnable by any method kind (method_kinds.hpp). Everything is
// type-erased over stacked std::vector<double> states (q then p), so the
// program holds all systems in one registry (systems.hpp); the runs
// themselves use sympl's templates on dynamic-size states (runner.hpp).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <iosfwd>
#include <string>
#include <vector>

#include "output/checkpoint.hpp"
#include "methods/method_kinds.hpp"

namespace sympl::app {

// Where a finite run counts as blown up, for every run of the program (single
// runs, the report, ensembles): a relative energy error above divergence_limit,
// or, for a system without an energy, a state grown by more than growth_limit.
// It is reported as unstable at that step, never as a huge number.
inline constexpr double divergence_limit = 1e3;
inline constexpr double growth_limit = 1e12;

// Checkpoints of the observed run (checkpoint.hpp): `save` is called every
// `every_steps` steps with the record filled in but for the caller's part
// (identity, trajectory bytes); `resume` continues a run from a record.
struct checkpoint_hooks {
    std::size_t every_steps = 0;  // 0: none
    const checkpoint_record* resume = nullptr;
    std::string resume_file;  // the file `resume` was read from, for a refusal's message
    std::function<void(checkpoint_record&)> save;
};

struct run_request {
    double dt = 0;                        // fixed-step methods (logh: the fictitious step)
    double tolerance = 0;                 // adaptive Odeint methods (absolute = relative)
    bool observed = true;                 // the measured run (energy, trajectory, final state, blow-up)
    bool energy = false;                  // track the max relative energy error
    std::size_t energy_series_every = 0;  // record (t, energy error) every k steps
    // Where: rows "t,error\n" written here as the run goes (`sympl run`'s
    // staged file: nothing held); null: into run_result::energy_series.
    std::ostream* energy_series_file = nullptr;
    std::size_t trajectory_every = 0;     // write t, q, p every k steps to *trajectory
    // Or write them at these times (sorted, in the span), interpolated inside
    // the steps by the Hermite interpolant of this order, 3 or 5 (5 needs T
    // quadratic in p): separable Hamiltonians only (drivers/hermite_interpolant.hpp).
    std::vector<double> output_times;
    int output_order = 3;
    std::ostream* trajectory = nullptr;
    int timing_repeats = 1;               // wall-time measurements of unobserved runs (0: no timing;
                                          // with observed false: one unobserved run, its final state kept)
    double min_measurement = 2e-3;        // each measurement repeats the run until it lasts this long [s]
    // Called with the current time every 2^18 steps of the observed run
    // (a terminal's progress line); empty: nothing.
    std::function<void(double t)> progress;
    // Called with the time and the stacked state (q then p) at t0 and after
    // every step of the observed run, in physical time for every kind (events
    // over any method, generic_path.cpp); empty: nothing. An exception it
    // throws ends the run there.
    std::function<void(double t, const std::vector<double>& x)> each_step;
    checkpoint_hooks checkpoint;  // tables and classic steppers without history
};

struct run_result {
    bool stable = true;
    std::size_t blowup_step = 0;  // unstable: the step that produced a non-finite state
    double blowup_time = 0;       // and the time it started from
    std::string failure;          // unstable: the message
    std::size_t steps = 0;
    std::uint64_t force_evaluations = 0;
    double seconds = -1;            // median wall time of one run (-1: not timed)
    double seconds_min = -1, seconds_max = -1;
    double max_energy_error = -1;   // -1: not measured (or no energy: not Hamiltonian)
    std::vector<double> final_state;
    std::vector<std::pair<double, double>> energy_series;
    // Ran on the generic path (generic_path.hpp): a kind the system's registry
    // entry does not compile, through the type-erased system; outputs mark it.
    bool generic = false;
};

// A method's run over [t0, t_end] from x0 (runnable.hpp).
using run_function = std::function<run_result(const method_spec&, const run_request&, double t0, double t_end,
                                              const std::vector<double>& x0)>;

// An ensemble of one system (ensemble.hpp): one table, one dt, many starts.
struct ensemble_request {
    std::optional<table> method;
    double t0 = 0, dt = 0;
    std::size_t steps = 0;
    std::size_t sample_every = 1;
    bool megno = false;
    double divergence = divergence_limit;
    int threads = 0;
};

struct ensemble_row {
    bool stable = true;
    std::size_t blowup_step = 0;
    double blowup_time = 0;
    std::string failure;
    double max_energy_error = -1;
    double megno = 0;
    std::vector<double> final_state;  // q then p
};

using ensemble_function =
    std::function<std::vector<ensemble_row>(const ensemble_request&, const std::vector<std::vector<double>>& starts)>;
using section_function = std::function<std::vector<std::vector<double>>(const table&, double dt, std::size_t steps,
                                                                        const std::vector<double>& x0)>;
// An event of a run (drivers/events.hpp): g(t, x) of the stacked state x (q
// then p), a crossing of zero counted in `direction` (+1 rising, -1 falling,
// 0 both); `stop` ends the run at the first.
struct event_spec {
    std::function<double(double t, const std::vector<double>& x)> g;
    int direction = 0;
    bool stop = false;
};
struct event_outcome {
    struct hit {
        std::size_t event = 0;  // index into the events given
        double t = 0;
        std::vector<double> x;  // interpolated at t
    };
    std::vector<hit> hits;  // in time order
    bool stopped = false;   // a stop event ended the run
    double t = 0;           // where the run ended (t_end, or the stop event's time)
    std::vector<double> x;  // its state there
};
// A method's run with events: any kind of the generic path (generic_path.cpp
// says how each is located) at steps of dt (LogH: its fictitious step), or
// controlled to `tolerance` (an RKN pair from a first step dt).
using events_function =
    std::function<event_outcome(const method_spec&, double dt, double tolerance, double t0, double t_end,
                                const std::vector<double>& x0, const std::vector<event_spec>&)>;
using reference_function =
    std::function<std::vector<double>(double t0, double t_end, double dt, const std::vector<double>& x0)>;

struct runnable_system {
    std::string system;
    bool hamiltonian = true;  // has an energy to watch
    system_form form;         // what its equations offer a method
    std::size_t degrees_of_freedom = 0;
    std::vector<double> x0;  // q then p
    // Exact state at time t (from x0 at t0 = 0); empty when there is none.
    std::function<std::vector<double>(double t)> exact;
    // A planetary system's masses (star first) and G, which a Wisdom-Holman
    // run of test particles needs beside x0 (run_test_particles.hpp); empty
    // and 0 for any other system.
    std::vector<double> masses;
    double G = 0;
    std::function<double(const std::vector<double>&)> energy;  // empty when not Hamiltonian
    // A method's run: its requirement asked of `form` once, here (a misfit
    // throws invalid_argument naming it), then `runner`, which trusts it.
    run_result run(const method_spec& m, const run_request& rq, double t0, double t_end,
                   const std::vector<double>& x0) const;
    run_function runner;  // the system's runs (runnable.hpp), unchecked
    // The kinds compiled for the system's own type (its registry entry's,
    // runnable.hpp); the others run on the generic path.
    compiled_methods compiled;
    // The ensemble runner (separable Hamiltonians only; empty otherwise).
    ensemble_function ensemble;
    // Upward crossings of q1 = 0 (a Poincare section) of `steps` steps of dt
    // from x0, as stacked states (separable Hamiltonians only).
    section_function section;
    // The events of a method's run from x0 at t0 to t_end (events_function),
    // separable Hamiltonians only: on the generic path, compiled once for
    // every system.
    events_function events;
    // A reference at t_end with step dt: Sofroniou-Spaletta 10 in long double
    // (a separable H), Gauss-Legendre 6 in long double (any other H), RK4.
    std::string reference_method;  // which, as the report names it
    reference_function reference;
};

// max_i |a_i - b_i| / max_i |b_i|
double relative_difference(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace sympl::app
