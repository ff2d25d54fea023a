#pragma once
// The exact Kepler flow of one body: two-body motion about a central mass GM
// over a time h (either sign), elliptic, parabolic or hyperbolic, in
// universal variables (Stumpff 1959; Danby 1988, "Fundamentals of Celestial
// Mechanics", 2nd ed., ch. 6.7-6.9). It is the drift of the Wisdom-Holman
// splitting: each planet moves on its Kepler orbit about the star.
// kepler_lanes.hpp drifts many bodies at once (kepler_drift_all).
//
// An elliptic drift longer than half a period is first reduced by whole
// periods (Wisdom & Hernandez 2015, MNRAS 453, 3015, do the same); the root
// of Kepler's equation is found by Danby's quartic iteration inside a
// bracket, replaced by bisection whenever it leaves the bracket or stalls,
// so the solve always ends (kepler_equation.hpp). The accuracy analysis is in
// docs/planetary.md ("The Kepler solve").
//
// Bad input (a body at the central mass, GM <= 0, non-finite numbers) is an
// invalid_argument naming the value and, in kepler_drift_all, the body.
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <type_traits>

#include <Eigen/Core>

#include "../../core/error.hpp"
#include "kepler_equation.hpp"

namespace sympl {

namespace detail {

template <class S>
std::string body_text(std::ptrdiff_t body) {
    return body < 0 ? std::string() : " of body " + std::to_string(body);
}

template <class S>
void check_kepler_input(const S* r, const S* v, S gm, S h, std::ptrdiff_t body) {
    const char* axis[] = {"x", "y", "z"};
    if (!(std::isfinite(gm) && gm > 0))
        throw invalid_argument("kepler_drift: GM = " + number_text(gm) + "; expected a finite GM > 0");
    if (!std::isfinite(h))
        throw invalid_argument("kepler_drift: h = " + number_text(h) + "; expected a finite time");
    for (int i = 0; i < 3; ++i) {
        if (!std::isfinite(r[i]))
            throw invalid_argument("kepler_drift: position " + std::string(axis[i]) + body_text<S>(body) + " = " +
                                   number_text(r[i]) + "; expected a finite number");
        if (!std::isfinite(v[i]))
            throw invalid_argument("kepler_drift: velocity " + std::string(axis[i]) + body_text<S>(body) + " = " +
                                   number_text(v[i]) + "; expected a finite number");
    }
    const S r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    if (!(r2 > 0) || !std::isfinite(r2))
        throw invalid_argument("kepler_drift: |r|" + body_text<S>(body) + " = " + number_text(std::sqrt(r2)) +
                               " (position (" + number_text(r[0]) + ", " + number_text(r[1]) + ", " +
                               number_text(r[2]) + ")); expected a body away from the central mass, 0 < |r|^2 < " +
                               number_text(std::numeric_limits<S>::max()));
}

// r and v carried by the f and g functions of the solved G's (kepler_equation.hpp).
template <class S>
void drift_by_f_and_g(S* r, S* v, S r0, S eta0, S gm, S g1, S g2, S rr) {
    apply_f_and_g(f_and_g_at(r0, eta0, gm, g1, g2, rr), r[0], r[1], r[2], v[0], v[1], v[2]);
}

template <class S>
void kepler_drift_body(S* r, S* v, S gm, S h, std::ptrdiff_t body) {
    check_kepler_input(r, v, gm, h, body);
    if (h == 0) return;
    const S r0 = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    const S eta0 = r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    const S v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    const kepler_orbit<S> o = make_orbit(r0, eta0, v2, gm, h);
    if (o.h == 0) return;  // whole periods: back at the start
    const kepler_residual<S> k = solve_universal(o, starting_value(o));
    drift_by_f_and_g(r, v, r0, eta0, gm, k.g1, k.g2, k.r);
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(r[i]) || !std::isfinite(v[i]))
            throw invalid_argument("kepler_drift: h = " + number_text(h) + body_text<S>(body) +
                                   " carries the body beyond the largest finite number");
}

}  // namespace detail

// The exact Kepler drift of one body about GM over time h, in place: r and v
// are the position and velocity relative to the central mass.
template <class S>
    requires std::is_floating_point_v<S>
void kepler_drift(Eigen::Matrix<S, 3, 1>& r, Eigen::Matrix<S, 3, 1>& v, S gm, S h) {
    detail::kepler_drift_body(r.data(), v.data(), gm, h, -1);
}

// Bodies as structure of arrays: body i is at (x[i], y[i], z[i]) with
// velocity (vx[i], vy[i], vz[i]); all six spans of equal length.
template <class S>
struct kepler_bodies {
    std::span<S> x, y, z, vx, vy, vz;
    std::size_t size() const { return x.size(); }
};

}  // namespace sympl
