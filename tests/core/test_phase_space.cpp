#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include <sympl/core/phase_space.hpp>

namespace test_core_test_phase_space {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

TEST_CASE("phase_space: mismatched dimensions are refused with both sizes named") {
    Eigen::VectorXd q(3), p(2);
    q.setZero();
    p.setZero();
    try {
        phase_space<double> x(q, p);
        FAIL("no exception");
    } catch (const invalid_argument& e) {
        CHECK(std::string(e.what()).find("q has 3 components but p has 2") != std::string::npos);
    }
    CHECK_THROWS_AS((phase_space<double, 2>(3)), invalid_argument);
}

TEST_CASE("phase_space: finiteness, distance and casts") {
    phase_space<double, 2> x(Eigen::Vector2d(1, 2), Eigen::Vector2d(3, 4));
    CHECK(is_finite(x));
    phase_space<double, 2> y = x;
    y.p[1] = 4.5;
    CHECK(max_difference(x, y) == 0.5);
    y.q[0] = std::numeric_limits<double>::quiet_NaN();
    CHECK_FALSE(is_finite(y));
    const auto d = x.cast<long double, Eigen::Dynamic>();
    CHECK(d.size() == 2);
    CHECK(d.p[1] == 4.0L);
}

}  // namespace test_core_test_phase_space
