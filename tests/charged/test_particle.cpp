// The particle: kinetic and canonical states, the Lorentz force, the energy,
// gamma, and bad input.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include <sympl/charged/particle.hpp>

namespace test_charged_test_particle {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using namespace sympl::charged;

TEST_CASE("particle: canonical momentum p = m v + e A and back, energy, Lorentz force, gamma") {
    const particle a{.mass = 2, .charge = -3, .speed_of_light = 10};
    const radial_mirror_field f{.field = 1.3, .field_length = 0.8, .confinement = 0.4};
    const kinetic_state<> k(vec3<>(0.7, -0.4, 0.3), vec3<>(0.1, 0.5, -0.2));
    const canonical_state<> c = to_canonical(a, f, k);
    CHECK((c.p - (2 * k.p - 3 * vec3<>(f.A(k.q)))).norm() < 1e-15);
    CHECK(max_difference(to_kinetic(a, f, c), k) < 1e-15);
    CHECK(std::abs(energy(a, f, k) - (k.p.squaredNorm() - 3 * f.phi(k.q))) < 1e-15);
    const vec3<> acc = lorentz_acceleration(a, f, k.q, k.p, 0.0);
    CHECK((acc - (-1.5) * (vec3<>(f.E(k.q, 0.0)) + k.p.cross(vec3<>(f.B(k.q, 0.0))))).norm() < 1e-15);
    CHECK(std::abs(lorentz_factor(a, vec3<>(0, 0, 10)) - std::sqrt(2.0)) < 1e-15);
    CHECK(lorentz_factor(particle{.speed_of_light = std::numeric_limits<double>::infinity()}, vec3<>(1, 2, 3)) == 1);
}

TEST_CASE("particle: bad mass, charge or speed of light is named") {
    CHECK_THROWS_WITH_AS(particle{.mass = 0}.check("who"), doctest::Contains("mass = 0"), invalid_argument);
    CHECK_THROWS_WITH_AS(particle{.charge = std::nan("")}.check("who"), doctest::Contains("charge = nan"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(particle{.speed_of_light = -1}.check("who"), doctest::Contains("speed_of_light = -1"),
                         invalid_argument);
}

}  // namespace test_charged_test_particle
