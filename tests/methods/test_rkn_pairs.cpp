// Embedded Runge-Kutta-Nystrom pairs (Dormand & Prince 1987; Dormand, El-Mikkawy
// & Prince 1987): the measured orders of the main and embedded formulae, step-size
// control, FSAL reuse, dense output and partial steps, bad input (tables: test_rkn_tables.cpp).
#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>  // sympl::quad (113 bits), for orders 10 and 12
#include <sympl/methods/rkn_pairs.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/relativistic_pendulum.hpp>

namespace test_methods_test_rkn_pairs {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
// The embedded formula of P as a pair of its own: its weights become the main ones.
template <class P>
struct embedded_of : P {
    static constexpr auto b = P::b_hat;
    static constexpr auto bp = P::bp_hat;
};

// The order read from successive differences |x(n) - x(2n)| at t_end: the last
// two slopes above `floor` (the asymptotic range, where pre-asymptotic terms
// have died out: the library's measure_order reads the first agreeing ones).
struct read_slopes {
    double last = 0, before = 0, finest_difference = 0;
};
template <class Run>
read_slopes finest_slopes(Run run, std::size_t n0, double floor, std::size_t n_max) {
    read_slopes r;
    auto previous = run(n0);
    double last_difference = 0;
    for (std::size_t n = 2 * n0; n <= n_max; n *= 2) {
        auto x = run(n);
        const double d = static_cast<double>(max_difference(previous, x));
        if (d < floor) break;
        if (last_difference > 0) {
            r.before = r.last;
            r.last = std::log2(last_difference / d);
            r.finest_difference = d;
        }
        last_difference = d;
        previous = std::move(x);
    }
    return r;
}

// The measured order of pair P in scalar S, read down to differences of `floor`.
template <class P, class S>
void check_measured_order(int nominal, std::size_t n0_kepler, std::size_t n0_pendulum, double floor) {
    const std::string pair = P::name;
    CAPTURE(pair);
    CAPTURE(nominal);
    using S2 = phase_space<S, 2>;
    using S1 = phase_space<S, 1>;
    // Kepler e = 0.5 from pericentre over half a period (the pericentre passage:
    // the hard part), and the pendulum q0 = 1.2, p0 = 0.3 over [0, 3].
    const S pi = boost::math::constants::pi<S>();
    const hamiltonians::kepler kepler{};
    const S2 k0 = hamiltonians::kepler::initial_state<S>(0.5);
    const auto kepler_run = [&](std::size_t n) {
        auto s = make_rkn_stepper<P, S2>(kepler);
        S2 x = k0;
        for (std::size_t i = 0; i < n; ++i) s.step(x, pi / S(n));
        return x;
    };
    const hamiltonians::pendulum pendulum{};
    const S1 p0(Eigen::Matrix<S, 1, 1>(S(1.2)), Eigen::Matrix<S, 1, 1>(S(0.3)));
    const auto pendulum_run = [&](std::size_t n) {
        auto s = make_rkn_stepper<P, S1>(pendulum);
        S1 x = p0;
        for (std::size_t i = 0; i < n; ++i) s.step(x, S(3) / S(n));
        return x;
    };
    const read_slopes k = finest_slopes(kepler_run, n0_kepler, floor, 8192);
    const read_slopes p = finest_slopes(pendulum_run, n0_pendulum, floor, 8192);
    CAPTURE(k.last);
    CAPTURE(k.before);
    CAPTURE(k.finest_difference);
    CAPTURE(p.last);
    CAPTURE(p.before);
    CAPTURE(p.finest_difference);
    CHECK(std::fabs(k.last - nominal) <= 0.15);
    CHECK(std::fabs(p.last - nominal) <= 0.15);
    // The slope before agrees too, or is still converging to the order.
    CHECK(std::fabs(k.before - nominal) <= 0.35);
    CHECK(std::fabs(p.before - nominal) <= 0.35);
}
}  // namespace

