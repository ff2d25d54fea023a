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
// so the solve always ends (kepler_equation.hpp). A hyperbolic drift of a
// large anomaly change goes in pieces (drift_in_pieces). The accuracy
// analysis is in docs/planetary.md ("The Kepler solve").
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

// A hyperbolic drift whose anomaly changes by more than 6 (-beta s^2 > 36)
// and whose update r = f r0 + g v0, with g = r0 G1 + eta0 G2, adds terms
// more than 256 times the result's size (they grow as cosh of the anomaly
// change; docs/planetary.md, "The Kepler solve") is taken in pieces
// (drift_in_pieces); one whose sums cancel less is better taken whole.
template <class S>
inline constexpr S hyperbolic_piece_limit = 36;
template <class S>
inline constexpr S hyperbolic_cancellation_limit = 256;

// One solve of Kepler's equation and its f and g update. Where may_split and
// the drift is a long hyperbolic one whose sums cancel, moves nothing and
// returns false (drift_in_pieces takes it).
template <class S>
bool drift_by_one_solve(S* r, S* v, S gm, S h, bool may_split) {
    const S r0 = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    const S eta0 = r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    const S v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    const kepler_orbit<S> o = make_orbit(r0, eta0, v2, gm, h);
    if (o.h == 0) return true;  // whole periods: back at the start
    const kepler_residual<S> k = solve_universal(o, starting_value(o));
    const f_and_g<S> fg = f_and_g_at(r0, eta0, gm, k.g1, k.g2, k.r);
    if (may_split && o.beta < 0 && -o.beta * k.s * k.s > hyperbolic_piece_limit<S> &&
        (2 + std::fabs(fg.fm1)) * r0 + (r0 * std::fabs(k.g1) + std::fabs(eta0 * k.g2)) * std::sqrt(v2) >
            hyperbolic_cancellation_limit<S> * k.r)
        return false;
    apply_f_and_g(fg, r[0], r[1], r[2], v[0], v[1], v[2]);
    return true;
}

template <class S>
stumpff_values<S> stumpff_at(S x) {
    stumpff_values<S> c;
    stumpff_lanes<S, 1>(&x, &c.c0, &c.c1, &c.c2, &c.c3);
    return c;
}

// One piece of length d in the universal variable, its Stumpff values c at
// beta d^2 at hand, where its time t(d) (Danby 1988, eq. 6.9.16) is within
// the time left: the body moved by f and g, and `left` less t(d). Else
// nothing moves and false is returned.
template <class S>
bool drift_piece(S* r, S* v, S gm, const stumpff_values<S>& c, S d, S& left) {
    const S g1 = d * c.c1, g2 = d * d * c.c2, g3 = d * d * d * c.c3;
    const S r0 = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
    const S eta0 = r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    const S t = (r0 * g1 + eta0 * g2) + gm * g3;
    if (!((left > 0) ? (left - t > 0) : (left - t < 0))) return false;
    drift_by_f_and_g(r, v, r0, eta0, gm, g1, g2, (r0 * c.c0 + eta0 * g1) + gm * g2);
    left -= t;
    return true;
}

// Most pieces of one drift: with the G's finite (cosh overflows past 710) a
// drift's anomaly changes by less than 1420, 710 pieces.
inline constexpr int most_hyperbolic_pieces = 1024;

// The drift over h in pieces of anomaly change 2, so that every f and g sum
// is of terms near the result's size; each piece's length in the universal
// variable, D = 2 / sqrt(-beta), from the beta of its own start (beta D^2 =
// -4 always: Stumpff's functions once), its time taken off h while it fits,
// the last piece solved for the time left, so that the pieces add up to h
// (the whole drift's root is not used: from far out Kepler's equation itself
// cancels). A pericentre passed on the way lies mid-piece: a piece boundary
// there would hold the body where GM / r, and the rounding of its energy, is
// largest (e near 1: 2 / (e - 1) times the energy's scale far out).
template <class S>
void drift_in_pieces(S* r, S* v, S gm, S h) {
    const S sign = h > 0 ? S(1) : S(-1);
    S left = h;
    {
        // The anomaly F0 at the start (e sinh F0 = eta0 sqrt(-beta) / GM, e
        // from the angular momentum: 1 for a radial orbit, no cancellation)
        // and the time to the pericentre, F = 0, by Kepler's equation
        // e sinh F - F = n t (Danby 1988, sec. 6.5).
        const S r0 = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
        const S eta0 = r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
        const S beta = 2 * gm / r0 - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        const S lx = r[1] * v[2] - r[2] * v[1], ly = r[2] * v[0] - r[0] * v[2], lz = r[0] * v[1] - r[1] * v[0];
        const S root = std::sqrt(-beta), e = std::sqrt(1 - beta * ((lx * lx + ly * ly + lz * lz) / (gm * gm)));
        const S es = eta0 * root / gm, f0 = std::asinh(es / e), n = -beta * root / gm;
        const S to_pericentre = (f0 - es) / n;
        if (sign * f0 < 0 && std::fabs(to_pericentre) < std::fabs(h)) {
            // The first piece ends one unit of anomaly past the pericentre, less whole pieces.
            const S first = std::fmod(std::fabs(f0) + 1, S(2)) / root;
            if (first > 0) (void)drift_piece(r, v, gm, stumpff_at(beta * first * first), sign * first, left);
        }
    }
    const stumpff_values<S> c = stumpff_at(S(-4));
    // A piece moves |r| by at most e^2 (< 8): from |r|^2 above max / 4096
    // the next could pass sqrt(max), where |r| no longer squares; the rest,
    // outward and far out, where the sums cancel little, goes in one solve.
    constexpr S farthest = std::numeric_limits<S>::max() / 4096;
    for (int piece = 0; piece < most_hyperbolic_pieces; ++piece) {
        const S r2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
        const S beta = 2 * gm / std::sqrt(r2) - (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        if (!(r2 <= farthest) || !(beta < 0) || !drift_piece(r, v, gm, c, sign * 2 / std::sqrt(-beta), left)) break;
    }
    if (left != 0) (void)drift_by_one_solve(r, v, gm, left, false);
}

template <class S>
void kepler_drift_body(S* r, S* v, S gm, S h, std::ptrdiff_t body) {
    check_kepler_input(r, v, gm, h, body);
    if (h == 0) return;
    if (!drift_by_one_solve(r, v, gm, h, true)) drift_in_pieces(r, v, gm, h);
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
