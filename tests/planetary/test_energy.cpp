// nbody_energy (energy.hpp): equal to the built-in outer solar system's
// Hamiltonian at its state; against a long-double sum on random systems; the
// energy the Wisdom-Holman leapfrog conserves to O(h^2); bad input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Core>

#include <sympl/core/hamiltonian.hpp>
#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/methods/catalog.hpp>
#include <sympl/planetary/energy.hpp>
#include <sympl/planetary/wisdom_holman_stepper.hpp>

namespace test_planetary_test_energy {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
constexpr double eps = std::numeric_limits<double>::epsilon();
using State = phase_space<double>;

// The same sum in long double, pair by pair, and the sum of the terms' sizes.
std::pair<long double, long double> energy_ld(const std::vector<double>& m, double G, const State& x) {
    long double h = 0, size = 0;
    for (std::size_t i = 0; i < m.size(); ++i) {
        long double p2 = 0;
        for (int k = 0; k < 3; ++k) p2 += (long double)x.p[Eigen::Index(3 * i) + k] * x.p[Eigen::Index(3 * i) + k];
        h += p2 / (2 * (long double)m[i]), size += p2 / (2 * (long double)m[i]);
        for (std::size_t j = i + 1; j < m.size(); ++j) {
            long double d2 = 0;
            for (int k = 0; k < 3; ++k) {
                const long double d = (long double)x.q[Eigen::Index(3 * i) + k] - x.q[Eigen::Index(3 * j) + k];
                d2 += d * d;
            }
            const long double v = (long double)G * m[i] * m[j] / std::sqrt(d2);
            h -= v, size += v;
        }
    }
    return {h, size};
}

// A star of mass 1 and planets of mass 1e-3 on nearly circular orbits at a = 1, 1.6, ...
State planets(const std::vector<double>& m, double G) {
    State x(3 * Eigen::Index(m.size()));
    x.q.setZero(), x.p.setZero();
    for (std::size_t i = 1; i < m.size(); ++i) {
        const double a = std::pow(1.6, double(i - 1)), v = std::sqrt(G * (m[0] + m[i]) / a), c = std::cos(2.0 * i),
                     s = std::sin(2.0 * i);
        const Eigen::Index k = Eigen::Index(3 * i);
        x.q[k] = a * c, x.q[k + 1] = a * s, x.q[k + 2] = 0.01 * a;
        x.p[k] = -m[i] * v * s, x.p[k + 1] = m[i] * v * c;
        x.p.segment<3>(0) -= x.p.segment<3>(k);  // the star's momentum: total zero
    }
    return x;
}
}  // namespace

TEST_CASE("nbody_energy: the outer solar system's own Hamiltonian, to rounding") {
    const hamiltonians::outer_solar_system sun{};
    using S18 = phase_space<double, 18>;
    const S18 x = sun.initial_state<double>();
    const double mine = nbody_energy(std::span<const double>(sun.mass), sun.G, x);
    const double theirs = energy(sun, x);
    CHECK(std::fabs(mine - theirs) <= 4 * eps * std::fabs(theirs));
}

TEST_CASE("nbody_energy: random systems against a long-double sum, within N^2 eps of the terms' size") {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> u(-1, 1), lm(-6, 0);
    double worst = 0;
    for (int bodies = 2; bodies <= 9; ++bodies)
        for (int trial = 0; trial < 50; ++trial) {
            std::vector<double> m(static_cast<std::size_t>(bodies));
            for (double& mi : m) mi = std::pow(10.0, lm(rng));
            State x(3 * bodies);
            for (Eigen::Index k = 0; k < x.size(); ++k) x.q[k] = 10 * u(rng), x.p[k] = u(rng);
            const auto [h, size] = energy_ld(m, 0.3, x);
            const double e = nbody_energy(std::span<const double>(m), 0.3, x);
            worst = std::max(worst, double(std::fabs(e - h) / size) / (bodies * bodies * eps));
        }
    MESSAGE("worst |error| / (N^2 eps size): " << worst);
    CHECK(worst <= 1);
}

// The leapfrog's energy error is O(eps h^2) (Wisdom & Holman 1991): halving h quarters it.
TEST_CASE("nbody_energy: conserved by the Wisdom-Holman leapfrog to O(h^2)") {
    const std::vector<double> m = {1, 1e-3, 1e-3};
    const double G = 1, period = 2 * 3.141592653589793;
    const State start = planets(m, G);
    const double e0 = nbody_energy(std::span<const double>(m), G, start);
    double worst[2] = {0, 0};
    for (int halving = 0; halving < 2; ++halving) {
        const int steps_per_period = 40 << halving;
        wisdom_holman_stepper<State> wh(m, G, method("leapfrog_kdk"));
        State x = start;
        for (int k = 0; k < 20 * steps_per_period; ++k) {
            wh.step(x, period / steps_per_period);
            worst[halving] = std::max(worst[halving], std::fabs(nbody_energy(std::span<const double>(m), G, x) / e0 - 1));
        }
    }
    MESSAGE("max relative energy error at h and h/2: " << worst[0] << ", " << worst[1]);
    CHECK(worst[0] / worst[1] > 3.5);
    CHECK(worst[0] / worst[1] < 4.5);
}

TEST_CASE("nbody_energy: bad input names the value") {
    const std::vector<double> m = {1, 1e-3, 1e-3};
    const State x = planets(m, 1);
    CHECK_THROWS_WITH_AS(nbody_energy(std::span<const double>(m).first(2), 1.0, x),
                         doctest::Contains("a state of 9 degrees of freedom for 2 bodies"), invalid_argument);
    const std::vector<double> bad = {1, -2, 1e-3};
    CHECK_THROWS_WITH_AS(nbody_energy(std::span<const double>(bad), 1.0, x), doctest::Contains("mass of body 1 = -2"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(nbody_energy(std::span<const double>(m), 0.0, x), doctest::Contains("G = 0"),
                         invalid_argument);
}

}  // namespace test_planetary_test_energy
