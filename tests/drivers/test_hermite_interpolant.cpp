// The Hermite interpolant of one step (step_interpolant): the end states
// exactly, one force and one velocity per end (cubic), the quintic's check of
// a quadratic kinetic energy. Its error orders are measured in
// test_dense_output.cpp, through integrate_dense.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <sympl/drivers/hermite_interpolant.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/relativistic_pendulum.hpp>

namespace test_drivers_test_hermite_interpolant {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using S1 = phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;

TEST_CASE("hermite interpolant: the end states exactly, the derivatives at each end once, ends handed on") {
    const hamiltonians::harmonic_oscillator h{};
    step_interpolant<hamiltonians::harmonic_oscillator, S1> dense(h, hermite_order::cubic);
    const S1 a(V1(1), V1(0)), b(V1(std::cos(0.1)), V1(-std::sin(0.1))), c(V1(std::cos(0.2)), V1(-std::sin(0.2)));
    dense.start(a, 0.0);
    dense.push(b, 0.1);
    S1 out = a;
    dense.evaluate(0.0, out);
    CHECK(max_difference(out, a) == 0);
    dense.evaluate(0.1, out);
    CHECK(max_difference(out, b) == 0);
    dense.evaluate(0.05, out);
    // Cubic Hermite: error <= dt^4 / 384 max|x''''| = 1e-4 / 384 on the oscillator.
    CHECK(std::fabs(out.q[0] - std::cos(0.05)) <= 1e-4 / 384);
    CHECK(dense.force_evaluations() == 2);
    CHECK(dense.velocity_evaluations() == 2);
    dense.push(c, 0.2);  // b is the new start, its derivatives kept
    dense.evaluate(0.15, out);
    CHECK(std::fabs(out.q[0] - std::cos(0.15)) <= 1e-4 / 384);
    CHECK(dense.force_evaluations() == 3);
}

TEST_CASE("hermite interpolant: the quintic refuses a kinetic energy that is not quadratic, the cubic takes it") {
    const hamiltonians::relativistic_pendulum h{};
    const S1 a(V1(1), V1(0));
    step_interpolant<hamiltonians::relativistic_pendulum, S1> cubic(h, hermite_order::cubic);
    CHECK_NOTHROW(cubic.start(a, 0.0));
    step_interpolant<hamiltonians::relativistic_pendulum, S1> quintic(h, hermite_order::quintic);
    CHECK_THROWS_WITH_AS(quintic.start(a, 0.0), doctest::Contains("step_interpolant: velocity(p) is not linear in p"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS((step_interpolant<hamiltonians::relativistic_pendulum, S1>(h, hermite_order(4))),
                         doctest::Contains("order = 4"), invalid_argument);
}

}  // namespace test_drivers_test_hermite_interpolant
