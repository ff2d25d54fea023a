#pragma once
// The Boost.Odeint kind's run (run_kind<odeint>): the report's competitors.
#include <cmath>
#include <functional>
#include <limits>
#include <span>
#include <vector>
#include <type_traits>
#include <utility>

#include <boost/numeric/odeint/integrate/integrate_adaptive.hpp>
#include <boost/numeric/odeint/integrate/max_step_checker.hpp>
#include <boost/numeric/odeint/util/detail/less_with_sign.hpp>
#include <sympl/interop/odeint.hpp>

#include "running/odeint_bulirsch_stoer_state.hpp"
#include "running/run_context.hpp"

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

template <int Dim, class OdeState = odeint_state<Dim>>
OdeState to_odeint(const state_of<Dim>& x) {
    OdeState y{};
    if constexpr (requires { y.resize(std::size_t(0)); }) y.resize(std::size_t(2 * x.size()));
    const auto v = stacked(x);
    std::copy(v.begin(), v.end(), y.begin());
    return y;
}

// Boost.Odeint's steppers on the library's bridge (odeint.hpp), whose
// workspace keeps the evaluations free of allocation and counts them, driven
// by Odeint's own integrate_adaptive: for runge_kutta4 its constant steps and
// a last one to end at t_end, for the controlled steppers its loop of
// try_step. Odeint's driver has no stop of its own for a blow-up or a step
// that stopped making progress, so its observer (called at t0 and after each
// step) checks them and throws, which ends integrate_adaptive; Odeint's own
// stop, 500 rejected step sizes in a row, is reported in the same words. The
// program's observer reaches the run type-erased (empty: not observed), so
// each Odeint stepper is compiled once per system, not once per observer; a
// call per step costs nothing next to an Odeint step.
template <class Sys, int Dim>
struct odeint_run {
    using State = state_of<Dim>;
    using OdeState = odeint_state<Dim>;
    using observer = observer_ref<State, double>;
    static constexpr int dimension = Dim;
    const Sys& sys;
    const method_spec& m;
    const run_request& rq;
    double t0, t_end;
    State& x;
    observer observe;

    bool observed() const { return observe.observing(); }

    // What integrate_adaptive's observer has seen: the accepted steps and the
    // time the last one ended at.
    struct progress {
        bool started = false;
        std::size_t steps = 0;
        double t = 0;
    };

    // integrate_adaptive calls the observer at t0, then once after each
    // accepted step: a non-finite state names its step, the time the step
    // started from and its size (blow_up, as sympl's drivers say it); a step
    // of 1e-14 of the span or less, short of t_end, is one the run would
    // never finish with; then `to` (the program's observer, or the
    // checkpointed run's around it) sees the state.
    auto checking_observer(progress& at, observer to) const {
        return [this, &at, to](const auto& y, double t) {
            if (!std::exchange(at.started, true)) {
                if (to.observing()) to(std::as_const(x), t0);
                return;
            }
            const double h = t - at.t;
            const std::size_t step = at.steps + 1;
            for (double v : y)
                if (!std::isfinite(v)) throw blow_up(step, at.t, h);
            if (!(h > 1e-14 * (t_end - t0)) && t < t_end)
                throw integration_error(m.name + ": step " + std::to_string(step) + " from t = " +
                                            format_number(at.t, 17) + " was dt = " + format_number(h, 3) +
                                            "; expected a step above 1e-14 of the span (Boost.Odeint's step size "
                                            "collapsed)",
                                        step, at.t);
            at.steps = step;
            at.t = t;
            if (to.observing()) to(to_state<Dim>(y), t);
        };
    }

    bool checkpointed() const { return observed() && rq.checkpoint.every_steps; }

    template <class Stepper>
    steps_and_forces run(Stepper stepper, double dt) const {
        if (checkpointed()) return run_checkpointed(std::move(stepper), dt);
        return run_whole(std::move(stepper), dt);
    }

