// Planetary coordinates (coordinates.hpp): democratic heliocentric and
// Jacobi both ways, what the splittings need of them, refused masses.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Core>

#include <sympl/planetary/coordinates.hpp>

namespace test_planetary_test_coordinates {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using ld = long double;
using V3 = Eigen::Matrix<ld, 3, 1>;
constexpr double eps = std::numeric_limits<double>::epsilon();
}  // namespace

namespace {
struct planetary_system {
    std::vector<double> mass;
    phase_space<double> x;
};

// A star of mass 1 and N - 1 planets of mass 10^[-9, 0] at 1..30 AU-like
// distances, moving at ~orbital speeds, in an inertial frame offset from the
// barycentre and moving.
planetary_system random_system(std::mt19937_64& rng, int bodies) {
    std::uniform_real_distribution<double> u(-1, 1);
    planetary_system s{std::vector<double>(std::size_t(bodies)), phase_space<double>(3 * bodies)};
    s.mass[0] = 1;
    for (int i = 1; i < bodies; ++i) s.mass[std::size_t(i)] = std::pow(10.0, -9 + 9 * (u(rng) + 1) / 2);
    for (int i = 0; i < bodies; ++i)
        for (int k = 0; k < 3; ++k) {
            s.x.q[3 * i + k] = 5 + (i == 0 ? 0.01 : 15) * u(rng);
            s.x.p[3 * i + k] = s.mass[std::size_t(i)] * (0.3 + (i == 0 ? 0.001 : 1) * u(rng));
        }
    return s;
}

// The largest error per body, in units of eps times the body's scale:
// N |q|_max for positions, N m_i |v|_max for momenta.
double roundtrip_error(const planetary_system& s, const phase_space<double>& back) {
    const Eigen::Index n = Eigen::Index(s.mass.size());
    double qmax = s.x.q.cwiseAbs().maxCoeff(), vmax = 0;
    for (Eigen::Index i = 0; i < n; ++i) vmax = std::max(vmax, s.x.p.segment<3>(3 * i).norm() / s.mass[std::size_t(i)]);
    double worst = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
        worst = std::max(worst, (back.q.segment<3>(3 * i) - s.x.q.segment<3>(3 * i)).norm() / (double(n) * qmax * eps));
        worst = std::max(worst, (back.p.segment<3>(3 * i) - s.x.p.segment<3>(3 * i)).norm() /
                                    (double(n) * s.mass[std::size_t(i)] * vmax * eps));
    }
    return worst;
}
}  // namespace

TEST_CASE("planetary coordinates: democratic heliocentric and Jacobi round trip to rounding, N = 2..10") {
    // Each coordinate is a sum of at most N terms of size <= the scale, each
    // rounded once or twice, both ways: the bound 8 eps N scale.
    std::mt19937_64 rng(5);
    double worst_dh = 0, worst_jacobi = 0;
    for (int bodies = 2; bodies <= 10; ++bodies)
        for (int trial = 0; trial < 200; ++trial) {
            const planetary_system s = random_system(rng, bodies);
            worst_dh = std::max(worst_dh, roundtrip_error(s, from_democratic_heliocentric(
                                                                 to_democratic_heliocentric(s.x, s.mass), s.mass)));
            worst_jacobi = std::max(worst_jacobi, roundtrip_error(s, from_jacobi(to_jacobi(s.x, s.mass), s.mass)));
        }
    MESSAGE("round trip <= " << worst_dh << " (democratic heliocentric), " << worst_jacobi
                             << " (Jacobi) eps N scale");
    CHECK(worst_dh <= 8);
    CHECK(worst_jacobi <= 8);
}

