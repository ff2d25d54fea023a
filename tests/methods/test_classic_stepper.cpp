// classic_stepper, whatever the rule: bad input refused with the value named,
// the evaluation counters, and the history of a multistep rule used only when
// the caller hands back the state the stepper returned.
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

namespace test_methods_test_classic_stepper {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using State = phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;

const State start(V1(1.2), V1(0.3));
const hamiltonians::harmonic_oscillator oscillator{};
const hamiltonians::pendulum pendulum{};
}  // namespace

TEST_CASE("classic_stepper: bad step sizes and states are rejected with the value named") {
    auto s = make_classic<rk4, State>(pendulum);
    State x = start;
    for (const double dt : {0.0, std::nan(""), HUGE_VAL}) {
        CAPTURE(dt);
        try {
            s.step(x, 0.0, dt);
            FAIL("expected invalid_argument");
        } catch (const invalid_argument& e) {
            CHECK(std::string(e.what()).find("rk4: dt = ") == 0);
        }
        CHECK(max_difference(x, start) == 0);
    }
    CHECK_THROWS_AS(integrate_steps(s, x, 0.0, -0.1, 10), invalid_argument);
    phase_space<double, Eigen::Dynamic> bad(Eigen::VectorXd::Zero(2), Eigen::VectorXd::Zero(2));
    bad.p.resize(1);
    auto d = make_classic<euler, phase_space<double, Eigen::Dynamic>>(oscillator);
    CHECK_THROWS_WITH_AS(d.step(bad, 0.0, 0.1), doctest::Contains("expected equal dimensions"), invalid_argument);
    State nan_state(V1(std::nan("")), V1(0.0));
    CHECK_THROWS_AS(integrate_steps(s, nan_state, 0.0, 0.1, 10), invalid_argument);
}

TEST_CASE("classic_stepper: a Hamiltonian reading past the state is refused at the first step") {
    using SX = phase_space<double>;
    auto h = make_hamiltonian([](const auto& p) { return 0.5 * p.squaredNorm(); },
                              [](const auto& q) { return 0.5 * (q[0] * q[0] + q[1] * q[1]); });
    auto s = make_classic<rk4, SX>(h);
    SX x(1);
    CHECK_THROWS_WITH_AS(s.step(x, 0.0, 0.1),
                         "rk4: the Hamiltonian's V(q) read q[1] of a state of dimension 1; expected indices 0..0",
                         invalid_argument);
    SX y(2);
    CHECK_NOTHROW(s.step(y, 0.0, 0.1));
}

TEST_CASE("classic_stepper: counters count each rate, and a multistep rule restarts on a state it did not return") {
    auto s = make_classic<rk4, State>(pendulum);
    State x = start;
    s.step(x, 0.0, 0.1);
    CHECK(s.force_evaluations() == 4);  // Sandvik's k1..k4
    CHECK(s.velocity_evaluations() == 4);
    s.reset_counters();
    CHECK(s.force_evaluations() == 0);
    // The half-step rule's history is used for its own state only: another
    // state gets the self-starting step (eq. 3.37c), as a fresh stepper would.
    auto used = make_classic<half_step, State>(pendulum);
    State y = start;
    used.step(y, 0.0, 0.1);
    State other(V1(0.7), V1(-0.2)), same = other;
    used.step(other, 0.0, 0.1);
    auto fresh = make_classic<half_step, State>(pendulum);
    fresh.step(same, 0.0, 0.1);
    CHECK(other.q[0] == same.q[0]);
    CHECK(other.p[0] == same.p[0]);
    // Handed back its own state, it continues (one force per step, not two).
    used.reset_counters();
    used.step(other, 0.1, 0.1);
    CHECK(used.force_evaluations() == 1);
}

TEST_CASE("classic_stepper: a system whose lambda captures is restored in place, and a refused list changes nothing") {
    // A capturing lambda cannot be assigned: the stepper is restored in place, not through a copy.
    const double k = 1.5;
    const auto spring = make_newtonian([k](const auto& x, auto) { return (-k * x).eval(); });
    auto first = make_classic<leapfrog_two_step, State>(spring);
    State x = start;
    for (int i = 0; i < 10; ++i) first.step(x, 0.01 * i, 0.01);
    const std::vector<double> list = first.carried();
    auto second = make_classic<leapfrog_two_step, State>(spring);
    second.restore_carried(list);
    CHECK(second.carried() == list);
    std::vector<double> longer = list;
    longer.push_back(0);  // read whole before it is refused
    CHECK_THROWS_WITH_AS(second.restore_carried(longer), doctest::Contains("is longer than"), invalid_argument);
    CHECK(second.carried() == list);
    State y = x;
    for (int i = 10; i < 20; ++i) first.step(x, 0.01 * i, 0.01), second.step(y, 0.01 * i, 0.01);
    CHECK(max_difference(x, y) == 0);
}

}  // namespace test_methods_test_classic_stepper
