// Extrapolation of symmetric methods: each column adds two orders, on a
// nonlinear problem, with non-quadratic kinetic energy, and in LogH time.
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include <sympl/methods/catalog.hpp>
#include <sympl/analysis/convergence.hpp>
#include <sympl/methods/extrapolation.hpp>
#include <sympl/drivers/fixed_step.hpp>
#include <sympl/core/splitting_stepper.hpp>
#include <sympl/methods/time_transformation.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/relativistic_pendulum.hpp>

namespace test_methods_test_extrapolation {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using X1 = phase_space<double, 1>;

namespace {
const double pi = std::numbers::pi;

template <class H>
double measured_order(const H& h, const char* name, int columns, double t_end, double floor = 1e-13) {
    order_options o;
    o.min_steps = 4;
    o.max_steps = 1 << 12;
    o.floor = floor;
    const auto m = measure_order(
        [&](std::size_t n) {
            X1 x(Eigen::Matrix<double, 1, 1>(1.2), Eigen::Matrix<double, 1, 1>(0.3));
            extrapolation_stepper s(splitting_stepper<H, X1>(h, method(name)), columns);
            integrate_steps(s, x, 0.0, t_end / double(n), n);
            return x;
        },
        t_end, o);
    CHECK(m.converged);
    return m.order;
}
}  // namespace

TEST_CASE("extrapolation: k columns of a symmetric order-p method give order p + 2(k - 1)") {
    // The pendulum is nonlinear; the relativistic pendulum has T = sqrt(1 + p^2) - 1, not quadratic.
    // (Order 8 and up leaves too short an asymptotic range above rounding in double to read.)
    for (const auto& entry : std::vector<std::pair<const char*, int>>{{"leapfrog_kdk", 2}, {"leapfrog_dkd", 2},
                                                                       {"forest_ruth_4", 4}}) {
        const char* name = entry.first;  // not a structured binding: CAPTURE takes none before clang 16
        const int p = entry.second;
        for (int k : {2, 3}) {
            if (p + 2 * (k - 1) > 6) continue;
            CAPTURE(name);
            CAPTURE(k);
            const double expected = p + 2 * (k - 1);
            CHECK(measured_order(hamiltonians::pendulum{}, name, k, 4.0) ==
                  doctest::Approx(expected).epsilon(0.15 / expected));
            CHECK(measured_order(hamiltonians::relativistic_pendulum{}, name, k, 4.0) ==
                  doctest::Approx(expected).epsilon(0.15 / expected));
        }
    }
}

TEST_CASE("extrapolation: the weights read a polynomial in h^2 at 0, their size bounds the rounding") {
    splitting_stepper<hamiltonians::pendulum, X1> inner(hamiltonians::pendulum{}, method("leapfrog_kdk"));
    CHECK(extrapolation_stepper(inner, 1).amplification() == 1.0);
    // Two columns: (4 T(h/2) - T(h)) / 3, Richardson's combination (Gould & Tobochnik, eq. 3.68).
    CHECK(extrapolation_stepper(inner, 2).amplification() == doctest::Approx(5.0 / 3.0).epsilon(1e-15));
    CHECK(extrapolation_stepper(inner, 4).order() == 8);
    // For a fourth-order inner method the weights cancel h^4, h^6, ... instead.
    splitting_stepper<hamiltonians::pendulum, X1> fr(hamiltonians::pendulum{}, method("forest_ruth_4"));
    for (int k = 1; k <= 8; ++k) {
        for (const auto& entry : {std::pair{extrapolation_stepper(inner, k), 2}, {extrapolation_stepper(fr, k), 4}}) {
            const auto& stepper = entry.first;  // not a structured binding: CAPTURE takes none before clang 16
            const int p = entry.second;
            CAPTURE(k);
            CAPTURE(p);
            const auto& c = stepper.combination();
            double sum = 0, size = 0;
            for (double w : c) sum += w, size += std::fabs(w);
            CHECK(sum == doctest::Approx(1).epsilon(1e-15 * size));
            for (int i = 0; i + 1 < k; ++i) {
                double moment = 0;
                for (int j = 1; j <= k; ++j) moment += c[j - 1] * std::pow(1.0 / j, p + 2 * i);
                CHECK(std::fabs(moment) < 1e-15 * size);
            }
            CHECK(stepper.order() == p + 2 * (k - 1));
        }
    }
    CHECK(extrapolation_stepper(inner, 6).inner_steps_per_step() == 21);
}

TEST_CASE("extrapolation: a table that is not symmetric, or a column count out of range, is refused with the value") {
    splitting_stepper<hamiltonians::pendulum, X1> ruth(hamiltonians::pendulum{}, method("ruth_3"));
    CHECK_THROWS_WITH_AS(extrapolation_stepper(ruth, 3), doctest::Contains("'ruth_3' is not symmetric"),
                         invalid_argument);
    splitting_stepper<hamiltonians::pendulum, X1> leapfrog(hamiltonians::pendulum{}, method("leapfrog_kdk"));
    CHECK_THROWS_WITH_AS(extrapolation_stepper(leapfrog, 0), doctest::Contains("columns = 0"), invalid_argument);
    CHECK_THROWS_WITH_AS(extrapolation_stepper(leapfrog, 17), doctest::Contains("columns = 17"), invalid_argument);
}

TEST_CASE("extrapolation: LogH leapfrog extrapolated keeps order 2k on Kepler e = 0.9 and lands on t_end") {
    using KX = phase_space<double, 3>;
    const hamiltonians::kepler h{};
    for (int k : {2, 3}) {
        CAPTURE(k);
        order_options o;
        o.min_steps = 16;
        o.max_steps = 1 << 12;
        o.floor = 1e-11;
        const auto m = measure_order(
            [&](std::size_t n) {
                KX X = to_extended(h, hamiltonians::kepler::initial_state(0.9));
                extrapolation_stepper s(splitting_stepper<logh<hamiltonians::kepler>, KX>({h}, method("leapfrog_dkd")), k);
                integrate_to_time(s, X, 2 * pi, 2 * pi / double(n));
                CHECK(physical_time(X) == 2 * pi);
                return physical_state(X);
            },
            2 * pi, o);
        CHECK(m.converged);
        CHECK(m.order == doctest::Approx(2 * k).epsilon(0.15 / (2 * k)));
    }
    // Against the exact orbit: 6 columns at 16 macro steps per orbit, 3 orbits, well below 1e-6.
    KX X = to_extended(h, hamiltonians::kepler::initial_state(0.9));
    extrapolation_stepper s(splitting_stepper<logh<hamiltonians::kepler>, KX>({h}, method("leapfrog_dkd")), 6);
    const auto r = integrate_to_time(s, X, 6 * pi, 2 * pi / 16);
    CHECK(physical_time(X) == 6 * pi);
    CHECK(max_difference(physical_state(X), hamiltonians::kepler::exact_state(0.9, 6 * pi)) < 1e-6);
    CHECK(r.force_evaluations >= 48 * 21);
}

}  // namespace test_methods_test_extrapolation
