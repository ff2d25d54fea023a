#pragma once
// Poincare surface of section: the points where an orbit crosses q_k = 0
// upwards (dq_k/dt > 0), as Henon & Heiles (1964) plotted them. Each crossing
// is located inside its step on the cubic Hermite interpolant of q and p
// through both ends of the step (values and time derivatives dq/dt = dT/dp,
// dp/dt = -dV/dq), so the points are accurate to O(dt^4) whatever the
// method's order, without stepping the flow backwards.
#include <cmath>
#include <cstddef>
#include <vector>

#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "../core/phase_space.hpp"

namespace sympl {

namespace detail {
// Cubic Hermite on [0, 1] with end values a, b and end slopes da, db (per unit s).
inline double hermite(double s, double a, double b, double da, double db) {
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * a + (s3 - 2 * s2 + s) * da + (-2 * s3 + 3 * s2) * b + (s3 - s2) * db;
}
}  // namespace detail

// Runs `steps` steps of dt from x with the stepper (any with step(x, dt) and
// hamiltonian()) and returns the states at the upward crossings of q_k = 0.
template <class Stepper, class State>
std::vector<State> section_crossings(Stepper& stepper, State x, double dt, std::size_t steps, Eigen::Index k = 0) {
    if (k < 0 || k >= x.size())
        throw invalid_argument("section_crossings: k = " + std::to_string(k) + " for a state of dimension " +
                               std::to_string(x.size()) + "; expected 0 <= k < dimension");
    const auto& h = stepper.hamiltonian();
    using Vec = typename State::vector;
    Vec v0, f0, v1, f1;
    velocity(h, x.p, v0);
    force(h, x.q, f0);
    std::vector<State> crossings;
    for (std::size_t i = 0; i < steps; ++i) {
        State y = x;
        stepper.step(y, dt);
        if (!is_finite(y)) throw blow_up(i + 1, (long double)(double(i) * dt), dt);
        velocity(h, y.p, v1);
        force(h, y.q, f1);
        if (x.q[k] < 0 && y.q[k] >= 0) {
            // Bisection on the interpolant of q_k: monotone enough within one step.
            double lo = 0, hi = 1;
            for (int it = 0; it < 60; ++it) {
                const double mid = (lo + hi) / 2;
                (detail::hermite(mid, x.q[k], y.q[k], dt * v0[k], dt * v1[k]) < 0 ? lo : hi) = mid;
            }
            const double s = (lo + hi) / 2;
            State c = x;
            for (Eigen::Index j = 0; j < x.size(); ++j) {
                c.q[j] = detail::hermite(s, x.q[j], y.q[j], dt * v0[j], dt * v1[j]);
                c.p[j] = detail::hermite(s, x.p[j], y.p[j], dt * f0[j], dt * f1[j]);
            }
            c.q[k] = 0;
            crossings.push_back(c);
        }
        x = y;
        v0 = v1;
        f0 = f1;
    }
    return crossings;
}

}  // namespace sympl
