#pragma once
// One runner that takes any method kind to any system, and model(), which
// makes a system of hamiltonians/ into the program's type-erased problem.
// Included by systems.cpp only: every system is instantiated there once.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <ostream>
#include <tuple>
#include <type_traits>
#include <utility>

#include <sympl/sympl.hpp>
#include <sympl/odeint.hpp>

#include "format.hpp"
#include "method_kinds.hpp"
#include "problem.hpp"

namespace sympl::app {

namespace detail {

namespace odeint = boost::numeric::odeint;

// States of Dim degrees of freedom: fixed-size for small systems, as a
// library user would write them (the program's timings are theirs).
template <int Dim>
using state_of = phase_space<double, Dim>;

// Odeint's state: std::array for a fixed size, std::vector otherwise.
template <int Dim>
struct odeint_state_of {
    using type = std::array<double, std::size_t(2 * Dim)>;
};
template <>
struct odeint_state_of<Eigen::Dynamic> {
    using type = std::vector<double>;
};
template <int Dim>
using odeint_state = typename odeint_state_of<Dim>::type;

template <int Dim, class Container>
state_of<Dim> to_state(const Container& x) {
    return from_stacked<state_of<Dim>>(x);
}

// Any state as stacked doubles (the reference runs in long double).
template <class X>
std::vector<double> to_vector(const X& x) {
    const auto y = stacked(x);
    return {y.begin(), y.end()};
}

template <int Dim>
odeint_state<Dim> to_odeint(const state_of<Dim>& x) {
    odeint_state<Dim> y{};
    if constexpr (Dim == Eigen::Dynamic) y.resize(std::size_t(2 * x.size()));
    const auto v = stacked(x);
    std::copy(v.begin(), v.end(), y.begin());
    return y;
}

inline double clock_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The first-order form dx/dt of any system, for Odeint, on stacked states.
// Odeint copies the system at every step, so the workspace lives outside it:
// no allocation per evaluation.
template <int Dim>
struct workspace {
    using vector = typename state_of<Dim>::vector;
    vector q, p, a, b;
    std::uint64_t evaluations = 0;
};

template <class Sys, int Dim>
struct first_order {
    using vector = typename state_of<Dim>::vector;
    const Sys* sys;
    workspace<Dim>* w;
    void operator()(const odeint_state<Dim>& x, odeint_state<Dim>& dxdt, double t) const {
        const auto n = static_cast<Eigen::Index>(x.size() / 2);
        w->q = Eigen::Map<const vector>(x.data(), n);
        w->p = Eigen::Map<const vector>(x.data() + n, n);
        if constexpr (separable_hamiltonian<Sys, vector>) {
            velocity(*sys, w->p, w->a);
            force(*sys, w->q, w->b);
        } else {
            sys->dq_dt(w->q, w->p, t, w->a);
            sys->dp_dt(w->q, w->p, t, w->b);
        }
        Eigen::Map<vector>(dxdt.data(), n) = w->a;
        Eigen::Map<vector>(dxdt.data() + n, n) = w->b;
        ++w->evaluations;
    }
};

// Whether a system of type Sys meets a method's requirement: decided by the
// library's concepts, at compile time; form_of<Sys>() is the registry's copy.
// (V < 0 is a property of the system's values, given by its registry entry.)
template <needs N, class Sys>
constexpr bool meets() {
    using State = phase_space<double>;
    using E = decltype(equations_of<State>(std::declval<Sys>()));
    if constexpr (N == needs::any) return true;
    else if constexpr (N == needs::separable_hamiltonian || N == needs::negative_potential)
        return separable_hamiltonian<Sys, State::vector>;
    else if constexpr (N == needs::differentiable_force) {
        if constexpr (separable_hamiltonian<Sys, State::vector>) return differentiable_force<Sys, State::vector>;
        else return false;
    } else if constexpr (N == needs::newtonian) return newtonian_form<E>;
    else return damped_newtonian_form<E, State>;
}

template <class Sys>
system_form form_of() {
    return {meets<needs::separable_hamiltonian, Sys>(), meets<needs::newtonian, Sys>(), meets<needs::damped_split, Sys>(),
            false, meets<needs::differentiable_force, Sys>()};
}

template <class Sys>
[[noreturn]] void refuse(const std::string& method, needs n) {
    throw invalid_argument("method '" + method + "' " + why_not(n, form_of<Sys>()));
}

template <class Sys, int Dim>
class runner {
public:
    using State = state_of<Dim>;
    using OdeState = odeint_state<Dim>;

