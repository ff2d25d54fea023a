#pragma once
// The embedded Runge-Kutta-Nystrom pairs (rkn_pairs.hpp), not symplectic:
// run_kind<dprkn>, the member's pair at a fixed step (the pair's higher order,
// its estimate unused) or with the step size controlled to the request's
// tolerance (absolute = relative), like the Odeint controlled steppers.
// Separable Hamiltonians with T quadratic in p only.
#include "run_context.hpp"

namespace sympl::app::detail {

template <>
struct run_kind<method_kind::dprkn> {
    template <class C>
    static steps_and_forces run(const C& c) {
        switch (c.m.parameters.pair) {
            case rkn_pair::dprkn6: return with_pair<dprkn6>(c);
            case rkn_pair::dprkn8: return with_pair<dprkn8>(c);
            case rkn_pair::dprkn12: return with_pair<dprkn12>(c);
        }
        throw invalid_argument("method '" + c.m.name + "': no such RKN pair");
    }

    // At a fixed step the last force is kept with the q it belongs to and
    // reused only when handed that q again, so a resumed run is bit for bit
    // the uninterrupted one. Controlled: from t0 to exactly t_end, the step
    // chosen by the pair's error estimate (never checkpointed: its row says
    // why, and run_method refuses it before).
    template <class Pair, class C>
    static steps_and_forces with_pair(const C& c) {
        auto stepper = make_rkn_stepper<Pair, typename C::State>(c.sys);
        if (!adaptive(c.m)) return c.drive(std::move(stepper));
        control_options control;
        control.absolute_tolerance = control.relative_tolerance = c.rq.tolerance;
        control_summary s;
        if constexpr (C::observed) {
            // Inside a step, the pair's own interpolation: the Hermite's is 1e5x the tolerance off here.
            if (c.interpolation)
                *c.interpolation = [&stepper](double theta, typename C::State& out) { stepper.interpolate(theta, out); };
            s = integrate_controlled(stepper, c.x, c.t0, c.t_end, control, c.observe);
        } else
            s = integrate_controlled(stepper, c.x, c.t0, c.t_end, control);
        return {s.accepted, s.force_evaluations};
    }
};

}  // namespace sympl::app::detail
