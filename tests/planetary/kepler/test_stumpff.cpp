// Stumpff's functions (stumpff.hpp) against their closed forms in long
// double, c0 = cos sqrt(x), c1 = sin sqrt(x) / sqrt(x), c2 = (1 - c0) / x,
// c3 = (1 - c1) / x (cosh and sinh for x < 0): one body, lanes and dual
// numbers give the same values, and the dual's derivative is dc0/dx = -c1/2.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <sympl/core/dual.hpp>
#include <sympl/planetary/kepler/stumpff.hpp>

namespace test_planetary_test_stumpff {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
constexpr double eps = std::numeric_limits<double>::epsilon();
using ld = long double;

// The closed forms in long double (x away from 0, where they cancel).
std::array<ld, 4> closed(ld x) {
    const ld r = std::sqrt(std::fabs(x));
    const ld c0 = x > 0 ? std::cos(r) : std::cosh(r), c1 = x > 0 ? std::sin(r) / r : std::sinh(r) / r;
    return {c0, c1, (1 - c0) / x, (1 - c1) / x};
}
}  // namespace

// |x| <= (pi + 2)^2 ~ 26.4, the drift's range after the period reduction;
// |x| >= 0.5, where the closed forms lose no more than a few long-double digits.
TEST_CASE("stumpff: one body, lanes and duals equal the closed forms to a few eps") {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.5, 26.4);
    double worst = 0;
    constexpr int W = 6;
    for (int trial = 0; trial < 2000; ++trial) {
        double x[W], c[4][W];
        for (double& xl : x) xl = (rng() % 2 ? 1 : -1) * u(rng);
        detail::stumpff_lanes<double, W>(x, c[0], c[1], c[2], c[3]);
        for (int l = 0; l < W; ++l) {
            double one[4];
            detail::stumpff_lanes<double, 1>(&x[l], &one[0], &one[1], &one[2], &one[3]);
            const detail::stumpff_values<dual<double, 1>> d = detail::stumpff(dual<double, 1>(x[l]));
            const double duals[4] = {d.c0.value, d.c1.value, d.c2.value, d.c3.value};
            const std::array<ld, 4> ref = closed(x[l]);
            for (int k = 0; k < 4; ++k) {
                // Absolute error against max(1, |c_k|): the recurrences keep it at a few eps.
                const double scale = std::max(1.0, double(std::fabs(ref[std::size_t(k)])));
                worst = std::max(worst, double(std::fabs(c[k][l] - ref[std::size_t(k)])) / (scale * eps));
                CHECK(one[k] == c[k][l]);
                CHECK(duals[k] == c[k][l]);
            }
        }
    }
    MESSAGE("worst error: " << worst << " eps");
    CHECK(worst <= 64);
}

TEST_CASE("stumpff: the dual's derivative is dc0/dx = -c1/2") {
    for (double x : {-20.0, -3.0, -0.05, 0.001, 0.3, 7.0, 25.0}) {
        dual<double, 1> d(x);
        d.grad[0] = 1;
        const detail::stumpff_values<dual<double, 1>> c = detail::stumpff(d);
        CHECK(std::fabs(c.c0.grad[0] + c.c1.value / 2) <= 64 * eps * std::max(1.0, std::fabs(c.c1.value)));
    }
}

}  // namespace test_planetary_test_stumpff
