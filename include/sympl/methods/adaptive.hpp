#pragma once
// Adaptive step size from Euler-Richardson's local error estimate |x2 - x1|,
// |v2 - v1| (Gould & Tobochnik, after eq. 3.44: "We can use these estimates
// to change the time step so that the error is always within some desired
// level of precision"), run by the one controlled driver
// (drivers/controlled.hpp): richardson_adaptive(s) makes a stepper with
// last_error_estimate() an error-estimating stepper.
//
// A step is accepted when the larger of the two estimates is at most the
// absolute tolerance (default 1e-6; relative_tolerance, default 0, adds
// relative_tolerance * max |component| of the trial state); the next step is
// dt * safety * sqrt(tolerance / estimate), since the estimate scales as
// dt^2 (the elementary controller, error order 2), limited to a change by a
// factor 5.
#include <cmath>
#include <type_traits>
#include <utility>

#include "../core/phase_space.hpp"
#include "../drivers/controlled.hpp"

namespace sympl {

// A stepper whose step(x, t, dt) leaves last_error_estimate().largest().
template <class S>
concept self_estimating_stepper = time_aware_stepper<S> && requires(const S& s) {
    { s.last_error_estimate().largest() } -> std::convertible_to<typename S::scalar>;
};

// The adapter: holds a reference to the stepper, which steps as it would alone.
template <self_estimating_stepper Stepper>
class richardson_adaptive {
public:
    using state_type = typename Stepper::state_type;
    using scalar = typename Stepper::scalar;
    static constexpr int error_order = 2;

    explicit richardson_adaptive(Stepper& s) : s_(s) {}

    static control_options default_control() {
        control_options o;
        o.absolute_tolerance = 1e-6;
        o.relative_tolerance = 0;
        o.alpha = 1;
        o.beta = 0;
        o.grow_after_rejection = true;
        return o;
    }

    double attempt(const state_type& x, scalar t, scalar dt, const control_options& o) {
        trial_ = x;
        s_.step(trial_, t, dt);
        if (!is_finite(trial_)) return HUGE_VAL;
        double tolerance = o.absolute_tolerance;
        if (o.relative_tolerance != 0) {
            using std::abs;
            scalar size(0);
            for (Eigen::Index i = 0; i < trial_.size(); ++i) {
                size = abs(trial_.q[i]) > size ? abs(trial_.q[i]) : size;
                size = abs(trial_.p[i]) > size ? abs(trial_.p[i]) : size;
            }
            tolerance += o.relative_tolerance * static_cast<double>(primal(size));
        }
        return static_cast<double>(primal(s_.last_error_estimate().largest())) / tolerance;
    }
    void accept(state_type& x) { std::swap(x, trial_); }

    std::uint64_t force_evaluations() const { return detail::forces(s_); }
    std::uint64_t velocity_evaluations() const { return detail::velocities(s_); }

private:
    Stepper& s_;
    state_type trial_;
};

}  // namespace sympl
