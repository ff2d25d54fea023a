#pragma once
// Richardson extrapolation (Gould & Tobochnik, eq. 3.68): two results of an order-p
// approximation at h and h/2 combine to cancel the leading error term,
//     R = A(h/2) + (A(h/2) - A(h)) / (2^p - 1).
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "../core/error.hpp"
#include "../drivers/fixed_step.hpp"
#include "../core/phase_space.hpp"

namespace sympl {

// f'(t) from the central difference D1(h) = (f(t + h) - f(t - h)) / (2h),
// error O(h^2) (Gould & Tobochnik, eq. 3.66), extrapolated as (4 D1(h) - D1(2h)) / 3
// (eq. 3.68): error O(h^4).
template <class F, class T>
auto richardson_derivative(const F& f, T t, T h) {
    using std::isfinite;
    if (!isfinite(h) || !(h > T(0)))
        throw invalid_argument("richardson_derivative: h = " + detail::number(h) + "; expected a finite h > 0");
    const auto d1 = [&](T step) { return (f(t + step) - f(t - step)) / (2 * step); };
    return (4 * d1(h) - d1(2 * h)) / 3;
}

// The combination for states: fine + (fine - coarse) / (2^order - 1).
template <class S, int D>
phase_space<S, D> richardson_combine(const phase_space<S, D>& coarse, const phase_space<S, D>& fine, int order) {
    if (order < 1)
        throw invalid_argument("richardson_combine: order = " + std::to_string(order) + "; expected >= 1");
    if (coarse.size() != fine.size())
        throw invalid_argument("richardson_combine: states of dimension " + std::to_string(coarse.size()) + " and " +
                               std::to_string(fine.size()) + "; expected equal dimensions");
    const S c = S(1) / (std::ldexp(S(1), order) - 1);
    return phase_space<S, D>(fine.q + (fine.q - coarse.q) * c, fine.p + (fine.p - coarse.p) * c);
}

// Any fixed-step method of order p, extrapolated step by step: one step of dt
// and two of dt/2, combined; the cost is three steps. The local error drops
// from O(dt^{p+1}) to O(dt^{p+2}): the global order rises to p + 1. A
// symmetric method gains two orders: it is the exact flow of a modified
// equation whose corrections are even in dt, so the dt^{p+2} term cancels too.
// The same holds for two whole runs at dt and dt/2 combined by
// richardson_combine (the global error of a symmetric method expands in even
// powers of dt). The result is no longer symplectic.
template <fixed_step_stepper Stepper>
class richardson_stepper {
public:
    using state_type = typename Stepper::state_type;
    using scalar = typename Stepper::scalar;

    richardson_stepper(Stepper inner, int order) : inner_(std::move(inner)), order_(order) {
        if (order < 1)
            throw invalid_argument("richardson_stepper: order = " + std::to_string(order) +
                                   "; expected the order (>= 1) of the wrapped method");
    }

    void step(state_type& x, scalar t, scalar dt) {
        coarse_ = x;
        detail::one_step(inner_, coarse_, t, dt);
        fine_ = x;
        detail::one_step(inner_, fine_, t, dt / 2);
        detail::one_step(inner_, fine_, t + dt / 2, dt / 2);
        x = richardson_combine(coarse_, fine_, order_);
    }

    std::uint64_t force_evaluations() const { return detail::forces(inner_); }
    std::uint64_t velocity_evaluations() const { return detail::velocities(inner_); }
    int order() const { return order_; }
    const Stepper& inner() const { return inner_; }

private:
    Stepper inner_;
    int order_;
    state_type coarse_, fine_;
};

}  // namespace sympl