    runner(Sys sys, std::function<double(const std::vector<double>&)> energy) : sys_(std::move(sys)), energy_(std::move(energy)) {}

    run_result operator()(const method_spec& m, const run_request& rq, double t0, double t_end,
                          const std::vector<double>& x0) const {
        run_result r;
        if (rq.observed) {
            observed_run(m, rq, t0, t_end, x0, r);
            if (!r.stable) return r;
        }
        // Timing: the same run with nothing observed. Each measurement repeats
        // the run until it lasts min_measurement seconds; median, min and max.
        std::vector<double> samples;
        for (int k = 0; k < rq.timing_repeats; ++k) {
            std::size_t runs = 0;
            const double start = clock_seconds();
            double elapsed = 0;
            do {
                State y = to_state<Dim>(x0);
                drive(m, rq, t0, t_end, y, no_observer{}, false);
                ++runs;
                elapsed = clock_seconds() - start;
            } while (elapsed < rq.min_measurement);
            samples.push_back(elapsed / double(runs));
        }
        if (!samples.empty()) {
            std::sort(samples.begin(), samples.end());
            r.seconds = samples[samples.size() / 2];
            r.seconds_min = samples.front();
            r.seconds_max = samples.back();
        }
        return r;
    }

private:
    // The measured run: observed every step for energy, trajectory and blow-up.
    void observed_run(const method_spec& m, const run_request& rq, double t0, double t_end, const std::vector<double>& x0,
                      run_result& r) const {
        const bool energy = rq.energy && energy_;
        const double e0 = energy ? energy_(x0) : 0;
        const double scale = e0 != 0 ? std::fabs(e0) : 1;
        std::size_t step = 0;  // the observer sees t0 (step 0), then every step
        std::vector<double> buffer;
        constexpr double divergence = 1e3;
        double size0 = 1;
        for (double v : x0) size0 = std::max(size0, std::fabs(v));
        const auto observe = [&](const State& x, double t) {
            if (energy || rq.energy_series_every || rq.trajectory_every) buffer = stacked(x);
            if (energy) {
                const double err = std::fabs(energy_(buffer) - e0) / scale;
                // A finite but exploding run is unstable too: report where, not a huge number.
                if (err > divergence) diverged("relative energy error " + format_number(err, 3) + " > 1e3", step, t);
                r.max_energy_error = std::max(r.max_energy_error, err);
                if (rq.energy_series_every && step % rq.energy_series_every == 0) r.energy_series.emplace_back(t, err);
            }
            if (!energy) {  // no energy to watch (damped systems): watch the size of the state
                const double size = std::max(x.q.cwiseAbs().maxCoeff(), x.p.cwiseAbs().maxCoeff());
                if (size > 1e12 * size0) diverged("|x| grew by more than 1e12", step, t);
            }
            if (rq.trajectory && rq.trajectory_every && step % rq.trajectory_every == 0) {
                *rq.trajectory << t;
                for (double v : buffer) *rq.trajectory << ',' << v;
                *rq.trajectory << '\n';
            }
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
        }
        if (rq.checkpoint.save)
            with_checkpoints.checkpoint.save = [&](checkpoint_record& record) {
                record.max_energy_error = r.max_energy_error;
                rq.checkpoint.save(record);
            };
        State x = to_state<Dim>(x0);
        try {
            const auto [steps, forces] = drive(m, with_checkpoints, t0, t_end, x, observe, true);
            r.steps = steps;
            r.force_evaluations = forces;
            r.final_state = to_vector(x);
        } catch (const integration_error& e) {
            r.stable = false;
            r.blowup_step = e.step;
            r.blowup_time = e.time;
            r.failure = e.what();
            r.max_energy_error = -1;
        }
    }

