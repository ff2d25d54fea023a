#pragma once
// The fixed-step drivers: n steps, or up to t_end, with an optional observer.
//
// Times are t = t0 + i*dt, never accumulated, and integrate_until lands exactly
// on t_end (the last step is shortened when dt does not divide the span). The
// state is checked for non-finite values every `check_every` steps; on a
// blow-up the run is replayed from the last finite checkpoint one step at a
// time, the state is left at the last finite step, and integration_error names
// the step and time. With no observer, nothing is recorded.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <sstream>
#include <stdexcept>
#include <string>

#include "../core/dual.hpp"
#include "../core/error.hpp"
#include "../core/phase_space.hpp"
#include "../core/time_span.hpp"
#include "observer.hpp"

namespace sympl {

// A stepper of autonomous systems has step(x, dt) (steps(x, dt, n) is used when
// present); a time-aware one (classic_steppers.hpp) has step(x, t, dt).
template <class S>
concept time_aware_stepper = requires(S s, typename S::state_type& x, typename S::scalar dt) {
    s.step(x, dt, dt);
};
template <class S>
concept fixed_step_stepper = time_aware_stepper<S> || requires(S s, typename S::state_type& x, typename S::scalar dt) {
    s.step(x, dt);
};

struct run_options {
    std::size_t observe_every = 1;  // observer called at t0, every k steps, and at the end
    // Finiteness check interval (steps). A stepper whose every return costs
    // extra work (wisdom_holman_stepper's corrector) may ask for longer chunks
    // by a member steps_per_check(); the larger of the two is taken.
    std::size_t check_every = 64;
    // Resume a run after its step `first_step` (a checkpoint): times stay
    // t0 + i*dt from the integer index, the observer is not called again for
    // the start, and the stepper is expected to hold the memory it had there
    // (splitting_stepper::restore). The steps are then grouped exactly as in
    // the uninterrupted run, so the result is bit for bit the same, when
    // first_step is a multiple of observe_every (observed) or of check_every
    // (not observed); other values are refused.
    std::size_t first_step = 0;
};

struct run_summary {
    std::size_t steps = 0;              // steps taken (a shortened last step counts as one)
    double t = 0;                       // time reached
    std::uint64_t force_evaluations = 0;
    std::uint64_t velocity_evaluations = 0;
};

namespace detail {
template <class T>
std::string number(T v) {
    return number_text(static_cast<long double>(primal(v)));
}

// One step from time t.
template <class Stepper, class State, class T>
void one_step(Stepper& s, State& x, T t, T dt) {
    if constexpr (time_aware_stepper<Stepper>)
        s.step(x, t, dt);
    else
        s.step(x, dt);
}

// n steps from step index `first` (time t0 + first*dt). `resume`: x is exactly
// what the stepper left, so it may carry its last force over. A stepper that
// throws integration_error itself (a corrector that does not converge) is
// reported with the index of the step.
template <class Stepper, class State, class T>
void advance(Stepper& s, State& x, T t0, T dt, std::size_t first, std::size_t n, bool resume) {
    if constexpr (time_aware_stepper<Stepper>) {
        for (std::size_t i = 0; i < n; ++i) {
            try {
                s.step(x, t0 + T(first + i) * dt, dt);
            } catch (const integration_error& e) {
                throw integration_error(std::string(e.what()) + " (step " + std::to_string(first + i + 1) + ")",
                                        first + i + 1, e.time);
            }
        }
    } else {
        if constexpr (requires { s.resume_steps(x, dt, n); }) {
            if (resume) return s.resume_steps(x, dt, n);
        }
        if constexpr (requires { s.steps(x, dt, n); })
            s.steps(x, dt, n);
        else
            for (std::size_t i = 0; i < n; ++i) s.step(x, dt);
    }
}

template <class Stepper>
std::size_t check_interval(const Stepper& s, std::size_t check_every) {
    if constexpr (requires { s.steps_per_check(); }) return std::max<std::size_t>(check_every, s.steps_per_check());
    else return check_every;
}

template <class Stepper>
std::uint64_t forces(const Stepper& s) {
    if constexpr (requires { s.force_evaluations(); }) return s.force_evaluations(); else return 0;
}
template <class Stepper>
std::uint64_t velocities(const Stepper& s) {
    if constexpr (requires { s.velocity_evaluations(); }) return s.velocity_evaluations(); else return 0;
}

// After a blow-up inside a chunk: the chunk replayed one step at a time from
// its start to find the first step that is not finite, the state left before
// it. Out of line and cold: no run pays for this copy of the step in its loop.
template <class Stepper, class State, class T>
[[noreturn, gnu::noinline, gnu::cold]] void replay_to_blow_up(Stepper& s, State& x, const State& checkpoint, T t0, T dt,
                                                               std::size_t first, std::size_t m) {
    x = checkpoint;
    for (std::size_t j = 0; j < m; ++j) {
        State before = x;
        one_step(s, x, t0 + T(first + j) * dt, dt);
        if (!is_finite(x)) {
            x = before;
            const std::size_t bad = first + j + 1;
            const T t_bad = t0 + T(bad - 1) * dt;
            throw blow_up(bad, static_cast<long double>(primal(t_bad)), static_cast<long double>(primal(dt)),
                          "; the state is left at t = " + number(t_bad));
        }
    }
    throw std::logic_error("a chunk of steps was not finite, but none of its steps replayed one at a time");
}

// `n` steps of size dt from step index `first` (time t0 + first*dt), checked.
template <class Stepper, class State, class T>
void checked_steps(Stepper& s, State& x, State& checkpoint, T t0, T dt, std::size_t first, std::size_t n,
                   std::size_t check_every) {
    std::size_t done = 0;
    while (done < n) {
        const std::size_t m = std::min(check_every, n - done);
        checkpoint = x;
        advance(s, x, t0, dt, first + done, m, first + done > 0);
        if (!is_finite(x)) replay_to_blow_up(s, x, checkpoint, t0, dt, first + done, m);
        done += m;
    }
}

// integrate_until's last, shortened step, out of line: it runs once a run.
template <class Stepper, class State, class T>
[[gnu::noinline]] void short_last_step(Stepper& s, State& x, T t, T rest, std::size_t n) {
    State last = x;
    one_step(s, x, t, rest);
    if (!is_finite(x)) {
        x = last;
        throw blow_up(n + 1, static_cast<long double>(primal(t)), static_cast<long double>(primal(rest)));
    }
}

template <class T>
void check_dt(T dt, const char* who) {
    using std::isfinite;
    if (!isfinite(dt) || !(dt > T(0)))
        throw invalid_argument(std::string(who) + ": dt = " + number(dt) + "; expected a finite step size > 0");
}

// integrate_until's steps from t0 to t_end: n steps of dt, then one of `rest`
// when rest > 0 (the span checked first; `who` names the caller in errors).
// integrate_dense (drivers/dense_output.hpp) needs the same step indices.
template <class T>
struct until_steps {
    std::size_t n = 0;
    T rest{};
};
template <class T>
until_steps<T> until_plan(T t0, T t_end, T dt, const char* who) {
    using std::isfinite;
    using std::floor;
    check_dt(dt, who);
    check_time_span(who, t0, t_end);
    const T span = t_end - t0;
    // The step count must fit before it is converted (a float beyond the
    // integer range is undefined behaviour).
    if (!(span / dt < T(1e18)))
        throw invalid_argument(std::string(who) + ": t_end - t0 = " + number(span) + " in steps of dt = " + number(dt) +
                               " is " + number(span / dt) + " steps; expected at most 1e18");
    auto n = static_cast<std::size_t>(floor(span / dt));
    T rest = span - T(n) * dt;
    // A remainder at roundoff level means dt divides the span.
    if (rest <= T(8) * std::numeric_limits<double>::epsilon() * span) rest = T(0);
    if (n == 0 && rest == T(0)) n = 1;
    return {n, rest};
}
}  // namespace detail

// n steps of size dt from time t0. observer(state, t) is called at t0, after
// every options.observe_every steps, and after the last step.
template <fixed_step_stepper Stepper, class Observer = no_observer>
run_summary integrate_steps(Stepper& stepper, typename Stepper::state_type& x, typename Stepper::scalar t0,
                            typename Stepper::scalar dt, std::size_t n, Observer&& observer = {},
                            run_options options = {}) {
    using T = typename Stepper::scalar;
    using State = typename Stepper::state_type;
    detail::check_dt(dt, "integrate_steps");
    using std::isfinite;
    if (!isfinite(t0)) throw invalid_argument("integrate_steps: t0 = " + detail::number(t0) + "; expected a finite time");
    if (options.observe_every == 0 || options.check_every == 0)
        throw invalid_argument("integrate_steps: observe_every = " + std::to_string(options.observe_every) +
                               ", check_every = " + std::to_string(options.check_every) + "; expected both >= 1");
    if (!is_finite(x)) throw invalid_argument("integrate_steps: the initial state is not finite; expected finite q and p");
    const auto f0 = detail::forces(stepper);
    const auto v0 = detail::velocities(stepper);
    const bool observed = detail::observing(observer);
    const std::size_t check_every = detail::check_interval(stepper, options.check_every);
    const std::size_t cadence = observed ? options.observe_every : check_every;
    if (options.first_step > n || options.first_step % cadence != 0)
        throw invalid_argument("integrate_steps: first_step = " + std::to_string(options.first_step) + " of " +
                               std::to_string(n) + " steps; expected a multiple of " + std::to_string(cadence) +
                               (observed ? " (observe_every)" : " (check_every)") +
                               " not beyond the last step, so that the steps group as in the uninterrupted run");
    State checkpoint = x;
    if (observed && options.first_step == 0) observer(std::as_const(x), t0);
    std::size_t done = options.first_step;
    while (done < n) {
        const std::size_t m = observed ? std::min(options.observe_every, n - done) : n - done;
        detail::checked_steps(stepper, x, checkpoint, t0, dt, done, m, check_every);
        done += m;
        if (observed) observer(std::as_const(x), t0 + T(done) * dt);
    }
    return {n - options.first_step, static_cast<double>(primal(t0 + T(n) * dt)), detail::forces(stepper) - f0,
            detail::velocities(stepper) - v0};
}

// From t0 up to exactly t_end with steps of dt (the last one shortened if needed).
template <fixed_step_stepper Stepper, class Observer = no_observer>
run_summary integrate_until(Stepper& stepper, typename Stepper::state_type& x, typename Stepper::scalar t0,
                            typename Stepper::scalar t_end, typename Stepper::scalar dt, Observer&& observer = {},
                            run_options options = {}) {
    using T = typename Stepper::scalar;
    const auto [n, rest] = detail::until_plan(t0, t_end, dt, "integrate_until");
    const auto f0 = detail::forces(stepper);
    const auto v0 = detail::velocities(stepper);
    run_summary r = integrate_steps(stepper, x, t0, dt, n, observer, options);
    if (rest > T(0)) {
        detail::short_last_step(stepper, x, t0 + T(n) * dt, rest, n);
        ++r.steps;
        if (detail::observing(observer)) observer(std::as_const(x), t_end);
    }
    r.force_evaluations = detail::forces(stepper) - f0;
    r.velocity_evaluations = detail::velocities(stepper) - v0;
    r.t = static_cast<double>(primal(t_end));
    return r;
}

}  // namespace sympl