    // Without checkpoints: Odeint's own integrate_adaptive.
    template <class Stepper>
    steps_and_forces run_whole(Stepper stepper, double dt) const {
        odeint_workspace<double, Dim> w;
        const auto f = make_odeint_system<Dim>(sys, &w);
        OdeState y = to_odeint<Dim>(x);
        // Unobserved at a fixed step, only the final state is checked (the
        // timed runs see Odeint's loop as a user's would).
        constexpr bool controlled =
            std::is_same_v<typename Stepper::stepper_category, odeint::controlled_stepper_tag>;
        const bool every_step = controlled || observed();
        progress at{.t = t0};
        std::size_t steps = 0;
        try {
            if constexpr (!controlled)
                if (!every_step) steps = odeint::integrate_adaptive(stepper, f, y, t0, t_end, dt);
            if (every_step)
                steps = odeint::integrate_adaptive(stepper, f, y, t0, t_end, dt, checking_observer(at, observe));
        } catch (const odeint::step_adjustment_error&) {
            rejected_in_a_row(at);
        }
        if (!every_step)
            for (double v : y)
                if (!std::isfinite(v)) throw blow_up(steps, t_end, dt);
        x = to_state<Dim>(y);
        return {steps, w.evaluations};
    }

    [[noreturn]] void rejected_in_a_row(const progress& at) const {
        throw integration_error(m.name + ": Boost.Odeint rejected 500 step sizes in a row from t = " +
                                    format_number(at.t, 17) + " (tolerance " + format_number(rq.tolerance, 3) +
                                    "); expected a step size its error estimate accepts",
                                at.steps + 1, at.t);
    }

    // What a checkpointed Odeint run carries: its time, next step size and
    // evaluations, and bulirsch_stoer's history (odeint_bulirsch_stoer_state.hpp).
    template <class Stepper>
    struct odeint_carried {
        double& t;
        double& dt;
        std::uint64_t& evaluations;
        Stepper& stepper;
        std::size_t size;
        const checkpoint_record* from = nullptr;  // the record resumed from
        template <class Self, class List>
        static void carried_fields(Self& self, List& l) {
            l.number(self.t), l.number(self.dt);
            l.check(std::isfinite(self.t) && std::isfinite(self.dt) && self.dt > 0 && self.t + self.dt > self.t,
                    "holds a time and step that cannot step");
            // The record's time was observed at this t: another would go on from elsewhere.
            l.check(!self.from || self.t == self.from->time, "holds a time that is not the run's");
            l.whole(self.evaluations, "holds a bad count of evaluations");
            if constexpr (std::is_same_v<Stepper, bulirsch_stoer_vector>) {
                bulirsch_stoer_history history{self.stepper, self.size};
                l.part(history);
            }
        }
    };

    // Checkpointed: Odeint's loops driven here as integrate_adaptive drives
    // them (integrate_const's steps and a last one to t_end; try_step until
    // accepted), the same calls on the same times, so that a run resumed after
    // step k from its state, time and next step size (with the evaluations)
    // goes on bit for bit. dopri5's derivative at the state (first same as
    // last) is evaluated again at the first step after a resume, on the same
    // state: the same bits, counted once. The first observation after a
    // resume is the checkpoint's, not repeated.
    template <class Stepper>
    steps_and_forces run_checkpointed(Stepper stepper, double dt) const {
        using Y = typename Stepper::state_type;
        constexpr bool fsal = [] {
            if constexpr (requires { typename Stepper::stepper_type::stepper_category; })
                return std::is_same_v<typename Stepper::stepper_type::stepper_category,
                                      odeint::explicit_error_stepper_fsal_tag>;
            else return false;
        }();
        odeint_workspace<double, Dim> w;
        const auto f = make_odeint_system<Dim>(sys, &w);
        double t = t0;
        odeint_carried<Stepper> more{t, dt, w.evaluations, stepper, std::size_t(2 * x.q.size()), rq.checkpoint.resume};
        return checkpointed_run(*this, stepper, more, [&](observer observe, const checkpoint_record* from, const auto&) {
            Y y = to_odeint<Dim, Y>(x);  // the record's state when resumed
            std::size_t steps = 0;
            progress at{.t = t0};
            bool skip = false;  // the next observation is the checkpoint's
            if (from) {
                if (fsal) w.evaluations -= 1;  // counted once (above)
                steps = from->step;
                at = {.started = true, .steps = steps, .t = t};
                skip = true;
            }
            const auto seen = checking_observer(at, observe);
            const auto observation = [&] {
                if (!std::exchange(skip, false)) seen(std::as_const(y), t);
            };
            try {
                hand_loop(stepper, f, y, t, dt, steps, observation);
            } catch (const odeint::step_adjustment_error&) {
                rejected_in_a_row(at);
            }
            x = to_state<Dim>(y);
            return steps_and_forces{steps, w.evaluations};
        });
    }

