// Events on the dense output (Brent 1973 on the Hermite interpolant): zero
// crossings of the oscillator and Kepler pericentre passages against exact
// times, directions, crossings inside one step, stop events, bad input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/drivers/events.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/methods/rkn_pairs.hpp>

namespace test_drivers_test_events {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using S1 = phase_space<double, 1>;
using S2 = phase_space<double, 2>;
using V1 = Eigen::Matrix<double, 1, 1>;
const double pi = std::numbers::pi;
const hamiltonians::harmonic_oscillator oscillator{};
const hamiltonians::kepler kepler{};

// q = cos(t - c), p = -sin(t - c).
S1 cosine(double t, double c = 0) { return S1(V1(std::cos(t - c)), V1(-std::sin(t - c))); }
S2 kepler_exact(double t) { return hamiltonians::kepler::exact_state(0.5, t); }

// The exact flow as a stepper: events then differ from exact times by the interpolation alone.
template <class State>
struct exact_stepper {
    using state_type = State;
    using scalar = double;
    std::function<State(double)> exact;
    void step(State& x, double t, double dt) { x = exact(t + dt); }
};

// Largest error of a run's step ends against the exact solution.
template <class Stepper, class State, class Exact>
double grid_error(Stepper s, State x, double t0, double t_end, double dt, Exact exact) {
    double worst = 0;
    integrate_until(s, x, t0, t_end, dt, [&](const State& y, double t) { worst = std::max(worst, max_difference(y, exact(t))); });
    return worst;
}

event<S1> zero_of_q(event_direction d, event_action a = event_action::record) {
    return {[](const S1& x, double) { return x.q[0]; }, d, a};
}
}  // namespace

TEST_CASE("events: oscillator zero crossings at pi/2 + k pi, within the interpolant's error") {
    // q = cos t: zeros at pi/2 + k pi, falling for even k. Cubic error
    // <= dt^4/384 max|q''''| in q, the max over the step holding the zero,
    // where |q''''| = |cos t| <= sin dt; |dq/dt| = 1 there; plus the method's
    // own error at the step ends (measured), carried by the interpolant.
    const double dt = 0.1, t_end = 20;
    const auto make = [] { return make_stepper<S1>(oscillator, method("yoshida_8")); };
    const double grid = grid_error(make(), cosine(0), 0.0, t_end, dt, [](double t) { return cosine(t); });
    const double bound = std::pow(dt, 4) / 384 * std::sin(dt) + 1.5 * grid + 1e-13;
    for (const auto d : {event_direction::both, event_direction::rising, event_direction::falling}) {
        auto s = make();
        S1 x = cosine(0);
        const auto run = integrate_events(s, x, 0.0, t_end, dt, {zero_of_q(d)});
        std::vector<double> expected;
        for (int k = 0; pi / 2 + k * pi < t_end; ++k)
            if (d == event_direction::both || (d == event_direction::falling) == (k % 2 == 0))
                expected.push_back(pi / 2 + k * pi);
        REQUIRE(run.hits.size() == expected.size());
        double worst = 0;
        for (std::size_t i = 0; i < expected.size(); ++i) {
            worst = std::max(worst, std::fabs(run.hits[i].t - expected[i]));
            CHECK(run.hits[i].rising == (std::cos(expected[i] + 0.1) > 0));
            CHECK(std::fabs(run.hits[i].state.q[0]) <= 1e-14);  // a zero of g on the interpolant, to rounding
        }
        CHECK(worst <= bound);
        CHECK_FALSE(run.stopped);
        CHECK(run.t == t_end);
        MESSAGE("oscillator zeros: largest time error " << worst << " (bound " << bound << ", grid error " << grid << ")");
    }
}

