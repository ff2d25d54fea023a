// The canonical splitting of |p - e A|^2/2m + e phi: each part's flow exact,
// orders 2, 4, 6 and 8 measured on the non-uniform radial mirror field and on
// the magnetic mirror, energy bounded, and refusals.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <sympl/sympl.hpp>
#include <sympl/charged/canonical_splitting.hpp>
#include <sympl/hamiltonians/charged_particle.hpp>

#include "measured_orders.hpp"

namespace test_charged_test_canonical_splitting {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using namespace sympl::charged;

const particle unit{.mass = 1, .charge = 1};

TEST_CASE("canonical splitting: one part's flow is exact (H_i and pi_i kept, the flow a group)") {
    const radial_mirror_field f{.field = 1.3, .field_length = 0.8, .confinement = 0.2};
    canonical_splitting_stepper<radial_mirror_field> s(unit, f, method("leapfrog_kdk"));
    vec3<> q(0.7, -0.4, 0.2), p(0.3, 1.1, -0.2), q2 = q, p2 = p;
    const double pi0 = p[0] - vec3<>(f.A(q))[0];
    s.flow_part(0, 0.9, q, p);
    CHECK(std::abs(p[0] - vec3<>(f.A(q))[0] - pi0) < 1e-15);
    // Two flows of 0.4 and 0.5 are one of 0.9 (an exact flow, not an approximation).
    s.flow_part(0, 0.4, q2, p2);
    s.flow_part(0, 0.5, q2, p2);
    CHECK((q - q2).norm() < 1e-14);
    CHECK((p - p2).norm() < 1e-14);
}

TEST_CASE("canonical splitting: orders on the non-uniform radial mirror field (2D, the built-in system)") {
    const radial_mirror_field f{.field = 1, .field_length = 1, .confinement = 0.2};
    testing::check_orders(
        [&](const std::string& name) { return canonical_splitting_stepper<radial_mirror_field, 2>(unit, f, method(name)); },
        phase_space<double, 2>(Eigen::Vector2d(1, 0), Eigen::Vector2d(0.4, 1)), 4,
        {{"leapfrog_kdk", 2}, {"yoshida_4", 4}, {"yoshida_6", 6}, {"kahan_li_8", 8}});
}

TEST_CASE("canonical splitting: orders on the magnetic mirror (3D, B_x, B_y, B_z all non-zero)") {
    const magnetic_mirror f{.field = 1, .field_length = 1};
    const kinetic_state<> k(vec3<>(0.5, 0, 0), vec3<>(0, 0.5, 0.3));
    testing::check_orders(
        [&](const std::string& name) { return canonical_splitting_stepper<magnetic_mirror, 3>(unit, f, method(name)); },
        to_canonical(unit, f, k), 4, {{"leapfrog_kdk", 2}, {"suzuki_4", 4}});
}

TEST_CASE("canonical splitting: the energy error stays bounded (symplectic), 2D against the built-in H") {
    const hamiltonians::charged_particle h{};
    canonical_splitting_stepper<radial_mirror_field, 2> s(h.particle(), h.electromagnetic_field(), method("yoshida_6"));
    phase_space<double, 2> x(Eigen::Vector2d(1, 0), Eigen::Vector2d(0.4, 1));
    const double e0 = h.energy(x.q, x.p);
    double early = 0, late = 0;
    for (int i = 0; i < 40000; ++i) {
        s.step(x, 0.1);
        (i < 4000 ? early : late) = std::max(i < 4000 ? early : late, std::abs(h.energy(x.q, x.p) / e0 - 1));
    }
    CAPTURE(early);
    CAPTURE(late);
    // Bounded: the worst over t in [400, 4000] within twice that over [0, 400] (a drift would grow tenfold).
    CHECK(late < 2 * early);
    CHECK(early < 1e-5);
}

TEST_CASE("canonical splitting: a table that is not a leapfrog composition is refused, naming it") {
    CHECK_THROWS_WITH_AS(
        canonical_splitting_stepper<uniform_field>(unit, uniform_field{}, method("blanes_moan_s6")),
        doctest::Contains("blanes_moan_s6"), invalid_argument);
}

}  // namespace test_charged_test_canonical_splitting