TEST_CASE("rkn pairs: measured orders of the main and embedded formulae on Kepler and the pendulum, in long double and 113 bits") {
    // dprkn6 in long double, down to differences of 1e-15, where its rounding
    // over at most 8192 steps stays below ~1e-17. dprkn8 in 113 bits, down to
    // 1e-22: its embedded formula on Kepler is still pre-asymptotic at 1e-16
    // (slopes 6.17, 6.09, 6.05, 6.02 at 1024 ... 8192 steps), where long
    // double's rounding moves the slope read by +-0.07. Orders 10 and 12 in 113
    // bits, down to 1e-28 (rounding over a few hundred steps below 1e-31).
    using ld = long double;
    check_measured_order<dprkn6, ld>(6, 16, 8, 1e-15);
    check_measured_order<embedded_of<dprkn6>, ld>(4, 64, 16, 1e-15);
    check_measured_order<dprkn8, quad>(8, 16, 4, 1e-22);
    check_measured_order<embedded_of<dprkn8>, quad>(6, 32, 8, 1e-22);
    check_measured_order<dprkn12, quad>(12, 8, 2, 1e-28);
    check_measured_order<embedded_of<dprkn12>, quad>(10, 8, 2, 1e-28);
}

namespace {
using L2 = phase_space<long double, 2>;

struct controlled_run {
    double error;  // final, against Kepler's exact orbit
    control_summary summary;
};
template <class P>
controlled_run kepler_controlled(double tol, control_options c = {}) {
    // Three periods of Kepler e = 0.5, in long double: at tol = 1e-12 the
    // 6th-order pair takes 2700 steps, whose rounding in double (~1e-13)
    // would be part of what is measured.
    const long double t_end = 6 * 3.14159265358979323846264338327950288L;
    auto s = make_rkn_stepper<P, L2>(hamiltonians::kepler{});
    L2 x = hamiltonians::kepler::initial_state<long double>(0.5);
    c.absolute_tolerance = c.relative_tolerance = tol;
    // A broken error estimate would crawl in tiny steps: stop it as an underflow
    // (dt_min = 1e-6 t_end; no rejected step of the three pairs comes near it here).
    c.dt_min = 1e-6 * double(t_end);
    const control_summary r = integrate_controlled(s, x, 0.0L, t_end, c);
    return {static_cast<double>(max_difference(x, hamiltonians::kepler::exact_state<long double>(0.5, t_end))), r};
}

// Tolerance proportionality: the global error follows the tolerance within this
// band over six decades (per step the estimate is held to tol; what the error
// does between steps, and how it adds up, varies with the problem).
constexpr double band_low = 1e-2, band_high = 10;

template <class P>
void check_tolerance_proportionality() {
    const std::string pair = P::name;
    CAPTURE(pair);
    double first = 0, last = 0;
    for (double tol = 1e-6; tol >= 0.9e-12; tol /= 10) {
        const controlled_run r = kepler_controlled<P>(tol);
        CAPTURE(tol);
        CAPTURE(r.error);
        CAPTURE(r.summary.accepted);
        CAPTURE(r.summary.rejected);
        CHECK(r.error / tol >= band_low);
        CHECK(r.error / tol <= band_high);
        CHECK(r.summary.largest_error <= 1.0);
        // Every attempt but the first starts from a force already known: FSAL
        // pairs pay s - 1 forces per attempt, the others s - 1 on a retry and s otherwise.
        const std::uint64_t attempts = r.summary.accepted + r.summary.rejected;
        if (rkn_coefficients<P, double>().fsal)
            CHECK(r.summary.force_evaluations == (P::stages - 1) * attempts + 1);
        else
            CHECK(r.summary.force_evaluations == (P::stages - 1) * attempts + r.summary.accepted);
        if (tol == 1e-6) first = r.error;
        last = r.error;
    }
    // Six decades of tolerance buy at least four decades of error.
    CHECK(last < 1e-4 * first);
}
}  // namespace

