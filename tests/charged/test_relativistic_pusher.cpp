// The Higuera-Cary pusher: order measured on a non-uniform field at half the
// speed of light, Boris's pusher at low speed, gamma kept in pure B, and the
// exact E x B drift.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include <sympl/sympl.hpp>
#include <sympl/charged/boris.hpp>
#include <sympl/charged/relativistic_pusher.hpp>

#include "measured_orders.hpp"

namespace test_charged_test_relativistic_pusher {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using namespace sympl::charged;

TEST_CASE("relativistic pusher: second order on the radial mirror field at |v| ~ c/2") {
    const particle a{.mass = 1, .charge = 1, .speed_of_light = 2};
    const radial_mirror_field f{.field = 1, .field_length = 1, .confinement = 0.2};
    const kinetic_state<> x0(vec3<>(1, 0, 0), vec3<>(0.4, 1, 0.3));  // u; |v| = 0.96
    const order_measurement m =
        testing::order_of([&] { return relativistic_pusher<radial_mirror_field>(a, f); }, x0, 5, 32);
    CAPTURE(m.order);
    CHECK(m.converged);
    CHECK(std::abs(m.order - 2) < 0.15);
}

TEST_CASE("relativistic pusher: Boris's pusher at low speed") {
    const radial_mirror_field f{.field = 1, .field_length = 1, .confinement = 0.2};
    const kinetic_state<> x0(vec3<>(1, 0, 0), vec3<>(0.4, 1, 0.3));
    const auto difference = [&](double c) {
        boris_stepper<radial_mirror_field> boris({.mass = 1, .charge = 1}, f);
        relativistic_pusher<radial_mirror_field> hc({.mass = 1, .charge = 1, .speed_of_light = c}, f);
        kinetic_state<> x = x0, y = x0;
        for (int i = 0; i < 100; ++i) {
            boris.step(x, 0.05);
            hc.step(y, 0.05);
        }
        return max_difference(x, y);
    };
    // c infinite: the same map (w + w x t is Boris's v+), to rounding.
    CHECK(difference(std::numeric_limits<double>::infinity()) < 1e-13);
    // Finite c: the motion differs by O(|v|^2 / c^2): a quarter at twice c.
    const double d1 = difference(1e3), d2 = difference(2e3);
    CAPTURE(d1);
    CAPTURE(d2);
    CHECK(d1 < 1e-5);
    CHECK(std::abs(d1 / d2 - 4) < 0.1);
}

TEST_CASE("relativistic pusher: gamma kept to rounding in pure B, exact E x B drift") {
    const particle a{.mass = 1, .charge = 1, .speed_of_light = 1};
    SUBCASE("pure B: |u| (so gamma) is rotated, not changed") {
        // Each step a rotation of u by a rounded map: |u| drifts at most about
        // eps a step (the systematic bound, as Boris's in test_boris.cpp).
        relativistic_pusher<uniform_field> s(a, uniform_field{.electric = vec3<>::Zero(), .magnetic = vec3<>(0.3, 0, 2)});
        kinetic_state<> x(vec3<>(0, 0, 0), vec3<>(3, 1, 0.5));  // gamma = 3.3
        const double u0 = x.p.norm();
        const std::size_t n = 100000;
        double worst = 0;
        for (std::size_t i = 0; i < n; ++i) {
            s.step(x, 0.3);
            worst = std::max(worst, std::abs(x.p.norm() / u0 - 1));
        }
        CAPTURE(worst);
        CHECK(worst < std::numeric_limits<double>::epsilon() * double(n));
    }
    SUBCASE("crossed E and B: the particle at rest in the drift frame moves at E x B / B^2") {
        // E = 0.5 x, B = z, c = 1: drift velocity (0, -0.5, 0); u = gamma v = (0, -0.5, 0)/sqrt(0.75).
        const uniform_field f{.electric = vec3<>(0.5, 0, 0), .magnetic = vec3<>(0, 0, 1)};
        relativistic_pusher<uniform_field> s(a, f);
        kinetic_state<> x(vec3<>(0, 0, 0), vec3<>(0, -0.5 / std::sqrt(0.75), 0));
        for (int i = 0; i < 1000; ++i) s.step(x, 0.7);
        CHECK(std::abs(x.q[1] + 0.5 * 700) < 1e-9);
        CHECK(std::abs(x.q[0]) < 1e-9);
    }
}

}  // namespace test_charged_test_relativistic_pusher
