#pragma once
// integrate_dense: the state at given times inside a run, read off each
// step's interpolant (hermite_interpolant.hpp) without touching the step sequence.
//
// integrate_dense leaves the run as integrate_until (drivers/fixed_step.hpp) makes
// it without an observer, bit for bit, also for a splitting stepper, which
// joins the last sub-step of a step with the first of the next inside the
// chunks an unobserved run steps in (observing every step would split them
// and change the rounding): the step ends inside a chunk that holds output
// times are formed on a copy of the stepper (see integrate_dense).
// Forces and velocities at a step end are evaluated at most once each, only
// when an interpolation inside a neighbouring step needs them, and reused by
// the next step (the end of one step is the start of the next); their count is
// reported apart from the stepper's own.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <concepts>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "fixed_step.hpp"
#include "../core/phase_space.hpp"

#include "controlled.hpp"
#include "hermite_interpolant.hpp"
#include "stepper_interpolant.hpp"

namespace sympl {

// What the dense output cost on top of the run, and the callbacks made.
struct dense_cost {
    std::uint64_t extra_force_evaluations = 0;     // for the interpolant (step ends; partial steps)
    std::uint64_t extra_velocity_evaluations = 0;  // at step ends (and quintic: M^-1 F, the solve for M dq)
    std::size_t outputs = 0;                       // callbacks made
};

// What integrate_dense did over fixed steps: integrate_until's summary
// (steps, time, the stepper's own evaluations) and the dense output's cost.
struct dense_summary : run_summary, dense_cost {
    // Steps made a second time, on a copy of the stepper, to form the step
    // ends inside a chunk that holds output times (integrate_dense), and their cost.
    std::size_t replayed_steps = 0;
    std::uint64_t replay_force_evaluations = 0;
    std::uint64_t replay_velocity_evaluations = 0;
};

// The same over a controlled run: integrate_controlled's summary and the cost.
struct controlled_dense_summary : control_summary, dense_cost {};

namespace detail {
// Times must be finite, inside [t0, t_end] and sorted (ties allowed).
template <class T>
void check_output_times(std::span<const T> times, T t0, T t_end, const char* who) {
    using std::isfinite;
    check_time_span(who, t0, t_end);
    for (std::size_t i = 0; i < times.size(); ++i) {
        const T t = times[i];
        const std::string name = std::string(who) + ": output_times[" + std::to_string(i) + "] = " + number(t);
        if (!isfinite(t) || t < t0 || t > t_end)
            throw invalid_argument(name + "; expected a finite time in [t0, t_end] = [" + number(t0) + ", " +
                                   number(t_end) + "]");
        if (i > 0 && t < times[i - 1])
            throw invalid_argument(name + " is before output_times[" + std::to_string(i - 1) + "] = " +
                                   number(times[i - 1]) + "; expected times sorted in increasing order");
    }
}
}  // namespace detail

namespace detail {
// A stepper whose steps(x, dt, n) or resume_steps differs from n calls of
// step() by rounding (a splitting stepper joins the last sub-step of a step
// with the first of the next; a processed stepper processes once per call):
// observing every step would change its run. Time-aware steppers are stepped
// one at a time by the drivers, observed or not.
template <class S>
concept groups_steps = !time_aware_stepper<S> && (requires(S s, typename S::state_type& x, typename S::scalar dt) {
    s.steps(x, dt, std::size_t(1));
} || requires(S s, typename S::state_type& x, typename S::scalar dt) { s.resume_steps(x, dt, std::size_t(1)); });
}  // namespace detail

namespace detail {
// integrate_dense's run of a stepper that groups steps: observed at the ends
// of its chunks only, the step ends inside a chunk that holds output times
// replayed on a copy of the stepper (see integrate_dense).
template <class Stepper, class Interpolant, class Emit, class Callback>
void dense_by_chunks(Stepper& stepper, typename Stepper::state_type& x, typename Stepper::scalar t0,
                     typename Stepper::scalar t_end, typename Stepper::scalar dt,
                     const until_steps<typename Stepper::scalar>& plan,
                     std::span<const typename Stepper::scalar> output_times, std::size_t& next, Interpolant& dense,
                     Emit& emit, Callback& callback, dense_summary& r) {
    using T = typename Stepper::scalar;
    using State = typename Stepper::state_type;
    static_assert(std::copy_constructible<Stepper>,
                  "integrate_dense replays chunks of a stepper that groups steps on a copy of it: "
                  "expected a copyable stepper");
    const std::size_t n = plan.n, last = plan.rest > T(0) ? n + 1 : n;  // index of the last step end
    const auto time_of = [&](std::size_t i) { return i <= n ? t0 + T(i) * dt : t_end; };
    run_options chunks;  // integrate_until's defaults, observed once per chunk
    chunks.observe_every = chunks.check_every;
    const std::size_t chunk = chunks.check_every;
    std::optional<Stepper> shadow;
    State start = x, y = x;
    std::size_t start_index = 0, dense_end = 0;  // dense_end: the interpolant's end, when it is a run state
    // m steps of the copy from step index `from`, y its state.
    const auto replay = [&](std::size_t from, std::size_t m) {
        if (!shadow) shadow.emplace(stepper);
        const auto f = detail::forces(*shadow), v = detail::velocities(*shadow);
        detail::advance(*shadow, y, t0, dt, from, m, false);
        r.replay_force_evaluations += detail::forces(*shadow) - f;
        r.replay_velocity_evaluations += detail::velocities(*shadow) - v;
        r.replayed_steps += m;
    };
    bool started = false;
    auto observer = [&](const State& s, T t) {
        if (!started) {
            started = true;
            dense.start(s, t);
            while (next < output_times.size() && output_times[next] <= t) emit();
            start = s;
            return;
        }
        const std::size_t i1 = start_index < n ? std::min(start_index + chunk, n) : n + 1;
        // The last chunk also takes times beyond its end by a rounding (see above).
        const auto inside = [&] { return next < output_times.size() && (output_times[next] <= t || i1 == last); };
        if (inside()) {
            std::size_t cur = start_index;
            if (dense_end != cur) dense.start(start, time_of(cur));
            y = start;
            while (inside()) {
                const T tau = output_times[next];
                if (tau == t && cur < i1) {  // the chunk's end: the run's own state, nothing to replay
                    callback(std::as_const(s), tau);
                    ++next;
                    continue;
                }
                std::size_t target = cur;  // the step (target - 1, target] holding tau
                while (target < i1 && tau > time_of(target)) ++target;
                if (target > cur) {
                    if (target - 1 > cur) {  // the steps before it in one call, as the run makes them
                        replay(cur, target - 1 - cur);
                        dense.start(y, time_of(target - 1));
                    }
                    if (target == i1) {
                        dense.push(s, t);
                    } else {
                        replay(target - 1, 1);
                        dense.push(y, time_of(target));
                    }
                    cur = target;
                }
                emit();
            }
            dense_end = cur;
        }
        start = s;
        start_index = i1;
    };
    static_cast<run_summary&>(r) = integrate_until(stepper, x, t0, t_end, dt, observer, chunks);
}
}  // namespace detail

// Runs stepper from x at t0 up to t_end with steps of dt and calls
// callback(state, t) at each of output_times (sorted, within [t0, t_end])
// with the state interpolated there (the end state itself when t is a step
// end). h is the Hamiltonian the stepper runs.
//
// The run is integrate_until(stepper, x, t0, t_end, dt) without an observer,
// bit for bit: the same steps grouped the same way, the same final x and the
// same run_summary. A stepper that groups steps (detail::groups_steps: a
// splitting, processed or Wisdom-Holman stepper) is run by integrate_until in
// its chunks of run_options::check_every steps, observed only at the chunk
// ends (which does not change how the steps group; fixed_step.hpp, first_step),
// and the step ends inside a chunk that holds output times are made by a copy
// of the stepper, replayed from the chunk's start: steps(m) up to the start of
// the step holding an output time, then steps(1) (the chunk's last step ends
// on the run's own state). Those inner step ends differ from the run's
// (which never forms them) by rounding only; the replay costs at most a
// chunk's steps per chunk holding outputs, counted in replayed_steps and
// replay_*_evaluations. So Stepper must be copyable, and a copy must step
// independently of the original. Other steppers (time-aware ones, or with
// step() only) are observed at every step, which is their unobserved run.
template <fixed_step_stepper Stepper, class H, class Callback>
    requires separable_hamiltonian<H, typename Stepper::state_type::vector>
dense_summary integrate_dense(Stepper& stepper, const H& h, typename Stepper::state_type& x,
                              typename Stepper::scalar t0, typename Stepper::scalar t_end,
                              typename Stepper::scalar dt, std::span<const typename Stepper::scalar> output_times,
                              Callback&& callback, hermite_order order = hermite_order::cubic) {
    using T = typename Stepper::scalar;
    using State = typename Stepper::state_type;
    const char* who = "integrate_dense";
    const auto plan = detail::until_plan(t0, t_end, dt, who);
    detail::check_output_times<T>(output_times, t0, t_end, who);
    step_interpolant<H, State> dense(h, order);
    State out = x;
    std::size_t next = 0;
    const auto emit = [&] {
        dense.evaluate(output_times[next], out);
        callback(std::as_const(out), output_times[next]);
        ++next;
    };
    dense_summary r;
    if constexpr (!detail::groups_steps<Stepper>) {
        bool started = false;
        auto observer = [&](const State& s, T t) {
            if (!started) {
                dense.start(s, t);
                started = true;
            } else {
                dense.push(s, t);
            }
            while (next < output_times.size() && output_times[next] <= t) emit();
        };
        static_cast<run_summary&>(r) = integrate_until(stepper, x, t0, t_end, dt, observer);
        // The last step ends at t0 + n dt, which may fall short of t_end by a
        // rounding when dt divides the span: the last polynomial covers the rest.
        while (next < output_times.size()) emit();
    } else {
        detail::dense_by_chunks(stepper, x, t0, t_end, dt, plan, output_times, next, dense, emit, callback, r);
    }
    r.outputs = output_times.size();
    r.extra_force_evaluations = dense.force_evaluations();
    r.extra_velocity_evaluations = dense.velocity_evaluations();
    return r;
}

// The same with the stepper's own Hamiltonian (steppers with hamiltonian():
// splitting_stepper, rkn_pair_stepper, processed steppers).
template <fixed_step_stepper Stepper, class Callback>
    requires requires(const Stepper& s) { s.hamiltonian(); }
dense_summary integrate_dense(Stepper& stepper, typename Stepper::state_type& x, typename Stepper::scalar t0,
                              typename Stepper::scalar t_end, typename Stepper::scalar dt,
                              std::span<const typename Stepper::scalar> output_times, Callback&& callback,
                              hermite_order order = hermite_order::cubic) {
    return integrate_dense(stepper, stepper.hamiltonian(), x, t0, t_end, dt, output_times,
                           std::forward<Callback>(callback), order);
}

// Over a controlled run (drivers/controlled.hpp): integrate_controlled's
// steps, unchanged by the outputs, and callback(state, t) at each of
// output_times (sorted, within [t0, t_end]). The state is the stepper's own
// interpolation where it has one (interpolating_stepper: the RKN pairs),
// otherwise the Hermite interpolant of `order` on its accepted steps.
template <class Stepper, class H, class Callback>
    requires error_estimating_stepper<Stepper> && separable_hamiltonian<H, typename Stepper::state_type::vector>
controlled_dense_summary integrate_dense(Stepper& stepper, const H& h, typename Stepper::state_type& x,
                                         typename Stepper::scalar t0, typename Stepper::scalar t_end,
                                         const control_options& options,
                                         std::span<const typename Stepper::scalar> output_times, Callback&& callback,
                                         hermite_order order = hermite_order::cubic) {
    using T = typename Stepper::scalar;
    using State = typename Stepper::state_type;
    detail::check_output_times<T>(output_times, t0, t_end, "integrate_dense");
    controlled_dense_summary r;
    const auto run = [&](auto& dense) {
        State out = x;
        std::size_t next = 0;
        bool started = false;
        auto observer = [&](const State& s, T t) {
            if (started) dense.push(s, t);
            else dense.start(s, t), started = true;
            for (; next < output_times.size() && output_times[next] <= t; ++next) {
                dense.evaluate(output_times[next], out);
                callback(std::as_const(out), output_times[next]);
            }
        };
        static_cast<control_summary&>(r) = integrate_controlled(stepper, x, t0, t_end, options, observer);
        r.outputs = next;
        r.extra_force_evaluations = dense.force_evaluations();
        r.extra_velocity_evaluations = dense.velocity_evaluations();
    };
    if constexpr (interpolating_stepper<Stepper>) {
        stepper_interpolant<Stepper> dense(stepper);
        run(dense);
    } else {
        step_interpolant<H, State> dense(h, order);
        run(dense);
    }
    return r;
}

// The same with the stepper's own Hamiltonian.
template <class Stepper, class Callback>
    requires error_estimating_stepper<Stepper> && requires(const Stepper& s) { s.hamiltonian(); }
controlled_dense_summary integrate_dense(Stepper& stepper, typename Stepper::state_type& x, typename Stepper::scalar t0,
                                         typename Stepper::scalar t_end, const control_options& options,
                                         std::span<const typename Stepper::scalar> output_times, Callback&& callback,
                                         hermite_order order = hermite_order::cubic) {
    return integrate_dense(stepper, stepper.hamiltonian(), x, t0, t_end, options, output_times,
                           std::forward<Callback>(callback), order);
}

}  // namespace sympl