TEST_CASE("events: far from t = 0 the root is located in the step, not limited by the rounding of t") {
    // From t0 = 1e6 the spacing of doubles near t is 1.2e-10: a root sought in
    // t could leave |g| up to 4 eps |t| |dg/dt| = 8.9e-10 on the interpolant.
    // Sought in the step's fraction, g at the returned state is zero to the
    // rounding of q (|q| <= 1 here: 1e-15), whatever t.
    const double t0 = 1e6, dt = 0.1;
    auto s = make_stepper<S1>(oscillator, method("leapfrog_kdk"));
    S1 x = cosine(0);
    const auto run = integrate_events(s, x, t0, t0 + 20, dt, {zero_of_q(event_direction::both)});
    REQUIRE(run.hits.size() >= 6);
    double worst = 0;
    for (const auto& hit : run.hits) worst = std::max(worst, std::fabs(hit.state.q[0]));
    CHECK(worst <= 1e-15);
    MESSAGE("t0 = 1e6: largest |g| at the located states " << worst << " (4 eps |t| = " << 4 * 2.2e-16 * t0 << ")");
}

TEST_CASE("events: with exact step ends the event time error is the interpolation's alone") {
    // q = cos t, step ends exact; dt = 0.3. Near a zero |q''''| = |q^(6)| =
    // |cos t| <= sin dt: the cubic's q error <= dt^4/384 sin dt = 6.2e-6, the
    // quintic's <= dt^6/46080 sin dt = 4.7e-9, and |dq/dt| = 1.
    const double dt = 0.3;
    exact_stepper<S1> s{[](double t) { return cosine(t); }};
    S1 x = cosine(0);
    const auto cubic = integrate_events(s, oscillator, x, 0.0, 10.0, dt, {zero_of_q(event_direction::both)});
    x = cosine(0);
    event_options quintic;
    quintic.order = hermite_order::quintic;
    const auto fine = integrate_events(s, oscillator, x, 0.0, 10.0, dt, {zero_of_q(event_direction::both)}, quintic);
    REQUIRE(cubic.hits.size() == 3);
    REQUIRE(fine.hits.size() == 3);
    double e3 = 0, e5 = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        e3 = std::max(e3, std::fabs(cubic.hits[k].t - (pi / 2 + double(k) * pi)));
        e5 = std::max(e5, std::fabs(fine.hits[k].t - (pi / 2 + double(k) * pi)));
    }
    CHECK(e3 <= std::pow(dt, 4) / 384 * std::sin(dt));
    CHECK(e5 <= std::pow(dt, 6) / 46080 * std::sin(dt) + 1e-15);  // the quintic's bound (q only enters g)
    MESSAGE("exact ends, dt = 0.3: cubic " << e3 << ", quintic " << e5);
}

