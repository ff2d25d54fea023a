#pragma once
// The embedded Runge-Kutta-Nystrom pairs (rkn_pairs.hpp), not symplectic:
// run_kind<dprkn>, the member's pair at a fixed step (the pair's higher order,
// its estimate unused) or with the step size controlled to the request's
// tolerance (absolute = relative), like the Odeint controlled steppers.
// Separable Hamiltonians with T quadratic in p only.
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "running/run_context.hpp"

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
    // reused only when handed that q again (the pair's carried list holds
    // it). Controlled: from t0 to exactly t_end, the step chosen by the pair's
    // error estimate; checkpointed, with the controller's state.
    template <class Pair, class C>
    static steps_and_forces with_pair(const C& c) {
        auto stepper = make_rkn_stepper<Pair, typename C::State>(c.sys);
        if (!adaptive(c.m)) return c.drive(std::move(stepper));
        control_options control;
        control.absolute_tolerance = control.relative_tolerance = c.rq.tolerance;
        // Inside a step, the pair's own interpolation: the Hermite's is 1e5x the tolerance off here.
        if (c.observed() && c.interpolation)
            *c.interpolation = [&stepper](double theta, typename C::State& out) { stepper.interpolate(theta, out); };
        return checkpointed_control(c, stepper, control);  // observed or not, checkpoints asked or not
    }

    // What a controlled run carries beyond the pair's own list: the
    // controller's state (time, next step, last error, the summary so far).
    struct controller {
        controller_state<double>& state;
        const checkpoint_record* from = nullptr;  // the record resumed from
        template <class Self, class List>
        static void carried_fields(Self& self, List& l) {
            controller_state<double>& s = self.state;
            control_summary& m = s.summary;
            l.number(s.t), l.number(s.dt), l.number(s.previous_error);
            // A step that cannot move t (t = -1e300) or a NaN step would never end the run.
            l.check(std::isfinite(s.t) && std::isfinite(s.dt) && s.dt > 0 && s.t + s.dt > s.t &&
                        s.previous_error >= 0 && std::isfinite(s.previous_error),
                    "holds a controller state that cannot step (t, dt, error)");
            l.whole(m.accepted, "holds a bad count of accepted steps");
            l.whole(m.rejected, "holds a bad count of rejected steps");
            l.number(m.t), l.number(m.dt_smallest), l.number(m.dt_largest), l.number(m.largest_error);
            l.whole(m.force_evaluations, "holds a bad count of force evaluations");
            // The record's time and step were observed from this state: one
            // set apart would go on from another time, or count on from another step.
            l.check(!self.from || (s.t == self.from->time && m.accepted == self.from->step),
                    "holds a controller time or count of accepted steps that is not the run's");
        }
    };

    // Every controlled run, timed or observed: observed, with a checkpoint
    // every rq.checkpoint.every_steps steps when that is not 0 (one driver
    // compiled).
    template <class C, class Stepper>
    static steps_and_forces checkpointed_control(const C& c, Stepper& stepper, const control_options& control) {
        using observer = typename C::observer;
        controller_state<double> state;
        if (!c.observed()) {
            const control_summary s = integrate_controlled(stepper, c.x, c.t0, c.t_end, control, observer{}, state);
            return {s.accepted, s.force_evaluations};
        }
        controller more{state, c.rq.checkpoint.resume};
        return checkpointed_run(c, stepper, more, [&](observer observe, const checkpoint_record*, const auto&) {
            const control_summary s = integrate_controlled(stepper, c.x, c.t0, c.t_end, control, observe, state);
            return steps_and_forces{s.accepted, s.force_evaluations};  // the summary counts the whole run
        });
    }
};

}  // namespace sympl::app::detail
