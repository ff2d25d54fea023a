// The scales of a problem read off a state (methods/problem_scales.hpp): the
// fastest frequency and the momentum per position of harmonic oscillators,
// where theory gives them, and Tao's binding chosen from them holding the
// copies of the outer solar system together over its scene's step sizes,
// with the semiexplicit method's projection converging there too.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/methods/problem_scales.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/outer_solar_system.hpp>

namespace test_methods_test_problem_scales {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

TEST_CASE("problem scales: an oscillator's frequency and m omega, per component") {
    // H = p^2/2m + m w^2 q^2/2: J has eigenvalues +-i w; kappa = sqrt(H_qq/H_pp) = m w.
    using S = phase_space<double, 2>;
    hamiltonians::harmonic_oscillator osc;
    osc.mass = 3e-6;
    osc.omega = 2.5e-3;
    const separable_as_general<hamiltonians::harmonic_oscillator> h{osc};
    const S x(Eigen::Vector2d(30.0, -4.0), Eigen::Vector2d(1e-7, 2e-8));
    CHECK(fastest_frequency(h, x) == doctest::Approx(2.5e-3).epsilon(1e-9));
    for (const double k : momentum_scales(h, x)) CHECK(k == doctest::Approx(3e-6 * 2.5e-3).epsilon(1e-12));
    CHECK(momentum_scale(x) == doctest::Approx(1e-7 / 30));
    const tao_options o = tao_options_for(h, x);
    CHECK(o.omega == doctest::Approx(4 * 2.5e-3).epsilon(1e-9));
    CHECK_THROWS_AS(tao_options_for(h, x, 0.0), invalid_argument);
}

TEST_CASE("problem scales: Tao and the semiexplicit method hold the outer solar system over its sweep") {
    // Momenta of 1e-11 (Pluto) to 1e-5 beside positions of 5 to 40 AU: Tao's
    // binding with omega = 20 and kappa = 1 separated the copies at step 1
    // (issue 39). In each component's units (kappa_k = m_k omega_k) and with
    // omega = 4 times Jupiter's frequency, tao(yoshida_6) holds them at every
    // step size of the scene's sweep (200 .. 5 days) over 4000 days (measured
    // largest divergence 1e-4 at 200 days, 6.5e-14 at 5), and the semiexplicit
    // projection, each half judged on its own half of the state, converges.
    using S = phase_space<double, hamiltonians::outer_solar_system::dimension>;
    const hamiltonians::outer_solar_system sun{};
    const separable_as_general<hamiltonians::outer_solar_system> h{sun};
    const S x0 = sun.initial_state();
    const double e0 = energy(sun, x0);
    const tao_options o = tao_options_for(h, x0);
    CHECK(o.omega == doctest::Approx(4 * 2 * 3.14159 / 4332.6).epsilon(0.3));  // Jupiter's 11.86 years
    for (int k = 0; k < 7; ++k) {
        const double dt = 200 * std::pow(5.0 / 200, k / 6.0);
        CAPTURE(dt);
        const long n = std::lround(4000 / dt);
        S x = x0, y = x0, z = x0;
        auto tao = make_tao_stepper<S>(h, method("yoshida_6"), o);
        auto semi4 = make_semiexplicit_stepper<S>(h, method("yoshida_4"));
        auto semi6 = make_semiexplicit_stepper<S>(h, method("yoshida_6"));
        for (long i = 0; i < n; ++i) {
            REQUIRE_NOTHROW(tao.step(x, dt));
            REQUIRE_NOTHROW(semi4.step(y, dt));
            REQUIRE_NOTHROW(semi6.step(z, dt));
        }
        CHECK(tao.max_divergence() < 1e-3);
        // The methods' own energy errors at 200-day steps: 5e-3 (Tao), 1e-4, 4e-6.
        CHECK(std::fabs(energy(sun, x) / e0 - 1) < 1e-2);
        CHECK(std::fabs(energy(sun, y) / e0 - 1) < 1e-3);
        CHECK(std::fabs(energy(sun, z) / e0 - 1) < 1e-4);
    }
}

}  // namespace test_methods_test_problem_scales