TEST_CASE("events: Kepler e = 0.5 pericentre passages (q.p rising) at the period multiples") {
    // dr/dt = q.p / r: q.p goes from < 0 to > 0 at pericentre, t = 2 pi k.
    // Error in q.p <= |q|_1 dp + |p|_1 dq with |q|_1 = 0.5, |p|_1 = sqrt 3 there,
    // d(q.p)/dt = |p|^2 + q.F = 3 - 2 = 1: the time error is that error.
    // dq, dp: the cubic's dt^4/384 max|x''''| (max|x''''| from the exact
    // orbit by finite differences over the orbit) plus the grid's error.
    // At apocentre |q|_1 = 1.5, |p|_1 = 1/sqrt 3, d(q.p)/dt = 1/3 - 2/3.
    // The run starts half a step after pericentre, so the pericentres fall mid-step.
    const double dt = 2 * pi / 200, t0 = dt / 2, t_end = 3 * 2 * pi + 1;
    double q4 = 0, p4 = 0;
    const double d = 1e-2;
    for (double t = -pi; t <= pi; t += 1e-3) {
        const S2 a = kepler_exact(t - 2 * d), b = kepler_exact(t - d), c = kepler_exact(t), e = kepler_exact(t + d),
                 f = kepler_exact(t + 2 * d);
        const S2 fourth((a.q - 4 * b.q + 6 * c.q - 4 * e.q + f.q) / std::pow(d, 4),
                        (a.p - 4 * b.p + 6 * c.p - 4 * e.p + f.p) / std::pow(d, 4));
        q4 = std::max(q4, fourth.q.cwiseAbs().maxCoeff());
        p4 = std::max(p4, fourth.p.cwiseAbs().maxCoeff());
    }
    const auto make = [] { return make_stepper<S2>(kepler, method("yoshida_8")); };
    const double grid = grid_error(make(), kepler_exact(t0), t0, t_end, dt, kepler_exact);
    const double dq = 1.1 * std::pow(dt, 4) / 384 * q4 + 1.5 * grid, dp = 1.1 * std::pow(dt, 4) / 384 * p4 + 1.5 * grid;
    const double bound = 0.5 * dp + std::sqrt(3.0) * dq;
    const double apocentre_bound = 3 * (1.5 * dp + dq / std::sqrt(3.0));
    const event<S2> pericentre{[](const S2& x, double) { return x.q.dot(x.p); }, event_direction::rising};
    const event<S2> apocentre{[](const S2& x, double) { return x.q.dot(x.p); }, event_direction::falling};
    auto s = make();
    S2 x = kepler_exact(t0);
    const auto run = integrate_events(s, x, t0, t_end, dt, {pericentre, apocentre});
    std::vector<double> peri, apo;
    for (const auto& hit : run.hits) (hit.event == 0 ? peri : apo).push_back(hit.t);
    REQUIRE(peri.size() == 3);
    REQUIRE(apo.size() == 3);
    double worst = 0;
    for (std::size_t k = 0; k < 3; ++k) {
        worst = std::max(worst, std::fabs(peri[k] - 2 * pi * double(k + 1)));
        CHECK(std::fabs(apo[k] - pi * double(2 * k + 1)) <= apocentre_bound);
    }
    CHECK(worst <= bound);
    CHECK(std::is_sorted(run.hits.begin(), run.hits.end(), [](const auto& a, const auto& b) { return a.t < b.t; }));
    // Only the steps with a crossing were interpolated: 6 steps, 2 ends each at most.
    CHECK(run.extra_force_evaluations <= 12);
    MESSAGE("Kepler pericentres: largest time error " << worst << " (bound " << bound << ", max|q''''| " << q4
                                                      << ", max|p''''| " << p4 << ", grid " << grid << ")");
}

TEST_CASE("events: two crossings inside one step are found only with interior points") {
    // q = cos(t - 1.1) peaks mid-step in [1.0, 1.2]: both ends are below 0.999,
    // the peak above. g = q - 0.999 crosses at 1.1 -+ acos(0.999).
    const double c = 1.1, dt = 0.2, w = std::acos(0.999);
    const event<S1> high{[](const S1& x, double) { return x.q[0] - 0.999; }};
    exact_stepper<S1> s{[&](double t) { return cosine(t, c); }};
    S1 x = cosine(0, c);
    const auto ends_only = integrate_events(s, oscillator, x, 0.0, 2.0, dt, {high});
    CHECK(ends_only.hits.empty());
    x = cosine(0, c);
    event_options options;
    options.interior_points = 3;
    const auto inside = integrate_events(s, oscillator, x, 0.0, 2.0, dt, {high}, options);
    REQUIRE(inside.hits.size() == 2);
    // q error <= dt^4/384, slope |dq/dt| = sin w: the time error at most their ratio.
    const double bound = std::pow(dt, 4) / 384 / std::sin(w);
    CHECK(inside.hits[0].rising);
    CHECK_FALSE(inside.hits[1].rising);
    CHECK(std::fabs(inside.hits[0].t - (c - w)) <= bound);
    CHECK(std::fabs(inside.hits[1].t - (c + w)) <= bound);
    // Interior points need both ends of every step: 11 ends over 10 steps.
    CHECK(inside.extra_force_evaluations == 11);
}

