// The Boris pusher: its order measured on a non-uniform field, and in a
// uniform B the speed and the gyration centre kept to rounding over 10^6
// gyrations.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include <sympl/sympl.hpp>
#include <sympl/charged/boris.hpp>

#include "measured_orders.hpp"

namespace test_charged_test_boris {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using namespace sympl::charged;

TEST_CASE("Boris: second order on the radial mirror field with a confining E") {
    const particle a{.mass = 1, .charge = 1};
    const radial_mirror_field f{.field = 1, .field_length = 1, .confinement = 0.2};
    const kinetic_state<> x0(vec3<>(1, 0, 0), vec3<>(0.4, 1, 0.3));
    const order_measurement m =
        testing::order_of([&] { return boris_stepper<radial_mirror_field>(a, f); }, x0, 5, 32);
    CAPTURE(m.order);
    CHECK(m.converged);
    CHECK(std::abs(m.order - 2) < 0.15);
}

TEST_CASE("Boris in uniform B: speed and gyration centre kept to rounding over 10^6 gyrations") {
    // omega = e B / m = 1, ten steps a gyration: 10^7 steps.
    // The speed: in uniform B every step applies the same rounded rotation
    // (tau is the same), whose norm differs from 1 by a fixed fraction of eps;
    // that error does not average out, so |v| drifts as eps N (measured: about
    // eps N / 20). Bound: eps N = 2.2e-9 relative, one unit roundoff a step.
    // The centre x + v x B / (omega |B|), exact for Boris's map in exact
    // arithmetic (docs/charged-particles.md), takes the rounding of x's drifts,
    // of either sign and independent from step to step: a random walk, eps
    // sqrt(N). Bound: 16 eps sqrt(N) = 1.1e-11 at radius 1 (measured 1.4e-12);
    // a bias of eps a step would reach 2e-9.
    const particle a{.mass = 1, .charge = 1};
    const uniform_field f{.electric = vec3<>::Zero(), .magnetic = vec3<>(0, 0, 1)};
    boris_stepper<uniform_field> s(a, f);
    kinetic_state<> x(vec3<>(1, 0, 0), vec3<>(0, 1, 0));
    const auto centre = [&](const kinetic_state<>& y) { return vec3<>(y.q + y.p.cross(vec3<>(0, 0, 1))); };
    const vec3<> c0 = centre(x);
    const double dt = 2 * std::numbers::pi / 10;
    const std::size_t n = 10'000'000;
    double worst_speed = 0, worst_centre = 0;
    for (std::size_t i = 1; i <= n; ++i) {
        s.step(x, dt);
        if (i % 1000 == 0) {
            worst_speed = std::max(worst_speed, std::abs(x.p.norm() - 1));
            worst_centre = std::max(worst_centre, (centre(x) - c0).norm());
        }
    }
    const double eps = std::numeric_limits<double>::epsilon();
    const double speed_bound = eps * double(n), centre_bound = 16 * eps * std::sqrt(double(n));
    CAPTURE(worst_speed);
    CAPTURE(worst_centre);
    CHECK(worst_speed < speed_bound);
    CHECK(worst_centre < centre_bound);
    CHECK(x.q[2] == 0);
}

TEST_CASE("Boris: bad input names the value") {
    CHECK_THROWS_WITH_AS(boris_stepper<uniform_field>(particle{.mass = -1}, uniform_field{}),
                         doctest::Contains("mass = -1"), invalid_argument);
}

}  // namespace test_charged_test_boris
