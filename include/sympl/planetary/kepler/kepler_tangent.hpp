#pragma once
// The tangent map of the exact Kepler drift (kepler_drift.hpp): a small change
// (dr, dv) of a body's position and velocity at the start of a drift, carried
// to the end, to first order. What the Wisdom-Holman stepper's MEGNO needs of
// its drifts (megno_tangent.hpp).
//
// The root s of Kepler's equation (Danby 1988, "Fundamentals of Celestial
// Mechanics", 2nd ed., eq. 6.9.16-6.9.22) is found in double as the drift
// finds it; then the equation, one Newton step ds = -t / r at that root and
// the f and g functions are evaluated once more with dual numbers (dual.hpp)
// carrying the start's change. By the implicit function theorem the Newton
// step's derivative part is exactly the root's change, so the result is the
// tangent map exact to rounding, no finite difference (docs/planetary.md,
// "MEGNO").
#include <cmath>
#include <cstddef>
#include <type_traits>

#include "../../core/dual.hpp"
#include "kepler_drift.hpp"
#include "kepler_equation.hpp"
#include "stumpff.hpp"

namespace sympl {

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
        const S turns = std::nearbyint((h - o.h) / detail::kepler_period(gm, o.beta));
        hd = h - turns * detail::kepler_period(gm, beta);
    }
    if (o.h == 0) {
        // A whole number of periods: back at the start, but a changed period moves the body.
        hd.value = 0;
    }
    const S s = o.h == 0 ? S(0) : detail::solve_universal(o, detail::starting_value(o)).s;
    const detail::stumpff_values<D> c = detail::stumpff(beta * (s * s));
    const detail::kepler_terms<D> k = detail::kepler_equation(r0, eta0, zeta0, beta, gm, hd, s, c);
    const D ds = -k.f / k.r;  // its derivative part is the root's change
    const D g1 = k.g1 + c.c0 * ds, g2 = k.g2 + k.g1 * ds, r1 = k.r + k.dr * ds;
    const detail::f_and_g<D> fg = detail::f_and_g_at(r0, eta0, gm, g1, g2, r1);
    detail::apply_f_and_g(fg, R[0], R[1], R[2], V[0], V[1], V[2]);
    for (int i = 0; i < 3; ++i) dr[i] = R[i].grad[0], dv[i] = V[i].grad[0];
}

}  // namespace sympl
