#pragma once
// The exact Kepler flow: two-body motion of a body about a central mass GM
// over a time h (either sign), elliptic, parabolic or hyperbolic, in
// universal variables (Stumpff 1959; Danby 1988, "Fundamentals of Celestial
// Mechanics", 2nd ed., ch. 6.7-6.9). It is the drift of the Wisdom-Holman
// splitting: each planet moves on its Kepler orbit about the star.
//
// With r0 = |r|, eta0 = r.v, beta = 2 GM / r0 - |v|^2 (= GM / a) and
// zeta0 = GM - beta r0, the universal anomaly s solves Kepler's equation
//     t(s) = r0 G1(s) + eta0 G2(s) + GM G3(s) = h,      G_n(s) = s^n c_n(beta s^2)
// (Danby 1988, eq. 6.9.16), whose derivative t'(s) = r(s) = r0 G0 + eta0 G1 + GM G2
// is the distance, so t is increasing and the root unique. Then the f and g
// functions (Danby 1988, eq. 6.9.20-6.9.22)
//     f = 1 - GM G2 / r0,   g = r0 G1 + eta0 G2,   fdot = -GM G1 / (r r0),   gdot = 1 - GM G2 / r
// give r(h) = f r0 + g v0, v(h) = fdot r0 + gdot v0.
//
// Accuracy: an elliptic drift longer than half a period is first reduced by
// whole periods (the flow is periodic; Wisdom & Hernandez 2015, MNRAS 453,
// 3015, do the same), which keeps beta s^2 <= (pi + 2)^2; the Stumpff functions
// are summed as series at |x| <= 0.1 and brought back up by the quarter-angle
// recurrences (Danby 1988, sec. 6.9). The root is found by Danby's quartic
// iteration (Danby 1988, eq. 6.6.7, after Danby & Burkardt 1983) from a
// starting value (Kepler's equation reverted as a series in h for short
// drifts of nearly circular orbits, a cubic in s for other short drifts,
// Danby's "M + 0.85 e" starter otherwise), kept inside a bracket [lo, hi] of
// the root and replaced by bisection whenever it leaves the bracket or
// stalls: the solve always ends, in at most kepler_max_iterations
// evaluations. A small last step is evaluated from the point before by the
// addition theorems of the G's rather than by the series. A Wisdom-Holman
// drift of the outer planets (h ~ 1/20 of Jupiter's period) sums the series
// once: one quartic step from the series starter reaches rounding.
//
// kepler_drift_all drifts many independent bodies held as structure of arrays:
// in lanes of `kepler_lanes` bodies (the last, or only, group narrower), each
// stage for all lanes before the next. A short drift (the Wisdom-Holman
// case) takes the scalar solve's path in the lanes: series starter, one
// summation of the Stumpff series, one quartic step, the convergence test.
// The lanes it leaves run a fixed number of quartic iterations together, with
// a per-lane convergence mask; a lane that has not converged by then is
// redone by the scalar drift with its bracket. All give the same state to
// rounding.
//
// Bad input (a body at the central mass, GM <= 0, non-finite numbers) is an
// invalid_argument naming the value and, in kepler_drift_all, the body.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <type_traits>

#include <Eigen/Core>

#include "../core/error.hpp"