    // Odeint's loops as integrate_adaptive runs them, from time t after
    // `steps` steps, `observation` at the start and after every step.
    template <class Stepper, class F, class Y, class Observation>
    void hand_loop(Stepper& stepper, const F& f, Y& y, double& t, double& dt, std::size_t& steps,
                   const Observation& observation) const {
        if constexpr (std::is_base_of_v<odeint::controlled_stepper_tag, typename Stepper::stepper_category>) {
            odeint::failed_step_checker fail_checker;
            while (odeint::detail::less_with_sign(t, t_end, dt)) {
                observation();
                if (odeint::detail::less_with_sign(t_end, static_cast<double>(t + dt), dt)) dt = t_end - t;
                odeint::controlled_step_result result;
                do {
                    result = stepper.try_step(f, y, t, dt);
                    fail_checker();
                } while (result == odeint::fail);
                fail_checker.reset();
                ++steps;
            }
            observation();
        } else {
            t = t0 + static_cast<double>(steps) * dt;
            while (odeint::detail::less_eq_with_sign(static_cast<double>(t + dt), t_end, dt)) {
                observation();
                stepper.do_step(f, y, t, dt);
                ++steps;
                t = t0 + static_cast<double>(steps) * dt;
            }
            observation();
            if (const double end = t0 + dt * static_cast<double>(steps); odeint::detail::less_with_sign(end, t_end, dt)) {
                stepper.do_step(f, y, end, t_end - end);
                ++steps;
                t = t_end;
                observation();
            }
        }
    }
};

// The kind's Odeint run with the context's observer type-erased.
template <class C, class Run>
steps_and_forces with_odeint(const C& c, Run run) {
    using R = odeint_run<typename C::system, C::dimension>;
    return run(R{c.sys, c.m, c.rq, c.t0, c.t_end, c.x, c.observe});
}

// One instantiation per system, whatever the observer: the member's stepper,
// a fixed step dt, or controlled to the tolerance (absolute = relative) from
// a first step of a thousandth of the span.
template <class Sys, int Dim>
steps_and_forces odeint_stepper_run(const odeint_run<Sys, Dim>& r) {
    using OdeState = odeint_state<Dim>;
    const double tol = r.rq.tolerance, first = (r.t_end - r.t0) / 1000;
    switch (r.m.parameters.stepper) {
        case odeint_stepper::rk4: return r.run(odeint::runge_kutta4<OdeState>(), r.rq.dt);
        case odeint_stepper::dopri5:
            return r.run(odeint::make_controlled(tol, tol, odeint::runge_kutta_dopri5<OdeState>()), first);
        case odeint_stepper::fehlberg78:
            return r.run(odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<OdeState>()), first);
        case odeint_stepper::bulirsch_stoer:
            // Its history is read from the std::vector-state stepper only
            // (odeint_bulirsch_stoer_state.hpp), which gives the same bits.
            if (r.checkpointed()) return r.run_checkpointed(bulirsch_stoer_vector(tol, tol), first);
            return r.run_whole(odeint::bulirsch_stoer<OdeState>(tol, tol), first);
    }
    throw invalid_argument("method '" + r.m.name + "': no such Boost.Odeint stepper");
}

template <>
struct run_kind<method_kind::odeint> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return with_odeint(c, odeint_stepper_run<typename C::system, C::dimension>);
    }
};

}  // namespace sympl::app::detail
