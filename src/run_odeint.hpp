#pragma once
// The Boost.Odeint kinds' runs (run_kind<odeint_*>): the report's competitors.
#include <cmath>
#include <functional>
#include <limits>
#include <utility>

#include <sympl/interop/odeint.hpp>

#include "run_context.hpp"

namespace sympl::app::detail {

namespace odeint = boost::numeric::odeint;

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

template <int Dim>
odeint_state<Dim> to_odeint(const state_of<Dim>& x) {
    odeint_state<Dim> y{};
    if constexpr (Dim == Eigen::Dynamic) y.resize(std::size_t(2 * x.size()));
    const auto v = stacked(x);
    std::copy(v.begin(), v.end(), y.begin());
    return y;
}

// Boost.Odeint's steppers on the library's bridge (odeint.hpp), whose
// workspace keeps the evaluations free of allocation and counts them. The
// observer reaches them type-erased (nullptr: not observed), so each Odeint
// stepper is compiled once per system, not once per observer; a call per
// step costs nothing next to an Odeint step.
template <class Sys, int Dim>
struct odeint_run {
    using State = state_of<Dim>;
    using OdeState = odeint_state<Dim>;
    const Sys& sys;
    const method_spec& m;
    const run_request& rq;
    double t0, t_end;
    State& x;
    const std::function<void(const State&, double)>* observe;

    static void check_finite(const OdeState& y, std::size_t step, double t, double h) {
        for (double v : y)
            if (!std::isfinite(v)) throw blow_up(step, t, h);
    }

    steps_and_forces fixed_step() const {
        odeint_workspace<double, Dim> w;
        const auto f = make_odeint_system<Dim>(sys, &w);
        OdeState y = to_odeint<Dim>(x);
        odeint::runge_kutta4<OdeState> rk4;
        const double dt = rq.dt, span = t_end - t0;
        const auto n = static_cast<std::size_t>(std::floor(span / dt));
        double rest = span - double(n) * dt;
        if (rest <= 8 * std::numeric_limits<double>::epsilon() * span) rest = 0;
        if (observe) (*observe)(std::as_const(x), t0);  // as sympl's driver: t0 first
        const std::size_t total = n + (rest > 0 ? 1 : 0);
        for (std::size_t i = 0; i < total; ++i) {
            const double t = t0 + double(i) * dt, h = i < n ? dt : rest;
            rk4.do_step(f, y, t, h);
            if (observe) {
                check_finite(y, i + 1, t, h);
                (*observe)(to_state<Dim>(y), t + h);
            }
        }
        if (!observe) check_finite(y, total, t_end, dt);
        x = to_state<Dim>(y);
        return {total, w.evaluations};
    }

    // Any Odeint controlled stepper (try_step), from t0 to exactly t_end.
    template <class Controlled>
    steps_and_forces controlled(Controlled stepper) const {
        odeint_workspace<double, Dim> w;
        const auto f = make_odeint_system<Dim>(sys, &w);
        OdeState y = to_odeint<Dim>(x);
        double t = t0, h = (t_end - t0) / 1000;
        std::size_t steps = 0, failed = 0;
        if (observe) (*observe)(std::as_const(x), t0);
        while (t < t_end) {
            if (t + h > t_end) h = t_end - t;
            if (!(h > 1e-14 * (t_end - t0)) || t + h == t || ++failed > 500)
                throw integration_error(m.name + ": step size underflow at t = " + format_number(t, 17) + " (dt = " +
                                            format_number(h, 3) + ")",
                                        steps + 1, t);
            if (stepper.try_step(f, y, t, h) == odeint::success) {
                ++steps;
                failed = 0;
                check_finite(y, steps, t, h);
                if (observe) (*observe)(to_state<Dim>(y), t);
            }
        }
        x = to_state<Dim>(y);
        return {steps, w.evaluations};
    }
};

// The kind's Odeint run with the context's observer type-erased.
template <class C, class Run>
steps_and_forces with_odeint(const C& c, Run run) {
    using R = odeint_run<typename C::system, C::dimension>;
    std::function<void(const typename C::State&, double)> observe;
    if constexpr (C::observed) observe = [&](const typename C::State& y, double t) { c.observe(y, t); };
    return run(R{c.sys, c.m, c.rq, c.t0, c.t_end, c.x, C::observed ? &observe : nullptr});
}

// One instantiation per system for each Odeint kind, whatever the observer.
template <class Sys, int Dim>
steps_and_forces odeint_rk4_run(const odeint_run<Sys, Dim>& r) {
    return r.fixed_step();
}
template <class Sys, int Dim>
steps_and_forces odeint_dopri5_run(const odeint_run<Sys, Dim>& r) {
    using OdeState = odeint_state<Dim>;
    return r.controlled(odeint::make_controlled(r.rq.tolerance, r.rq.tolerance, odeint::runge_kutta_dopri5<OdeState>()));
}
template <class Sys, int Dim>
steps_and_forces odeint_fehlberg78_run(const odeint_run<Sys, Dim>& r) {
    using OdeState = odeint_state<Dim>;
    return r.controlled(
        odeint::make_controlled(r.rq.tolerance, r.rq.tolerance, odeint::runge_kutta_fehlberg78<OdeState>()));
}
template <class Sys, int Dim>
steps_and_forces odeint_bulirsch_stoer_run(const odeint_run<Sys, Dim>& r) {
    return r.controlled(odeint::bulirsch_stoer<odeint_state<Dim>>(r.rq.tolerance, r.rq.tolerance));
}

template <>
struct run_kind<method_kind::odeint_rk4> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return with_odeint(c, odeint_rk4_run<typename C::system, C::dimension>);
    }
};

template <>
struct run_kind<method_kind::odeint_dopri5> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return with_odeint(c, odeint_dopri5_run<typename C::system, C::dimension>);
    }
};

template <>
struct run_kind<method_kind::odeint_fehlberg78> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return with_odeint(c, odeint_fehlberg78_run<typename C::system, C::dimension>);
    }
};

template <>
struct run_kind<method_kind::odeint_bulirsch_stoer> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return with_odeint(c, odeint_bulirsch_stoer_run<typename C::system, C::dimension>);
    }
};

}  // namespace sympl::app::detail