TEST_CASE("rkn pairs: step-size control keeps the global error proportional to the tolerance") {
    check_tolerance_proportionality<dprkn6>();
    check_tolerance_proportionality<dprkn8>();
    check_tolerance_proportionality<dprkn12>();
}

TEST_CASE("rkn pairs: rejected steps are counted, the step never grows by more than max_factor") {
    // A first trial step of half the span must be rejected, and retried from the same force.
    control_options c;
    c.dt_initial = 3 * 3.14159265358979323846;
    c.max_factor = 2;
    std::vector<long double> times;
    auto s = make_rkn_stepper<dprkn8, L2>(hamiltonians::kepler{});
    L2 x = hamiltonians::kepler::initial_state<long double>(0.5);
    c.absolute_tolerance = c.relative_tolerance = 1e-10;
    const control_summary r =
        integrate_controlled(s, x, 0.0L, 6 * 3.14159265358979323846264338327950288L, c,
                             [&](const L2&, long double t) { times.push_back(t); });
    CHECK(r.rejected >= 1);
    CHECK(r.accepted + 1 == times.size());
    for (std::size_t i = 2; i + 1 < times.size(); ++i)  // the last step is cut to land on t_end
        CHECK(double(times[i] - times[i - 1]) <= 2 * double(times[i - 1] - times[i - 2]) * (1 + 1e-12));
    CHECK(r.force_evaluations == 8 * (r.accepted + r.rejected) + 1);
}

TEST_CASE("rkn pairs: a step-size underflow names the time and step size and keeps the last accepted state") {
    control_options c;
    c.absolute_tolerance = c.relative_tolerance = 1e-14;
    c.dt_initial = 0.5;
    c.dt_min = 0.2;  // far too large for 1e-14 at the pericentre of e = 0.5
    auto s = make_rkn_stepper<dprkn6, phase_space<double, 2>>(hamiltonians::kepler{});
    auto x = hamiltonians::kepler::initial_state(0.5);
    const auto x0 = x;
    try {
        integrate_controlled(s, x, 0.0, 10.0, c);
        FAIL("expected integration_error");
    } catch (const integration_error& e) {
        const std::string what = e.what();
        CAPTURE(what);
        CHECK(what.find("step size underflow at t = 0") != std::string::npos);
        CHECK(what.find("dt = 0.2") != std::string::npos);
        CHECK(e.time == 0.0);
        CHECK(x.q == x0.q);
        CHECK(x.p == x0.p);
    }
}

TEST_CASE("rkn pairs: fixed steps reuse the last force where the pair is FSAL") {
    using S = phase_space<double, 2>;
    const auto count = [](auto stepper) {
        S x = hamiltonians::kepler::initial_state(0.5);
        integrate_steps(stepper, x, 0.0, 0.01, 100);
        return stepper.force_evaluations();
    };
    CHECK(count(make_rkn_stepper<dprkn6, S>(hamiltonians::kepler{})) == 5 * 100 + 1);
    CHECK(count(make_rkn_stepper<dprkn8, S>(hamiltonians::kepler{})) == 8 * 100 + 1);
    CHECK(count(make_rkn_stepper<dprkn12, S>(hamiltonians::kepler{})) == 17 * 100);
    // A state the stepper did not produce gets its force afresh.
    auto s = make_rkn_stepper<dprkn6, S>(hamiltonians::kepler{});
    S x = hamiltonians::kepler::initial_state(0.5);
    s.step(x, 0.01);
    x.q[0] += 1e-3;
    s.step(x, 0.01);
    CHECK(s.force_evaluations() == 12);
}

