#pragma once
// runnable(): a system of hamiltonians/ as the program's type-erased runnable_system.
// Its run() takes any method kind (run_kinds.hpp) over a span: the observed
// run (energy, trajectory, blow-up, checkpoints), then the timed runs with
// nothing observed; the methods its registry entry compiles for its own type
// run there, any other on the generic path (generic_path.hpp). Included by
// the systems' translation units (systems/*.cpp), each instantiating one
// system, and by the generic path's.
#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "running/erased_system.hpp"
#include "running/general_system.hpp"
#include "running/generic_path.hpp"
#include "running/run_kinds.hpp"
#include "running/runnable_parts.hpp"
#include "report/timing.hpp"

namespace sympl::app {

namespace detail {

// Trajectory rows at given times (run_request::output_times), read off the
// Hermite interpolant (drivers/hermite_interpolant.hpp) of the step that holds each
// time, between the states the observed run sees anyway: the run steps
// exactly as without them. A kind whose stepper interpolates its own steps
// sets interpolation() (run_context.hpp), read instead. Only a separable
// Hamiltonian has the velocity and force the Hermite interpolant needs (the
// program refuses other systems first).
template <class Sys, class State>
class timed_rows {
public:
    timed_rows(const Sys&, const run_request& rq) {
        if (!rq.output_times.empty())
            throw invalid_argument("output times: the system is not a separable Hamiltonian, whose velocity and force "
                                   "the interpolant between steps needs");
    }
    void start(const State&, double, bool) {}
    void after_step(const State&, double) {}
    void finish(const State&, double) {}
    own_interpolation<State>* interpolation() { return nullptr; }
};

template <class Sys, class State>
    requires separable_hamiltonian<Sys, typename State::vector>
class timed_rows<Sys, State> {
public:
    timed_rows(const Sys& sys, const run_request& rq)
        : times_(rq.output_times), out_(rq.trajectory),
          interpolant_(sys, rq.output_order == 5 ? hermite_order::quintic : hermite_order::cubic) {}

    // The run's first state: t0 (its rows are x itself), or a checkpoint's,
    // whose rows up to t were written before it was saved.
    void start(const State& x, double t, bool resumed) {
        started_ = true;
        t_last_ = t;
        interpolant_.start(x, t);
        while (next_ < times_.size() && times_[next_] <= t) {
            if (!resumed) write(times_[next_], x);
            ++next_;
        }
    }
    void after_step(const State& x, double t) {
        if (!started_) return start(x, t, false);
        interpolant_.push(x, t);
        for (; next_ < times_.size() && times_[next_] <= t; ++next_) {
            const double at = times_[next_];
            if (!own_) interpolant_.evaluate(at, at_);
            else if (at == t) at_ = x;
            else own_((at - t_last_) / (t - t_last_), at_);  // in (0, 1): t_last < at < t
            write(at, at_);
        }
        t_last_ = t;
    }

    // The run ended at t_end, though its last step's time may be a rounding
    // below it (t0 + n dt): times up to t_end get the final state.
    void finish(const State& x, double t_end) {
        for (; next_ < times_.size() && times_[next_] <= t_end; ++next_) write(times_[next_], x);
    }
    own_interpolation<State>* interpolation() { return &own_; }

private:
    void write(double t, const State& x) {
        if (!out_) return;
        *out_ << t;
        for (double v : stacked(x)) *out_ << ',' << v;
        *out_ << '\n';
    }

    const std::vector<double>& times_;
    std::ostream* out_;
    step_interpolant<Sys, State> interpolant_;
    own_interpolation<State> own_;
    State at_;
    double t_last_ = 0;
    std::size_t next_ = 0;
    bool started_ = false;
};

// The runs of one system type: the methods in Own compiled for it, any other
// handed to `generic` (the generic path, generic_path.hpp).
template <class Sys, int Dim, compiled_methods Own = compiled_methods{}>
class runner {
public:
    using State = state_of<Dim>;

    runner(Sys sys, std::function<double(const std::vector<double>&)> energy, run_function generic = nullptr)
        : sys_(std::move(sys)), energy_(std::move(energy)), generic_(std::move(generic)) {}

