#pragma once
// One runner that takes any method kind to any system, and model(), which
// makes a system of hamiltonians/ into the program's type-erased problem.
// Included by systems.cpp only: every system is instantiated there once.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
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

using State = phase_space<double>;
using Vec = State::vector;
namespace odeint = boost::numeric::odeint;

inline State to_state(const std::vector<double>& x) { return from_stacked<State>(x); }

// Any state as stacked doubles (the reference runs in long double).
template <class X>
std::vector<double> to_vector(const X& x) {
    const auto y = stacked(x);
    return {y.begin(), y.end()};
}

inline double clock_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The first-order form dx/dt of any system, for Odeint, on stacked vectors.
// Odeint copies the system at every step, so the workspace lives outside it:
// no allocation per evaluation.
struct workspace {
    Vec q, p, a, b;
    std::uint64_t evaluations = 0;
};

template <class Sys>
struct first_order {
    const Sys* sys;
    workspace* w;
    void operator()(const std::vector<double>& x, std::vector<double>& dxdt, double t) const {
        const auto n = static_cast<Eigen::Index>(x.size() / 2);
        w->q = Eigen::Map<const Vec>(x.data(), n);
        w->p = Eigen::Map<const Vec>(x.data() + n, n);
        if constexpr (separable_hamiltonian<Sys, Vec>) {
            velocity(*sys, w->p, w->a);
            force(*sys, w->q, w->b);
        } else {
            sys->dq_dt(w->q, w->p, t, w->a);
            sys->dp_dt(w->q, w->p, t, w->b);
        }
        Eigen::Map<Vec>(dxdt.data(), n) = w->a;
        Eigen::Map<Vec>(dxdt.data() + n, n) = w->b;
        ++w->evaluations;
    }
};

// Whether a system of type Sys meets a method's requirement: decided by the
// library's concepts, at compile time; form_of<Sys>() is the registry's copy.
template <needs N, class Sys>
constexpr bool meets() {
    using E = decltype(equations_of<State>(std::declval<Sys>()));
    if constexpr (N == needs::any) return true;
    else if constexpr (N == needs::separable_hamiltonian) return separable_hamiltonian<Sys, Vec>;
    else if constexpr (N == needs::newtonian) return newtonian_form<E>;
    else return damped_newtonian_form<E, State>;
}

template <class Sys>
system_form form_of() {
    return {meets<needs::separable_hamiltonian, Sys>(), meets<needs::newtonian, Sys>(), meets<needs::damped_split, Sys>()};
}

template <class Sys>
[[noreturn]] void refuse(const std::string& method, needs n) {
    throw invalid_argument("method '" + method + "' " + why_not(n, form_of<Sys>()));
}

template <class Sys>
class runner {
public:
    runner(Sys sys, std::function<double(const std::vector<double>&)> energy) : sys_(std::move(sys)), energy_(std::move(energy)) {}

    run_result operator()(const method_spec& m, const run_request& rq, double t0, double t_end,
                          const std::vector<double>& x0) const {
        run_result r;
        // The measured run: observed every step for energy, trajectory and blow-up.
        const bool energy = rq.energy && energy_;
        const double e0 = energy ? energy_(x0) : 0;
        const double scale = e0 != 0 ? std::fabs(e0) : 1;
        std::size_t step = 0;  // the observer sees t0 (step 0), then every step
        std::vector<double> buffer;
        constexpr double divergence = 1e3;
        double size0 = 1;
        for (double v : x0) size0 = std::max(size0, std::fabs(v));
        const auto observe = [&](const auto& x, double t) {
            if (energy || rq.energy_series_every || rq.trajectory_every) buffer = stacked(x);
            if (energy) {
                const double err = std::fabs(energy_(buffer) - e0) / scale;
                // A finite but exploding run is unstable too: report where, not a huge number.
                if (err > divergence) diverged("relative energy error " + format_number(err, 3) + " > 1e3", step, t);
                r.max_energy_error = std::max(r.max_energy_error, err);
                if (rq.energy_series_every && step % rq.energy_series_every == 0) r.energy_series.emplace_back(t, err);
            }
            if (!energy) {  // no energy to watch (damped systems): watch the size of the state
                double size = 0;
                for (Eigen::Index i = 0; i < x.q.size(); ++i) size = std::max({size, std::fabs(double(x.q[i])), std::fabs(double(x.p[i]))});
                if (size > 1e12 * size0) diverged("|x| grew by more than 1e12", step, t);
            }
            if (rq.trajectory && rq.trajectory_every && step % rq.trajectory_every == 0) {
                *rq.trajectory << t;
                for (double v : buffer) *rq.trajectory << ',' << v;
                *rq.trajectory << '\n';
            }
            ++step;
        };
        if (energy) r.max_energy_error = 0;
        State x = to_state(x0);
        try {
            const auto [steps, forces] = drive(m, rq, t0, t_end, x, observe, true);
            r.steps = steps;
            r.force_evaluations = forces;
            r.final_state = to_vector(x);
        } catch (const integration_error& e) {
            r.stable = false;
            r.blowup_step = e.step;
            r.blowup_time = e.time;
            r.failure = e.what();
            r.max_energy_error = -1;
            return r;
        }
        // Timing: the same run with nothing observed, best of several.
        for (int k = 0; k < rq.timing_repeats; ++k) {
            State y = to_state(x0);
            const double start = clock_seconds();
            drive(m, rq, t0, t_end, y, no_observer{}, false);
            const double s = clock_seconds() - start;
            r.seconds = r.seconds < 0 ? s : std::min(r.seconds, s);
        }
        return r;
    }

