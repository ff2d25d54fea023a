#pragma once
// The embedded Runge-Kutta-Nystrom pairs (rkn_pairs.hpp), not symplectic:
// run_kind<dprkn>, the member's pair at a fixed step (the pair's higher order,
// its estimate unused) or with the step size controlled to the request's
// tolerance (absolute = relative), like the Odeint controlled steppers.
// Separable Hamiltonians with T quadratic in p only.
#include <cstdint>
#include <span>
#include <vector>

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

    // Every controlled run, timed or observed: observed, with a checkpoint
    // every rq.checkpoint.every_steps steps when that is not 0 (one driver
    // compiled, not three). The record's carried list: the controller's state (time, next
    // step, last error, the summary so far), then the pair's carried list.
    template <class C, class Stepper>
    static steps_and_forces checkpointed_control(const C& c, Stepper& stepper, const control_options& control) {
        controller_state<double> state;
        checkpoint_keeper<C, Stepper> keeper(c, stepper);
        const auto restore = [&](std::span<const double> carried) {
            sympl::detail::carried_reader<double> r{carried, "checkpoint of a controlled run"};
            state.t = r.number(), state.dt = r.number(), state.previous_error = r.number();
            control_summary& m = state.summary;
            m.accepted = std::size_t(r.number()), m.rejected = std::size_t(r.number());
            m.t = r.number(), m.dt_smallest = r.number(), m.dt_largest = r.number(), m.largest_error = r.number();
            m.force_evaluations = std::uint64_t(r.number());
            std::vector<double> pair;
            r.numbers(pair);
            r.done();
            stepper.restore_carried(pair);
        };
        using observer = typename C::observer;
        if (!c.observed()) {
            const control_summary s = integrate_controlled(stepper, c.x, c.t0, c.t_end, control, observer{}, state);
            return {s.accepted, s.force_evaluations};
        }
        if (const checkpoint_record* from = keeper.restore(restore)) c.x = to_state<C::dimension>(from->state);
        const auto carried = [&] {
            std::vector<double> out;
            sympl::detail::carried_writer<double> w{out};
            const control_summary& m = state.summary;
            for (double v : {state.t, state.dt, state.previous_error, double(m.accepted), double(m.rejected), m.t,
                             m.dt_smallest, m.dt_largest, m.largest_error, double(m.force_evaluations)})
                w.number(v);
            w.numbers(stepper.carried());
            return out;
        };
        const auto observe = [&](const typename C::State& y, double t) {
            c.observe(y, t);
            if (state.summary.accepted > 0) keeper.after_step(y, t, carried);  // not at t0
        };
        const control_summary s = integrate_controlled(stepper, c.x, c.t0, c.t_end, control, observer(observe), state);
        return {s.accepted, s.force_evaluations};
    }
};

}  // namespace sympl::app::detail
