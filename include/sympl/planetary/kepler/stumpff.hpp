#pragma once
// Stumpff's functions c_k(x) = sum_j (-x)^j / (2j + k)!, k = 0..3, the
// building blocks of the universal-variable Kepler drift (Stumpff 1959;
// Danby 1988, "Fundamentals of Celestial Mechanics", 2nd ed., sec. 6.9).
// One series and one quarter-angle recurrence, written once for any scalar
// with the arithmetic of a double: one body (float, double), W bodies in
// SIMD-friendly lanes (stumpff_lanes) and dual numbers (stumpff, for the
// drift's tangent map). Branches compare primal values. The error analysis
// of the term counts is in docs/planetary.md ("Stumpff's series").
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

#include "../../core/dual.hpp"

namespace sympl::detail {

template <class T>
using primal_t = decltype(primal(std::declval<T>()));

// How many terms of Stumpff's series reach S's rounding at |x| <= bound: n,
// the first left out of c2's, bound^n / (2n + 2)!, being <= eps / 64. For
// double: 7 terms at |x| <= 0.1, 5 at 1e-2, 4 at 1e-3.
template <class S>
constexpr int stumpff_terms(long double bound) {
    long double term = 0.5L;  // c2's term n at |x| = bound: bound^n / (2n + 2)!
    for (int n = 1;; ++n) {
        term *= bound / ((2 * n + 1) * (2 * n + 2));
        if (term <= static_cast<long double>(std::numeric_limits<S>::epsilon()) / 64 || n == 12) return n;
    }
}

// 1/m!, m = 0..25, rounded once from long double: c2's terms are
// 1/(2j + 2)!, c3's 1/(2j + 3)!, j < 12.
template <class S>
inline constexpr std::array<S, 26> inverse_factorial = [] {
    std::array<S, 26> a{};
    long double m_factorial = 1;
    a[0] = 1;
    for (int m = 1; m < 26; ++m) a[std::size_t(m)] = S(1 / (m_factorial *= m));
    return a;
}();

template <class T>
struct stumpff_values {
    T c0, c1, c2, c3;
};

// c0..c3 at y by n terms of the series (Horner: c2 = 1/2! - y/4! + ..., c3 =
// 1/3! - y/5! + ...; c0 = 1 - y c2, c1 = 1 - y c3).
template <class T>
[[gnu::always_inline]] inline stumpff_values<T> stumpff_series(const T& y, int n) {
    using S = primal_t<T>;
    T s2 = T(inverse_factorial<S>[std::size_t(2 * n)]), s3 = T(inverse_factorial<S>[std::size_t(2 * n + 1)]);
    for (int j = n - 2; j >= 0; --j) {
        s2 = inverse_factorial<S>[std::size_t(2 * j + 2)] - y * s2;
        s3 = inverse_factorial<S>[std::size_t(2 * j + 3)] - y * s3;
    }
    return {1 - y * s2, 1 - y * s3, s2, s3};
}

// The c_k at 4x from those at x (Danby 1988, sec. 6.9), x4 = 4x:
//     c3(4x) = (c2 + c0 c3) / 4,  c2(4x) = c1^2 / 2,  c1(4x) = c0 c1,  c0(4x) = 1 - 4x c2(4x).
// c0 by 1 - x c2 rather than 2 c0^2 - 1, which would multiply its error by 4 a level.
template <class T>
stumpff_values<T> stumpff_quadrupled(const stumpff_values<T>& c, const T& x4) {
    using S = primal_t<T>;
    const T n2 = c.c1 * c.c1 * S(0.5);
    return {1 - x4 * n2, c.c0 * c.c1, n2, (c.c2 + c.c0 * c.c3) * S(0.25)};
}

// c0..c3 at x for any scalar T (a dual number for the tangent map): x
// quartered until |x| <= 0.1, the series there, the recurrence back up.
template <class T>
stumpff_values<T> stumpff(T x) {
    using S = primal_t<T>;
    int levels = 0;
    while (std::fabs(primal(x)) > S(0.1) && levels < 1100) x = x * S(0.25), ++levels;
    stumpff_values<T> c = stumpff_series(x, stumpff_terms<S>(0.1L));
    for (; levels > 0; --levels) {
        x = x * 4;
        c = stumpff_quadrupled(c, x);
    }
    return c;
}

// The same for W lanes at once (W = 1: one body, which sums only as many
// terms as its |x| needs). Every lane runs the same loops, a lane's levels
// selected by masks, so that the loops vectorise.
template <class S, int W>
void stumpff_lanes(const S* x_in, S* c0, S* c1, S* c2, S* c3) {
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
    int n = terms;
    if constexpr (W == 1) n = std::fabs(x[0]) <= S(1e-3) ? terms_3 : std::fabs(x[0]) <= S(1e-2) ? terms_2 : terms;
    for (int l = 0; l < W; ++l) {
        const stumpff_values<S> c = stumpff_series(x[l], n);
        c0[l] = c.c0, c1[l] = c.c1, c2[l] = c.c2, c3[l] = c.c3;
    }
    for (int level = most - 1; level >= 0; --level)
        for (int l = 0; l < W; ++l) {
            const bool up = level < levels[l];
            const S nx = x[l] * 4;
            const stumpff_values<S> c = stumpff_quadrupled(stumpff_values<S>{c0[l], c1[l], c2[l], c3[l]}, nx);
            c3[l] = up ? c.c3 : c3[l];
            c2[l] = up ? c.c2 : c2[l];
            c1[l] = up ? c.c1 : c1[l];
            c0[l] = up ? c.c0 : c0[l];
            x[l] = up ? nx : x[l];
        }
}

}  // namespace sympl::detail
