#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/kepler.hpp>

namespace test_drivers_test_fixed_step {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using State = phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;

// An oscillator whose force blows up past |q| = 2 (to test the blow-up report).
struct breaking_oscillator {
    template <class V> auto kinetic(const V& p) const { return 0.5 * p.squaredNorm(); }
    template <class V> auto potential(const V& q) const { return 0.5 * q.squaredNorm(); }
    template <class V> void force(const V& q, V& f) const {
        f = -q;
        if (std::fabs(q[0]) > 2) f[0] = std::nan("");
    }
};
}  // namespace

TEST_CASE("integrate_until lands exactly on t_end, with a shortened last step") {
    splitting_stepper<hamiltonians::harmonic_oscillator, State> s({}, method("forest_ruth_4"));
    State x(V1(1.0), V1(0.0));
    const run_summary r = integrate_until(s, x, 0.0, 1.05, 0.1, no_observer{});
    CHECK(r.steps == 11);  // 10 steps of 0.1 and one of 0.05
    CHECK(r.t == 1.05);
    const State exact = hamiltonians::harmonic_oscillator{}.exact(State(V1(1.0), V1(0.0)), 1.05);
    CHECK(max_difference(x, exact) < 1e-5);
    // dt that divides the span: exactly n steps, no sliver step.
    State y(V1(1.0), V1(0.0));
    CHECK(integrate_until(s, y, 0.0, 0.3, 0.1).steps == 3);
}

TEST_CASE("integrate_steps calls the observer at t0, every k steps and at the end, with t = t0 + i*dt") {
    splitting_stepper<hamiltonians::kepler, phase_space<double, 2>> s({}, method("leapfrog_kdk"));
    auto x = hamiltonians::kepler::initial_state(0.5);
    std::vector<double> times;
    run_options opt;
    opt.observe_every = 3;
    const run_summary r = integrate_steps(s, x, 1.0, 0.1, 10, [&](const auto&, double t) { times.push_back(t); }, opt);
    REQUIRE(times.size() == 5);  // t0, 3, 6, 9 and the last step (10)
    CHECK(times[0] == 1.0);
    CHECK(times[1] == 1.0 + 3 * 0.1);
    CHECK(times[3] == 1.0 + 9 * 0.1);
    CHECK(times[4] == 1.0 + 10 * 0.1);
    CHECK(r.steps == 10);
    CHECK(r.force_evaluations == 11);  // leapfrog: one per step, plus the first
}

TEST_CASE("a run that blows up reports the step and time and keeps the last finite state") {
    splitting_stepper<breaking_oscillator, State> s({}, method("leapfrog_kdk"));
    // The amplitude grows past 2 only through a violent kick: start beyond it moving out.
    State x(V1(1.9), V1(3.0));
    try {
        integrate_steps(s, x, 0.0, 0.01, 1000);
        FAIL("no exception");
    } catch (const integration_error& e) {
        CAPTURE(e.what());
        CHECK(e.step >= 1);
        CHECK(e.time == doctest::Approx(0.01 * (e.step - 1)));
        CHECK(std::string(e.what()).find("step " + std::to_string(e.step)) != std::string::npos);
        CHECK(is_finite(x));
        CHECK(std::fabs(x.q[0]) <= 2.0);  // the last state before the force broke
        // Replaying by hand from the start reaches the same state at step-1.
        State y(V1(1.9), V1(3.0));
        for (std::size_t i = 1; i < e.step; ++i) s.step(y, 0.01);
        CHECK(max_difference(x, y) == 0.0);
    }
}