    run_result operator()(const method_spec& m, const run_request& rq, double t0, double t_end,
                          const std::vector<double>& x0) const {
        if (!compiled_has(Own, m) && generic_) return generic_(m, rq, t0, t_end, x0);
        run_result r;
        if (!rq.observed && rq.timing_repeats == 0) {
            final_only_run(m, rq, t0, t_end, x0, r);
            return r;
        }
        if (rq.observed) {
            observed_run(m, rq, t0, t_end, x0, r);
            if (!r.stable) return r;
        }
        const timing t = time_per_call(
            [&] {
                State y = to_state<Dim>(x0);
                run_method(run_context<Sys, Dim, Own>{sys_, m, rq, t0, t_end, y, {}});
            },
            rq.timing_repeats, rq.min_measurement);
        r.seconds = t.median;
        r.seconds_min = t.min;
        r.seconds_max = t.max;
        return r;
    }

private:
    // One run with nothing observed, as a timed one, keeping its end: the
    // final state, steps and forces (Python's run(observe=False)). A state
    // that stops being finite is caught where the driver checks it.
    void final_only_run(const method_spec& m, const run_request& rq, double t0, double t_end,
                        const std::vector<double>& x0, run_result& r) const {
        State x = to_state<Dim>(x0);
        try {
            const auto [steps, forces] = run_method(run_context<Sys, Dim, Own>{sys_, m, rq, t0, t_end, x, {}});
            r.steps = steps;
            r.force_evaluations = forces;
            r.final_state = to_vector(x);
        } catch (const integration_error& e) {
            r.stable = false;
            r.blowup_step = e.step;
            r.blowup_time = e.time;
            r.failure = e.what();
        }
    }

    // The measured run: observed every step for energy, trajectory and blow-up.
    void observed_run(const method_spec& m, const run_request& rq, double t0, double t_end, const std::vector<double>& x0,
                      run_result& r) const {
        const bool energy = rq.energy && energy_;
        const double e0 = energy ? energy_(x0) : 0;
        const double scale = e0 != 0 ? std::fabs(e0) : 1;
        std::size_t step = 0;  // the observer sees t0 (step 0), then every step
        std::vector<double> buffer;
        double size0 = 1;
        for (double v : x0) size0 = std::max(size0, std::fabs(v));
        const bool timed = !rq.output_times.empty();
        timed_rows<Sys, State> rows(sys_, rq);
        // H as the system's energy function computes it, on a dynamic state (the same
        // bits), without its conversion and allocations at every step.
        phase_space<double> held = from_stacked<phase_space<double>>(x0);
        const auto energy_of = [&](const State& x) {
            if constexpr (requires { sympl::energy(sys_, held); }) {
                held.q = x.q, held.p = x.p;
                return double(sympl::energy(sys_, held));
            } else {
                return energy_(stacked(x));
            }
        };
        const auto observe = [&](const State& x, double t) {
            if (rq.trajectory && rq.trajectory_every && step % rq.trajectory_every == 0) buffer = stacked(x);
            if (energy) {
                const double err = std::fabs(energy_of(x) - e0) / scale;
                // A finite but exploding run is unstable too: report where, not a huge number.
                if (err > divergence_limit)
                    diverged("relative energy error " + format_number(err, 3) + " > " + format_number(divergence_limit),
                             step, t);
                r.max_energy_error = std::max(r.max_energy_error, err);
                if (rq.energy_series_every && step % rq.energy_series_every == 0) {
                    if (rq.energy_series_file) *rq.energy_series_file << t << ',' << err << '\n';
                    else r.energy_series.emplace_back(t, err);
                }
            } else {  // no energy to watch (damped systems): watch the size of the state
                const double size = std::max(x.q.cwiseAbs().maxCoeff(), x.p.cwiseAbs().maxCoeff());
                if (size > growth_limit * size0) diverged("|x| grew by more than " + format_number(growth_limit), step, t);
            }
            if (rq.trajectory && rq.trajectory_every && step % rq.trajectory_every == 0) {
                *rq.trajectory << t;
                for (double v : buffer) *rq.trajectory << ',' << v;
                *rq.trajectory << '\n';
            }
            if (timed) rows.after_step(x, t);
            if (rq.each_step) rq.each_step(t, stacked(x));
            if (rq.progress && (step & 0x3FFFF) == 0 && step > 0) rq.progress(t);
            ++step;
        };
        if (energy) r.max_energy_error = 0;
        // A resumed run continues the observer where the checkpoint left it;
        // a checkpoint carries the observer's maximum so far.
        run_request with_checkpoints = rq;
        if (const checkpoint_record* from = rq.checkpoint.resume) {
            step = from->step + 1;
            r.max_energy_error = from->max_energy_error;
            if (timed) rows.start(to_state<Dim>(from->state), from->time, true);
        }
        if (rq.checkpoint.save)
            with_checkpoints.checkpoint.save = [&](checkpoint_record& record) {
                record.max_energy_error = r.max_energy_error;
                rq.checkpoint.save(record);
            };
        State x = to_state<Dim>(x0);
        try {
            const auto [steps, forces] =
                run_method(run_context<Sys, Dim, Own>{sys_, m, with_checkpoints, t0, t_end, x, observe,
                                                      timed ? rows.interpolation() : nullptr});
            r.steps = steps;
            r.force_evaluations = forces;
            r.final_state = to_vector(x);
            if (timed) rows.finish(x, t_end);
        } catch (const integration_error& e) {
            r.stable = false;
            r.blowup_step = e.step;
            r.blowup_time = e.time;
            r.failure = e.what();
            r.max_energy_error = -1;
        }
    }

