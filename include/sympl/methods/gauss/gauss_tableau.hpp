#pragma once
// The Butcher tableaus of the s-stage Gauss-Legendre collocation methods,
// s = 1 .. 6 (orders 2 .. 12): s = 1, 2, 3 in closed form (Butcher 1964;
// Hairer, Lubich & Wanner, Geometric Numerical Integration, 2nd ed. 2006,
// Table II.1.1), s = 4, 5, 6 computed in long double from their definition
// (nodes the zeros of the shifted Legendre polynomial, A and b the integrals
// of the Lagrange basis on them: GNI sec. II.1.3, eq. (1.17)),
// d = A^-T b for the update y1 = y0 + sum_i d_i Z_i (GNI sec. VIII.6), and
// the starting approximation of the next step's stage values from this
// step's collocation polynomial (GNI sec. VIII.6.1, eq. (6.6)).
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include "../../core/error.hpp"

namespace sympl {

inline constexpr int max_gauss_stages = 6;

struct gauss_tableau {
    int stages = 0;
    int order = 0;
    std::array<long double, max_gauss_stages> c{};
    std::array<std::array<long double, max_gauss_stages>, max_gauss_stages> a{};
    std::array<long double, max_gauss_stages> b{};
    std::array<long double, max_gauss_stages> d{};  // y1 = y0 + sum d_i Z_i (GNI sec. VIII.6)
};

namespace detail {
// P_s(x) and P_s'(x), the Legendre polynomial by its three-term recurrence.
inline std::pair<long double, long double> legendre(int s, long double x) {
    long double p0 = 1, p1 = x;
    for (int k = 2; k <= s; ++k) {
        const long double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    return {p1, s * (x * p1 - p0) / (x * x - 1)};
}

// The collocation method on the zeros of P_s(2c - 1), from the definition:
// x_i by Newton from cos(pi (i - 1/4) / (s + 1/2)) (Abramowitz & Stegun
// 22.16.6's first approximation), b_i = 1 / ((1 - x_i^2) P_s'(x_i)^2) (the
// Gauss weights on [0, 1]), a_ij = int_0^c_i l_j (C(s), GNI eq. (1.17)),
// d_j = L_j(1) for L_j the Lagrange basis on {0, c_1, .., c_s} (d^T A = b^T).
inline gauss_tableau computed_gauss_tableau(int s) {
    gauss_tableau t;
    t.stages = s;
    t.order = 2 * s;
    for (int i = 0; i < s; ++i) {
        long double x = std::cos(std::numbers::pi_v<long double> * (i + 0.75L) / (s + 0.5L));
        for (int it = 0; it < 100; ++it) {
            const auto [p, dp] = legendre(s, x);
            const long double dx = p / dp;
            x -= dx;
            if (std::fabs(dx) <= 2 * std::numeric_limits<long double>::epsilon()) break;
        }
        const long double dp = legendre(s, x).second;
        t.c[s - 1 - i] = (1 + x) / 2;  // the cosines fall with i
        t.b[s - 1 - i] = 1 / ((1 - x * x) * dp * dp);
    }
    for (int j = 0; j < s; ++j) {
        // l_j as coefficients in t: prod_{k != j} (t - c_k) / (c_j - c_k).
        std::array<long double, max_gauss_stages + 1> l{};
        l[0] = 1;
        int degree = 0;
        for (int k = 0; k < s; ++k) {
            if (k == j) continue;
            const long double w = t.c[j] - t.c[k];
            for (int m = degree + 1; m >= 0; --m) l[m] = ((m > 0 ? l[m - 1] : 0) - t.c[k] * l[m]) / w;
            ++degree;
        }
        for (int i = 0; i < s; ++i) {
            long double integral = 0, power = t.c[i];
            for (int m = 0; m <= degree; ++m, power *= t.c[i]) integral += l[m] * power / (m + 1);
            t.a[i][j] = integral;
        }
        long double d = 1 / t.c[j];
        for (int k = 0; k < s; ++k)
            if (k != j) d *= (1 - t.c[k]) / (t.c[j] - t.c[k]);
        t.d[j] = d;
    }
    return t;
}
}  // namespace detail

// Nodes c_i are the zeros of the shifted Legendre polynomial P_s(2c - 1).
inline gauss_tableau gauss_legendre_tableau(int stages) {
    const long double r3 = std::numbers::sqrt3_v<long double>, r15 = std::sqrt(15.0L);
    gauss_tableau t;
    t.stages = stages;
    t.order = 2 * stages;
    switch (stages) {
    case 1:  // the implicit midpoint rule
        t.c = {0.5L};
        t.a[0] = {0.5L};
        t.b = {1.0L};
        t.d = {2.0L};
        break;
    case 2:
        t.c = {0.5L - r3 / 6, 0.5L + r3 / 6};
        t.a[0] = {0.25L, 0.25L - r3 / 6};
        t.a[1] = {0.25L + r3 / 6, 0.25L};
        t.b = {0.5L, 0.5L};
        t.d = {-r3, r3};
        break;
    case 3:
        t.c = {0.5L - r15 / 10, 0.5L, 0.5L + r15 / 10};
        t.a[0] = {5.0L / 36, 2.0L / 9 - r15 / 15, 5.0L / 36 - r15 / 30};
        t.a[1] = {5.0L / 36 + r15 / 24, 2.0L / 9, 5.0L / 36 - r15 / 24};
        t.a[2] = {5.0L / 36 + r15 / 30, 2.0L / 9 + r15 / 15, 5.0L / 36};
        t.b = {5.0L / 18, 4.0L / 9, 5.0L / 18};
        t.d = {5.0L / 3, -4.0L / 3, 5.0L / 3};
        break;
    default:
        if (stages < 1 || stages > max_gauss_stages)
            throw invalid_argument("gauss_legendre_tableau: stages = " + std::to_string(stages) +
                                   "; expected 1 to " + std::to_string(max_gauss_stages) + " (orders 2 to " +
                                   std::to_string(2 * max_gauss_stages) + ")");
        return detail::computed_gauss_tableau(stages);
    }
    return t;
}

// The next step's stage values from this step's: the collocation polynomial
// u of the step just taken (u(0) = y0, u(c_j) = y0 + Z_j, in units of its step
// h) extrapolated to the next step's nodes 1 + r c_i, r = h_next / h:
//     Z_next_i = u(1 + r c_i) - y1 = sum_j (l_j(1 + r c_i) - d_j) Z_j,
// l_j the Lagrange basis on the nodes {0, c_1, ..., c_s} (u(1) = y1 gives
// l_j(1) = d_j). Its error is O(h^(s+1)) (GNI sec. VIII.6.1).
inline std::array<std::array<long double, max_gauss_stages>, max_gauss_stages>
gauss_extrapolation(const gauss_tableau& t, long double r) {
    std::array<std::array<long double, max_gauss_stages>, max_gauss_stages> beta{};
    const int s = t.stages;
    for (int i = 0; i < s; ++i) {
        const long double theta = 1 + r * t.c[i];
        for (int j = 0; j < s; ++j) {
            long double l = theta / t.c[j];  // the node 0
            for (int k = 0; k < s; ++k)
                if (k != j) l *= (theta - t.c[k]) / (t.c[j] - t.c[k]);
            beta[i][j] = l - t.d[j];
        }
    }
    return beta;
}

}  // namespace sympl