    // Runs the span, calling obs(x, t) at t0 and after every step when observed.
    // Returns (steps, force evaluations).
    template <class Observer>
    std::pair<std::size_t, std::uint64_t> drive(const method_spec& m, const run_request& rq, double t0, double t_end,
                                                State& x, Observer&& obs, bool observed) const {
        const auto with_driver = [&](auto stepper) -> std::pair<std::size_t, std::uint64_t> {
            run_summary s;
            if (observed && rq.checkpoint.every_steps) return checkpointed(stepper, rq, t0, t_end, x, obs);
            if (observed)
                s = integrate_until(stepper, x, t0, t_end, rq.dt, obs);
            else
                s = integrate_until(stepper, x, t0, t_end, rq.dt);
            return {s.steps, s.force_evaluations};
        };
        switch (m.kind) {
            case method_kind::table:
                if constexpr (meets<needs::separable_hamiltonian, Sys>()) {
                    if constexpr (!meets<needs::differentiable_force, Sys>())
                        if (m.coefficients->has_force_gradient()) refuse<Sys>(m.name, needs::differentiable_force);
                    splitting_stepper<Sys, State> stepper(sys_, *m.coefficients, {m.compensated});
                    if (m.extrapolation_columns > 0)
                        return with_driver(extrapolation_stepper(std::move(stepper), m.extrapolation_columns));
                    return with_driver(std::move(stepper));
                } else
                    refuse<Sys>(m.name, needs::separable_hamiltonian);
            case method_kind::processed:
                if constexpr (meets<needs::separable_hamiltonian, Sys>())
                    return with_driver(processed_stepper<Sys, State>(sys_, *m.processing));
                else
                    refuse<Sys>(m.name, needs::separable_hamiltonian);
            case method_kind::logh:
                if constexpr (meets<needs::separable_hamiltonian, Sys>())
                    return in_logh_time(*m.coefficients, m.extrapolation_columns, rq.dt, t0, t_end, x, obs, observed);
                else
                    refuse<Sys>(m.name, needs::separable_hamiltonian);
            case method_kind::classic:
                return classic(m.name, with_driver);
            case method_kind::odeint_rk4:
                return odeint_fixed(rq.dt, t0, t_end, x, obs, observed);
            case method_kind::odeint_dopri5:
                return odeint_adaptive(
                    m.name, odeint::make_controlled(rq.tolerance, rq.tolerance, odeint::runge_kutta_dopri5<OdeState>()),
                    t0, t_end, x, obs, observed);
            case method_kind::odeint_fehlberg78:
                return odeint_adaptive(
                    m.name, odeint::make_controlled(rq.tolerance, rq.tolerance, odeint::runge_kutta_fehlberg78<OdeState>()),
                    t0, t_end, x, obs, observed);
            case method_kind::odeint_bulirsch_stoer:
                return odeint_adaptive(m.name, odeint::bulirsch_stoer<OdeState>(rq.tolerance, rq.tolerance), t0, t_end, x,
                                       obs, observed);
        }
        throw invalid_argument("method '" + m.name + "' is of an unknown kind");
    }

    // The observed run with a checkpoint every rq.checkpoint.every_steps steps,
    // or its continuation from rq.checkpoint.resume: the driver resumes at the
    // checkpoint's step (times from the integer index), the stepper from its
    // saved memory, so the rest of the run is bit for bit the uninterrupted one.
    template <class Stepper, class Observer>
    std::pair<std::size_t, std::uint64_t> checkpointed(Stepper& stepper, const run_request& rq, double t0,
                                                       double t_end, State& x, Observer& obs) const {
        constexpr bool has_memory = requires { stepper.memory(); };
        const checkpoint_record* from = rq.checkpoint.resume;
        run_options options;
        std::uint64_t forces_before = 0, velocities_before = 0;
        if (from) {
            x = to_state<Dim>(from->state);
            if constexpr (has_memory) {
                using vector = typename State::vector;
                const auto as_vector = [](const std::vector<double>& v) {
                    return vector(Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size())));
                };
                stepper_memory<vector> memory{as_vector(from->force), as_vector(from->velocity), as_vector(from->q_error),
                                              as_vector(from->p_error), from->force_fresh, from->velocity_fresh,
                                              from->force_evaluations, from->velocity_evaluations};
                stepper.restore(memory);
            }
            forces_before = from->force_evaluations;
            velocities_before = from->velocity_evaluations;
            options.first_step = from->step;
        }
        std::size_t done = options.first_step;
        bool at_start = options.first_step == 0;  // the observer's first call is t0, not a step
        const auto observe = [&](const State& y, double t) {
            obs(y, t);
            if (at_start) {
                at_start = false;
                return;
            }
            ++done;
            if (done % rq.checkpoint.every_steps != 0 || t == t_end) return;
            checkpoint_record record;
            record.step = done;
            record.state = to_vector(y);
            if constexpr (has_memory) {
                const auto memory = stepper.memory();
                const auto as_std = [](const auto& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
                record.force = as_std(memory.force);
                record.velocity = as_std(memory.velocity);
                record.q_error = as_std(memory.q_error);
                record.p_error = as_std(memory.p_error);
                record.force_fresh = memory.force_fresh;
                record.velocity_fresh = memory.velocity_fresh;
                record.force_evaluations = memory.force_evaluations;
                record.velocity_evaluations = memory.velocity_evaluations;
            } else {
                record.force_evaluations = forces_before + stepper.force_evaluations();
                record.velocity_evaluations = velocities_before + stepper.velocity_evaluations();
            }
            rq.checkpoint.save(record);
        };
        const run_summary s = integrate_until(stepper, x, t0, t_end, rq.dt, observe, options);
        return {options.first_step + s.steps, forces_before + s.force_evaluations};
    }

