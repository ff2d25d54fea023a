// The Gauss stepper's options check and its componentwise correction measure
// (methods/gauss/gauss_options.hpp): each component judged against its own half of
// the state (q or p), not against the largest component, and a NaN kept.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include <sympl/sympl.hpp>
#include <sympl/methods/gauss/gauss_options.hpp>

namespace test_methods_test_gauss_options {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

TEST_CASE("gauss_options: the tolerance asked, and bad options refused by name") {
    const double eps = std::numeric_limits<double>::epsilon();
    gauss_options o;
    CHECK(detail::checked_relative_tolerance(o, eps) == eps);
    o.tolerance = 1e-10;
    CHECK(detail::checked_relative_tolerance(o, eps) == 1e-10);
    o.tolerance = -1;
    CHECK_THROWS_WITH_AS(detail::checked_relative_tolerance(o, eps), doctest::Contains("tolerance = -1"),
                         invalid_argument);
    o.tolerance.reset();
    o.absolute_tolerance = std::nan("");
    CHECK_THROWS_WITH_AS(detail::checked_relative_tolerance(o, eps), doctest::Contains("absolute_tolerance = "),
                         invalid_argument);
    o.absolute_tolerance.reset();
    o.max_iterations = 0;
    CHECK_THROWS_WITH_AS(detail::checked_relative_tolerance(o, eps), doctest::Contains("max_iterations = 0"),
                         invalid_argument);
}

TEST_CASE("gauss_options: a correction is measured against its own half of the state, a NaN kept") {
    using S = phase_space<double, 2>;
    using Stages = Eigen::Matrix<double, 4, Eigen::Dynamic>;
    const double rtol = 1e-10;
    // Positions of 2 beside momenta of 1e-5 (the outer solar system's contrast).
    const S x(Eigen::Vector2d(2.0, 0.0), Eigen::Vector2d(1e-5, 0.0));
    Stages z = Stages::Zero(4, 2), dz = Stages::Zero(4, 2);
    Eigen::Vector4d ymax;
    // q_0 against rtol (|q_0| + max |q|) = 4 rtol: half of it is 0.5.
    dz(0, 1) = 2 * rtol;
    CHECK(detail::scaled_correction(x, z, dz, ymax, rtol, std::nullopt) == doctest::Approx(0.5));
    // p_0 against rtol (|p_0| + max |p|) = 2e-5 rtol, not against the positions: a full 1.
    dz(2, 0) = 2e-5 * rtol;
    CHECK(detail::scaled_correction(x, z, dz, ymax, rtol, std::nullopt) == doctest::Approx(1.0));
    CHECK(ymax[0] == 2.0);
    CHECK(ymax[2] == 1e-5);
    // With atol = 1e-12 every component is judged on atol + rtol |y_k|: now
    // q_0's 2 rtol against 1e-12 + 2 rtol is the largest (p_0's about 0.002).
    CHECK(detail::scaled_correction(x, z, dz, ymax, rtol, 1e-12) == doctest::Approx(2 * rtol / (1e-12 + 2 * rtol)));
    // A stage value beyond y0 raises the scale: |q_0 + Z| = 6.
    z(0, 0) = 4.0;
    CHECK(detail::scaled_correction(x, z, dz, ymax, rtol, std::nullopt) == doctest::Approx(1.0));
    CHECK(ymax[0] == 6.0);
    dz(3, 1) = std::nan("");
    CHECK(std::isnan(detail::scaled_correction(x, z, dz, ymax, rtol, std::nullopt)));
}

}  // namespace test_methods_test_gauss_options