TEST_CASE("planetary coordinates: centre of mass, total momentum and kinetic energy as the splittings need them") {
    std::mt19937_64 rng(9);
    double worst = 0;
    for (int bodies = 2; bodies <= 10; ++bodies)
        for (int trial = 0; trial < 100; ++trial) {
            const planetary_system s = random_system(rng, bodies);
            const std::size_t n = s.mass.size();
            // Long-double references of the centre of mass, total momentum, kinetic energy.
            ld M = 0, T = 0;
            V3 com = V3::Zero(), P = V3::Zero();
            for (std::size_t i = 0; i < n; ++i) {
                const Eigen::Index k = Eigen::Index(3 * i);
                M += s.mass[i];
                com += ld(s.mass[i]) * s.x.q.segment<3>(k).cast<ld>();
                P += s.x.p.segment<3>(k).cast<ld>();
                T += s.x.p.segment<3>(k).cast<ld>().squaredNorm() / (2 * ld(s.mass[i]));
            }
            com /= M;
            const double qscale = s.x.q.cwiseAbs().maxCoeff();
            const ld pscale = [&] {
                ld m = 0;
                for (std::size_t i = 0; i < n; ++i) m += s.x.p.segment<3>(Eigen::Index(3 * i)).cast<ld>().norm();
                return m;
            }();
            const auto q0 = [](const phase_space<double>& y) { return V3(y.q.segment<3>(0).cast<ld>()); };
            const auto p0 = [](const phase_space<double>& y) { return V3(y.p.segment<3>(0).cast<ld>()); };

            // Democratic heliocentric (Duncan, Levison & Lee 1998, eq. 2-4).
            const phase_space<double> dh = to_democratic_heliocentric(s.x, s.mass);
            V3 planets = V3::Zero();
            ld T_dh = p0(dh).squaredNorm() / (2 * M);
            for (std::size_t i = 1; i < n; ++i) {
                const V3 Pi = dh.p.segment<3>(Eigen::Index(3 * i)).cast<ld>();
                planets += Pi;
                T_dh += Pi.squaredNorm() / (2 * ld(s.mass[i]));
                // Heliocentric positions.
                const V3 rel = (s.x.q.segment<3>(Eigen::Index(3 * i)) - s.x.q.segment<3>(0)).cast<ld>();
                worst = std::max(worst, double((dh.q.segment<3>(Eigen::Index(3 * i)).cast<ld>() - rel).norm() / (qscale * eps)));
            }
            T_dh += planets.squaredNorm() / (2 * ld(s.mass[0]));
            // The planets' barycentric momenta sum to minus the star's.
            const V3 star_bary = s.x.p.segment<3>(0).cast<ld>() - ld(s.mass[0]) / M * P;
            worst = std::max(worst, double((planets + star_bary).norm() / (double(n) * pscale * eps)));
            worst = std::max(worst, double((q0(dh) - com).norm() / (double(n) * qscale * eps)));
            worst = std::max(worst, double((p0(dh) - P).norm() / (double(n) * pscale * eps)));
            worst = std::max(worst, double(std::fabs(T_dh - T) / (double(n) * T * eps)));

            // Jacobi (Wisdom & Holman 1991, sec. 3): the kinetic energy keeps its form in the Jacobi masses.
            const phase_space<double> jac = to_jacobi(s.x, s.mass);
            const std::vector<double> mj = jacobi_masses(s.mass);
            ld T_j = 0;
            for (std::size_t i = 0; i < n; ++i)
                T_j += jac.p.segment<3>(Eigen::Index(3 * i)).cast<ld>().squaredNorm() / (2 * ld(mj[i]));
            worst = std::max(worst, double(std::fabs(T_j - T) / (double(n) * T * eps)));
            worst = std::max(worst, double((q0(jac) - com).norm() / (double(n) * qscale * eps)));
            worst = std::max(worst, double((p0(jac) - P).norm() / (double(n) * pscale * eps)));
            // The innermost Jacobi position is heliocentric.
            worst = std::max(worst, double((jac.q.segment<3>(3) - (s.x.q.segment<3>(3) - s.x.q.segment<3>(0))).cast<ld>().norm() /
                                           (qscale * eps)));
        }
    MESSAGE("centre of mass, momentum and kinetic energy relations hold to " << worst << " eps N scale");
    CHECK(worst <= 8);
}

TEST_CASE("planetary coordinates: a non-positive mass is refused, naming the body and the value") {
    std::mt19937_64 rng(1);
    planetary_system s = random_system(rng, 4);
    s.mass[2] = -1e-3;
    CHECK_THROWS_WITH_AS(to_jacobi(s.x, s.mass), doctest::Contains("mass of body 2 = -0.001"), invalid_argument);
    CHECK_THROWS_WITH_AS(from_democratic_heliocentric(s.x, s.mass), doctest::Contains("mass of body 2 = -0.001"),
                         invalid_argument);
    s.mass[2] = 0;
    CHECK_THROWS_WITH_AS(to_democratic_heliocentric(s.x, s.mass), doctest::Contains("mass of body 2 = 0"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(jacobi_masses(s.mass), doctest::Contains("mass of body 2 = 0"), invalid_argument);
    s.mass[2] = 1e-3;
    s.mass.push_back(1);
    CHECK_THROWS_WITH_AS(from_jacobi(s.x, s.mass), doctest::Contains("12 degrees of freedom for 5 bodies"),
                         invalid_argument);
}

}  // namespace test_planetary_test_coordinates