    [[noreturn]] static void diverged(const std::string& what, std::size_t step, double t) {
        throw integration_error("the run diverged: " + what + " after step " + std::to_string(step) + " (t = " +
                                    format_number(t, 17) + ")",
                                step, t);
    }

    // The table in LogH fictitious time (time_transformation.hpp), extrapolated
    // when columns > 0 (extrapolation.hpp); ds = dt.
    template <class Observer>
    std::pair<std::size_t, std::uint64_t> in_logh_time(const table& t, int columns, double ds, double t0, double t_end,
                                                       State& x, Observer& obs, bool observed) const {
        using Extended = phase_space<double, extended_dimension(Dim)>;
        splitting_stepper<logh<Sys>, Extended> inner(logh<Sys>{sys_}, t);
        if (columns > 0)
            return in_logh_time(extrapolation_stepper(std::move(inner), columns), ds, t0, t_end, x, obs, observed);
        return in_logh_time(std::move(inner), ds, t0, t_end, x, obs, observed);
    }
    template <class Stepper, class Observer>
    std::pair<std::size_t, std::uint64_t> in_logh_time(Stepper stepper, double ds, double t0, double t_end, State& x,
                                                       Observer& obs, bool observed) const {
        using Extended = typename Stepper::state_type;
        Extended X = to_extended(sys_, x, t0);
        run_summary s;
        if (observed) {
            obs(std::as_const(x), t0);
            s = integrate_to_time(stepper, X, t_end, ds, [&](const Extended& y, double time) { obs(physical_state(y), time); });
        } else {
            s = integrate_to_time(stepper, X, t_end, ds);
        }
        x = physical_state(X);
        return {s.steps, s.force_evaluations};
    }

    // The classic stepper of that name (classic_methods), where the system meets its requirement.
    template <class Drive>
    std::pair<std::size_t, std::uint64_t> classic(const std::string& name, Drive&& go) const {
        std::optional<std::pair<std::size_t, std::uint64_t>> done;
        const auto attempt = [&]<template <class, class> class Stepper, needs N>(const classic_method<Stepper, N>& c) {
            if (done || name != c.name) return;
            if constexpr (meets<N, Sys>())
                done = go(make_classic<Stepper, State>(sys_));
            else
                refuse<Sys>(name, N);
        };
        std::apply([&](const auto&... c) { (attempt(c), ...); }, classic_methods);
        if (!done) throw invalid_argument("method '" + name + "' is not a classic method");
        return *done;
    }

    static void check_step(const OdeState& y, std::size_t step, double t, double h) {
        for (double v : y)
            if (!std::isfinite(v)) throw blow_up(step, t, h);
    }

    template <class Observer>
    std::pair<std::size_t, std::uint64_t> odeint_fixed(double dt, double t0, double t_end, State& x, Observer& obs,
                                                       bool observed) const {
        workspace<Dim> w;
        first_order<Sys, Dim> f{&sys_, &w};
        OdeState y = to_odeint<Dim>(x);
        odeint::runge_kutta4<OdeState> rk4;
        const auto n = static_cast<std::size_t>(std::floor((t_end - t0) / dt));
        double rest = (t_end - t0) - double(n) * dt;
        if (rest <= 8 * std::numeric_limits<double>::epsilon() * (t_end - t0)) rest = 0;
        if (observed) obs(std::as_const(x), t0);  // like sympl's driver: the observer sees t0 first
        const std::size_t total = n + (rest > 0 ? 1 : 0);
        for (std::size_t i = 0; i < total; ++i) {
            const double t = t0 + double(i) * dt, h = i < n ? dt : rest;
            rk4.do_step(f, y, t, h);
            if (observed) {
                check_step(y, i + 1, t, h);
                obs(to_state<Dim>(y), t + h);
            }
        }
        if (!observed) check_step(y, total, t_end, dt);
        x = to_state<Dim>(y);
        return {total, w.evaluations};
    }