TEST_CASE("events: a stop event ends the run at its time, the steps before it unchanged") {
    // q = cos t: falling zero at pi/2 recorded, rising zero at 3 pi/2 stops.
    const double dt = 0.1;
    const auto make = [] { return make_stepper<S1>(oscillator, method("yoshida_8")); };
    auto s = make();
    S1 x = cosine(0);
    const auto run = integrate_events(
        s, x, 0.0, 10.0, dt, {zero_of_q(event_direction::falling), zero_of_q(event_direction::rising, event_action::stop)});
    REQUIRE(run.stopped);
    REQUIRE(run.hits.size() == 2);
    CHECK(run.hits[0].event == 0);
    CHECK(run.hits[1].event == 1);
    const double t_stop = run.hits[1].t;
    CHECK(std::fabs(t_stop - 3 * pi / 2) <= std::pow(dt, 4) / 384 + 1e-9);
    CHECK(run.t == t_stop);
    CHECK(x.q == run.hits[1].state.q);  // x is the interpolated state at the event
    CHECK(x.p == run.hits[1].state.p);
    CHECK(max_difference(x, cosine(t_stop)) <= std::pow(dt, 4) / 384 + 1e-9);
    const auto steps = static_cast<std::size_t>(std::ceil(3 * pi / 2 / dt));  // the step holding the event, no more
    CHECK(run.steps == steps);
    auto reference = make();
    S1 y = cosine(0);
    const run_summary r = integrate_steps(reference, y, 0.0, dt, steps, [](const S1&, double) {});
    CHECK(run.force_evaluations == r.force_evaluations);
    // The same run without the stop: its first event bit for bit the same.
    auto s2 = make();
    S1 z = cosine(0);
    const auto full = integrate_events(s2, z, 0.0, 10.0, dt, {zero_of_q(event_direction::falling)});
    REQUIRE(!full.hits.empty());
    CHECK(full.hits[0].t == run.hits[0].t);
    CHECK(full.hits[0].state.q == run.hits[0].state.q);
    CHECK(full.hits[0].state.p == run.hits[0].state.p);
}

TEST_CASE("events: a coarse time tolerance is met, and q[1] rising matches section_crossings") {
    const double dt = 1.0 / 16;  // exact in binary: t_end = 400 dt = 25 exactly
    const event<S2> upward{[](const S2& x, double) { return x.q[1]; }, event_direction::rising};
    auto s = make_stepper<S2>(kepler, method("leapfrog_kdk"));
    S2 x = kepler_exact(0);
    const auto run = integrate_events(s, x, 0.0, 25.0, dt, {upward});
    auto s2 = make_stepper<S2>(kepler, method("leapfrog_kdk"));
    const auto points = section_crossings(s2, kepler_exact(0), dt, 400, 1);
    REQUIRE(points.size() == 3);
    REQUIRE(run.hits.size() == 3);
    for (std::size_t k = 0; k < 3; ++k) CHECK(max_difference(points[k], run.hits[k].state) <= 1e-13);
    event_options coarse;
    coarse.time_tolerance = 1e-3;
    auto s3 = make_stepper<S2>(kepler, method("leapfrog_kdk"));
    S2 y = kepler_exact(0);
    const auto rough = integrate_events(s3, y, 0.0, 25.0, dt, {upward}, coarse);
    REQUIRE(rough.hits.size() == 3);
    for (std::size_t k = 0; k < 3; ++k) CHECK(std::fabs(rough.hits[k].t - run.hits[k].t) <= 1e-3 + 1e-12);
}

