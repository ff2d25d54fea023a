#pragma once
// Adaptive step size from a local error estimate: Euler-Richardson's
// |x2 - x1|, |v2 - v1| (Gould & Tobochnik, after eq. 3.44: "We can use these estimates
// to change the time step so that the error is always within some desired
// level of precision").
//
// A step is accepted when the larger of the two estimates is at most the
// tolerance; either way the next step is dt * safety * sqrt(tolerance /
// estimate), since the estimate scales as dt^2, limited to a change by a
// factor 5 and to [dt_min, dt_max]. A rejected step that cannot shrink below
// dt_min stops the run with an error naming the time and step size; the state
// is left at the last accepted step. The run lands exactly on t_end.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

#include "../core/error.hpp"
#include "../core/integrate.hpp"
#include "../core/phase_space.hpp"

namespace sympl {

template <class S>
concept error_estimating_stepper = time_aware_stepper<S> && requires(const S& s) {
    { s.last_error_estimate().largest() } -> std::convertible_to<typename S::scalar>;
};

struct adaptive_options {
    double tolerance = 1e-6;  // bound on the estimate of every accepted step
    double dt_initial = 0;    // first trial step; 0 means (t_end - t0) / 100
    double dt_min = 0;        // 0 means 1e-12 (t_end - t0)
    double dt_max = std::numeric_limits<double>::infinity();
    double safety = 0.9;
};

struct adaptive_summary {
    std::size_t accepted = 0;
    std::size_t rejected = 0;
    double t = 0;
    double dt_smallest = std::numeric_limits<double>::infinity();  // of the accepted steps
    double dt_largest = 0;
    double largest_estimate = 0;  // of the accepted steps: never above the tolerance
    std::uint64_t force_evaluations = 0;
};

// From t0 to exactly t_end. observer(state, t) is called at t0 and after every accepted step.
template <error_estimating_stepper Stepper, class Observer = no_observer>
adaptive_summary integrate_adaptive(Stepper& stepper, typename Stepper::state_type& x, typename Stepper::scalar t0,
                                    typename Stepper::scalar t_end, adaptive_options options = {},
                                    Observer&& observer = {}) {
    using T = typename Stepper::scalar;
    using State = typename Stepper::state_type;
    using std::isfinite;
    using std::sqrt;
    using detail::number;
    if (!isfinite(t0) || !isfinite(t_end) || !(t_end > t0))
        throw invalid_argument("integrate_adaptive: t_end = " + number(t_end) + " with t0 = " + number(t0) +
                               "; expected finite times with t_end > t0");
    const double span = static_cast<double>(primal(t_end - t0));
    if (options.dt_initial == 0) options.dt_initial = span / 100;
    if (options.dt_min == 0) options.dt_min = 1e-12 * span;
    if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
        throw invalid_argument("integrate_adaptive: tolerance = " + number(options.tolerance) +
                               "; expected a finite tolerance > 0");
    if (!(options.dt_min > 0) || !(options.dt_max >= options.dt_min) || !(options.dt_initial > 0) ||
        !std::isfinite(options.dt_initial))
        throw invalid_argument("integrate_adaptive: dt_min = " + number(options.dt_min) + ", dt_initial = " +
                               number(options.dt_initial) + ", dt_max = " + number(options.dt_max) +
                               "; expected 0 < dt_min <= dt_max and a finite dt_initial > 0");
    if (!(options.safety > 0 && options.safety <= 1))
        throw invalid_argument("integrate_adaptive: safety = " + number(options.safety) + "; expected 0 < safety <= 1");
    if (!is_finite(x)) throw invalid_argument("integrate_adaptive: the initial state is not finite; expected finite q and p");

    adaptive_summary r;
    const auto f0 = detail::forces(stepper);
    constexpr bool observed = !std::is_same_v<std::decay_t<Observer>, no_observer>;
    if constexpr (observed) observer(std::as_const(x), t0);
    T t = t0;
    double dt = std::clamp(options.dt_initial, options.dt_min, options.dt_max);
    State trial = x;
    while (t < t_end) {
        const bool last = T(dt) >= t_end - t;
        const T h = last ? t_end - t : T(dt);
        trial = x;
        stepper.step(trial, t, h);
        const double estimate =
            is_finite(trial) ? static_cast<double>(primal(stepper.last_error_estimate().largest())) : HUGE_VAL;
        const double hd = static_cast<double>(primal(h));
        const double factor = estimate == 0 ? 5.0
                                            : std::clamp(options.safety * std::sqrt(options.tolerance / estimate), 0.2, 5.0);
        if (estimate <= options.tolerance) {
            std::swap(x, trial);
            t = last ? t_end : t + h;
            ++r.accepted;
            r.dt_smallest = std::min(r.dt_smallest, hd);
            r.dt_largest = std::max(r.dt_largest, hd);
            r.largest_estimate = std::max(r.largest_estimate, estimate);
            if constexpr (observed) observer(std::as_const(x), t);
            dt = std::clamp(hd * factor, options.dt_min, options.dt_max);
        } else {
            ++r.rejected;
            if (hd <= options.dt_min * (1 + 1e-12) && !last)
                throw integration_error("integrate_adaptive: step size underflow at t = " + number(t) +
                                            ": dt = " + number(hd) + " is dt_min and its error estimate " +
                                            number(estimate) + " exceeds the tolerance " + number(options.tolerance) +
                                            "; expected a larger tolerance or a smaller dt_min; the state is left at t",
                                        r.accepted + 1, static_cast<double>(primal(t)));
            dt = std::max(hd * factor, options.dt_min);
        }
    }
    r.t = static_cast<double>(primal(t_end));
    r.force_evaluations = detail::forces(stepper) - f0;
    return r;
}

}  // namespace sympl
