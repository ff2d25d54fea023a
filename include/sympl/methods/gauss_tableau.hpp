#pragma once
// The Butcher tableaus of the s-stage Gauss-Legendre collocation methods,
// s = 1, 2, 3 (orders 2, 4, 6), in closed form (Butcher 1964; Hairer, Lubich
// & Wanner, Geometric Numerical Integration, 2nd ed. 2006, Table II.1.1),
// d = A^-T b for the update y1 = y0 + sum_i d_i Z_i (GNI sec. VIII.6), and
// the starting approximation of the next step's stage values from this
// step's collocation polynomial (GNI sec. VIII.6.1, eq. (6.6)).
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "../core/error.hpp"

namespace sympl {

inline constexpr int max_gauss_stages = 3;

struct gauss_tableau {
    int stages = 0;
    int order = 0;
    std::array<long double, max_gauss_stages> c{};
    std::array<std::array<long double, max_gauss_stages>, max_gauss_stages> a{};
    std::array<long double, max_gauss_stages> b{};
    std::array<long double, max_gauss_stages> d{};  // y1 = y0 + sum d_i Z_i (GNI sec. VIII.6)
};

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
        throw invalid_argument("gauss_legendre_tableau: stages = " + std::to_string(stages) +
                               "; expected 1, 2 or 3 (orders 2, 4, 6)");
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