TEST_CASE("rkn pairs: dprkn6's dense output is of order 6 in q and 5 in p inside a step") {
    // One step from x0 on the oscillator and on Kepler e = 0.5 (a point after
    // the pericentre); the largest error at theta = 0.1, 0.2, ..., 0.9 against
    // the exact flow is local error of order 7 in q and 6 in p: halving dt
    // divides it by 2^7 and 2^6.
    using S = phase_space<long double, 2>;
    const hamiltonians::harmonic_oscillator osc{};
    const S o0(Eigen::Matrix<long double, 2, 1>(1.0L, 0.3L), Eigen::Matrix<long double, 2, 1>(-0.2L, 0.8L));
    const long double t0 = 0.7L;
    const S k0 = hamiltonians::kepler::exact_state<long double>(0.5, t0);
    const auto worst = [&](bool kepler, long double dt) {
        long double eq = 0, ep = 0;
        S x = kepler ? k0 : o0;
        const S start = x;
        if (kepler) {
            auto s = make_rkn_stepper<dprkn6, S>(hamiltonians::kepler{});
            s.step(x, dt);
            for (int i = 1; i <= 9; ++i) {
                const S y = s.dense_output(i / 10.0L);
                const S e = hamiltonians::kepler::exact_state<long double>(0.5, t0 + i * dt / 10);
                eq = std::max(eq, (y.q - e.q).cwiseAbs().maxCoeff());
                ep = std::max(ep, (y.p - e.p).cwiseAbs().maxCoeff());
            }
            // theta = 0 and 1 are the step's ends.
            CHECK(max_difference(s.dense_output(0), start) == 0);
            CHECK(max_difference(s.dense_output(1), x) <= 1e-17L);
        } else {
            auto s = make_rkn_stepper<dprkn6, S>(osc);
            s.step(x, dt);
            for (int i = 1; i <= 9; ++i) {
                const S y = s.dense_output(i / 10.0L);
                const S e = osc.exact(start, i * dt / 10);
                eq = std::max(eq, (y.q - e.q).cwiseAbs().maxCoeff());
                ep = std::max(ep, (y.p - e.p).cwiseAbs().maxCoeff());
            }
        }
        return std::pair{eq, ep};
    };
    for (bool kepler : {false, true}) {
        CAPTURE(kepler);
        const long double dt = kepler ? 0.05L : 0.2L;
        // Named values, not a structured binding: CAPTURE's lambda cannot take
        // one before clang 16 (the sanitizer build's compiler is clang 14).
        const auto coarse = worst(kepler, dt), fine = worst(kepler, dt / 2);
        const long double q1 = coarse.first, p1 = coarse.second, q2 = fine.first, p2 = fine.second;
        CAPTURE(double(q1));
        CAPTURE(double(q2));
        CAPTURE(double(p1));
        CAPTURE(double(p2));
        CHECK(std::fabs(double(std::log2(q1 / q2)) - 7) <= 0.3);
        CHECK(std::fabs(double(std::log2(p1 / p2)) - 6) <= 0.3);
    }
    auto s = make_rkn_stepper<dprkn6, S>(osc);
    CHECK_THROWS_AS(s.dense_output(0.5L), invalid_argument);  // no step yet
}

