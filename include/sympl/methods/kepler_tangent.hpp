#pragma once
// The tangent map of the exact Kepler drift (kepler_drift.hpp): a small change
// (dr, dv) of a body's position and velocity at the start of a drift, carried
// to the end, to first order. What the Wisdom-Holman stepper's MEGNO needs of
// its drifts (wisdom_holman.hpp).
//
// The drift solves Kepler's equation t(s) = r0 G1(s) + eta0 G2(s) + GM G3(s) = h
// for the universal anomaly s and applies the f and g functions (Danby 1988,
// "Fundamentals of Celestial Mechanics", 2nd ed., eq. 6.9.16-6.9.22). The
// root s depends on the start through r0, eta0 and beta; by the implicit
// function theorem its change is ds = -dt / r with dt the change of t(s) at
// fixed s and r = t'(s) the distance. So the root is found in double as the
// drift finds it, then everything is evaluated once more with dual numbers
// (dual.hpp) carrying the start's change: Kepler's equation at that root
// (its value is zero to rounding, its derivative part is dt), one Newton step
// ds = -t / r whose derivative part is exactly the implicit one, the G's and
// r carried to s + ds to first order (G1' = G0, G2' = G1, r' = eta0 G0 +
// zeta0 G1), and the f and g functions. The derivative parts of the result are
// the tangent map applied to (dr, dv), exact to rounding: no finite
// difference. A drift reduced by whole periods keeps the period's dependence
// on the orbit (h - n P(beta), P = 2 pi GM / beta^(3/2)).
#include <cmath>
#include <cstddef>
#include <type_traits>

#include "../core/dual.hpp"
#include "kepler_drift.hpp"

namespace sympl {

namespace detail {
// Stumpff's c0..c3 at x for any scalar with the arithmetic of a double (a dual
// number here): quartered until |x| <= 0.1, summed to the terms rounding
// needs there, brought back by the recurrences (as stumpff_lanes).
template <class T>
void stumpff_any(T x, T& c0, T& c1, T& c2, T& c3) {
    using std::fabs;
    int levels = 0;
    while (fabs(primal(x)) > 0.1 && levels < 1100) x = x * 0.25, ++levels;
    constexpr int n = stumpff_terms<double>(0.1L);
    long double inverse_factorial[2 * n + 4];
    long double m_factorial = 1;
    inverse_factorial[0] = 1;
    for (int m = 1; m < 2 * n + 4; ++m) inverse_factorial[m] = 1 / (m_factorial *= m);
    T s2 = T(double(inverse_factorial[2 * n])), s3 = T(double(inverse_factorial[2 * n + 1]));
    for (int j = n - 2; j >= 0; --j) {
        s2 = T(double(inverse_factorial[2 * j + 2])) - x * s2;
        s3 = T(double(inverse_factorial[2 * j + 3])) - x * s3;
    }
    c2 = s2, c3 = s3, c1 = 1 - x * s3, c0 = 1 - x * s2;
    for (; levels > 0; --levels) {
        const T n3 = (c2 + c0 * c3) * 0.25, n2 = c1 * c1 * 0.5, n1 = c0 * c1;
        x = x * 4;
        c3 = n3, c2 = n2, c1 = n1, c0 = 1 - x * n2;
    }
}
}  // namespace detail

// The tangent map of kepler_drift(r, v, gm, h): r and v are the body's
// position and velocity relative to the central mass at the start of the
// drift (not changed); dr and dv, the change at the start, become the change
// at the end. Bad input as kepler_drift (an invalid_argument).
template <class S>
    requires std::is_floating_point_v<S>
void kepler_drift_tangent(const S* r, const S* v, S* dr, S* dv, S gm, S h) {
    using D = dual<S, 1>;
    using std::sqrt;
    detail::check_kepler_input(r, v, gm, h, -1);
    if (h == 0) return;
    const S r0p = sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    const S eta0p = r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    const S v2p = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    const detail::kepler_orbit<S> o = detail::make_orbit(r0p, eta0p, v2p, gm, h);
    D R[3], V[3];
    for (int i = 0; i < 3; ++i) {
        R[i] = D(r[i]), V[i] = D(v[i]);
        R[i].grad[0] = dr[i], V[i].grad[0] = dv[i];
    }
    const D r0 = sqrt(R[0] * R[0] + R[1] * R[1] + R[2] * R[2]);
    const D eta0 = R[0] * V[0] + R[1] * V[1] + R[2] * V[2];
    const D beta = 2 * gm / r0 - (V[0] * V[0] + V[1] * V[1] + V[2] * V[2]);
    const D zeta0 = gm - beta * r0;
    D hd(h);
    if (o.h != h) {
        // Whole periods taken off: their length moves with the orbit.
        const S turns = std::nearbyint((h - o.h) / (2 * 3.14159265358979323846264338327950288L * gm /
                                                    (o.beta * sqrt(o.beta))));
        hd = h - turns * (S(2 * 3.14159265358979323846264338327950288L) * gm / (beta * sqrt(beta)));
    }
    if (o.h == 0) {
        // A whole number of periods: back at the start, but a changed period moves the body.
        hd.value = 0;
    }
    const S s = o.h == 0 ? S(0) : detail::solve_universal(o, detail::starting_value(o)).s;
    D c0, c1, c2, c3;
    detail::stumpff_any(beta * (s * s), c0, c1, c2, c3);
    const D G1 = s * c1, G2 = (s * s) * c2, G3 = (s * s * s) * c3;
    const D t = r0 * G1 + eta0 * G2 + gm * G3 - hd;
    const D rr = r0 * c0 + eta0 * G1 + gm * G2;
    const D ds = -t / rr;
    const D g1 = G1 + c0 * ds, g2 = G2 + G1 * ds, r1 = rr + (eta0 * c0 + zeta0 * G1) * ds;
    const D fm1 = -gm * g2 / r0, g = r0 * g1 + eta0 * g2, fdot = -gm * g1 / (r1 * r0), gdm1 = -gm * g2 / r1;
    for (int i = 0; i < 3; ++i) {
        const D ri = R[i] + (fm1 * R[i] + g * V[i]), vi = V[i] + (fdot * R[i] + gdm1 * V[i]);
        dr[i] = ri.grad[0], dv[i] = vi.grad[0];
    }
}

}  // namespace sympl