TEST_CASE("bad arguments: non-positive or non-finite dt, t_end before t0, non-finite state") {
    splitting_stepper<hamiltonians::harmonic_oscillator, State> s({}, method("leapfrog_kdk"));
    State x(V1(1.0), V1(0.0));
    CHECK_THROWS_WITH_AS(integrate_steps(s, x, 0.0, -0.1, 10), doctest::Contains("dt = -0.1"), invalid_argument);
    CHECK_THROWS_AS(integrate_steps(s, x, 0.0, 0.0, 10), invalid_argument);
    CHECK_THROWS_AS(integrate_until(s, x, 0.0, 1.0, INFINITY), invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_until(s, x, 2.0, 1.0, 0.1), doctest::Contains("t_end = 1"), invalid_argument);
    State bad(V1(NAN), V1(0.0));
    CHECK_THROWS_AS(integrate_steps(s, bad, 0.0, 0.1, 10), invalid_argument);
    // A step count beyond any integer is refused with the figures, before it is converted.
    CHECK_THROWS_WITH_AS(integrate_until(s, x, 0.0, 1e300, 1e-320), doctest::Contains("steps; expected at most 1e18"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_steps(s, x, NAN, 0.1, 10), doctest::Contains("t0 = nan"), invalid_argument);
    CHECK(x.q[0] == 1.0);  // nothing computed was lost or changed
}

TEST_CASE("a run stopped after step k and resumed from the state and the stepper's memory is bit for bit the same") {
    using K = phase_space<double, 2>;
    using Stepper = splitting_stepper<hamiltonians::kepler, K>;
    const double dt = 0.01;
    const std::size_t n = 1000, k = 640;  // k: a multiple of observe_every (10) and of check_every (64)
    for (bool compensated : {false, true})
        for (const char* name : {"leapfrog_kdk", "blanes_moan_s6"})
            for (bool observed : {false, true}) {
                CAPTURE(compensated);
                CAPTURE(name);
                CAPTURE(observed);
                run_options options;
                options.observe_every = 10;
                std::vector<double> seen_whole, seen_parts;
                const auto recorder = [](std::vector<double>& into) {
                    return [&into](const K& x, double t) { into.insert(into.end(), {t, x.q[0], x.q[1], x.p[0], x.p[1]}); };
                };
                const auto run = [&](Stepper& s, K& x, std::size_t steps, std::vector<double>& into) {
                    if (observed) integrate_steps(s, x, 0.25, dt, steps, recorder(into), options);
                    else integrate_steps(s, x, 0.25, dt, steps, no_observer{}, options);
                };
                Stepper whole({}, method(name), {compensated});
                K a = hamiltonians::kepler::initial_state(0.7);
                run(whole, a, n, seen_whole);

                Stepper first({}, method(name), {compensated});
                K b = hamiltonians::kepler::initial_state(0.7);
                run(first, b, k, seen_parts);
                const auto memory = first.memory();  // what a checkpoint file carries, with b
                Stepper second({}, method(name), {compensated});
                second.restore(memory);
                options.first_step = k;
                run(second, b, n, seen_parts);
                for (int i = 0; i < 2; ++i) {
                    CHECK(a.q[i] == b.q[i]);
                    CHECK(a.p[i] == b.p[i]);
                }
                CHECK(whole.force_evaluations() == second.force_evaluations());
                CHECK(seen_whole == seen_parts);
                if (compensated) CHECK(memory.q_error.size() == 2);
            }
}

TEST_CASE("a resume point that would group the steps differently is refused") {
    splitting_stepper<hamiltonians::harmonic_oscillator, State> s({}, method("leapfrog_kdk"));
    State x(V1(1.0), V1(0.0));
    run_options options;
    options.first_step = 100;  // not a multiple of check_every = 64
    CHECK_THROWS_WITH_AS(integrate_steps(s, x, 0.0, 0.1, 1000, no_observer{}, options),
                         doctest::Contains("first_step = 100 of 1000 steps; expected a multiple of 64 (check_every)"),
                         invalid_argument);
    options.first_step = 2000;
    CHECK_THROWS_AS(integrate_steps(s, x, 0.0, 0.1, 1000, [](const State&, double) {}, options), invalid_argument);
    // Memory of another size is refused by restore().
    splitting_stepper<hamiltonians::harmonic_oscillator, phase_space<double>> d({}, method("leapfrog_kdk"), {true});
    stepper_memory<Eigen::VectorXd> bad;
    bad.force = bad.velocity = Eigen::VectorXd::Zero(3);
    CHECK_THROWS_WITH_AS(d.restore(bad), doctest::Contains("memory of sizes 3, 3, 0, 0 (compensated)"), invalid_argument);
}

}  // namespace test_drivers_test_fixed_step