TEST_CASE("events: bad events and options are refused, naming the value") {
    auto s = make_stepper<S1>(oscillator, method("leapfrog_kdk"));
    S1 x = cosine(0);
    const auto g = zero_of_q(event_direction::both);
    CHECK_THROWS_WITH_AS(integrate_events(s, x, 0.0, 1.0, 0.1, {event<S1>{}}), doctest::Contains("event 0 has no function g"),
                         invalid_argument);
    event_options o;
    o.interior_points = -1;
    CHECK_THROWS_WITH_AS(integrate_events(s, x, 0.0, 1.0, 0.1, {g}, o), doctest::Contains("interior_points = -1"),
                         invalid_argument);
    o = {};
    o.time_tolerance = -0.5;
    CHECK_THROWS_WITH_AS(integrate_events(s, x, 0.0, 1.0, 0.1, {g}, o), doctest::Contains("time_tolerance = -0.5"),
                         invalid_argument);
    o.time_tolerance = std::nan("");
    CHECK_THROWS_WITH_AS(integrate_events(s, x, 0.0, 1.0, 0.1, {g}, o), doctest::Contains("time_tolerance = nan"),
                         invalid_argument);
    event<S1> odd = g;
    odd.direction = static_cast<event_direction>(7);
    CHECK_THROWS_WITH_AS(integrate_events(s, x, 0.0, 1.0, 0.1, {g, odd}), doctest::Contains("event 1's direction = 7"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_events(s, x, 2.0, 1.0, 0.1, {g}), doctest::Contains("t_end = 1"), invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_events(s, x, 0.0, 1.0, -0.1, {g}), doctest::Contains("dt = -0.1"), invalid_argument);
    CHECK(x.q == cosine(0).q);  // nothing ran
    const event<S1> nan_g{[](const S1&, double t) { return t > 0.5 ? std::nan("") : 1.0; }};
    CHECK_THROWS_WITH_AS(integrate_events(s, x, 0.0, 1.0, 0.1, {nan_g}), doctest::Contains("event 0's g = nan at t = 0.6"),
                         invalid_argument);
}

TEST_CASE("events over a controlled run: q = 0 of the pendulum by dprkn6, dprkn8, dprkn12 within 10 tolerances") {
    // From q0 = 2.5 at rest (H = p^2/2 - cos q), q crosses 0 at (2n + 1) K(k),
    // k = sin(q0 / 2), K the complete elliptic integral of the first kind:
    // a quarter period (Landau & Lifshitz, Mechanics, sect. 11, problem 1).
    const long double K = std::comp_ellint_1(std::sin(2.5L / 2));
    using P1 = phase_space<double, 1>;
    const std::vector<event<P1>> crossing{{[](const P1& y, double) { return y.q[0]; }, event_direction::both}};
    const auto check_pair = [&]<class Pair>(double tol) {
        auto s = make_rkn_stepper<Pair, P1>(hamiltonians::pendulum{});
        P1 x(1);
        x.q[0] = 2.5;
        x.p[0] = 0;
        control_options c;
        c.absolute_tolerance = c.relative_tolerance = tol;
        const auto run = integrate_events(s, x, 0.0, 20.0, c, crossing);
        REQUIRE(run.hits.size() == 4);  // K = 2.58: K, 3K, 5K, 7K before t = 20
        double worst = 0;
        for (std::size_t n = 0; n < run.hits.size(); ++n) {
            worst = std::max(worst, double(std::fabs(run.hits[n].t - (2 * n + 1) * K)));
            CHECK(run.hits[n].rising == (n % 2 == 1));
        }
        MESSAGE(std::string(Pair::name), " at tolerance ", tol, ": ", run.accepted, " steps, crossing times off by ", worst);
        // The time's error is q's error over |dq/dt| = |p| = sqrt(2 (1 - cos 2.5)) = 1.9
        // at the crossing; q's error is within 10 tolerances (test_dense_output.cpp).
        CHECK(worst <= 10 * tol);
    };
    for (double tol : {1e-8, 1e-10}) {
        check_pair.template operator()<dprkn6>(tol);
        check_pair.template operator()<dprkn8>(tol);
        check_pair.template operator()<dprkn12>(tol);
    }
}

TEST_CASE("events over a controlled run: a stop event ends the run with the accepted and rejected steps counted") {
    using P1 = phase_space<double, 1>;
    auto s = make_rkn_stepper<dprkn8, P1>(hamiltonians::pendulum{});
    P1 x(1);
    x.q[0] = 2.5;
    x.p[0] = 0;
    const std::vector<event<P1>> stop{
        {[](const P1& y, double) { return y.q[0]; }, event_direction::falling, event_action::stop}};
    const auto run = integrate_events(s, x, 0.0, 20.0, control_options{}, stop);
    REQUIRE(run.hits.size() == 1);
    CHECK(run.stopped);
    CHECK(run.t == double(run.hits[0].t));
    CHECK(std::fabs(x.q[0]) <= 1e-9);  // the state interpolated at the event
    CHECK(run.accepted > 0);
    CHECK(run.force_evaluations > 0);
}

}  // namespace test_drivers_test_events
