// The starting values of gauss_tableau.hpp: the last step's collocation
// polynomial extrapolated to the next step's nodes reproduces a polynomial
// of degree s exactly and errs by O(h^(s+1)) on a smooth solution (GNI sec.
// VIII.6.1), and at r = -1 (a step back) it interpolates.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include <sympl/methods/gauss/gauss_tableau.hpp>

namespace test_methods_test_gauss_tableau {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

TEST_CASE("gauss_tableau: extrapolated stage values are exact for degree s and err by O(h^(s+1))") {
    const long double tol = 64 * std::numeric_limits<long double>::epsilon();
    for (int s = 1; s <= 3; ++s) {
        CAPTURE(s);
        const gauss_tableau t = gauss_legendre_tableau(s);
        // Z_next_i = sum_j beta_ij Z_j, where Z_j = u(c_j h) - u(0) and the next
        // step's stages are u(h + r c_i h) - u(h).
        const auto predicted_error = [&](auto u, long double h, long double r) {
            const auto beta = gauss_extrapolation(t, r);
            long double worst = 0;
            for (int i = 0; i < s; ++i) {
                long double z = 0;
                for (int j = 0; j < s; ++j) z += beta[i][j] * (u(t.c[j] * h) - u(0.0L));
                worst = std::max(worst, std::fabs(z - (u(h + r * t.c[i] * h) - u(h))));
            }
            return worst;
        };
        // A polynomial of degree s: exact, for any ratio r.
        const auto poly = [s](long double x) { return 1 + 0.3L * x + std::pow(x, (long double)s); };
        for (const long double r : {1.0L, 0.5L, 2.0L, -1.0L}) CHECK(predicted_error(poly, 1.0L, r) <= tol);
        // exp: the error falls as h^(s+1).
        const auto e = [](long double x) { return std::exp(x); };
        const long double order = std::log2(predicted_error(e, 0.1L, 1.0L) / predicted_error(e, 0.05L, 1.0L));
        MESSAGE("s = " << s << ": order " << double(order));
        CHECK(std::fabs(double(order) - (s + 1)) <= 0.1);
    }
}

}  // namespace test_methods_test_gauss_tableau
