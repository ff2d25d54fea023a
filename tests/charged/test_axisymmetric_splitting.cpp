// The splitting in cylindrical coordinates for fields symmetric about z:
// p_theta exact, the round trip of coordinates, orders of kick-drift tables
// (Runge-Kutta-Nystrom ones too) on the radial mirror field and the magnetic
// mirror, and agreement with the canonical splitting.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <sympl/sympl.hpp>
#include <sympl/charged/axisymmetric_splitting.hpp>
#include <sympl/charged/canonical_splitting.hpp>

#include "measured_orders.hpp"

namespace test_charged_test_axisymmetric_splitting {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using namespace sympl::charged;

const particle unit{.mass = 1, .charge = 1};

TEST_CASE("axisymmetric splitting: the coordinates' round trip and the exact p_theta") {
    using S = axisymmetric_splitting_stepper<magnetic_mirror, 3>;
    const phase_space<double, 3> x(vec3<>(0.3, -0.7, 0.2), vec3<>(0.4, 0.9, -0.1));
    const phase_space<double, 3> y = S::to_cartesian(S::to_cylindrical(x));
    CHECK(max_difference(x, y) < 1e-15);
    S s(unit, magnetic_mirror{}, method("blanes_moan_srkn11b"));
    phase_space<double, 3> z = x;
    s.steps(z, 0.05, 2000);
    const double l0 = x.q[0] * x.p[1] - x.q[1] * x.p[0], l1 = z.q[0] * z.p[1] - z.q[1] * z.p[0];
    CHECK(std::abs(l1 - l0) < 1e-14);
}

TEST_CASE("axisymmetric splitting: orders on the radial mirror field (2D)") {
    const radial_mirror_field f{.field = 1, .field_length = 1, .confinement = 0.2};
    testing::check_orders(
        [&](const std::string& name) { return axisymmetric_splitting_stepper<radial_mirror_field, 2>(unit, f, method(name)); },
        phase_space<double, 2>(Eigen::Vector2d(1, 0), Eigen::Vector2d(0.4, 1)), 4,
        {{"leapfrog_kdk", 2}, {"blanes_moan_srkn6b", 4}, {"blanes_moan_srkn11b", 6}, {"kahan_li_8", 8}});
}

TEST_CASE("axisymmetric splitting: orders on the magnetic mirror (3D: r and z kicked)") {
    // Over t = 10, a third of a bounce: the slopes of orders 6 and 8 there
    // swing by a unit between step sizes before they settle (error constants
    // that change sign), so orders 2 and 4 are read here, the higher ones on
    // the planar field above.
    const magnetic_mirror f{.field = 1, .field_length = 1};
    const kinetic_state<> k(vec3<>(0.5, 0, 0), vec3<>(0, 0.5, 0.6));
    testing::check_orders(
        [&](const std::string& name) { return axisymmetric_splitting_stepper<magnetic_mirror, 3>(unit, f, method(name)); },
        to_canonical(unit, f, k), 10, {{"leapfrog_kdk", 2}, {"blanes_moan_srkn6b", 4}});
}

TEST_CASE("axisymmetric splitting: the same motion as the canonical splitting") {
    const radial_mirror_field f{.field = 1, .field_length = 1, .confinement = 0.2};
    phase_space<double, 2> x(Eigen::Vector2d(1, 0), Eigen::Vector2d(0.4, 1)), y = x;
    axisymmetric_splitting_stepper<radial_mirror_field, 2> a(unit, f, method("blanes_moan_srkn11b"));
    canonical_splitting_stepper<radial_mirror_field, 2> c(unit, f, method("kahan_li_8"));
    a.steps(x, 0.01, 1000);
    for (int i = 0; i < 1000; ++i) c.step(y, 0.01);
    CHECK(max_difference(x, y) < 1e-10);
}

TEST_CASE("axisymmetric splitting: a particle on the axis is refused") {
    axisymmetric_splitting_stepper<magnetic_mirror, 3> s(unit, magnetic_mirror{}, method("leapfrog_kdk"));
    phase_space<double, 3> x(vec3<>(0, 0, 1), vec3<>(0, 0, 1));
    CHECK_THROWS_WITH_AS(s.step(x, 0.1), doctest::Contains("r = 0"), invalid_argument);
}

}  // namespace test_charged_test_axisymmetric_splitting