    // Any Odeint controlled stepper (try_step), from t0 to exactly t_end.
    template <class Controlled, class Observer>
    std::pair<std::size_t, std::uint64_t> odeint_adaptive(const std::string& name, Controlled stepper, double t0,
                                                          double t_end, State& x, Observer& obs, bool observed) const {
        workspace<Dim> w;
        first_order<Sys, Dim> f{&sys_, &w};
        OdeState y = to_odeint<Dim>(x);
        double t = t0, h = (t_end - t0) / 1000;
        std::size_t steps = 0, failed = 0;
        if (observed) obs(std::as_const(x), t0);
        while (t < t_end) {
            if (t + h > t_end) h = t_end - t;
            if (!(h > 1e-14 * (t_end - t0)) || t + h == t || ++failed > 500)
                throw integration_error(name + ": step size underflow at t = " + format_number(t, 17) + " (dt = " +
                                            format_number(h, 3) + ")",
                                        steps + 1, t);
            if (stepper.try_step(f, y, t, h) == odeint::success) {
                ++steps;
                failed = 0;
                check_step(y, steps, t, h);
                if (observed) obs(to_state<Dim>(y), t);
            }
        }
        x = to_state<Dim>(y);
        return {steps, w.evaluations};
    }

    Sys sys_;
    std::function<double(const std::vector<double>&)> energy_;
};

}  // namespace detail

// A system of hamiltonians/ as the program's problem: its default state x0
// and, when it has one, its exact solution from x0.
// Dim: the degrees of freedom when fixed (small systems), Eigen::Dynamic otherwise.
template <int Dim = Eigen::Dynamic, class Sys>
problem model(Sys sys, std::vector<double> x0, std::function<std::vector<double>(double)> exact = nullptr) {
    using State = phase_space<double>;
    using detail::to_vector;
    if (Dim != Eigen::Dynamic && x0.size() != std::size_t(2 * Dim))
        throw invalid_argument("model: a state of " + std::to_string(x0.size()) + " numbers for " + std::to_string(Dim) +
                               " degrees of freedom");
    problem p;
    p.form = detail::form_of<Sys>();
    p.hamiltonian = p.form.separable_hamiltonian;
    p.degrees_of_freedom = x0.size() / 2;
    p.x0 = std::move(x0);
    p.exact = std::move(exact);
    if constexpr (separable_hamiltonian<Sys, State::vector>) {
        p.energy = [sys](const std::vector<double>& x) { return energy(sys, from_stacked<State>(x)); };
        p.reference = [sys](double t0, double t_end, double dt, const std::vector<double>& x) {
            using L = phase_space<long double>;
            L y = from_stacked<L>(x);
            splitting_stepper<Sys, L> ss(sys, method("sofroniou_spaletta_10"));
            integrate_until(ss, y, (long double)t0, (long double)t_end, (long double)dt);
            return to_vector(y);
        };
        p.ensemble = [sys](const ensemble_request& rq, const std::vector<std::vector<double>>& starts) {
            using S = detail::state_of<Dim>;
            std::vector<S> states;
            states.reserve(starts.size());
            for (const auto& x : starts) states.push_back(from_stacked<S>(x));
            ensemble_options o;
            o.t0 = rq.t0;
            o.dt = rq.dt;
            o.steps = rq.steps;
            o.sample_every = rq.sample_every;
            o.megno = rq.megno;
            o.divergence = rq.divergence;
            o.threads = rq.threads;
            std::vector<ensemble_row> rows;
            rows.reserve(starts.size());
            for (const auto& r : run_ensemble(sys, *rq.method, states, o))
                rows.push_back({r.stable, r.blowup_step, r.blowup_time, r.failure, r.max_energy_error, r.megno,
                                to_vector(r.final_state)});
            return rows;
        };
        p.section = [sys](const table& m, double dt, std::size_t steps, const std::vector<double>& x0) {
            using S = detail::state_of<Dim>;
            splitting_stepper<Sys, S> stepper(sys, m);
            std::vector<std::vector<double>> points;
            for (const S& c : section_crossings(stepper, from_stacked<S>(x0), dt, steps)) points.push_back(to_vector(c));
            return points;
        };
    } else {
        p.reference = [sys](double t0, double t_end, double dt, const std::vector<double>& x) {
            State y = from_stacked<State>(x);
            auto s4 = make_classic<rk4, State>(sys);
            integrate_until(s4, y, t0, t_end, dt);
            return to_vector(y);
        };
    }
    p.run = detail::runner<Sys, Dim>(sys, p.energy);
    return p;
}

}  // namespace sympl::app
