// Jayawardana & Ohsawa's semiexplicit method (methods/semiexplicit.hpp):
// symplectic in the original space, and a projection that does not converge
// stops the run. Its orders, energy error, counts and refusals are measured
// beside Tao's in test_extended_phase_space.cpp.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>

#include <sympl/sympl.hpp>
#include <sympl/methods/semiexplicit.hpp>

#include "nonseparable_problems.hpp"

namespace test_methods_test_semiexplicit {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using namespace sympl::nonseparable_testing;

namespace {
using V1 = Eigen::Matrix<double, 1, 1>;
using State = phase_space<double, 1>;
}  // namespace

TEST_CASE("semiexplicit: the map is symplectic in the original space to rounding") {
    // J&O 2023: symplectic in the original phase space once the projection is
    // solved (here to 8 machine epsilons); 1000 steps to t = 10.
    using D2 = dual<double, 2>;
    using S2 = phase_space<D2, 1>;
    using V2 = Eigen::Matrix<D2, 1, 1>;
    for (const table* t : {&leapfrog, &order4, &order6})
        for (const auto& h : {0, 1}) {
            S2 x(V2(D2::variable(h == 0 ? -3.0 : 2.5, 0)), V2(D2::variable(0.0, 1)));
            x = h == 0 ? run<D2>(make_semiexplicit_stepper<S2>(product, *t), x, 10.0, 1000)
                       : run<D2>(make_semiexplicit_stepper<S2>(varying_mass, *t), x, 10.0, 1000);
            std::printf("semiexplicit, original space, t = 10, %-26s %s: |det M - 1| = %.2e\n", t->name().c_str(),
                        h == 0 ? "product     " : "varying mass", area_defect(x));
            CAPTURE(t->name());
            CHECK(area_defect(x) <= 1e-12);
        }
}

TEST_CASE("semiexplicit: a projection that does not converge stops the step, the state left as it was") {
    auto s = make_semiexplicit_stepper<State>(product, leapfrog);
    State x(V1(-3.0), V1(0.0));
    CHECK_THROWS_AS(s.step(x, 0.5), integration_error);
    CHECK(x.q[0] == -3.0);
}

}  // namespace test_methods_test_semiexplicit
