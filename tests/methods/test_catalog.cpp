// The catalog as a whole: look-up by name, families, symmetry and reversibility,
// energy behaviour; the tables entry by entry are test_catalog_tables.cpp.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

namespace test_methods_test_catalog {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using V1 = Eigen::Matrix<double, 1, 1>;
using State1 = phase_space<double, 1>;
}  // namespace

TEST_CASE("catalog: symmetric methods retrace their steps, step(dt) then step(-dt)") {
    for (const table& t : catalog()) {
        if (!t.is_symmetric()) continue;
        CAPTURE(t.name());
        splitting_stepper<hamiltonians::pendulum, State1> s({}, t);
        const State1 x0(V1(1.1), V1(-0.4));
        State1 x = x0;
        for (int i = 0; i < 10; ++i) s.step(x, 0.1);
        for (int i = 0; i < 10; ++i) s.step(x, -0.1);
        CHECK(max_difference(x, x0) <= 1e-13);
    }
}

TEST_CASE("catalog: adjoint(adjoint(t)) == t, and symmetric entries are their own adjoint") {
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        CHECK(adjoint(adjoint(t)) == t);
        if (t.is_symmetric()) CHECK(adjoint(t) == t);
    }
}

TEST_CASE("catalog: Gould & Tobochnik's Verlet table is velocity Verlet") {
    // Gould & Tobochnik eq. 3.75: M = 2, a = (1, 1), b = (2, 0) reduces to eq. 3.48.
    CHECK(method("verlet_seed") == method("leapfrog_kdk"));
    splitting_stepper<hamiltonians::pendulum, State1> seed({}, method("verlet_seed"));
    State1 x(V1(1.0), V1(0.2)), y = x;
    seed.steps(x, 0.05, 100);
    const auto verlet_by_hand = [](State1& s, double dt) {  // Gould & Tobochnik eq. 3.48
        const double a0 = -std::sin(s.q[0]);
        s.q[0] += s.p[0] * dt + 0.5 * a0 * dt * dt;
        s.p[0] += 0.5 * (a0 - std::sin(s.q[0])) * dt;
    };
    for (int i = 0; i < 100; ++i) verlet_by_hand(y, 0.05);
    CHECK(max_difference(x, y) <= 1e-13);
}

TEST_CASE("catalog: symplectic methods show no energy drift over 1e5 pendulum steps") {
    // A symplectic method's energy error stays bounded: its largest excursion in
    // the last tenth of the run is no larger than in the first tenth (a drifting
    // method grows ~10x). dt is chosen per method so that the energy error sits
    // between 1e-10 and 1e-4, far above roundoff.
    const hamiltonians::pendulum h;
    const State1 x0(V1(2.0), V1(0.0));
    const double e0 = energy(h, x0);
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        splitting_stepper<hamiltonians::pendulum, State1> s(h, t);
        double dt = 0.5 * t.stability_interval();
        for (;; dt /= 2) {
            State1 x = x0;
            double worst = 0;
            for (int i = 0; i < 200; ++i) {
                s.step(x, dt);
                worst = std::max(worst, std::fabs(energy(h, x) - e0));
            }
            if (worst < 1e-4) break;
        }
        CAPTURE(dt);
        const int n = 100000;
        double first = 0, last = 0;
        State1 x = x0;
        for (int i = 1; i <= n; ++i) {
            s.steps(x, dt, 1);
            const double err = std::fabs(energy(h, x) - e0);
            if (i <= n / 10) first = std::max(first, err);
            if (i > n - n / 10) last = std::max(last, err);
        }
        CAPTURE(first);
        CAPTURE(last);
        CHECK(last <= 1.5 * first + 1e-13);
    }
    // The same criterion catches a method that drifts: explicit Euler.
    State1 x = x0;
    double first = 0, last = 0;
    for (int i = 1; i <= 100000; ++i) {
        const double q = x.q[0];
        x.q[0] += 1e-3 * x.p[0];
        x.p[0] -= 1e-3 * std::sin(q);
        const double err = std::fabs(energy(h, x) - e0);
        if (i <= 10000) first = std::max(first, err);
        if (i > 90000) last = std::max(last, err);
    }
    CHECK(last > 1.5 * first);
}

TEST_CASE("catalog: at least 50 entries, each in a family, the Laskar-Robutel first members are the leapfrogs") {
    CHECK(catalog().size() >= 50);
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        CHECK(!t.family().empty());
        CHECK(t.family() == (t.needs_quadratic_kinetic() ? "RKN" : t.family()));
    }
    CHECK(method("saba_1") == method("leapfrog_dkd"));
    CHECK(method("sbab_1") == method("leapfrog_kdk"));
    CHECK(method("yoshida_4") == triple_jump(method("leapfrog_kdk")));
    CHECK(method("suzuki_4") == suzuki_fractal(method("leapfrog_kdk")));
}

TEST_CASE("catalog: unknown names list the valid ones") {
    try {
        (void)method("leapfrog_kdx");
        FAIL("no exception");
    } catch (const invalid_argument& e) {
        const std::string what = e.what();
        CHECK(what.find("'leapfrog_kdx'") != std::string::npos);
        CHECK(what.find("leapfrog_kdk") != std::string::npos);
        CHECK(what.find("sofroniou_spaletta_10") != std::string::npos);
    }
}

}  // namespace test_methods_test_catalog
