#pragma once
// The embedded Runge-Kutta-Nystrom pairs (rkn_pairs.hpp), not symplectic:
// run_kind<dprkn*> at a fixed step (the pair's higher order, its estimate
// unused), run_kind<dprkn*_controlled> with the step size controlled to the
// request's tolerance (absolute = relative), like the Odeint controlled
// steppers. Separable Hamiltonians with T quadratic in p only.
#include "run_context.hpp"

namespace sympl::app::detail {

// At a fixed step. The last force is kept with the q it belongs to and
// reused only when handed that q again, so a resumed run is bit for bit the
// uninterrupted one.
template <class Pair>
struct rkn_fixed_run {
    template <class C>
    static steps_and_forces run(const C& c) {
        return c.drive(make_rkn_stepper<Pair, typename C::State>(c.sys));
    }
};

// From t0 to exactly t_end, the step chosen by the pair's error estimate.
template <class Pair>
struct rkn_controlled_run {
    template <class C>
    static steps_and_forces run(const C& c) {
        auto stepper = make_rkn_stepper<Pair, typename C::State>(c.sys);
        control_options control;
        control.absolute_tolerance = control.relative_tolerance = c.rq.tolerance;
        control_summary s;
        if constexpr (C::observed) {
            if (c.rq.checkpoint.every_steps) throw invalid_argument(why_not_resumable(c.m));
            s = integrate_controlled(stepper, c.x, c.t0, c.t_end, control, c.observe);
        } else {
            s = integrate_controlled(stepper, c.x, c.t0, c.t_end, control);
        }
        return {s.accepted, s.force_evaluations};
    }
};

template <>
struct run_kind<method_kind::dprkn6> : rkn_fixed_run<dprkn6> {};
template <>
struct run_kind<method_kind::dprkn8> : rkn_fixed_run<dprkn8> {};
template <>
struct run_kind<method_kind::dprkn12> : rkn_fixed_run<dprkn12> {};
template <>
struct run_kind<method_kind::dprkn6_controlled> : rkn_controlled_run<dprkn6> {};
template <>
struct run_kind<method_kind::dprkn8_controlled> : rkn_controlled_run<dprkn8> {};
template <>
struct run_kind<method_kind::dprkn12_controlled> : rkn_controlled_run<dprkn12> {};

}  // namespace sympl::app::detail
