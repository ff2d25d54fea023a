#pragma once
// Step-size control, written once for every error-estimating stepper (the
// Runge-Kutta-Nystrom pairs, Euler-Richardson through methods/adaptive.hpp):
// integrate_controlled runs from t0 to exactly t_end; a trial step is
// accepted when its error estimate, in units of the tolerance, is at most 1.
// The next step is h * safety * err^(-alpha/k) * err_prev^(beta/k), k the
// stepper's error order (the estimate scales as h^k): alpha = 0.7, beta = 0.4
// is the PI controller of Gustafsson (1991, ACM TOMS 17, 533-554; Hairer,
// Norsett & Wanner, Solving ODE I, sect. II.4, "stabilized step size
// control"); alpha = 1, beta = 0 the elementary controller. The factor is
// limited to [min_factor, max_factor], and after a rejection to at most 1
// unless grow_after_rejection; a rejected step shrinks by safety *
// err^(-1/k). A rejected step that cannot shrink below dt_min stops the run
// with an integration_error naming the time and step size; x is left at the
// last accepted step.
#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

#include "../core/error.hpp"
#include "../core/phase_space.hpp"
#include "../core/time_span.hpp"
#include "fixed_step.hpp"

namespace sympl {

struct control_options {
    double absolute_tolerance = 1e-10;  // per component of q and p
    double relative_tolerance = 1e-10;  // of max(|y_old|, |y_new|)
    double dt_initial = 0;              // first trial step; 0 means (t_end - t0) / 100
    double dt_min = 0;                  // 0 means 1e-12 (t_end - t0)
    double dt_max = std::numeric_limits<double>::infinity();
    double max_factor = 5;    // largest growth of the step from one step to the next
    double min_factor = 0.2;  // largest shrink
    double safety = 0.9;
    double alpha = 0.7, beta = 0.4;     // the controller's exponents times k (PI; 1 and 0: elementary)
    bool grow_after_rejection = false;  // may the step grow right after a rejection
};

struct control_summary {
    std::size_t accepted = 0;
    std::size_t rejected = 0;
    double t = 0;
    double dt_smallest = std::numeric_limits<double>::infinity();  // of the accepted steps
    double dt_largest = 0;
    double largest_error = 0;  // of the accepted steps, in units of the tolerance (<= 1)
    std::uint64_t force_evaluations = 0;
};

// Where a controlled run is after an accepted step and what its controller
// carries to the next: the time, the next trial step, the last error (the PI
// controller's memory; after an accepted step no rejection is pending) and the
// summary so far. Saved with the state (and the stepper's carried list) when
// the observer sees that step, and handed back to integrate_controlled, it
// continues the run bit for bit (a checkpoint).
template <class T>
struct controller_state {
    T t{};
    double dt = 0, previous_error = 1;
    control_summary summary;  // accepted == 0: the run starts at t0
};

// A stepper that takes a trial step from x by dt at time t, x untouched,
// returns its error estimate in units of the options' tolerances, and on
// accept(x) moves x to the trial; error_order k: the estimate scales as dt^k.
template <class S>
concept error_estimating_stepper = requires(S& s, const typename S::state_type& x, typename S::state_type& y,
                                            typename S::scalar t, const control_options& o) {
    { S::error_order } -> std::convertible_to<int>;
    { s.attempt(x, t, t, o) } -> std::convertible_to<double>;
    s.accept(y);
};

// The stepper's own defaults (default_control()) where it has them, else control_options{}.
template <class S>
control_options default_control_of() {
    if constexpr (requires { S::default_control(); }) return S::default_control();
    else return control_options{};
}

namespace detail {
template <class T>
void check_control(const control_options& o, T t0, T t_end, const char* who) {
    const std::string w = std::string(who) + ": ";
    check_time_span(who, t0, t_end);
    const auto finite = [&](double v, bool ok, const char* what, const char* expected) {
        if (!ok || !std::isfinite(v))
            throw invalid_argument(w + what + " = " + number(v) + "; expected a finite " + expected);
    };
    finite(o.absolute_tolerance, o.absolute_tolerance > 0, "absolute_tolerance", "value > 0");
    finite(o.relative_tolerance, o.relative_tolerance >= 0, "relative_tolerance", "value >= 0");
    finite(o.safety, o.safety > 0 && o.safety <= 1, "safety", "value with 0 < safety <= 1");
    finite(o.alpha, o.alpha > 0, "alpha", "value > 0");
    finite(o.beta, o.beta >= 0, "beta", "value >= 0");
    if (!(o.max_factor > 1) || !std::isfinite(o.max_factor) || !(o.min_factor > 0) || !(o.min_factor < 1))
        throw invalid_argument(w + "max_factor = " + number(o.max_factor) + ", min_factor = " + number(o.min_factor) +
                               "; expected a finite max_factor > 1 and 0 < min_factor < 1");
    if (!(o.dt_min > 0) || !(o.dt_max >= o.dt_min) || !(o.dt_initial > 0) || !std::isfinite(o.dt_initial))
        throw invalid_argument(w + "dt_min = " + number(o.dt_min) + ", dt_initial = " + number(o.dt_initial) +
                               ", dt_max = " + number(o.dt_max) +
                               "; expected 0 < dt_min <= dt_max and a finite dt_initial > 0");
}

// The loop of integrate_controlled, r kept up to date step by step (so that a
// caller whose observer ends the run by an exception still has the counts).
template <class Stepper, class Observer>
void control_loop(Stepper& stepper, typename Stepper::state_type& x, typename Stepper::scalar t0,
                  typename Stepper::scalar t_end, control_options o, Observer& observer, control_summary& r,
                  controller_state<typename Stepper::scalar>* state = nullptr) {
    using T = typename Stepper::scalar;
    const char* who = "integrate_controlled";
    const double span = static_cast<double>(primal(t_end - t0));
    if (o.dt_initial == 0) o.dt_initial = span / 100;
    if (o.dt_min == 0) o.dt_min = 1e-12 * span;
    check_control(o, t0, t_end, who);
    if (!is_finite(x)) throw invalid_argument(std::string(who) + ": the initial state is not finite; expected finite q and p");

    const double k = Stepper::error_order;
    const double alpha = o.alpha / k, beta = o.beta / k;
    auto f0 = forces(stepper);
    const bool observed = observing(observer);
    T t = t0;
    double dt = std::clamp(o.dt_initial, o.dt_min, o.dt_max);
    double previous_error = 1;
    bool after_rejection = false;
    if (state && state->summary.accepted > 0) {  // resumed after an accepted step
        t = state->t, dt = state->dt, previous_error = state->previous_error;
        r = state->summary;
        f0 -= r.force_evaluations;
    } else if (observed) {
        observer(std::as_const(x), t0);
    }
    while (t < t_end) {
        const bool last = T(dt) >= t_end - t;
        const T h = last ? T(t_end - t) : T(dt);
        const double hd = static_cast<double>(primal(h));
        double err = static_cast<double>(stepper.attempt(std::as_const(x), t, h, o));
        if (!std::isfinite(err)) err = HUGE_VAL;
        if (err <= 1) {
            stepper.accept(x);
            t = last ? t_end : T(t + h);
            ++r.accepted;
            r.dt_smallest = std::min(r.dt_smallest, hd);
            r.dt_largest = std::max(r.dt_largest, hd);
            r.largest_error = std::max(r.largest_error, err);
            r.t = static_cast<double>(primal(t));
            r.force_evaluations = forces(stepper) - f0;
            const double e = std::max(err, 1e-10);
            double factor = o.safety * std::pow(e, -alpha) * (beta == 0 ? 1.0 : std::pow(previous_error, beta));
            factor = std::clamp(factor, o.min_factor, after_rejection && !o.grow_after_rejection ? 1.0 : o.max_factor);
            previous_error = e;
            after_rejection = false;
            if (!last) dt = std::clamp(hd * factor, o.dt_min, o.dt_max);
            if (state) *state = {t, dt, previous_error, r};
            if (observed) observer(std::as_const(x), t);
        } else {
            ++r.rejected;
            after_rejection = true;
            r.force_evaluations = forces(stepper) - f0;
            if (hd <= o.dt_min * (1 + 1e-12) && !last)
                throw integration_error(std::string(who) + ": step size underflow at t = " + number(t) + ": dt = " +
                                            number(hd) + " is dt_min and its error estimate is " + number(err) +
                                            " times the tolerance; expected a larger tolerance or a smaller dt_min; "
                                            "the state is left at t",
                                        r.accepted + 1, static_cast<double>(primal(t)));
            const double factor = std::isfinite(err) ? o.safety * std::pow(err, -1.0 / k) : o.min_factor;
            dt = std::max(hd * std::clamp(factor, o.min_factor, 1.0), o.dt_min);
        }
    }
    r.t = static_cast<double>(primal(t_end));
    r.force_evaluations = forces(stepper) - f0;
}
}  // namespace detail

// From t0 to exactly t_end with the step size controlled (see the top of
// this header). observer(x, t) is called at t0 and after every accepted step.
// The stepper may be a temporary adapter (methods/adaptive.hpp).
template <class Stepper, class Observer = no_observer>
    requires error_estimating_stepper<std::remove_cvref_t<Stepper>>
control_summary integrate_controlled(Stepper&& stepper, typename std::remove_cvref_t<Stepper>::state_type& x,
                                     typename std::remove_cvref_t<Stepper>::scalar t0,
                                     typename std::remove_cvref_t<Stepper>::scalar t_end,
                                     control_options options = default_control_of<std::remove_cvref_t<Stepper>>(),
                                     Observer&& observer = {}) {
    control_summary r;
    detail::control_loop(stepper, x, t0, t_end, options, observer, r);
    return r;
}

// The same, `state` kept up to date before the observer sees each accepted
// step; a state of an earlier run (summary.accepted > 0) resumes that run
// after its step, x and the stepper as they were then (the stepper's
// carried list restored), without observing t0 again. The summary counts the
// whole run.
template <class Stepper, class Observer>
    requires error_estimating_stepper<std::remove_cvref_t<Stepper>>
control_summary integrate_controlled(Stepper&& stepper, typename std::remove_cvref_t<Stepper>::state_type& x,
                                     typename std::remove_cvref_t<Stepper>::scalar t0,
                                     typename std::remove_cvref_t<Stepper>::scalar t_end, control_options options,
                                     Observer&& observer,
                                     controller_state<typename std::remove_cvref_t<Stepper>::scalar>& state) {
    control_summary r;
    detail::control_loop(stepper, x, t0, t_end, options, observer, r, &state);
    return r;
}

}  // namespace sympl
