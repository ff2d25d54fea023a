#pragma once
// Kepler's equation in universal variables and its bracketed solve: the
// orbit's constants, the equation t(s) - h and its derivatives at s (one
// template for scalars, lanes and dual numbers), the step to a nearby s by
// the addition theorems, Danby's quartic step, the starting values, the
// f and g update. kepler_drift.hpp and kepler_lanes.hpp run them.
//
// With r0 = |r|, eta0 = r.v, beta = 2 GM / r0 - |v|^2 and zeta0 = GM - beta r0,
//     t(s) = r0 G1(s) + eta0 G2(s) + GM G3(s) = h,   G_n(s) = s^n c_n(beta s^2)
// (Danby 1988, "Fundamentals of Celestial Mechanics", 2nd ed., eq. 6.9.16),
// t'(s) = r(s), and r(h) = f r0 + g v0, v(h) = fdot r0 + gdot v0 (eq.
// 6.9.20-6.9.22). Quartic step: Danby 1988, eq. 6.6.7 (Danby & Burkardt
// 1983); series reversion: Abramowitz & Stegun 1964, eq. 3.6.25. The
// derivations of the starters, the shift and their ranges are in
// docs/planetary.md ("The Kepler solve").
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "stumpff.hpp"

namespace sympl {

// Evaluations of Kepler's equation the scalar solve may spend (quartic steps
// and bisections together); a bracket of doubles is bisected to its last bit
// well within it.
inline constexpr int kepler_max_iterations = 300;

namespace detail {

// What the solve needs of one orbit, from r0, v0, GM and h.
template <class S>
struct kepler_orbit {
    S r0, eta0, beta, zeta0, gm, h;  // h reduced by whole periods when elliptic
};

// The period 2 pi GM / beta^(3/2) of an elliptic orbit, for any scalar T.
template <class T, class G>
T kepler_period(const G& gm, const T& beta) {
    using std::sqrt;
    using S = primal_t<T>;
    return S(2 * std::numbers::pi_v<S>) * gm / (beta * sqrt(beta));
}

template <class S>
kepler_orbit<S> make_orbit(S r0, S eta0, S v2, S gm, S h) {
    kepler_orbit<S> o{r0, eta0, 2 * gm / r0 - v2, S(0), gm, h};
    o.zeta0 = gm - o.beta * r0;
    const S u = h / r0;
    // beta u^2 <= 2 puts h within half a period (docs/planetary.md): no square root.
    if (o.beta > 0 && !(o.beta * u * u <= 2)) {
        // Whole periods taken off (the flow is periodic): |h| <= P/2 keeps |beta s^2| <= (pi + 2)^2.
        const S period = kepler_period(gm, o.beta);
        if (std::fabs(h) > period / 2) {
            const S turns = std::nearbyint(h / period);
            o.h = std::fma(-turns, period, h);
        }
    }
    return o;
}

// Kepler's equation and its derivatives at s from the c_k at beta s^2
// (Danby 1988, eq. 6.9.16-6.9.19), for scalars, lanes and dual numbers alike:
// f = t(s) - h = a + b + c - h, r = t', dr = t'', ddr = t'''.
template <class T>
struct kepler_terms {
    T g1, g2, g3, a, b, c, f, r, dr, ddr;
};

template <class T, class R, class E, class Z, class B, class G, class H, class U>
[[gnu::always_inline]] inline kepler_terms<T> kepler_equation(const R& r0, const E& eta0, const Z& zeta0, const B& beta,
                                                              const G& gm, const H& h, const U& s,
                                                              const stumpff_values<T>& c) {
    kepler_terms<T> k;
    const U ss = s * s;
    k.g1 = s * c.c1, k.g2 = ss * c.c2, k.g3 = ss * s * c.c3;
    k.a = r0 * k.g1, k.b = eta0 * k.g2, k.c = gm * k.g3;
    k.f = (k.a + k.b + k.c) - h;
    k.r = r0 * c.c0 + eta0 * k.g1 + gm * k.g2;
    k.dr = eta0 * c.c0 + zeta0 * k.g1;
    k.ddr = zeta0 * c.c0 - eta0 * beta * k.g1;
    return k;
}

// The rounding level of f.
template <class S>
[[gnu::always_inline]] inline S kepler_noise(const kepler_terms<S>& k, S h) {
    return 8 * std::numeric_limits<S>::epsilon() * (std::fabs(k.a) + std::fabs(k.b) + std::fabs(k.c) + std::fabs(h));
}

// Kepler's equation reverted as a series in u = h / r0 to u^5, in A = eta0 u
// / (2 r0), B = zeta0 u^2 / (6 r0), w = beta u^2 (Abramowitz & Stegun 1964,
// eq. 3.6.25; docs/planetary.md).
template <class S>
[[gnu::always_inline]] inline S series_start(S u, S A, S B, S w) {
    const S AA = A * A;
    const S third = 2 * AA - B;
    // Products by the rounded 1/12 and 1/20: a division each would cost the
    // short-drift lanes more than the rest of the starter (a last-bit change
    // of a starting value, which the solve then corrects).
    const S fourth = A * (5 * B - 5 * AA + w * (S(1) / 12));
    const S fifth = AA * (14 * AA - 21 * B - w / 2) + B * (3 * B + w * (S(1) / 20));
    return u + u * (((fifth + fourth) + third) - A);
}

// f - 1, g, fdot and gdot - 1 from the solved G's (Danby 1988, eq.
// 6.9.20-6.9.22), any scalar T; applied as increments (apply_f_and_g), so
// that a short drift adds a small change to r0 and v0.
template <class T>
struct f_and_g {
    T fm1, g, fdot, gdm1;
};

template <class T, class R, class E, class G>
f_and_g<T> f_and_g_at(const R& r0, const E& eta0, const G& gm, const T& g1, const T& g2, const T& r) {
    return {-gm * g2 / r0, r0 * g1 + eta0 * g2, -gm * g1 / (r * r0), -gm * g2 / r};
}

// The same with 1/r0 and 1/r at hand (the short-drift lanes: products in
// place of the divisions, the last bit not always the same).
template <class T>
[[gnu::always_inline]] inline f_and_g<T> f_and_g_by_reciprocals(T r0, T eta0, T gm, T g1, T g2, T per_r0, T per_r) {
    return {-gm * g2 * per_r0, r0 * g1 + eta0 * g2, -gm * g1 * per_r * per_r0, -gm * g2 * per_r};
}

template <class T, class C>
[[gnu::always_inline]] inline void apply_f_and_g(const f_and_g<C>& k, T& x, T& y, T& z, T& vx, T& vy, T& vz) {
    const T px = x + (k.fm1 * x + k.g * vx), py = y + (k.fm1 * y + k.g * vy), pz = z + (k.fm1 * z + k.g * vz);
    const T qx = vx + (k.fdot * x + k.gdm1 * vx), qy = vy + (k.fdot * y + k.gdm1 * vy),
            qz = vz + (k.fdot * z + k.gdm1 * vz);
    x = px, y = py, z = pz, vx = qx, vy = qy, vz = qz;
}

// One orbit's equation at s with its rounding level, for the scalar solve.
template <class S>
struct kepler_residual {
    S f, r, dr, ddr;      // t(s) - h, t' = r, t'' = r', t''' = r''
    S noise;              // rounding level of f
    S c0, g1, g2;         // G0 = c0, G1, G2 at s
    S s;                  // the point itself
};

template <class S>
kepler_residual<S> residual_at(const kepler_orbit<S>& o, S s) {
    S x = o.beta * s * s;
    stumpff_values<S> c;
    stumpff_lanes<S, 1>(&x, &c.c0, &c.c1, &c.c2, &c.c3);
    const kepler_terms<S> k = kepler_equation(o.r0, o.eta0, o.zeta0, o.beta, o.gm, o.h, s, c);
    return {k.f, k.r, k.dr, k.ddr, kepler_noise(k, o.h), c.c0, k.g1, k.g2, s};
}

// G_k(d) = d^k c_k(beta d^2), k = 0..3, to y^2 in y = beta d^2: for the small
// shifts, |y| <= 2^-16, of residual_shifted and the short-drift lanes.
template <class S>
struct small_shift {
    S g0, g1, g2, g3;
};

template <class S>
[[gnu::always_inline]] inline small_shift<S> small_shift_at(S beta, S d) {
    const S y = beta * d * d;
    return {1 - y * (S(1) / 2 - y * (S(1) / 24)), d * (1 - y * (S(1) / 6 - y * (S(1) / 120))),
            d * d * (S(1) / 2 - y * (S(1) / 24 - y * (S(1) / 720))),
            d * d * d * (S(1) / 6 - y * (S(1) / 120 - y * (S(1) / 5040)))};
}

// The equation at s + d carried from its values at s by the addition
// theorems of the G's (docs/planetary.md, "The Kepler solve"), exact for any
// d; taken for |beta d^2| <= 2^-16 and |d| <= |s| / 16. The noise stays k's.
template <class S>
kepler_residual<S> residual_shifted(const kepler_orbit<S>& o, const kepler_residual<S>& k, S d) {
    const small_shift<S> G = small_shift_at(o.beta, d);
    kepler_residual<S> n;
    n.f = k.f + (k.r * d + (k.dr * G.g2 + k.ddr * G.g3));
    n.noise = k.noise;
    n.r = k.r + (k.dr * G.g1 + k.ddr * G.g2);
    n.dr = k.dr * G.g0 + k.ddr * G.g1;
    n.ddr = k.ddr * G.g0 - o.beta * k.dr * G.g1;
    n.c0 = k.c0 - o.beta * (k.g1 * G.g1 + k.c0 * G.g2);
    n.g1 = k.g1 + (k.c0 * G.g1 - o.beta * k.g1 * G.g2);
    n.g2 = k.g2 + (k.g1 * G.g1 + k.c0 * G.g2);
    n.s = k.s + d;
    return n;
}

// Danby's quartic correction (Danby 1988, eq. 6.6.7), or for a small step,
// |a2 d1| and |a3 d1^2| <= 2^-16, the cubic reverted as a series in the Newton
// step d1 (Abramowitz & Stegun 1964, eq. 3.6.25): one division, not three.
// The series form, from d1, a2 d1 and a3 d1^2.
template <class S>
[[gnu::always_inline]] inline S quartic_series_step(S d1, S a2d, S a3dd) {
    return d1 * (1 - a2d + (2 * a2d * a2d - a3dd));
}

template <class S>
S quartic_step(S f, S r, S dr, S ddr) {
    const S per_r = 1 / r, d1 = -f * per_r;
    const S a2d = dr * per_r / 2 * d1, a3dd = ddr * per_r * (S(1) / 6) * d1 * d1;
    if (std::fabs(a2d) <= S(0x1p-16) && std::fabs(a3dd) <= S(0x1p-16)) return quartic_series_step(d1, a2d, a3dd);
    const S d2 = -f / (r + d1 * dr / 2);
    return -f / (r + d2 * dr / 2 + d2 * d2 * ddr / 6);
}

// Starting value of s: series_start for a short arc of a nearly circular
// orbit (|A| + |B| <= 1/8, |w| <= 1); else the cubic r0 s + eta0 s^2/2 +
// zeta0 s^3/6 = h by Newton for a short arc (|beta| s^2 <= 1); else the
// anomaly, elliptic E = M + 0.85 e sign(sin M), hyperbolic F = sign(M)
// ln(2|M|/e + 1.8) (Danby 1988, sec. 6.6 and 6.9; Danby & Burkardt 1983).
// Only the number of iterations depends on it: the solve brackets the root.
template <class S>
S starting_value(const kepler_orbit<S>& o) {
    {
        const S per_r0 = 1 / o.r0, u = o.h * per_r0;
        const S A = o.eta0 * u * per_r0 / 2, B = o.zeta0 * u * u * per_r0 * (S(1) / 6), w = o.beta * u * u;
        if (std::fabs(A) + std::fabs(B) <= S(0.125) && std::fabs(w) <= 1) return series_start(u, A, B, w);
    }
    S s = o.h / o.r0;
    for (int i = 0; i < 3; ++i) {
        const S p = s * (o.r0 + s * (o.eta0 / 2 + s * o.zeta0 / 6)) - o.h;
        const S dp = o.r0 + s * (o.eta0 + s * o.zeta0 / 2);
        if (!(dp > 0)) break;
        s -= p / dp;
    }
    if (std::isfinite(s) && std::fabs(o.beta) * s * s <= 1) return s;
    constexpr S pi = std::numbers::pi_v<S>;
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

}  // namespace detail
}  // namespace sympl
