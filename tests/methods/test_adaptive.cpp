// The adaptive Euler-Richardson method (Gould & Tobochnik, after eq. 3.44), run by integrate_controlled
// with e = 0.9: it meets its tolerance with fewer steps than the best fixed step.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/kepler.hpp>

namespace test_methods_test_adaptive {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using State = phase_space<double, 2>;
const hamiltonians::kepler kepler{};
const double period = 2 * M_PI;
using ER = decltype(make_classic<euler_richardson, State>(kepler));

// Largest Euler-Richardson estimate over one period with n fixed steps.
double largest_fixed_estimate(std::size_t n) {
    auto s = make_classic<euler_richardson, State>(kepler);
    State x = hamiltonians::kepler::initial_state(0.9);
    const double dt = period / double(n);
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i) {
        s.step(x, double(i) * dt, dt);
        worst = std::max(worst, s.last_error_estimate().largest());
    }
    return worst;
}
}  // namespace

TEST_CASE("adaptive: Euler-Richardson meets its tolerance on Kepler e = 0.9 with fewer steps than any fixed step") {
    control_options o = richardson_adaptive<ER>::default_control();
    o.absolute_tolerance = 1e-6;
    auto s = make_classic<euler_richardson, State>(kepler);
    State x = hamiltonians::kepler::initial_state(0.9);
    double largest_seen = 0;
    const control_summary r = integrate_controlled(richardson_adaptive(s), x, 0.0, period, o, [&](const State&, double) {
        largest_seen = std::max(largest_seen, s.last_error_estimate().largest());
    });
    CHECK(r.t == period);
    CHECK(r.largest_error <= 1);  // in units of the tolerance
    CHECK(largest_seen <= o.absolute_tolerance);
    // Steps adapt to the orbit: much smaller at pericentre than at apocentre.
    CHECK(r.dt_largest > 10 * r.dt_smallest);

    // The best fixed step: the fewest steps whose largest estimate meets the tolerance.
    std::size_t hi = 1024;
    while (largest_fixed_estimate(hi) > o.absolute_tolerance) hi *= 2;
    std::size_t lo = hi / 2;
    while (hi - lo > 1) {
        const std::size_t mid = (lo + hi) / 2;
        (largest_fixed_estimate(mid) > o.absolute_tolerance ? lo : hi) = mid;
    }
    MESSAGE("Kepler e = 0.9, tolerance 1e-6: adaptive ", r.accepted, " accepted + ", r.rejected,
            " rejected steps; best fixed step needs ", hi);
    CHECK(r.accepted + r.rejected < hi);
    // The orbit closes to within what the local tolerance allows over the steps taken.
    CHECK(max_difference(x, hamiltonians::kepler::exact_state(0.9, period)) < 1e-6 * double(r.accepted));
}

TEST_CASE("adaptive: a step that cannot shrink enough stops with an error, the state stays at the last accepted step") {
    control_options o = richardson_adaptive<ER>::default_control();
    o.absolute_tolerance = 1e-30;
    o.dt_min = 1e-6;
    auto s = make_classic<euler_richardson, State>(kepler);
    State x = hamiltonians::kepler::initial_state(0.9);
    const State x0 = x;
    try {
        integrate_controlled(richardson_adaptive(s), x, 0.0, period, o);
        FAIL("expected integration_error");
    } catch (const integration_error& e) {
        CHECK(std::string(e.what()).find("step size underflow at t = 0") != std::string::npos);
        CHECK(e.time == 0);
        CHECK(max_difference(x, x0) == 0);
    }
}

TEST_CASE("adaptive: bad options and states are rejected with the value named") {
    auto s = make_classic<euler_richardson, State>(kepler);
    State x = hamiltonians::kepler::initial_state(0.5);
    control_options o = richardson_adaptive<ER>::default_control();
    o.absolute_tolerance = -1;
    CHECK_THROWS_WITH_AS(integrate_controlled(richardson_adaptive(s), x, 0.0, 1.0, o), doctest::Contains("tolerance = -1"), invalid_argument);
    o.absolute_tolerance = 1e-6;
    o.dt_min = 1;
    o.dt_max = 0.5;
    CHECK_THROWS_WITH_AS(integrate_controlled(richardson_adaptive(s), x, 0.0, 1.0, o), doctest::Contains("dt_min = 1"), invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_controlled(richardson_adaptive(s), x, 1.0, 0.0), doctest::Contains("t_end = 0"), invalid_argument);
    State bad = x;
    bad.q[0] = HUGE_VAL;
    CHECK_THROWS_WITH_AS(integrate_controlled(richardson_adaptive(s), bad, 0.0, 1.0), doctest::Contains("not finite"), invalid_argument);
}

}  // namespace test_methods_test_adaptive
