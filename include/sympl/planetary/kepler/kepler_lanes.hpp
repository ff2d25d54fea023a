#pragma once
// Many Kepler drifts at once: kepler_drift_all drifts bodies held as
// structure of arrays in lanes of `kepler_lanes` bodies (the last, or only,
// group narrower), each stage for all lanes before the next, so that the
// loops vectorise. A short drift (the Wisdom-Holman case) takes the scalar
// solve's path in the lanes: series starter, one summation of Stumpff's
// series, one quartic step, the convergence test. The lanes it leaves run a
// fixed number of quartic iterations together, with a per-lane convergence
// mask; a lane not converged by then is redone by the scalar drift
// (kepler_drift.hpp) with its bracket. All give the same state to rounding.
// The lanes' accuracy and the measured figures behind their choices are in
// docs/planetary.md ("The Kepler drift in lanes").
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <type_traits>

#include "../../core/error.hpp"
#include "../../core/wide_lanes.hpp"
#include "kepler_drift.hpp"
#include "kepler_equation.hpp"
#include "stumpff.hpp"

namespace sympl {

// Bodies per lane group of kepler_drift_all, and the quartic iterations all
// lanes run together before a lane falls back to the scalar solve.
inline constexpr int kepler_lanes = 8;
inline constexpr int kepler_lane_iterations = 6;

namespace detail {

// The short-drift lanes take |beta s^2| <= this, where Stumpff's series is
// summed directly (stumpff_terms<S>(4) terms, 12 for double): |A| + |B| <= 1/8
// keeps |beta s^2| <= 2.9 (docs/planetary.md).
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

// The lane loops are written so that GCC vectorises them with SSE2 as with
// AVX-512: every value is computed in every lane and stored, and only then
// selected; masks are held as S, 1 or 0 (bools beside doubles do not
// vectorise); the square roots are taken in vector registers by
// square_roots (wide_lanes.hpp: a loop of std::sqrt keeps a branch to set
// errno and runs one lane at a time); and the lanes are members of one
// struct, which the compiler knows do not overlap.
template <class S, int W>
struct lane_bodies {
    S x[W], y[W], z[W], vx[W], vy[W], vz[W], gm[W];
};

// What the short-drift path keeps per lane between its stages.
template <class S, int W>
struct short_lanes {
    S r0[W], per_r0[W], eta0[W], beta[W], zeta0[W], s[W], ok[W];
    S c0[W], g1[W], g2[W], f[W], noise[W], r[W], dr[W], ddr[W];
};

// The orbit of each lane and starting_value's series starter, taken to
// |w| <= 2 here (the convergence test decides). Whether any lane can go on.
template <bool Wide, class S, int W>
[[gnu::always_inline]] inline bool short_start(const lane_bodies<S, W>& b, S h, short_lanes<S, W>& w) {
    for (int l = 0; l < W; ++l) w.r0[l] = b.x[l] * b.x[l] + b.y[l] * b.y[l] + b.z[l] * b.z[l];
    square_roots<Wide>(w.r0, w.r0, W);
    for (int l = 0; l < W; ++l) {
        w.per_r0[l] = 1 / w.r0[l];
        w.eta0[l] = b.x[l] * b.vx[l] + b.y[l] * b.vy[l] + b.z[l] * b.vz[l];
        const S v2 = b.vx[l] * b.vx[l] + b.vy[l] * b.vy[l] + b.vz[l] * b.vz[l];
        w.beta[l] = 2 * b.gm[l] * w.per_r0[l] - v2;
        w.zeta0[l] = b.gm[l] - w.beta[l] * w.r0[l];
        const S u = h * w.per_r0[l];
        const S A = w.eta0[l] * u * w.per_r0[l] / 2, B = w.zeta0[l] * u * u * w.per_r0[l] * (S(1) / 6),
                ww = w.beta[l] * u * u;
        w.s[l] = series_start(u, A, B, ww);
        w.ok[l] = all_of(std::fabs(A) + std::fabs(B) <= S(0.125), std::fabs(ww) <= 2) ? S(1) : S(0);
    }
    S any(0);
    for (int l = 0; l < W; ++l) any = any < w.ok[l] ? w.ok[l] : any;  // a max: no branch
    return any != 0;
}

// Kepler's equation at the starter (Stumpff's series summed once, no
// quarterings), one quartic step in its series form (none where s already
// passes solve_universal's test), and the equation carried to the new s by
// the addition theorems (residual_shifted; d = 0 gives back the values at s).
// Stumpff's series in every lane at y = beta s^2, `terms` terms.
template <int terms, class S, int W>
[[gnu::always_inline]] inline void short_equation(const lane_bodies<S, W>& b, S h, const S (&y)[W],
                                                  short_lanes<S, W>& w) {
    for (int l = 0; l < W; ++l) {
        const stumpff_values<S> c = stumpff_series(y[l], terms);
        const kepler_terms<S> k = kepler_equation(w.r0[l], w.eta0[l], w.zeta0[l], w.beta[l], b.gm[l], h, w.s[l], c);
        w.c0[l] = c.c0, w.g1[l] = k.g1, w.g2[l] = k.g2, w.f[l] = k.f, w.noise[l] = kepler_noise(k, h);
        w.r[l] = k.r, w.dr[l] = k.dr, w.ddr[l] = k.ddr;
    }
}

template <class S, int W>
[[gnu::always_inline]] inline void short_solve(const lane_bodies<S, W>& b, S h, short_lanes<S, W>& w) {
    constexpr S eps = std::numeric_limits<S>::epsilon();
    S y[W], taken[W], largest(0);
    for (int l = 0; l < W; ++l) {
        y[l] = w.beta[l] * (w.s[l] * w.s[l]);
        w.ok[l] = all_of(w.ok[l] != 0, std::fabs(y[l]) <= S(kepler_short_x)) ? S(1) : S(0);
        taken[l] = w.ok[l] != 0 ? std::fabs(y[l]) : S(0);
    }
    for (int l = 0; l < W; ++l) largest = largest < taken[l] ? taken[l] : largest;  // a max: no branch
    // As many terms as the group's largest |y| needs: for double 7 at 0.1 (a
    // Wisdom-Holman step of a twentieth of an orbit or less), 9 at 1, else
    // the range's 12.
    if (largest <= S(0.1))
        short_equation<stumpff_terms<S>(0.1L)>(b, h, y, w);
    else if (largest <= S(1))
        short_equation<stumpff_terms<S>(1.0L)>(b, h, y, w);
    else
        short_equation<stumpff_terms<S>(kepler_short_x)>(b, h, y, w);
    S per_r[W], step[W], still[W];
    for (int l = 0; l < W; ++l) per_r[l] = 1 / w.r[l];
    for (int l = 0; l < W; ++l) {
        const S d1 = -w.f[l] * per_r[l];
        const S a2d = w.dr[l] * per_r[l] / 2 * d1, a3dd = w.ddr[l] * per_r[l] * (S(1) / 6) * d1 * d1;
        step[l] = quartic_series_step(d1, a2d, a3dd);
        const bool small = all_of(std::fabs(a2d) <= S(0x1p-16), std::fabs(a3dd) <= S(0x1p-16));
        const bool converged = any_of(std::fabs(w.f[l]) <= w.noise[l], std::fabs(d1) <= 4 * eps * std::fabs(w.s[l]));
        still[l] = converged ? S(0) : S(1);
        w.ok[l] = all_of(w.ok[l] != 0, small) ? S(1) : S(0);
    }
    for (int l = 0; l < W; ++l) step[l] = still[l] != 0 ? step[l] : S(0);
    for (int l = 0; l < W; ++l) {
        const S d = step[l], y = w.beta[l] * d * d;
        const small_shift<S> G = small_shift_at(w.beta[l], d);
        w.f[l] = w.f[l] + (w.r[l] * d + (w.dr[l] * G.g2 + w.ddr[l] * G.g3));
        w.r[l] = w.r[l] + (w.dr[l] * G.g1 + w.ddr[l] * G.g2);
        const S g1n = w.g1[l] + (w.c0[l] * G.g1 - w.beta[l] * w.g1[l] * G.g2);
        const S g2n = w.g2[l] + (w.g1[l] * G.g1 + w.c0[l] * G.g2);
        w.g1[l] = g1n;
        w.g2[l] = g2n;
        w.ok[l] = all_of(w.ok[l] != 0, std::fabs(y) <= S(0x1p-16), 16 * std::fabs(d) <= std::fabs(w.s[l])) ? S(1)
                                                                                                              : S(0);
        w.s[l] = w.s[l] + d;
    }
}

// The short drift of W bodies at once (docs/planetary.md): the scalar
// solve's path for a Wisdom-Holman drift with its tests. A lane outside its
// range, or failing a test, has done[l] = false and is for the bracketed
// solve, from the caller's copy (every lane of b is overwritten); a done
// lane holds the drifted state. Wide: in the AVX2 clone.
template <class S, int W, bool Wide = false>
void short_drift_lanes(lane_bodies<S, W>& b, S h, bool (&done)[W]) {
    constexpr S eps = std::numeric_limits<S>::epsilon(), big = std::numeric_limits<S>::max();
    short_lanes<S, W> w;
    const bool any = short_start<Wide>(b, h, w);
    for (int l = 0; l < W; ++l) done[l] = false;
    if (!any) return;
    short_solve(b, h, w);
    S per_rn[W];
    for (int l = 0; l < W; ++l) per_rn[l] = 1 / w.r[l];
    // f and g into every lane: the caller takes the done ones.
    for (int l = 0; l < W; ++l)
        apply_f_and_g(f_and_g_by_reciprocals(w.r0[l], w.eta0[l], b.gm[l], w.g1[l], w.g2[l], w.per_r0[l], per_rn[l]),
                      b.x[l],
                      b.y[l], b.z[l], b.vx[l], b.vy[l], b.vz[l]);
    // Done: solve_universal's test passed at s + d, and the results are finite (|v| <= max, which a NaN fails).
    for (int l = 0; l < W; ++l) {
        const bool there =
            any_of(std::fabs(w.f[l]) <= w.noise[l], std::fabs(w.f[l] * per_rn[l]) <= 4 * eps * std::fabs(w.s[l]));
        w.ok[l] = all_of(w.ok[l] != 0, there, w.r[l] > 0) ? S(1) : S(0);
    }
    for (int l = 0; l < W; ++l) {
        w.ok[l] = all_of(w.ok[l] != 0, std::fabs(b.x[l]) <= big, std::fabs(b.y[l]) <= big, std::fabs(b.z[l]) <= big,
                         std::fabs(b.vx[l]) <= big, std::fabs(b.vy[l]) <= big, std::fabs(b.vz[l]) <= big)
                      ? S(1)
                      : S(0);
    }
    for (int l = 0; l < W; ++l) done[l] = w.ok[l] != 0;
}

// The bodies first..first + count (count <= W; the other lanes repeat body
// first, their results dropped) by short_drift_lanes, the done ones written
// back; done[l] false for those left to the caller. Wide: in the AVX2 clone,
// the copies in and out too.
template <class S, int W, bool Wide, class GM>
[[gnu::always_inline]] inline void short_drift_group(const kepler_bodies<S>& b, GM gm_of, S h, std::size_t first,
                                                    int count, bool (&done)[W]) {
    lane_bodies<S, W> lanes;
    const auto copy_in = [&](int l, std::size_t i) {
        lanes.x[l] = b.x[i], lanes.y[l] = b.y[i], lanes.z[l] = b.z[i];
        lanes.vx[l] = b.vx[i], lanes.vy[l] = b.vy[i], lanes.vz[l] = b.vz[i];
        lanes.gm[l] = gm_of(i);
    };
    const auto copy_out = [&](int l, std::size_t i) {
        b.x[i] = lanes.x[l], b.y[i] = lanes.y[l], b.z[i] = lanes.z[l];
        b.vx[i] = lanes.vx[l], b.vy[i] = lanes.vy[l], b.vz[i] = lanes.vz[l];
    };
    // A whole group (all but the last) in and out in vector loads and
    // stores; a group with lanes left over, lane by lane.
    if (count == W)
        for (int l = 0; l < W; ++l) copy_in(l, first + std::size_t(l));
    else
        for (int l = 0; l < W; ++l) copy_in(l, first + std::size_t(l < count ? l : 0));
    short_drift_lanes<S, W, Wide>(lanes, h, done);
    int all_done = 1;
    for (int l = 0; l < W; ++l) all_done &= int(done[l]);
    if (count == W && all_done != 0)
        for (int l = 0; l < W; ++l) copy_out(l, first + std::size_t(l));
    else
        for (int l = 0; l < count; ++l)
            if (done[l]) copy_out(l, first + std::size_t(l));
}

// The same, compiled for AVX2 (wide_lanes.hpp).
template <class S, int W, class GM>
SYMPL_AVX2_CLONE void short_drift_group_wide(const kepler_bodies<S>& b, GM gm_of, S h, std::size_t first, int count,
                                             bool (&done)[W]) {
    short_drift_group<S, W, true>(b, gm_of, h, first, count, done);
}

// Quartic iterations in all lanes together from each lane's starting value,
// with a per-lane convergence mask (the test of solve_universal); active[l]
// is left true for a lane not converged in kepler_lane_iterations.
template <class S, int W>
void general_iterations(const S (&r0)[W], const S (&eta0)[W], const S (&gm)[W], const kepler_orbit<S> (&o)[W],
                        S (&s)[W], bool (&active)[W], S (&g1)[W], S (&g2)[W], S (&rr)[W]) {
    constexpr S eps = std::numeric_limits<S>::epsilon();
    S c0[W], c1[W], c2[W], c3[W];
    for (int it = 0; it < kepler_lane_iterations; ++it) {
        S x[W];
        for (int l = 0; l < W; ++l) x[l] = o[l].beta * s[l] * s[l];
        stumpff_lanes<S, W>(x, c0, c1, c2, c3);
        bool any = false;
        for (int l = 0; l < W; ++l) {
            const kepler_terms<S> k = kepler_equation(r0[l], eta0[l], o[l].zeta0, o[l].beta, gm[l], o[l].h, s[l],
                                                      stumpff_values<S>{c0[l], c1[l], c2[l], c3[l]});
            const S noise = kepler_noise(k, o[l].h);
            const S d1 = -k.f / k.r;
            const S d2 = -k.f / (k.r + d1 * k.dr / 2);
            const S d3 = -k.f / (k.r + d2 * k.dr / 2 + d2 * d2 * k.ddr / 6);
            const bool converged = std::fabs(k.f) <= noise || std::fabs(d1) <= 4 * eps * std::fabs(s[l]);
            const bool take = active[l];
            g1[l] = take ? k.g1 : g1[l];
            g2[l] = take ? k.g2 : g2[l];
            rr[l] = take ? k.r : rr[l];
            s[l] = (take && !converged) ? s[l] + d3 : s[l];
            active[l] = take && !converged;
            any = any || active[l];
        }
        if (!any) break;
    }
}

// The bodies idx[0..count) (count <= W; the other lanes repeat body idx[0],
// their results dropped) by general_iterations; a lane not converged, or a
// long hyperbolic drift (drift_in_pieces), is redone by the scalar drift.
// For the lanes the short-drift path did not take. Returns the bodies redone.
template <class S, int W, class GM>
std::size_t general_lanes(const kepler_bodies<S>& b, GM gm_of, S h, const std::size_t (&idx)[W], int count) {
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
    kepler_orbit<S> o[W];
    S s[W], g1[W], g2[W], rr[W];
    bool active[W];
    for (int l = 0; l < W; ++l) {
        o[l] = make_orbit(r0[l], eta0[l], v2[l], gm[l], h);
        s[l] = starting_value(o[l]);
        active[l] = o[l].h != 0;
        g1[l] = g2[l] = 0;
        rr[l] = r0[l];
    }
    general_iterations<S, W>(r0, eta0, gm, o, s, active, g1, g2, rr);
    for (int l = 0; l < count; ++l) {
        S r[3] = {rx[l], ry[l], rz[l]}, v[3] = {ux[l], uy[l], uz[l]};
        const std::size_t i = idx[l];
        const bool finite = std::isfinite(g1[l]) && std::isfinite(g2[l]) && std::isfinite(rr[l]) && rr[l] > 0;
        // Maybe a drift the scalar path takes in pieces (it decides).
        const bool in_pieces = o[l].beta < 0 && -o[l].beta * s[l] * s[l] > hyperbolic_piece_limit<S>;
        if (active[l] || !finite || in_pieces) {
            ++fallbacks;
            kepler_drift_body(r, v, gm[l], h, std::ptrdiff_t(i));  // the bracketed scalar solve
        } else if (o[l].h != 0) {
            drift_by_f_and_g(r, v, r0[l], eta0[l], gm[l], g1[l], g2[l], rr[l]);
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
    const bool wide = std::is_floating_point_v<S> && W >= 4 && wide_lanes();
    for (; first < last; first += W) {
        const int count = int(std::min<std::size_t>(W, last - first));
        bool done[W];
        if (wide) short_drift_group_wide<S, W>(b, gm_of, h, first, count, done);
        else short_drift_group<S, W, false>(b, gm_of, h, first, count, done);
        std::size_t rest[W];
        int left = 0;
        for (int l = 0; l < count; ++l)
            if (!done[l]) rest[left++] = first + std::size_t(l);
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
    // over all bodies at once, in sums and minima that vectorise: a sum of
    // magnitudes is finite (<= max, which a NaN fails) when every term is,
    // and r^2 and GM are positive when their least is. Only if it fails (or
    // a sum of finite values overflows) are they checked one by one, for the
    // message.
    {
        constexpr S big = std::numeric_limits<S>::max();
        constexpr std::size_t L = 4;  // a sum and minima per lane: one reduction in order would not vectorise
        S size[L] = {}, least_r2[L], least_gm[L];
        for (std::size_t l = 0; l < L; ++l) least_r2[l] = least_gm[l] = big;
        for (std::size_t first = 0; first < n; first += L)
            for (std::size_t l = 0; l < L; ++l) {
                const std::size_t i = std::min(first + l, n - 1);  // the last group's spare lanes repeat body n - 1
                const S x = b.x[i], y = b.y[i], z = b.z[i], gm = gm_of(i);
                const S r2 = x * x + y * y + z * z;
                size[l] += (std::fabs(b.vx[i]) + std::fabs(b.vy[i]) + std::fabs(b.vz[i])) + (r2 + gm);
                least_r2[l] = r2 < least_r2[l] ? r2 : least_r2[l];
                least_gm[l] = gm < least_gm[l] ? gm : least_gm[l];
            }
        bool fine = std::fabs(h) <= big;
        for (std::size_t l = 0; l < L; ++l) fine = all_of(fine, size[l] <= big, least_r2[l] > 0, least_gm[l] > 0);
        if (!fine)
            for (std::size_t i = 0; i < n; ++i) {
                const S r[3] = {b.x[i], b.y[i], b.z[i]}, v[3] = {b.vx[i], b.vy[i], b.vz[i]};
                check_kepler_input(r, v, gm_of(i), h, std::ptrdiff_t(i));
            }
    }
    if (h == 0) return 0;
    // Groups of kepler_lanes, then the rest (the whole batch for the 5 planets
    // of a Wisdom-Holman step) in one group of the next even width: two
    // lanes to an SSE2 register, and the fewest padded lanes (measured in
    // docs/planetary.md, "The Kepler drift in lanes").
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
