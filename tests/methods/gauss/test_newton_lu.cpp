// The LU factorisation of the Newton matrix (methods/gauss/newton_lu.hpp): solves
// against Eigen's own on matrices that need row swaps at several columns
// (the swaps move the stored multipliers of L, which the solve must honour),
// and a singular matrix names its pivot.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include <sympl/methods/gauss/newton_lu.hpp>

namespace test_methods_test_newton_lu {  // one per file: the tests build in batches (CMakeLists.txt)

TEST_CASE("newton_lu: solves agree with Eigen's where partial pivoting swaps rows") {
    // Random 12 x 12 matrices scaled so that the largest entry of each column
    // lies below the diagonal: every column swaps. The solution's residual is
    // rounding: a few eps times |A| |x| times N.
    const double eps = std::numeric_limits<double>::epsilon();
    for (int trial = 0; trial < 20; ++trial) {
        CAPTURE(trial);
        const int N = 12;
        Eigen::MatrixXd A = Eigen::MatrixXd::Random(N, N);
        for (int k = 0; k + 1 < N; ++k) A(N - 1 - (k + trial) % (N - k - 1) - 0, k) = 50.0 + k;  // large below the diagonal
        sympl::detail::newton_lu<double> lu;
        lu.resize(N);
        lu.matrix = A;
        REQUIRE(lu.factor() == -1);
        int swaps = 0;
        for (int k = 0; k < N; ++k) swaps += lu.pivot[k] != k;
        CHECK(swaps >= 2);
        const Eigen::VectorXd b = Eigen::VectorXd::Random(N);
        Eigen::VectorXd x = b;
        lu.solve(x);
        const Eigen::VectorXd reference = A.partialPivLu().solve(b);
        const double scale = A.cwiseAbs().maxCoeff() * reference.cwiseAbs().maxCoeff();
        CHECK((A * x - b).cwiseAbs().maxCoeff() <= 64 * N * eps * scale);
    }
}

TEST_CASE("newton_lu: a singular matrix is reported at its zero pivot") {
    sympl::detail::newton_lu<double> lu;
    lu.resize(3);
    lu.matrix << 1, 2, 3, 2, 4, 6, 1, 0, 1;
    CHECK(lu.factor() >= 0);
}

}  // namespace test_methods_test_newton_lu
