// chaos_indicator.hpp: MEGNO from the tangent map of the numerical flow,
// against the limits theory gives (Cincotta, Giordano & Simo 2003).
#include <doctest/doctest.h>

#include <cmath>

#include <sympl/analysis/chaos_indicator.hpp>
#include <sympl/parallel/ensemble.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/sympl.hpp>

namespace test_analysis_test_chaos_indicator {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using hh = hamiltonians::henon_heiles;

TEST_CASE("chaos_indicator: the accumulator gives 2 for linear growth and 0 for a bounded tangent vector") {
    megno_accumulator<double> linear, bounded;
    for (int j = 1; j <= 100000; ++j) {
        const double t = 0.01 * j;
        linear.add(t, std::log(t));             // |delta| grows like t
        bounded.add(t, std::log(2 + std::sin(t)) - std::log(2.0));  // |delta| oscillates
    }
    CHECK(linear.mean() == doctest::Approx(2).epsilon(0.01));
    CHECK(std::fabs(bounded.mean()) < 0.05);
}

TEST_CASE("chaos_indicator: MEGNO tends to 2 on quasi-periodic orbits and to 0 on the isochronous oscillator") {
    const double dt = 0.05;
    SUBCASE("a regular Henon-Heiles orbit (E = 1/12)") {
        const double y = megno(hh{}, method("blanes_moan_s6"), hh::initial_state(1.0 / 12, 0.1, 0.0), dt, 40000, 10);
        CHECK(std::fabs(y - 2) < 0.1);
    }
    SUBCASE("the pendulum, whose period depends on the amplitude") {
        using P = phase_space<double, 1>;
        // <Y> approaches 2 like ln(t)/t: 1.84 at t = 2000, 1.95 at t = 10^4.
        const double y = megno(hamiltonians::pendulum{}, method("leapfrog_kdk"),
                               P(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.0)), 0.1, 100000, 10);
        CHECK(std::fabs(y - 2) < 0.1);
    }
    SUBCASE("the harmonic oscillator: every orbit has the same period, |delta| stays bounded") {
        using P = phase_space<double, 1>;
        const double y = megno(hamiltonians::harmonic_oscillator{}, method("leapfrog_kdk"),
                               P(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.0)), dt, 40000, 10);
        CHECK(std::fabs(y) < 0.1);
    }
}

TEST_CASE("chaos_indicator: MEGNO grows linearly on a chaotic Henon-Heiles orbit (E = 1/6)") {
    // (q2, p2) = (-0.1, 0) at E = 1/6 lies in the chaotic sea of the section
    // (Henon & Heiles 1964, fig. 5): <Y> ~ lambda t / 2 with lambda ~ 0.05.
    const auto x0 = hh::initial_state(1.0 / 6, -0.1, 0.0);
    const double y1 = megno(hh{}, method("blanes_moan_s6"), x0, 0.05, 20000, 10);
    const double y2 = megno(hh{}, method("blanes_moan_s6"), x0, 0.05, 40000, 10);
    CHECK(y1 > 4);
    CHECK(y2 > 1.5 * y1);  // linear growth doubles it; regular orbits stay at 2
}

}  // namespace test_analysis_test_chaos_indicator