    // Runs the span, calling obs(x, t) after every step when observed.
    // Returns (steps, force evaluations).
    template <class Observer>
    std::pair<std::size_t, std::uint64_t> drive(const method_spec& m, const run_request& rq, double t0, double t_end,
                                                State& x, Observer&& obs, bool observed) const {
        const auto with_driver = [&](auto stepper) -> std::pair<std::size_t, std::uint64_t> {
            run_summary s;
            if (observed)
                s = integrate_until(stepper, x, t0, t_end, rq.dt, obs);
            else
                s = integrate_until(stepper, x, t0, t_end, rq.dt);
            return {s.steps, s.force_evaluations};
        };
        switch (m.kind) {
            case method_kind::table:
                if constexpr (meets<needs::separable_hamiltonian, Sys>())
                    return with_driver(splitting_stepper<Sys, State>(sys_, *m.coefficients));
                else
                    refuse<Sys>(m.name, needs::separable_hamiltonian);
            case method_kind::classic:
                return classic(m.name, with_driver);
            case method_kind::odeint_rk4:
                return odeint_fixed(rq.dt, t0, t_end, x, obs, observed);
            case method_kind::odeint_dopri5:
                return odeint_adaptive(rq.tolerance, t0, t_end, x, obs, observed);
        }
        throw invalid_argument("method '" + m.name + "' is of an unknown kind");
    }

private:
    [[noreturn]] static void diverged(const std::string& what, std::size_t step, double t) {
        throw integration_error("the run diverged: " + what + " after step " + std::to_string(step) + " (t = " +
                                    format_number(t, 17) + ")",
                                step, t);
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

    static void check_step(const std::vector<double>& y, std::size_t step, double t, double h) {
        for (double v : y)
            if (!std::isfinite(v)) throw blow_up(step, t, h);
    }

    template <class Observer>
    std::pair<std::size_t, std::uint64_t> odeint_fixed(double dt, double t0, double t_end, State& x, Observer& obs,
                                                       bool observed) const {
        workspace w;
        first_order<Sys> f{&sys_, &w};
        std::vector<double> y = to_vector(x);
        odeint::runge_kutta4<std::vector<double>> rk4;
        const auto n = static_cast<std::size_t>(std::floor((t_end - t0) / dt));
        double rest = (t_end - t0) - double(n) * dt;
        if (rest <= 8 * std::numeric_limits<double>::epsilon() * (t_end - t0)) rest = 0;
        State view = x;
        if (observed) obs(view, t0);  // like sympl's driver: the observer sees t0 first
        const std::size_t total = n + (rest > 0 ? 1 : 0);
        for (std::size_t i = 0; i < total; ++i) {
            const double t = t0 + double(i) * dt, h = i < n ? dt : rest;
            rk4.do_step(f, y, t, h);
            if (observed) {
                check_step(y, i + 1, t, h);
                view = to_state(y);
                obs(view, t + h);
            }
        }
        if (!observed) check_step(y, total, t_end, dt);
        x = to_state(y);
        return {total, w.evaluations};
    }

    template <class Observer>
    std::pair<std::size_t, std::uint64_t> odeint_adaptive(double tolerance, double t0, double t_end, State& x,
                                                          Observer& obs, bool observed) const {
        workspace w;
        first_order<Sys> f{&sys_, &w};
        std::vector<double> y = to_vector(x);
        auto stepper = odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_dopri5<std::vector<double>>());
        double t = t0, h = (t_end - t0) / 1000;
        std::size_t steps = 0, failed = 0;
        State view = x;
        if (observed) obs(view, t0);
        while (t < t_end) {
            if (t + h > t_end) h = t_end - t;
            if (stepper.try_step(f, y, t, h) == odeint::success) {
                ++steps;
                failed = 0;
                check_step(y, steps, t, h);
                if (observed) {
                    view = to_state(y);
                    obs(view, t);
                }
            } else if (++failed > 500 || h < 1e-14 * (t_end - t0)) {
                throw integration_error("odeint_dopri5: step size underflow at t = " + std::to_string(t), steps + 1, t);
            }
        }
        x = to_state(y);
        return {steps, w.evaluations};
    }

    Sys sys_;
    std::function<double(const std::vector<double>&)> energy_;
};

}  // namespace detail

// A system of hamiltonians/ as the program's problem: its default state x0
// and, when it has one, its exact solution from x0.
template <class Sys>
problem model(Sys sys, std::vector<double> x0, std::function<std::vector<double>(double)> exact = nullptr) {
    using detail::State;
    using detail::to_state;
    using detail::to_vector;
    problem p;
    p.form = detail::form_of<Sys>();
    p.hamiltonian = p.form.separable_hamiltonian;
    p.degrees_of_freedom = x0.size() / 2;
    p.x0 = std::move(x0);
    p.exact = std::move(exact);
    if constexpr (separable_hamiltonian<Sys, State::vector>) {
        p.energy = [sys](const std::vector<double>& x) { return energy(sys, to_state(x)); };
        p.reference = [sys](double t0, double t_end, double dt, const std::vector<double>& x) {
            using L = phase_space<long double>;
            L y = from_stacked<L>(x);
            splitting_stepper<Sys, L> ss(sys, method("sofroniou_spaletta_10"));
            integrate_until(ss, y, (long double)t0, (long double)t_end, (long double)dt);
            return to_vector(y);
        };
    } else {
        p.reference = [sys](double t0, double t_end, double dt, const std::vector<double>& x) {
            State y = to_state(x);
            auto s4 = make_classic<rk4, State>(sys);
            integrate_until(s4, y, t0, t_end, dt);
            return to_vector(y);
        };
    }
    p.run = detail::runner<Sys>(sys, p.energy);
    return p;
}

}  // namespace sympl::app
