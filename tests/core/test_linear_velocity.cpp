// The one check that velocity(p) is linear in p (T quadratic): a mass matrix
// passes to rounding, an affine or a relativistic velocity fails by O(1) with
// the component and both values named.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <sympl/core/linear_velocity.hpp>
#include <sympl/core/dual.hpp>

namespace test_core_test_linear_velocity {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using V = Eigen::VectorXd;

TEST_CASE("linear velocity: M^-1 p passes, affine and relativistic velocities fail with the defect named") {
    Eigen::MatrixXd m_inverse(3, 3);
    m_inverse << 2, 0.5, 0, 0.5, 1, 0.25, 0, 0.25, 3;
    CHECK_NOTHROW(check_linear_velocity<V>([&](const V& p, V& v) { v = m_inverse * p; }, 3, "t", "u"));
    const auto affine = [](const V& p, V& v) { v = p.array() + 0.1; };
    CHECK_THROWS_WITH_AS(check_linear_velocity<V>(affine, 3, "stepper", "the method"),
                         doctest::Contains("stepper: velocity(p) is not linear in p: component 0"), invalid_argument);
    // p / sqrt(1 + p^2): the relativistic pendulum's kinetic energy.
    const auto relativistic = [](const V& p, V& v) { v = p.array() / (1 + p.array().square()).sqrt(); };
    CHECK_THROWS_WITH_AS(check_linear_velocity<V>(relativistic, 2, "s", "a quadratic T"),
                         doctest::Contains("as a quadratic T needs"), invalid_argument);
    // Dual numbers: the primal parts are compared.
    using D = dual<double, 1>;
    using VD = Eigen::Matrix<D, Eigen::Dynamic, 1>;
    CHECK_NOTHROW(check_linear_velocity<VD>([](const VD& p, VD& v) { v = p * D(0.5); }, 2, "t", "u"));
}

}  // namespace test_core_test_linear_velocity
