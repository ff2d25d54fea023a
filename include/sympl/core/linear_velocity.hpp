#pragma once
// The check that dq/dt = velocity(p) is linear in p, as a quadratic kinetic
// energy T = p.M^-1.p / 2 gives: Runge-Kutta-Nystrom methods build positions
// from accelerations M^-1 F, the damped drift of the conformal splitting is
// integrated in closed form, and the quintic Hermite interpolant applies M
// term by term; all three need it. One probe per dimension on two fixed
// momenta a, b: velocity(a + 2b) against velocity(a) + 2 velocity(b), to
// 1024 rounding units of the terms' size (an affine or a relativistic
// velocity fails by O(1)). A non-linearity that this probe cannot see is not
// detected. The probe's evaluations are not counted as the stepper's.
#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "dual.hpp"
#include "error.hpp"

namespace sympl {

// velocity(p, out) writes dq/dt for momenta p (vectors of dimension n);
// `who` and `why` name the caller and what it needs linearity for.
template <class Vector, class Velocity>
void check_linear_velocity(Velocity&& velocity, Eigen::Index n, std::string_view who, std::string_view why) {
    using S = typename Vector::Scalar;
    using std::abs;
    Vector a(n), b(n), sum(n), va(n), vb(n), vsum(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        a[i] = S(0.75) + S(0.125) * S(i % 7);
        b[i] = S(-1.5) + S(0.25) * S(i % 5);
    }
    sum = a + S(2) * b;
    velocity(a, va);
    velocity(b, vb);
    velocity(sum, vsum);
    using P = std::decay_t<decltype(primal(S()))>;
    const P tolerance = P(1024) * std::numeric_limits<P>::epsilon();
    const auto text = [](const S& v) { return detail::number_text(static_cast<long double>(primal(v))); };
    for (Eigen::Index i = 0; i < n; ++i) {
        const S expected = va[i] + S(2) * vb[i];
        const S scale = abs(va[i]) + S(2) * abs(vb[i]) + abs(vsum[i]);
        if (!(primal(abs(vsum[i] - expected)) <= tolerance * primal(scale)))
            throw invalid_argument(std::string(who) + ": velocity(p) is not linear in p: component " + std::to_string(i) +
                                   " of velocity(a + 2b) is " + text(vsum[i]) + " against velocity(a) + 2 velocity(b) = " +
                                   text(expected) + "; expected a quadratic kinetic energy T = p.M^-1.p / 2, as " +
                                   std::string(why) + " needs");
    }
}

}  // namespace sympl
