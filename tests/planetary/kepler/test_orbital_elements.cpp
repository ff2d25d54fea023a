// Orbital elements to positions and velocities (orbital_elements.hpp;
// Murray & Dermott 1999, sec. 2.8), checked against what the elements mean:
//   (a) energy -GM / 2a, angular momentum sqrt(GM a (1 - e^2)) along
//       (sin i sin Omega, -sin i cos Omega, cos i), pericentre a (1 - e) at M = 0
//       in the direction omega from the node, apocentre a (1 + e) at M = pi;
//   (b) the exact Kepler drift (kepler_drift.hpp) over t takes M to M + n t;
//   (c) a grid of particles about the star of a planetary state, a varying
//       fastest; bad input named.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/planetary/kepler/kepler_drift.hpp>
#include <sympl/planetary/kepler/orbital_elements.hpp>

namespace test_planetary_test_orbital_elements {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using V3 = Eigen::Vector3d;
V3 vec(const std::array<double, 3>& a) { return V3(a[0], a[1], a[2]); }
}  // namespace

TEST_CASE("orbital elements: energy, angular momentum, pericentre and apocentre") {
    const double gm = 2.5;
    for (double e : {0.0, 0.1, 0.5, 0.95})
        for (double M : {0.0, 1.0, 3.0, -2.0}) {
            CAPTURE(e);
            CAPTURE(M);
            const orbital_elements o{3.0, e, 0.4, 1.1, 2.3, M};
            const auto rv = to_cartesian(o, gm);
            const V3 r = vec(rv.first), v = vec(rv.second);
            const double energy = v.squaredNorm() / 2 - gm / r.norm();
            // v^2/2 and GM/r cancel: at pericentre each is (1 + e)/(1 - e) times the energy.
            CHECK(std::fabs(energy / (-gm / (2 * o.a)) - 1) < 1e-14 * (1 + e) / (1 - e));
            const V3 h = r.cross(v);
            CHECK(std::fabs(h.norm() / std::sqrt(gm * o.a * (1 - e * e)) - 1) < 1e-14);
            const V3 normal(std::sin(o.inclination) * std::sin(o.node), -std::sin(o.inclination) * std::cos(o.node),
                            std::cos(o.inclination));
            CHECK((h.normalized() - normal).norm() < 1e-14);
        }
    const orbital_elements peri{3.0, 0.3, 0.4, 1.1, 2.3, 0.0}, apo{3.0, 0.3, 0.4, 1.1, 2.3, 3.141592653589793};
    const V3 rp = vec(to_cartesian(peri, gm).first);
    CHECK(std::fabs(rp.norm() - 3.0 * 0.7) < 1e-14);
    CHECK(std::fabs(vec(to_cartesian(apo, gm).first).norm() - 3.0 * 1.3) < 1e-14);
    // The pericentre lies omega from the ascending node (cos Omega, sin Omega, 0), in the orbit's plane.
    const V3 node(std::cos(peri.node), std::sin(peri.node), 0);
    CHECK(std::fabs(rp.normalized().dot(node) - std::cos(peri.pericentre)) < 1e-14);
}

TEST_CASE("orbital elements: the Kepler drift over t takes M to M + n t") {
    const double gm = 1.0;
    for (double e : {0.0, 0.2, 0.7, 0.9}) {
        CAPTURE(e);
        const orbital_elements o{1.7, e, 0.2, 0.3, 0.9, 0.5};
        const double n = std::sqrt(gm / (o.a * o.a * o.a)), t = 3.7;
        const auto start = to_cartesian(o, gm);
        Eigen::Vector3d r = vec(start.first), v = vec(start.second);
        kepler_drift(r, v, gm, t);
        orbital_elements later = o;
        later.mean_anomaly += n * t;
        const auto end = to_cartesian(later, gm);
        CHECK((r - vec(end.first)).norm() < 1e-13 * o.a);
        CHECK((v - vec(end.second)).norm() < 1e-13 * std::sqrt(gm / o.a) / (1 - e));
    }
}

TEST_CASE("orbital elements: a grid of particles about the star, bad input named") {
    const hamiltonians::outer_solar_system sys{};
    const std::vector<double> m(sys.mass.begin(), sys.mass.end());
    const auto x0 = sys.initial_state();
    const phase_space<double> x(x0.q, x0.p);
    const std::vector<orbital_elements> g = element_grid(6, 9, 4, 0, 0.3, 3);
    REQUIRE(g.size() == 12);
    CHECK(g[1].a == 7);
    CHECK(g[1].e == 0);
    CHECK(g[4].a == 6);
    CHECK(std::fabs(g[4].e - 0.15) < 1e-15);
    const test_particle_set<double> p = particles_on(g, x, m, sys.G);
    REQUIRE(p.size() == 12);
    CHECK(p.id[11] == 11);
    // Circular (e = 0) at a = 6 about the star: distance 6 from the star's position.
    CHECK(std::fabs(std::hypot(p.x[0] - x.q[0], p.y[0] - x.q[1], p.z[0] - x.q[2]) - 6) < 1e-12);
    CHECK_THROWS_WITH_AS(to_cartesian({1, 1.0}, 1), doctest::Contains("e = 1; expected 0 <= e < 1"), invalid_argument);
    CHECK_THROWS_WITH_AS(to_cartesian({-1, 0}, 1), doctest::Contains("a = -1; expected a finite a > 0"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(element_grid(6, 9, 0, 0, 0.3, 3), doctest::Contains("0 x 3 points"), invalid_argument);
}

}  // namespace test_planetary_test_orbital_elements