    [[noreturn]] static void diverged(const std::string& what, std::size_t step, double t) {
        throw integration_error("the run diverged: " + what + " after step " + std::to_string(step) + " (t = " +
                                    format_number(t, 17) + ")",
                                step, t);
    }

    Sys sys_;
    std::function<double(const std::vector<double>&)> energy_;
    run_function generic_;
};

// The generic path's runner over a type-erased system (generic_path.cpp):
// every kind it can run, its results marked wherever they are read.
template <class Sys>
run_function generic_runner(Sys sys, std::function<double(const std::vector<double>&)> energy) {
    using every_generic_kind = runner<Sys, Eigen::Dynamic, compiled_methods{.kinds = generic_kinds()}>;
    return [r = every_generic_kind(std::move(sys), std::move(energy))](
               const method_spec& m, const run_request& rq, double t0, double t_end, const std::vector<double>& x0) {
        run_result out = r(m, rq, t0, t_end, x0);
        out.generic = true;
        return out;
    };
}

}  // namespace detail

// A 1-D coordinate or momentum, for the default states of 1-D systems.
inline Eigen::Matrix<double, 1, 1> one_dof(double v) { return Eigen::Matrix<double, 1, 1>(v); }

// The exact flow x(t) = h.exact(x0, t) of a system that has one, as stacked vectors.
template <class H, class X>
std::function<std::vector<double>(double)> exact_flow(H h, X x0) {
    return [h, x0](double t) { return detail::to_vector(h.exact(x0, t)); };
}

// What a system's registry entry compiles for its own type (runnable's template
// argument): the method kinds its built-in scenes run, or of the classic kind
// only the steppers they name (tests/program/test_generic_path.cpp holds
// every entry to that), and ensembles and Poincare sections where a built-in
// scene maps the system. Everything else runs on the generic path
// (generic_path.hpp), marked as such.
struct compiled {
    kind_set kinds{};
    classic_set classic{};  // with kinds holding `classic`: all of them
    bool extrapolated = false;  // extrapolated(...) tables, with the table or LogH kind
    bool ensembles = false;
};

namespace detail {
// The methods compiled for Sys: those its entry names, and the kinds the
// generic path cannot run (Wisdom-Holman, the charged pushers: they need more
// than a Hamiltonian). A system that is no Hamiltonian (damped, driven) has
// no generic path: every method it meets is compiled.
template <class Sys>
constexpr compiled_methods compiled_for(compiled named) {
    using V = phase_space<double>::vector;
    if constexpr (separable_hamiltonian<Sys, V> || is_general_system<Sys>) {
        compiled_methods c;
        c.kinds = named.kinds | kind_set::from_bits(all_kinds.bits & ~generic_kinds().bits);
        if (named.kinds.has(method_kind::classic)) {
            c.classic = all_classic;
        } else if (named.classic.bits != 0) {
            c.kinds = c.kinds | kind_set{method_kind::classic};
            c.classic = named.classic;
        }
        c.extrapolated = named.extrapolated;
        return c;
    } else {
        return compiled_methods{};
    }
}

// Whether Sys meets the requirement of some kind in Own: whether a runner of
// its own has anything to run.
template <class Sys, compiled_methods Own>
constexpr bool runs_any() {
    return []<std::size_t... K>(std::index_sequence<K...>) {
        return ((Own.kinds.has(method_kind(K)) && meets<entry_of(method_kind(K)).requirement, Sys>()) || ...);
    }(std::make_index_sequence<method_kind_count>{});
}
}  // namespace detail

// A system of hamiltonians/ as the program runs it: its default state x0
// and, when it has one, its exact solution from x0.
// Dim: the degrees of freedom when fixed (small systems), Eigen::Dynamic otherwise.
// A general H(q, p) that does not split runs as general_system<H>.
template <int Dim = Eigen::Dynamic, compiled Own = compiled{.kinds = all_kinds, .extrapolated = true, .ensembles = true},
          class Sys>
runnable_system runnable(Sys sys, std::vector<double> x0, std::function<std::vector<double>(double)> exact = nullptr) {
    using V = phase_space<double>::vector;
    if constexpr (general_hamiltonian<Sys, V> && !separable_hamiltonian<Sys, V> && !detail::is_general_system<Sys>) {
        return runnable<Dim, Own>(general_system<Sys>{std::move(sys)}, std::move(x0), std::move(exact));
    } else {
        if (Dim != Eigen::Dynamic && x0.size() != std::size_t(2 * Dim))
            throw invalid_argument("runnable: a state of " + std::to_string(x0.size()) + " numbers for " +
                                   std::to_string(Dim) + " degrees of freedom");
        runnable_system p;
        p.form = detail::form_of<Sys>();
        p.hamiltonian = p.form.general_hamiltonian;  // separable or not
        p.degrees_of_freedom = x0.size() / 2;
        p.x0 = std::move(x0);
        p.exact = std::move(exact);
        if constexpr (detail::form_of<Sys>().planetary) {
            for (const auto& m : sys.mass) p.masses.push_back(double(m));
            p.G = double(sys.G);
        }
        constexpr compiled_methods methods = detail::compiled_for<Sys>(Own);
        p.compiled = methods;
        run_function generic;
        if constexpr (separable_hamiltonian<Sys, V> || detail::is_general_system<Sys>) {
            p.energy = [sys](const std::vector<double>& x) {
                return energy(sys, from_stacked<phase_space<double>>(x));
            };
            detail::generic_parts g = detail::generic_parts_of(sys, p.energy);
            p.reference_method = g.reference_method;
            p.reference = std::move(g.reference);
            p.events = std::move(g.events);
            if constexpr (separable_hamiltonian<Sys, V> && Own.ensembles) {
                p.ensemble = detail::ensemble_of<Dim, native_double_width>(sys);
                p.section = detail::section_of<Dim>(sys);
            } else {
                p.ensemble = std::move(g.ensemble);
                p.section = std::move(g.section);
            }
            generic = std::move(g.run);
        } else {
            p.reference_method = "rk4";
            p.reference = detail::reference_by_rk4(sys);
        }
        if constexpr (detail::runs_any<Sys, methods>())
            p.runner = detail::runner<Sys, Dim, methods>(sys, p.energy, std::move(generic));
        else
            p.runner = std::move(generic);
        return p;
    }
}

}  // namespace sympl::app