namespace sympl {

// Evaluations of Kepler's equation the scalar solve may spend (quartic steps
// and bisections together); a bracket of doubles is bisected to its last bit
// well within it.
inline constexpr int kepler_max_iterations = 300;
// Bodies per lane group of kepler_drift_all, and the quartic iterations all
// lanes run together before a lane falls back to the scalar solve.
inline constexpr int kepler_lanes = 8;
inline constexpr int kepler_lane_iterations = 6;

namespace detail {

// How many terms of Stumpff's series reach S's rounding at |x| <= bound: n,
// the first left out of c2's being bound^n / (2n + 2)! <= eps / 64, a
// sixteenth of c2's rounding (eps/2 of its 1/2). c3's, bound^n / (2n + 3)! against 1/6, is
// smaller still, and c0 = 1 - x c2, c1 = 1 - x c3 carry x times these. (For
// x < 0 the terms do not alternate, and the rest is below 1.001 times the
// first.) For double: 7 terms at |x| <= 0.1, 5 at 1e-2, 4 at 1e-3.
template <class S>
constexpr int stumpff_terms(long double bound) {
    long double term = 0.5L;  // c2's term n at |x| = bound: bound^n / (2n + 2)!
    for (int n = 1;; ++n) {
        term *= bound / ((2 * n + 1) * (2 * n + 2));
        if (term <= static_cast<long double>(std::numeric_limits<S>::epsilon()) / 64 || n == 12) return n;
    }
}

// Stumpff's functions c_k(x) = sum_j (-x)^j / (2j + k)!, k = 0..3, for W
// lanes at once (W = 1: one body). x is divided by 4 until |x| <= 0.1, where
// the series is summed to stumpff_terms<S>(0.1) terms (fewer for one body at
// |x| <= 1e-2 or 1e-3, as the short drifts of the outer planets have), and the
// quarter-angle recurrences bring it back (Danby 1988, sec. 6.9):
//     c3(4x) = (c2(x) + c0(x) c3(x)) / 4,  c2(4x) = c1(x)^2 / 2,  c1(4x) = c0(x) c1(x).
// c0 is taken at each level as 1 - x c2 rather than by c0(4x) = 2 c0(x)^2 - 1,
// which multiplies c0's absolute error by 4 per level; this way every c_k
// keeps an absolute error of a few units of rounding for |x| up to (pi + 2)^2.
template <class S, int W>
void stumpff_lanes(const S* x_in, S* c0, S* c1, S* c2, S* c3) {
    // 1/m!, m = 0..25: c2's terms are 1/(2j + 2)!, c3's 1/(2j + 3)!, j < 12.
    static constexpr auto inverse_factorial = [] {
        std::array<long double, 26> a{};
        long double m_factorial = 1;
        a[0] = 1;
        for (int m = 1; m < 26; ++m) a[std::size_t(m)] = 1 / (m_factorial *= m);
        return a;
    }();
    constexpr int terms = stumpff_terms<S>(0.1L), terms_2 = stumpff_terms<S>(1e-2L), terms_3 = stumpff_terms<S>(1e-3L);
    S x[W];
    int levels[W];
    int most = 0;
    for (int l = 0; l < W; ++l) {
        x[l] = x_in[l];
        levels[l] = 0;
    }
    // |x| <= max double needs at most ~520 quarterings; finite x always ends.
    for (bool more = true; more;) {
        more = false;
        for (int l = 0; l < W; ++l) {
            const bool big = std::fabs(x[l]) > S(0.1);
            x[l] = big ? x[l] * S(0.25) : x[l];
            levels[l] += big ? 1 : 0;
            more = more || big;
        }
        most += more ? 1 : 0;
        if (most > 1100) break;  // only a non-finite x gets here
    }
    // Lanes sum a fixed number of terms (the loops vectorise); one body as few as its |x| needs.
    int n = terms;
    if constexpr (W == 1) n = std::fabs(x[0]) <= S(1e-3) ? terms_3 : std::fabs(x[0]) <= S(1e-2) ? terms_2 : terms;
    for (int l = 0; l < W; ++l) {
        const S y = x[l];
        // Horner: c2 = 1/2! - y/4! + y^2/6! - ..., c3 = 1/3! - y/5! + ...
        S s2 = S(inverse_factorial[std::size_t(2 * n)]), s3 = S(inverse_factorial[std::size_t(2 * n + 1)]);
        for (int j = n - 2; j >= 0; --j) {
            s2 = S(inverse_factorial[std::size_t(2 * j + 2)]) - y * s2;
            s3 = S(inverse_factorial[std::size_t(2 * j + 3)]) - y * s3;
        }
        c2[l] = s2;
        c3[l] = s3;
        c1[l] = 1 - y * s3;
        c0[l] = 1 - y * s2;
    }
    for (int level = most - 1; level >= 0; --level)
        for (int l = 0; l < W; ++l) {
            const bool up = level < levels[l];
            const S n3 = (c2[l] + c0[l] * c3[l]) * S(0.25);
            const S n2 = c1[l] * c1[l] * S(0.5);
            const S n1 = c0[l] * c1[l];
            const S nx = x[l] * 4;
            const S n0 = 1 - nx * n2;
            c3[l] = up ? n3 : c3[l];
            c2[l] = up ? n2 : c2[l];
            c1[l] = up ? n1 : c1[l];
            c0[l] = up ? n0 : c0[l];
            x[l] = up ? nx : x[l];
        }
}

// What the solve needs of one orbit, from r0, v0, GM and h.
template <class S>
struct kepler_orbit {
    S r0, eta0, beta, zeta0, gm, h;  // h reduced by whole periods when elliptic
};

template <class S>
kepler_orbit<S> make_orbit(S r0, S eta0, S v2, S gm, S h) {
    kepler_orbit<S> o{r0, eta0, 2 * gm / r0 - v2, S(0), gm, h};
    o.zeta0 = gm - o.beta * r0;
    const S u = h / r0;
    // beta <= 2 GM / r0 bounds (n h)^2 = beta^3 h^2 / GM^2 by 4 beta u^2: with
    // beta u^2 <= 2, n |h| <= sqrt(8) < pi and h is within half a period
    // (the short drifts of a Wisdom-Holman step skip the square root).
    if (o.beta > 0 && !(o.beta * u * u <= 2)) {
        // Whole periods P = 2 pi GM / beta^(3/2) taken off (the flow is
        // periodic): |h| <= P/2 keeps |beta s^2| <= (pi + 2)^2.
        const S period = S(2 * 3.14159265358979323846264338327950288L) * gm / (o.beta * std::sqrt(o.beta));
        if (std::fabs(h) > period / 2) {
            const S turns = std::nearbyint(h / period);
            o.h = std::fma(-turns, period, h);
        }
    }
    return o;
}

// Kepler's equation and its derivatives at s (Danby 1988, eq. 6.9.16-6.9.19).
template <class S>
struct kepler_residual {
    S f, r, dr, ddr;      // t(s) - h, t' = r, t'' = r', t''' = r''
    S noise;              // rounding level of f
    S c0, g1, g2;         // G0 = c0, G1, G2 at s
    S s;                  // the point itself
};

template <class S>
kepler_residual<S> residual_at(const kepler_orbit<S>& o, S s) {
    S x = o.beta * s * s, c0, c1, c2, c3;
    stumpff_lanes<S, 1>(&x, &c0, &c1, &c2, &c3);
    kepler_residual<S> k;
    const S ss = s * s;
    const S g1 = s * c1, g2 = ss * c2, g3 = ss * s * c3;
    const S a = o.r0 * g1, b = o.eta0 * g2, c = o.gm * g3;
    k.f = (a + b + c) - o.h;
    k.noise = 8 * std::numeric_limits<S>::epsilon() * (std::fabs(a) + std::fabs(b) + std::fabs(c) + std::fabs(o.h));
    k.r = o.r0 * c0 + o.eta0 * g1 + o.gm * g2;
    k.dr = o.eta0 * c0 + o.zeta0 * g1;
    k.ddr = o.zeta0 * c0 - o.eta0 * o.beta * g1;
    k.c0 = c0;
    k.g1 = g1;
    k.g2 = g2;
    k.s = s;
    return k;
}

// The same at s + d, carried from the values k at s instead of summing the
// Stumpff series again: the last step of a converging solve is small, and
// this is its whole cost. t(s), r(s) and the G's solve y''' = -beta y'
// (G0' = -beta G1, G1' = G0, G2' = G1, r'' = GM - beta r), whose solutions are
// y(s + d) = y + y' G1(d) + y'' G2(d), so, exactly for any d,
//     t(s + d) = t + r d + r' G2(d) + r'' G3(d),   r(s + d) = r + r' G1(d) + r'' G2(d),
//     r'(s + d) = r' G0(d) + r'' G1(d),            r''(s + d) = r'' G0(d) - beta r' G1(d),
//     G1(s + d) = G1 + G0 G1(d) - beta G1 G2(d),   G2(s + d) = G2 + G1 G1(d) + G0 G2(d),
//     G0(s + d) = G0 - beta (G1 G1(d) + G0 G2(d))
// (the addition theorems of cos and sin, cosh and sinh, in the universal
// G's). Taken only for |beta d^2| <= 2^-16 and |d| <= |s| / 16: the
// G_k(d) = d^k c_k(beta d^2) then need the c_k to y^2 only, the first term left
// out, |y|^3 / (k + 6)!, being below 2^-48 / 720 of c_k's leading 1/k!, and
// s + d is near s, so every sum above adds terms no larger than the result's
// scale (no cancellation beyond a direct evaluation's). The rounding of t(s)
// is carried along, as it would be met again at s + d: the noise stays k's.
template <class S>
kepler_residual<S> residual_shifted(const kepler_orbit<S>& o, const kepler_residual<S>& k, S d) {
    const S y = o.beta * d * d;
    const S G0d = 1 - y * (S(1) / 2 - y * (S(1) / 24));
    const S G1d = d * (1 - y * (S(1) / 6 - y * (S(1) / 120)));
    const S G2d = d * d * (S(1) / 2 - y * (S(1) / 24 - y * (S(1) / 720)));
    const S G3d = d * d * d * (S(1) / 6 - y * (S(1) / 120 - y * (S(1) / 5040)));
    kepler_residual<S> n;
    n.f = k.f + (k.r * d + (k.dr * G2d + k.ddr * G3d));
    n.noise = k.noise;
    n.r = k.r + (k.dr * G1d + k.ddr * G2d);
    n.dr = k.dr * G0d + k.ddr * G1d;
    n.ddr = k.ddr * G0d - o.beta * k.dr * G1d;
    n.c0 = k.c0 - o.beta * (k.g1 * G1d + k.c0 * G2d);
    n.g1 = k.g1 + (k.c0 * G1d - o.beta * k.g1 * G2d);
    n.g2 = k.g2 + (k.g1 * G1d + k.c0 * G2d);
    n.s = k.s + d;
    return n;
}

// Danby's quartic correction (Danby 1988, eq. 6.6.7): Newton, then two
// refinements with the second and third derivatives. Both it and the cubic
// r d + r' d^2/2 + r'' d^3/6 = -f reverted as a series in the Newton step d1
// (Abramowitz & Stegun 1964, eq. 3.6.25),
//     d = d1 - a2 d1^2 + (2 a2^2 - a3) d1^3,   a2 = r' / (2 r),  a3 = r'' / (6 r),
// miss the cubic's root by O(d1^4) (by (a2^3 - a2 a3) d1^4 and five times
// that): the series, one division instead of three in a row, is taken for a
// small step, |a2 d1| and |a3 d1^2| <= 2^-16, where it misses by less than
// 2^-29 of d1 (a step from within 1e-6 of the root, as the series starter
// gives the outer planets, lands at rounding either way).
template <class S>
S quartic_step(S f, S r, S dr, S ddr) {
    const S per_r = 1 / r, d1 = -f * per_r;
    const S a2d = dr * per_r / 2 * d1, a3dd = ddr * per_r / 6 * d1 * d1;
    if (std::fabs(a2d) <= S(0x1p-16) && std::fabs(a3dd) <= S(0x1p-16)) return d1 * (1 - a2d + (2 * a2d * a2d - a3dd));
    const S d2 = -f / (r + d1 * dr / 2);
    return -f / (r + d2 * dr / 2 + d2 * d2 * ddr / 6);
}

// Starting value of s. For a short arc of a nearly circular orbit (the
// Wisdom-Holman drift), Kepler's equation reverted as a series in u = h / r0:
// its Taylor series in s has t^(k)(0) = r0, eta0, zeta0, -beta eta0,
// -beta zeta0 (t''' = r'' = GM - beta r, so t^(k+2) = -beta t^(k) for k >= 2; Danby
// 1988, sec. 6.9), i.e. t / r0 = s + a2 s^2 + ... + a5 s^5 + O(s^6) with
// a_k = t^(k)(0) / (k! r0), and its reversion (Abramowitz & Stegun 1964, eq. 3.6.25)
//     s = u - a2 u^2 + (2 a2^2 - a3) u^3 + (5 a2 a3 - 5 a2^3 - a4) u^4
//           + (14 a2^4 - 21 a2^2 a3 + 6 a2 a4 + 3 a3^2 - a5) u^5 + O(u^6).
// In A = a2 u = eta0 u / (2 r0), B = a3 u^2 = zeta0 u^2 / (6 r0) and
// w = beta u^2 (a4 u^3 = -w A / 12, a5 u^4 = -w B / 20) every correction to
// s = u carries A or B, both of the size of the eccentricity (eta0 =
// sqrt(GM a) e sin E, zeta0 = GM e cos E). Measured on the outer solar
// system's Wisdom-Holman drifts at h = 1/20 of Jupiter's period, it starts
// within 1e-6 of the root for Jupiter and 1e-8 for the planets beyond (the
// cubic: 1e-4 and 5e-6), and one quartic step reaches rounding. (The
// previous drift's s of the same planet, the same h a step earlier, is off
// by 2e-2 and 7e-3: not a better start.) Taken while |A| + |B| <= 1/8 and |w| <= 1,
// where the u^6 term left out (-42 A^5 + 84 A^3 B - 28 A B^2 + ..., with w)
// stays below ~1e-2 of s, as does the cubic's own s^4 term. Otherwise the cubic
// r0 s + eta0 s^2/2 + zeta0 s^3/6 = h, Kepler's equation to third order in s
// (Danby 1988, sec. 6.9), by Newton from s = h / r0, for a short arc
// (|beta| s^2 <= 1); else the anomaly:
// elliptic E = M + 0.85 e sign(sin M), hyperbolic F = sign(M) ln(2|M|/e + 1.8)
// (Danby 1988, sec. 6.6 and 6.9; Danby & Burkardt 1983), as s = dE / sqrt(beta).
// Only the number of iterations depends on the starter: solve_universal
// brackets the root whatever it is handed.
template <class S>
S starting_value(const kepler_orbit<S>& o) {
    {
        const S per_r0 = 1 / o.r0, u = o.h * per_r0;
        const S A = o.eta0 * u * per_r0 / 2, B = o.zeta0 * u * u * per_r0 / 6, w = o.beta * u * u;
        if (std::fabs(A) + std::fabs(B) <= S(0.125) && std::fabs(w) <= 1) {
            const S AA = A * A;
            const S third = 2 * AA - B;
            const S fourth = A * (5 * B - 5 * AA + w / 12);
            const S fifth = AA * (14 * AA - 21 * B - w / 2) + B * (3 * B + w / 20);
            return u + u * (((fifth + fourth) + third) - A);
        }
    }
    S s = o.h / o.r0;
    for (int i = 0; i < 3; ++i) {
        const S p = s * (o.r0 + s * (o.eta0 / 2 + s * o.zeta0 / 6)) - o.h;
        const S dp = o.r0 + s * (o.eta0 + s * o.zeta0 / 2);
        if (!(dp > 0)) break;
        s -= p / dp;
    }
    if (std::isfinite(s) && std::fabs(o.beta) * s * s <= 1) return s;
    constexpr S pi = S(3.14159265358979323846264338327950288L);
    if (o.beta > 0) {
        const S sb = std::sqrt(o.beta), n = o.beta * sb / o.gm;
        const S ec = o.zeta0 / o.gm, es = o.eta0 * sb / o.gm, e = std::hypot(ec, es);
        const S e0 = std::atan2(es, ec), m1 = e0 - es + n * o.h;
        const S m = std::remainder(m1, 2 * pi);
        const S e1 = m + S(0.85) * e * (std::sin(m) >= 0 ? 1 : -1);
        return (e1 + (m1 - m) - e0) / sb;
    }
    if (o.beta < 0) {
        const S sb = std::sqrt(-o.beta), n = -o.beta * sb / o.gm;
        const S ec = o.zeta0 / o.gm, es = o.eta0 * sb / o.gm;
        const S e = std::sqrt(std::max(S(0), (ec - es) * (ec + es)));
        if (e > 0) {
            const S f0 = std::asinh(es / e), m1 = es - f0 + n * o.h;
            const S f1 = (m1 >= 0 ? 1 : -1) * std::log(2 * std::fabs(m1) / e + S(1.8));
            return (f1 - f0) / sb;
        }
    }
    return s;
}

// Kepler's equation solved for s inside a bracket of its root: quartic steps
// while they stay inside and shrink, bisection (geometric while the bracket
// spans decades) when not. Ends in at most kepler_max_iterations evaluations.
// A point a small step from one where the series were summed is evaluated
// by residual_shifted from there (never from a shifted one, so its rounding
// is that of one shift): a converging solve sums the series once less.
template <class S>
kepler_residual<S> solve_universal(const kepler_orbit<S>& o, S guess) {
    constexpr S inf = std::numeric_limits<S>::infinity(), eps = std::numeric_limits<S>::epsilon();
    const bool forward = o.h > 0;
    // t(s) increases and t(0) = 0: the root has the sign of h.
    S lo = forward ? S(0) : -inf, hi = forward ? inf : S(0);
    S s = (std::isfinite(guess) && guess > lo && guess < hi) ? guess : o.h / o.r0;
    kepler_residual<S> best{}, summed{};
    S best_f = inf, last_step = inf, step_before = inf, summed_at = 0;
    bool shift_from_summed = false;
    for (int it = 0; it < kepler_max_iterations; ++it) {
        const S d = s - summed_at;  // exact: within |s| / 16 of summed_at when taken
        kepler_residual<S> k;
        if (shift_from_summed && std::fabs(o.beta) * d * d <= S(0x1p-16) && 16 * std::fabs(d) <= std::fabs(summed_at)) {
            k = residual_shifted(o, summed, d);
            shift_from_summed = false;
        } else {
            k = residual_at(o, s);
            summed = k;
            summed_at = s;
            shift_from_summed = std::isfinite(k.f) && std::isfinite(k.r);
        }
        bool done = false;
        if (!std::isfinite(k.f) || !std::isfinite(k.r)) {
            // Only |s| far beyond the root overflows the c_k: the root lies nearer 0.
            (forward ? hi : lo) = s;
        } else {
            if (std::fabs(k.f) < best_f) { best_f = std::fabs(k.f); best = k; }
            if (k.f < 0) lo = s; else hi = s;
            done = std::fabs(k.f) <= k.noise || std::fabs(k.f / k.r) <= 4 * eps * std::fabs(s);
        }
        if (done) return k;
        S next = s;
        if (std::isfinite(k.f) && std::isfinite(k.r)) next = s + quartic_step(k.f, k.r, k.dr, k.ddr);
        const bool stalls = it >= 6 && std::fabs(next - s) > step_before / 2;
        if (!(next > lo && next < hi) || stalls) {
            if (std::isinf(hi)) next = std::max(2 * lo, o.h / o.r0);        // forward, root beyond lo
            else if (std::isinf(lo)) next = std::min(2 * hi, o.h / o.r0);   // backward, root below hi
            else if (lo == 0 || hi == 0) next = (lo + hi) / 4;              // towards the root's sign
            else if (std::fabs(hi) > 4 * std::fabs(lo) || std::fabs(lo) > 4 * std::fabs(hi))
                next = (forward ? 1 : -1) * std::sqrt(lo * hi);            // geometric: decades first
            else next = lo + (hi - lo) / 2;
            if (!(next > lo && next < hi)) return best_f < inf ? best : k;  // bracket down to adjacent doubles
        }
        step_before = last_step;
        last_step = std::fabs(next - s);
        s = next;
    }
    return best;
}

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

// r(h) = f r0 + g v0, v(h) = fdot r0 + gdot v0 from the solved G's (Danby
// 1988, eq. 6.9.20-6.9.22), written as increments so that a short drift adds
// a small change to r0 and v0.
template <class S>
void apply_f_and_g(S* r, S* v, S r0, S eta0, S gm, S g1, S g2, S rr) {
    const S fm1 = -gm * g2 / r0;
    const S g = r0 * g1 + eta0 * g2;
    const S fdot = -gm * g1 / (rr * r0);
    const S gdm1 = -gm * g2 / rr;
    for (int i = 0; i < 3; ++i) {
        const S ri = r[i], vi = v[i];
        r[i] = ri + (fm1 * ri + g * vi);
        v[i] = vi + (fdot * ri + gdm1 * vi);
    }
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
    apply_f_and_g(r, v, r0, eta0, gm, k.g1, k.g2, k.r);
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

namespace detail {
// The short drift of W bodies at once, every stage done for all lanes before
// the next: the lanes are independent, so the CPU overlaps their divisions,
// square roots and series (with SSE2 only, too), and the loops vectorise. It
// is the scalar solve's path for a Wisdom-Holman drift, with its tests: the
// series starter (starting_value), the Stumpff functions summed once at it,
// one small quartic step (quartic_step's series form) and the point after it
// carried by the addition theorems (residual_shifted), where the convergence
// test of solve_universal must pass. A lane outside that range, or failing any
// of those tests, has done[l] = false and is for the bracketed solve, from
// the caller's copy (every lane of b's r and v is overwritten); a done lane
// holds the drifted state.
//
// The series starter is taken to |w| <= 2 here (the scalar solve: 1, where
// it needs no test of its own): at |w| <= 2, beta u^2 <= 2 and make_orbit
// would reduce no period, and the convergence test decides whether one step
// sufficed. On Jupiter's drifts of a fifth of its period (w ~ 1.6) it does in
// 95% of them (bench_kepler_drift). Against a long-double drift, on 2 10^5
// random orbits of a = 5..40 AU, e < 0.1, h = 0.02..0.27 periods, the lanes
// erred as the scalar solve did: at most 1.6 eps and 2.5 eps of |r| at
// |w| < 0.5 and 0.5..1, 22 and 30 eps (scalar: 23 and 24) at 1..1.5 and 1.5..2,
// where the drift is worse conditioned. |A| + |B| <= 1/8 keeps s within
// 1.2 u (|s/u - 1| <= 1/8 + 2/64 + ...), so |x| = |beta s^2| <= 2.9; it is
// tested against kepler_short_x, to which Stumpff's series is summed
// directly (stumpff_terms<S>(4) terms, 12 for double) without the quarterings
// of stumpff_lanes: fewer operations and no loop whose length depends on the
// lane. 1/r0 and 1/r are each taken once and multiplied where the scalar
// solve divides.
inline constexpr long double kepler_short_x = 4;

// All and any of several conditions, each evaluated (no short circuit: the
// lane loops stay free of branches), as ints (clang warns of & on bools).
template <class... B>
constexpr bool all_of(B... b) {
    return (int(b) & ...) != 0;
}
template <class... B>
constexpr bool any_of(B... b) {
    return (int(b) | ...) != 0;
}

// The lane loops are written so that GCC vectorises them with SSE2 (the
// default x86-64 flags) as with AVX-512: every value is computed in every
// lane and stored, and only then selected (an operation whose result only one
// arm of a condition uses is moved into that arm, and as it may trap it is
// not speculated: the loop keeps a branch); the masks are held as S, 1 or 0
// (bools beside doubles do not vectorise); the square root has a loop of its
// own (std::sqrt keeps a branch to set errno, which stops its loop from
// vectorising); and the lanes are members of one struct, which the compiler
// knows do not overlap.
template <class S, int W>
struct lane_bodies {
    S x[W], y[W], z[W], vx[W], vy[W], vz[W], gm[W];  // one struct: the compiler sees that they do not overlap
};

template <class S, int W>
void short_drift_lanes(lane_bodies<S, W>& b, S h, bool (&done)[W]) {
    constexpr S eps = std::numeric_limits<S>::epsilon(), big = std::numeric_limits<S>::max();
    S* const rx = b.x;
    S* const ry = b.y;
    S* const rz = b.z;
    S* const ux = b.vx;
    S* const uy = b.vy;
    S* const uz = b.vz;
    const S* const gm = b.gm;
    S r0[W], per_r0[W], eta0[W], beta[W], zeta0[W], s[W], ok[W];
    for (int l = 0; l < W; ++l) r0[l] = rx[l] * rx[l] + ry[l] * ry[l] + rz[l] * rz[l];
    for (int l = 0; l < W; ++l) r0[l] = std::sqrt(r0[l]);
    for (int l = 0; l < W; ++l) {
        per_r0[l] = 1 / r0[l];
        eta0[l] = rx[l] * ux[l] + ry[l] * uy[l] + rz[l] * uz[l];
        const S v2 = ux[l] * ux[l] + uy[l] * uy[l] + uz[l] * uz[l];
        beta[l] = 2 * gm[l] * per_r0[l] - v2;
        zeta0[l] = gm[l] - beta[l] * r0[l];
        // starting_value's series (Kepler's equation reverted in u = h / r0).
        const S u = h * per_r0[l];
        const S A = eta0[l] * u * per_r0[l] / 2, B = zeta0[l] * u * u * per_r0[l] / 6, w = beta[l] * u * u;
        const S AA = A * A;
        const S third = 2 * AA - B;
        const S fourth = A * (5 * B - 5 * AA + w / 12);
        const S fifth = AA * (14 * AA - 21 * B - w / 2) + B * (3 * B + w / 20);
        s[l] = u + u * (((fifth + fourth) + third) - A);
        ok[l] = all_of(std::fabs(A) + std::fabs(B) <= S(0.125), std::fabs(w) <= 2) ? S(1) : S(0);
    }
    bool any = false;
    for (int l = 0; l < W; ++l) {
        any = any || ok[l] != 0;
        done[l] = false;
    }
    if (!any) return;
    // Stumpff's series at x = beta s^2 (as stumpff_lanes, without quartering).
    constexpr int terms = stumpff_terms<S>(kepler_short_x);
    static constexpr auto inverse_factorial = [] {
        std::array<S, 2 * terms + 2> a{};
        long double m_factorial = 1;
        a[0] = 1;
        for (int m = 1; m < 2 * terms + 2; ++m) a[std::size_t(m)] = S(1 / (m_factorial *= m));
        return a;
    }();
    S c0[W], g1[W], g2[W], f[W], noise[W], r[W], dr[W], ddr[W];
    for (int l = 0; l < W; ++l) {
        const S ss = s[l] * s[l], y = beta[l] * ss;
        ok[l] = all_of(ok[l] != 0, std::fabs(y) <= S(kepler_short_x)) ? S(1) : S(0);
        S s2 = inverse_factorial[std::size_t(2 * terms)], s3 = inverse_factorial[std::size_t(2 * terms + 1)];
        for (int j = terms - 2; j >= 0; --j) {
            s2 = inverse_factorial[std::size_t(2 * j + 2)] - y * s2;
            s3 = inverse_factorial[std::size_t(2 * j + 3)] - y * s3;
        }
        c0[l] = 1 - y * s2;
        const S c1 = 1 - y * s3;
        // Kepler's equation and its derivatives at s (residual_at).
        g1[l] = s[l] * c1;
        g2[l] = ss * s2;
        const S g3 = ss * s[l] * s3;
        const S a = r0[l] * g1[l], b = eta0[l] * g2[l], c = gm[l] * g3;
        f[l] = (a + b + c) - h;
        noise[l] = 8 * eps * (std::fabs(a) + std::fabs(b) + std::fabs(c) + std::fabs(h));
        r[l] = r0[l] * c0[l] + eta0[l] * g1[l] + gm[l] * g2[l];
        dr[l] = eta0[l] * c0[l] + zeta0[l] * g1[l];
        ddr[l] = zeta0[l] * c0[l] - eta0[l] * beta[l] * g1[l];
    }
    S per_r[W];
    for (int l = 0; l < W; ++l) per_r[l] = 1 / r[l];
    // One quartic step (quartic_step's series form: only small steps here),
    // none if s already passes solve_universal's test.
    S step[W], still[W];
    for (int l = 0; l < W; ++l) {
        const S d1 = -f[l] * per_r[l];
        const S a2d = dr[l] * per_r[l] / 2 * d1, a3dd = ddr[l] * per_r[l] / 6 * d1 * d1;
        step[l] = d1 * (1 - a2d + (2 * a2d * a2d - a3dd));
        const bool small = all_of(std::fabs(a2d) <= S(0x1p-16), std::fabs(a3dd) <= S(0x1p-16));
        const bool converged = any_of(std::fabs(f[l]) <= noise[l], std::fabs(d1) <= 4 * eps * std::fabs(s[l]));
        still[l] = converged ? S(0) : S(1);
        ok[l] = all_of(ok[l] != 0, small) ? S(1) : S(0);
    }
    for (int l = 0; l < W; ++l) step[l] = still[l] != 0 ? step[l] : S(0);
    // residual_shifted at s + d (its range: |beta d^2| <= 2^-16, |d| <= |s| / 16);
    // d = 0 gives back the values at s exactly.
    for (int l = 0; l < W; ++l) {
        const S d = step[l], y = beta[l] * d * d;
        const S G1d = d * (1 - y * (S(1) / 6 - y * (S(1) / 120)));
        const S G2d = d * d * (S(1) / 2 - y * (S(1) / 24 - y * (S(1) / 720)));
        const S G3d = d * d * d * (S(1) / 6 - y * (S(1) / 120 - y * (S(1) / 5040)));
        f[l] = f[l] + (r[l] * d + (dr[l] * G2d + ddr[l] * G3d));
        r[l] = r[l] + (dr[l] * G1d + ddr[l] * G2d);
        const S g1n = g1[l] + (c0[l] * G1d - beta[l] * g1[l] * G2d);
        const S g2n = g2[l] + (g1[l] * G1d + c0[l] * G2d);
        g1[l] = g1n;
        g2[l] = g2n;
        ok[l] = all_of(ok[l] != 0, std::fabs(y) <= S(0x1p-16), 16 * std::fabs(d) <= std::fabs(s[l])) ? S(1) : S(0);
        s[l] = s[l] + d;
    }
    S per_rn[W];
    for (int l = 0; l < W; ++l) per_rn[l] = 1 / r[l];
    // f and g (apply_f_and_g, with the reciprocals at hand), into every lane:
    // the caller takes the done ones. Done: solve_universal's test passed at
    // s + d, and the results are finite (|v| <= max, which a NaN fails).
    for (int l = 0; l < W; ++l) {
        const S fm1 = -gm[l] * g2[l] * per_r0[l];
        const S g = r0[l] * g1[l] + eta0[l] * g2[l];
        const S fdot = -gm[l] * g1[l] * per_rn[l] * per_r0[l];
        const S gdm1 = -gm[l] * g2[l] * per_rn[l];
        const S px = rx[l] + (fm1 * rx[l] + g * ux[l]), py = ry[l] + (fm1 * ry[l] + g * uy[l]),
                pz = rz[l] + (fm1 * rz[l] + g * uz[l]);
        const S qx = ux[l] + (fdot * rx[l] + gdm1 * ux[l]), qy = uy[l] + (fdot * ry[l] + gdm1 * uy[l]),
                qz = uz[l] + (fdot * rz[l] + gdm1 * uz[l]);
        rx[l] = px, ry[l] = py, rz[l] = pz;
        ux[l] = qx, uy[l] = qy, uz[l] = qz;
    }
    for (int l = 0; l < W; ++l) {
        const bool there = any_of(std::fabs(f[l]) <= noise[l], std::fabs(f[l] * per_rn[l]) <= 4 * eps * std::fabs(s[l]));
        ok[l] = all_of(ok[l] != 0, there, r[l] > 0) ? S(1) : S(0);
    }
    for (int l = 0; l < W; ++l) {
        ok[l] = all_of(ok[l] != 0, std::fabs(rx[l]) <= big, std::fabs(ry[l]) <= big, std::fabs(rz[l]) <= big,
                       std::fabs(ux[l]) <= big, std::fabs(uy[l]) <= big, std::fabs(uz[l]) <= big)
                    ? S(1)
                    : S(0);
    }
    for (int l = 0; l < W; ++l) done[l] = ok[l] != 0;
}

// The bodies idx[0..count) (count <= W; the other lanes repeat body idx[0],
// their results dropped) by a fixed number of quartic iterations in all lanes
// together, with a per-lane convergence mask (the test of solve_universal); a
// lane not converged by then is redone by the scalar drift with its bracket.
// For the lanes the short-drift path did not take. Returns the bodies redone.
template <class S, int W, class GM>
std::size_t general_lanes(const kepler_bodies<S>& b, GM gm_of, S h, const std::size_t (&idx)[W], int count) {
    constexpr S eps = std::numeric_limits<S>::epsilon();
    std::size_t fallbacks = 0;
    S rx[W], ry[W], rz[W], ux[W], uy[W], uz[W], r0[W], eta0[W], v2[W], gm[W];
    for (int l = 0; l < W; ++l) {
        const std::size_t i = idx[l < count ? l : 0];
        rx[l] = b.x[i]; ry[l] = b.y[i]; rz[l] = b.z[i];
        ux[l] = b.vx[i]; uy[l] = b.vy[i]; uz[l] = b.vz[i];
        gm[l] = gm_of(i);
    }
    for (int l = 0; l < W; ++l) {
        r0[l] = std::sqrt(rx[l] * rx[l] + ry[l] * ry[l] + rz[l] * rz[l]);
        eta0[l] = rx[l] * ux[l] + ry[l] * uy[l] + rz[l] * uz[l];
        v2[l] = ux[l] * ux[l] + uy[l] * uy[l] + uz[l] * uz[l];
    }
    // Orbit and starting value per lane (period reduction, logarithms and
    // trigonometry of the starter: scalar, once per drift).
    S beta[W], zeta0[W], hh[W], s[W];
    for (int l = 0; l < W; ++l) {
        const kepler_orbit<S> o = make_orbit(r0[l], eta0[l], v2[l], gm[l], h);
        beta[l] = o.beta;
        zeta0[l] = o.zeta0;
        hh[l] = o.h;
        s[l] = starting_value(o);
    }
    bool active[W];
    S c0[W], c1[W], c2[W], c3[W], g1[W], g2[W], rr[W];
    for (int l = 0; l < W; ++l) {
        active[l] = hh[l] != 0;
        g1[l] = g2[l] = 0;
        rr[l] = r0[l];
    }
    for (int it = 0; it < kepler_lane_iterations; ++it) {
        S x[W];
        for (int l = 0; l < W; ++l) x[l] = beta[l] * s[l] * s[l];
        stumpff_lanes<S, W>(x, c0, c1, c2, c3);
        bool any = false;
        for (int l = 0; l < W; ++l) {
            const S ss = s[l] * s[l];
            const S G1 = s[l] * c1[l], G2 = ss * c2[l], G3 = ss * s[l] * c3[l];
            const S a = r0[l] * G1, bb = eta0[l] * G2, c = gm[l] * G3;
            const S f = (a + bb + c) - hh[l];
            const S noise = 8 * eps * (std::fabs(a) + std::fabs(bb) + std::fabs(c) + std::fabs(hh[l]));
            const S r = r0[l] * c0[l] + eta0[l] * G1 + gm[l] * G2;
            const S dr = eta0[l] * c0[l] + zeta0[l] * G1;
            const S ddr = zeta0[l] * c0[l] - eta0[l] * beta[l] * G1;
            const S d1 = -f / r;
            const S d2 = -f / (r + d1 * dr / 2);
            const S d3 = -f / (r + d2 * dr / 2 + d2 * d2 * ddr / 6);
            const bool converged = std::fabs(f) <= noise || std::fabs(d1) <= 4 * eps * std::fabs(s[l]);
            const bool take = active[l];
            g1[l] = take ? G1 : g1[l];
            g2[l] = take ? G2 : g2[l];
            rr[l] = take ? r : rr[l];
            s[l] = (take && !converged) ? s[l] + d3 : s[l];
            active[l] = take && !converged;
            any = any || active[l];
        }
        if (!any) break;
    }
    for (int l = 0; l < count; ++l) {
        S r[3] = {rx[l], ry[l], rz[l]}, v[3] = {ux[l], uy[l], uz[l]};
        const std::size_t i = idx[l];
        const bool finite = std::isfinite(g1[l]) && std::isfinite(g2[l]) && std::isfinite(rr[l]) && rr[l] > 0;
        if (active[l] || !finite) {
            ++fallbacks;
            kepler_drift_body(r, v, gm[l], h, std::ptrdiff_t(i));  // the bracketed scalar solve
        } else if (hh[l] != 0) {
            apply_f_and_g(r, v, r0[l], eta0[l], gm[l], g1[l], g2[l], rr[l]);
            for (int k = 0; k < 3; ++k)
                if (!std::isfinite(r[k]) || !std::isfinite(v[k])) kepler_drift_body(r, v, gm[l], h, std::ptrdiff_t(i));
        }
        b.x[i] = r[0]; b.y[i] = r[1]; b.z[i] = r[2];
        b.vx[i] = v[0]; b.vy[i] = v[1]; b.vz[i] = v[2];
    }
    return fallbacks;
}

// Groups of W bodies (the last one padded with copies of its first body,
// their results dropped): the short-drift path in all lanes, then the lanes it
// left by general_lanes, or by the scalar solve when only one is left.
template <class S, int W, class GM>
std::size_t drift_groups(const kepler_bodies<S>& b, GM gm_of, S h, std::size_t first, std::size_t last) {
    std::size_t fallbacks = 0;
    for (; first < last; first += W) {
        const int count = int(std::min<std::size_t>(W, last - first));
        lane_bodies<S, W> lanes;
        bool done[W];
        for (int l = 0; l < W; ++l) {
            const std::size_t i = first + std::size_t(l < count ? l : 0);
            lanes.x[l] = b.x[i]; lanes.y[l] = b.y[i]; lanes.z[l] = b.z[i];
            lanes.vx[l] = b.vx[i]; lanes.vy[l] = b.vy[i]; lanes.vz[l] = b.vz[i];
            lanes.gm[l] = gm_of(i);
        }
        short_drift_lanes<S, W>(lanes, h, done);
        std::size_t rest[W];
        int left = 0;
        for (int l = 0; l < count; ++l) {
            const std::size_t i = first + std::size_t(l);
            if (!done[l]) {
                rest[left++] = i;
                continue;
            }
            b.x[i] = lanes.x[l]; b.y[i] = lanes.y[l]; b.z[i] = lanes.z[l];
            b.vx[i] = lanes.vx[l]; b.vy[i] = lanes.vy[l]; b.vz[i] = lanes.vz[l];
        }
        if (left == 1) {
            const std::size_t i = rest[0];
            S r[3] = {b.x[i], b.y[i], b.z[i]}, v[3] = {b.vx[i], b.vy[i], b.vz[i]};
            kepler_drift_body(r, v, gm_of(i), h, std::ptrdiff_t(i));
            b.x[i] = r[0]; b.y[i] = r[1]; b.z[i] = r[2];
            b.vx[i] = v[0]; b.vy[i] = v[1]; b.vz[i] = v[2];
            ++fallbacks;
        } else if (left > 1) {
            fallbacks += general_lanes<S, W>(b, gm_of, h, rest, left);
        }
    }
    return fallbacks;
}

template <class S, class GM>
std::size_t kepler_drift_lanes(const kepler_bodies<S>& b, GM gm_of, S h) {
    const std::size_t n = b.size();
    const std::span<S>* parts[] = {&b.y, &b.z, &b.vx, &b.vy, &b.vz};
    const char* names[] = {"y", "z", "vx", "vy", "vz"};
    for (int i = 0; i < 5; ++i)
        if (parts[i]->size() != n)
            throw invalid_argument("kepler_drift_all: " + std::to_string(parts[i]->size()) + " values in " + names[i] +
                                   " and " + std::to_string(n) + " in x; expected one per body in each");
    // Every body checked before any moves. The test of check_kepler_input
    // over all bodies at once (finite: |u| <= max, which a NaN fails); only
    // if it fails are they checked one by one, for the message.
    {
        constexpr S big = std::numeric_limits<S>::max();
        bool fine = std::fabs(h) <= big;
        for (std::size_t i = 0; i < n; ++i) {
            const S x = b.x[i], y = b.y[i], z = b.z[i], gm = gm_of(i);
            const S r2 = x * x + y * y + z * z;
            fine = all_of(fine, std::fabs(x) <= big, std::fabs(y) <= big, std::fabs(z) <= big,
                          std::fabs(b.vx[i]) <= big, std::fabs(b.vy[i]) <= big, std::fabs(b.vz[i]) <= big, r2 > 0,
                          r2 <= big, gm > 0, gm <= big);
        }
        if (!fine)
            for (std::size_t i = 0; i < n; ++i) {
                const S r[3] = {b.x[i], b.y[i], b.z[i]}, v[3] = {b.vx[i], b.vy[i], b.vz[i]};
                check_kepler_input(r, v, gm_of(i), h, std::ptrdiff_t(i));
            }
    }
    if (h == 0) return 0;
    // Groups of kepler_lanes, then the rest (the whole batch for the 5 planets
    // of a Wisdom-Holman step) in one group of the next even width: two
    // lanes to an SSE2 register, and the fewest padded lanes (for 5 bodies 6
    // lanes cost 15% less per step than 8 with SSE2, the same with AVX-512).
    static_assert(kepler_lanes == 8, "the rest below is fewer than 8 bodies");
    constexpr std::size_t W = kepler_lanes;
    const std::size_t full = n / W * W, rest = n - full;
    std::size_t fallbacks = drift_groups<S, kepler_lanes>(b, gm_of, h, 0, full);
    if (rest > 6) fallbacks += drift_groups<S, 8>(b, gm_of, h, full, n);
    else if (rest > 4) fallbacks += drift_groups<S, 6>(b, gm_of, h, full, n);
    else if (rest > 2) fallbacks += drift_groups<S, 4>(b, gm_of, h, full, n);
    else if (rest > 0) fallbacks += drift_groups<S, 2>(b, gm_of, h, full, n);
    return fallbacks;
}
}  // namespace detail

// Every body drifted about the same GM over h (democratic heliocentric
// coordinates: each planet about the star). Returns how many bodies the
// lanes left to the scalar solve (0 for well-behaved orbits and drifts).
template <class S>
    requires std::is_floating_point_v<S>
std::size_t kepler_drift_all(const kepler_bodies<S>& bodies, S gm, S h) {
    return detail::kepler_drift_lanes(bodies, [gm](std::size_t) { return gm; }, h);
}

// Body i drifted about gm[i] (Jacobi coordinates: each planet about the
// interior mass).
template <class S>
    requires std::is_floating_point_v<S>
std::size_t kepler_drift_all(const kepler_bodies<S>& bodies, std::span<const S> gm, S h) {
    if (gm.size() != bodies.size())
        throw invalid_argument("kepler_drift_all: " + std::to_string(gm.size()) + " values of GM for " +
                               std::to_string(bodies.size()) + " bodies; expected one per body");
    return detail::kepler_drift_lanes(bodies, [gm](std::size_t i) { return gm[i]; }, h);
}

}  // namespace sympl