TEST_CASE("rkn pairs: bad input is refused with the bad value named") {
    using S = phase_space<double, 2>;
    auto s = make_rkn_stepper<dprkn8, S>(hamiltonians::kepler{});
    S x = hamiltonians::kepler::initial_state(0.5);
    const auto message = [](auto&& f) {
        try {
            f();
        } catch (const invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no invalid_argument");
    };
    CHECK(message([&] { s.step(x, std::nan("")); }).find("dt = nan") != std::string::npos);
    CHECK(message([&] { s.step(x, HUGE_VAL); }).find("dt = inf") != std::string::npos);
    CHECK(message([&] { s.step(x, 0.0); }).find("dt = 0;") != std::string::npos);
    control_options c;
    c.absolute_tolerance = 0;
    CHECK(message([&] { integrate_controlled(s, x, 0.0, 1.0, c); }).find("absolute_tolerance = 0;") != std::string::npos);
    c = {};
    c.relative_tolerance = -1e-8;
    CHECK(message([&] { integrate_controlled(s, x, 0.0, 1.0, c); }).find("relative_tolerance = -1e-08") !=
          std::string::npos);
    c = {};
    c.relative_tolerance = std::nan("");
    CHECK(message([&] { integrate_controlled(s, x, 0.0, 1.0, c); }).find("relative_tolerance = nan") != std::string::npos);
    c = {};
    c.max_factor = 1;
    CHECK(message([&] { integrate_controlled(s, x, 0.0, 1.0, c); }).find("max_factor = 1,") != std::string::npos);
    CHECK(message([&] { integrate_controlled(s, x, 1.0, 1.0); }).find("t_end = 1 with t0 = 1") != std::string::npos);
    CHECK(message([&] { make_rkn_stepper<dprkn8, S>(hamiltonians::kepler{}).accept(x); }).find("no trial step") !=
          std::string::npos);
    CHECK(message([&] { s.attempt(x, 0.0, std::nan(""), control_options{}); }).find("attempt: dt = nan") != std::string::npos);
    S bad = x;
    bad.q[1] = std::nan("");
    CHECK(message([&] { s.step(bad, 0.1); }).find("not finite") != std::string::npos);
    // A kinetic energy that is not quadratic: RKN methods lose their order, refused.
    using S1 = phase_space<double, 1>;
    auto rel = make_rkn_stepper<dprkn6, S1>(hamiltonians::relativistic_pendulum{});
    S1 y(Eigen::Matrix<double, 1, 1>(1.2), Eigen::Matrix<double, 1, 1>(0.9));
    CHECK(message([&] { rel.step(y, 0.1); }).find("velocity(p) is not linear in p") != std::string::npos);
    // The quadratic one of the same pendulum passes.
    auto ok = make_rkn_stepper<dprkn6, S1>(hamiltonians::pendulum{});
    CHECK_NOTHROW(ok.step(y, 0.1));
}

TEST_CASE("rkn pairs: a controlled run resumed from its controller's state and the stepper's carried list goes on bit for bit") {
    using S = phase_space<double, 2>;
    control_options c;
    c.absolute_tolerance = c.relative_tolerance = 1e-9;
    const S start = hamiltonians::kepler::initial_state(0.8);
    const double t_end = 30;
    auto whole = make_rkn_stepper<dprkn6, S>(hamiltonians::kepler{});
    S a = start;
    std::vector<double> times;
    const control_summary all = integrate_controlled(whole, a, 0.0, t_end, c, [&](const S&, double t) { times.push_back(t); });
    REQUIRE(all.rejected > 0);  // the controller's memory is exercised: steps were rejected
    // Saved when the observer sees accepted step 40, resumed by another stepper.
    auto first = make_rkn_stepper<dprkn6, S>(hamiltonians::kepler{});
    controller_state<double> state, saved;
    S b = start, saved_x = start;
    std::vector<double> carried;
    integrate_controlled(first, b, 0.0, t_end, c, [&](const S& y, double) {
        if (state.summary.accepted == 40) saved = state, saved_x = y, carried = first.carried();
    }, state);
    REQUIRE(saved.summary.accepted == 40);
    auto second = make_rkn_stepper<dprkn6, S>(hamiltonians::kepler{});
    second.restore_carried(carried);
    std::vector<double> later;
    const control_summary rest =
        integrate_controlled(second, saved_x, 0.0, t_end, c, [&](const S&, double t) { later.push_back(t); }, saved);
    CHECK(saved_x.q == a.q);
    CHECK(saved_x.p == a.p);
    CHECK(rest.accepted == all.accepted);  // the summary counts the whole run
    CHECK(rest.rejected == all.rejected);
    CHECK(rest.force_evaluations == all.force_evaluations);
    CHECK(rest.largest_error == all.largest_error);
    CHECK(later == std::vector<double>(times.begin() + 41, times.end()));  // t0 and steps 1..40 not seen again
}

}  // namespace test_methods_test_rkn_pairs
