// Dense output (Hairer, Norsett & Wanner I, sec. II.6): the cubic and quintic
// Hermite interpolants inside the steps, their error against exact solutions
// and its order, the run unchanged bit for bit, the evaluations it costs.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/drivers/dense_output.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/methods/rkn_pairs.hpp>

#include <random>

namespace test_drivers_test_dense_output {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using S2 = phase_space<double, 2>;
const double two_pi = 2 * std::numbers::pi;
const hamiltonians::harmonic_oscillator oscillator{};
const hamiltonians::kepler kepler{};
const S2 oscillator_start(Eigen::Vector2d(1, 0), Eigen::Vector2d(0, 0.5));  // q = (cos t, sin t / 2)

S2 oscillator_exact(double t) { return oscillator.exact(oscillator_start, t); }
S2 kepler_exact(double t) { return hamiltonians::kepler::exact_state(0.5, t); }

// The exact flow as a (time-aware) stepper: step ends exact to rounding, so
// what is measured between them is the interpolation error alone.
struct exact_stepper {
    using state_type = S2;
    using scalar = double;
    std::function<S2(double)> exact;
    void step(S2& x, double t, double dt) { x = exact(t + dt); }
};

struct errors {
    double q = 0, p = 0;
};

// Largest error at the interior points theta = 1/4, 1/2, 3/4 of every step over [0, span].
template <class Stepper, class H>
errors interpolation_error(Stepper stepper, const H& h, const std::function<S2(double)>& exact, double span, std::size_t n,
                           hermite_order order) {
    const double dt = span / double(n);
    std::vector<double> times;
    for (std::size_t i = 0; i < n; ++i)
        for (double theta : {0.25, 0.5, 0.75}) times.push_back((double(i) + theta) * dt);
    S2 x = exact(0);
    errors e;
    std::size_t calls = 0;
    integrate_dense(stepper, h, x, 0.0, span, dt, times, [&](const S2& y, double t) {
        const S2 z = exact(t);
        e.q = std::max(e.q, (y.q - z.q).cwiseAbs().maxCoeff());
        e.p = std::max(e.p, (y.p - z.p).cwiseAbs().maxCoeff());
        ++calls;
    }, order);
    CHECK(calls == times.size());
    return e;
}

double slope(double coarse, double fine) { return std::log2(coarse / fine); }
}  // namespace

TEST_CASE("dense output: the cubic Hermite on the oscillator meets its error bound dt^4/384 max|x''''|") {
    // Every component of q and p is a sinusoid of amplitude <= 1, so |x''''| <= 1,
    // and at a step's midpoint the bound is reached where |x''''| = 1.
    for (std::size_t n : {32, 64}) {
        const double dt = two_pi / double(n);
        const errors e = interpolation_error(exact_stepper{oscillator_exact}, oscillator, oscillator_exact, two_pi, n,
                                             hermite_order::cubic);
        const double bound = std::pow(dt, 4) / 384;
        CHECK(e.q <= bound * (1 + 1e-6));
        CHECK(e.p <= bound * (1 + 1e-6));
        CHECK(e.q >= 0.9 * bound);  // the bound is sharp: a wrong basis would miss it either way
    }
}

TEST_CASE("dense output: the quintic Hermite on the oscillator meets its bound dt^6/46080 max|q^(6)|") {
    for (std::size_t n : {32, 64}) {
        const double dt = two_pi / double(n);
        const errors e = interpolation_error(exact_stepper{oscillator_exact}, oscillator, oscillator_exact, two_pi, n,
                                             hermite_order::quintic);
        const double bound = std::pow(dt, 6) / 46080;
        CHECK(e.q <= bound * (1 + 1e-5) + 1e-15);
        CHECK(e.q >= 0.9 * bound);
        // p = M dq/dt: one order less, O(dt^5), still well below the cubic's dt^4/384.
        CHECK(e.p <= std::pow(dt, 4) / 384 / 10);
    }
}

TEST_CASE("dense output: measured orders, oscillator and Kepler e = 0.5 (cubic 4, quintic 6 in q and 5 in p)") {
    // max error over interior points as dt halves: dt^4 for the cubic, dt^6
    // for the quintic's q, dt^5 for its p (the derivative of the quintic).
    struct expect {
        hermite_order order;
        double q, p;
    };
    for (const expect x : {expect{hermite_order::cubic, 4, 4}, expect{hermite_order::quintic, 6, 5}}) {
        CAPTURE(static_cast<int>(x.order));
        std::vector<errors> osc, kep;
        // Kepler's pericentre (r = 0.5, speed sqrt 3) needs smaller steps to be asymptotic:
        // measured slopes 3.55, 3.89 (cubic q) from 32 steps per orbit, 3.89, 3.97 from 128.
        for (std::size_t n : {32, 64, 128}) {
            osc.push_back(interpolation_error(exact_stepper{oscillator_exact}, oscillator, oscillator_exact, two_pi,
                                              n, x.order));
            kep.push_back(interpolation_error(exact_stepper{kepler_exact}, kepler, kepler_exact, two_pi, 4 * n,
                                              x.order));
        }
        for (std::size_t i = 0; i + 1 < osc.size(); ++i) {
            CAPTURE(i);
            CHECK(std::fabs(slope(osc[i].q, osc[i + 1].q) - x.q) <= 0.3);
            CHECK(std::fabs(slope(osc[i].p, osc[i + 1].p) - x.p) <= 0.3);
            CHECK(std::fabs(slope(kep[i].q, kep[i + 1].q) - x.q) <= 0.3);
            CHECK(std::fabs(slope(kep[i].p, kep[i + 1].p) - x.p) <= 0.3);
        }
        MESSAGE("order " << static_cast<int>(x.order) << ": oscillator q " << osc[0].q << " " << osc[1].q << " "
                         << osc[2].q << ", p " << osc[0].p << " " << osc[1].p << " " << osc[2].p << "; Kepler q "
                         << kep[0].q << " " << kep[1].q << " " << kep[2].q << ", p " << kep[0].p << " " << kep[1].p
                         << " " << kep[2].p);
    }
}

TEST_CASE("dense output: with a real method the error is the step error plus the interpolation error") {
    // Yoshida's order-8 composition on Kepler e = 0.5: at the step ends its own
    // error; inside, at most that error carried by the interpolant plus the
    // interpolation bound. The cubic interpolant of the grid's errors e_i
    // (with slopes dt |e'| <~ dt |F'| e) stays below 1.5 max e_i for these dt.
    const auto stepper = make_stepper<S2>(kepler, method("yoshida_8"));
    for (std::size_t n : {200, 400}) {
        const double dt = two_pi / double(n);
        std::vector<double> ends, mids;
        for (std::size_t i = 1; i < n; ++i) ends.push_back(double(i) * dt);
        for (std::size_t i = 0; i < n; ++i) mids.push_back((double(i) + 0.5) * dt);
        double grid = 0, inside = 0, interpolation = 0;
        S2 x = kepler_exact(0);
        auto s = stepper;
        integrate_dense(s, x, 0.0, two_pi, dt, ends, [&](const S2& y, double t) {
            grid = std::max(grid, max_difference(y, kepler_exact(t)));
        });
        x = kepler_exact(0);
        s = stepper;
        integrate_dense(s, x, 0.0, two_pi, dt, mids, [&](const S2& y, double t) {
            inside = std::max(inside, max_difference(y, kepler_exact(t)));
        });
        const errors pure = interpolation_error(exact_stepper{kepler_exact}, kepler, kepler_exact, two_pi, n,
                                                hermite_order::cubic);
        interpolation = std::max(pure.q, pure.p);
        CAPTURE(n);
        CAPTURE(grid);
        CAPTURE(interpolation);
        CHECK(inside <= interpolation + 1.5 * grid);
        CHECK(inside >= 0.5 * interpolation);  // the interpolation error is seen, not hidden by the grid's
        MESSAGE(n << " steps: grid error " << grid << ", interpolation alone " << interpolation << ", total " << inside);
    }
}

TEST_CASE("dense output: the run is integrate_until's without an observer, bit for bit, for tables joined across steps") {
    // leapfrog_kdk and yoshida_8 start and end with a kick: an unobserved
    // splitting run joins those kicks across the steps of a chunk, which an
    // observer at every step would split (p + h/2 f + h/2 f is not p + h f in
    // rounding). The dense run must make exactly the unobserved run's
    // operations: final states compared with ==. 140 steps of 0.05 and a
    // shortened one: three chunks of check_every = 64, outputs in each, at
    // step ends inside a chunk, at chunk ends, at t0, at t_end, and ties.
    const double t_end = 7.03, dt = 0.05;
    const std::vector<double> times{0.0, 0.0, 0.01, 0.05, 1.234, 3.2, 3.2, 3.225, 4.0, 6.4, 6.99, 7.0, 7.03};
    for (const std::string name : {"leapfrog_kdk", "yoshida_8", "leapfrog_dkd"}) {
        CAPTURE(name);
        const auto make = [&] { return make_stepper<S2>(kepler, method(name)); };
        auto plain = make();
        S2 x_plain = kepler_exact(0);
        const run_summary r_plain = integrate_until(plain, x_plain, 0.0, t_end, dt);
        // The same run observed at every step: the step ends the outputs are compared with.
        auto observed = make();
        S2 x_observed = kepler_exact(0);
        std::vector<S2> ends;
        integrate_until(observed, x_observed, 0.0, t_end, dt, [&](const S2& y, double) { ends.push_back(y); });
        auto dense = make();
        S2 x_dense = kepler_exact(0);
        std::vector<S2> seen;
        const dense_summary r = integrate_dense(dense, x_dense, 0.0, t_end, dt, times,
                                                [&](const S2& y, double) { seen.push_back(y); });
        CHECK(x_dense.q == x_plain.q);
        CHECK(x_dense.p == x_plain.p);
        CHECK(r.steps == r_plain.steps);
        CHECK(r.force_evaluations == r_plain.force_evaluations);
        CHECK(r.velocity_evaluations == r_plain.velocity_evaluations);
        CHECK(r.t == r_plain.t);
        // The observed run does differ from the plain one for leapfrog (else this test proves nothing).
        const double split = max_difference(x_observed, x_plain);
        if (name == "leapfrog_kdk") CHECK(split > 0);
        // The outputs: at t0 the start itself, at chunk ends (3.2 = 64 dt, 6.4 = 128 dt) the run's
        // states, elsewhere within rounding of the observed run's interpolant (the inner step ends
        // are replayed on a copy of the stepper, from the chunk's start).
        REQUIRE(seen.size() == times.size());
        CHECK(seen[0].q == kepler_exact(0).q);
        CHECK(seen[12].q == x_plain.q);
        CHECK(seen[12].p == x_plain.p);
        double worst = 0;
        for (std::size_t i = 0; i < times.size(); ++i) {
            // At step ends: the observed run's state there, rounding apart.
            const auto k = static_cast<std::size_t>(std::lround(times[i] / dt));
            const double d = max_difference(seen[i], ends[std::min(k, ends.size() - 1)]);
            if (std::fabs(times[i] - double(k) * dt) < 1e-12) worst = std::max(worst, d);
        }
        CHECK(worst <= 1e-12);  // step ends: the replayed ones differ from the observed run's by rounding
        // Replayed: up to the step holding 1.234 (25), 4.0 (80 - 64 = 16) and 6.99 (140 - 128 - 1 = 11);
        // the chunk ends 3.2 and 6.4 are the run's own states.
        CHECK(r.replayed_steps == 25 + 16 + 11);
        MESSAGE(name << ": observed run - plain run " << split << ", step-end outputs - observed step ends " << worst
                     << ", " << r.replayed_steps << " steps replayed of " << r.steps);
    }
    // A processed stepper (its kernel's steps joined within a call, the
    // processor applied once per call) likewise.
    const auto processed_one = [] {
        return processed_stepper<hamiltonians::kepler, S2>(kepler, processed("bcm_2006_p8"));
    };
    auto plain = processed_one(), observed = processed_one(), dense = processed_one();
    S2 x_plain = kepler_exact(0), x_observed = x_plain, x_dense = x_plain;
    integrate_until(plain, x_plain, 0.0, t_end, dt);
    integrate_until(observed, x_observed, 0.0, t_end, dt, [](const S2&, double) {});
    const dense_summary r = integrate_dense(dense, x_dense, 0.0, t_end, dt, times, [](const S2&, double) {});
    CHECK(x_dense.q == x_plain.q);
    CHECK(x_dense.p == x_plain.p);
    CHECK(r.replayed_steps == 25 + 16 + 11);
    MESSAGE("bcm_2006_p8 processed: observed run - plain run " << max_difference(x_observed, x_plain));
}

TEST_CASE("dense output: step ends are the run's, and each step end is evaluated once") {
    // A stepper without steps(): observed at every step, which is its unobserved run.
    const auto make = [] { return make_classic<rk4, S2>(kepler); };
    const double t_end = 7.03, dt = 0.05;  // dt does not divide the span: a shortened last step
    // integrate_until with an observer, the step ends recorded.
    auto s1 = make();
    S2 x1 = kepler_exact(0);
    std::vector<S2> ends;
    std::vector<double> end_times;
    const run_summary r1 = integrate_until(s1, x1, 0.0, t_end, dt, [&](const S2& y, double t) {
        ends.push_back(y);
        end_times.push_back(t);
    });
    // The same with dense output at every step end and every midpoint.
    std::vector<double> times;
    for (std::size_t i = 0; i < end_times.size(); ++i) {
        times.push_back(end_times[i]);
        if (i + 1 < end_times.size()) times.push_back((end_times[i] + end_times[i + 1]) / 2);
    }
    auto s2 = make();
    S2 x2 = kepler_exact(0);
    std::vector<S2> seen;
    const dense_summary r2 = integrate_dense(s2, kepler, x2, 0.0, t_end, dt, times, [&](const S2& y, double) { seen.push_back(y); });
    CHECK(x2.q == x1.q);
    CHECK(x2.p == x1.p);
    CHECK(r2.steps == r1.steps);
    CHECK(r2.t == r1.t);
    CHECK(r2.replayed_steps == 0);
    REQUIRE(seen.size() == times.size());
    bool same_ends = true;
    for (std::size_t i = 0; i < ends.size(); ++i) same_ends = same_ends && seen[2 * i].q == ends[i].q && seen[2 * i].p == ends[i].p;
    CHECK(same_ends);
    CHECK(r2.outputs == times.size());
    // Every step interpolated: each of the steps + 1 ends evaluated once.
    CHECK(r2.extra_force_evaluations == r1.steps + 1);
    CHECK(r2.extra_velocity_evaluations == r1.steps + 1);

    // A splitting stepper with outputs in every step: each end once too, and
    // every step but the last of each chunk replayed once.
    auto s3 = make_stepper<S2>(kepler, method("yoshida_8"));
    auto s4 = make_stepper<S2>(kepler, method("yoshida_8"));
    S2 x3 = kepler_exact(0), x4 = x3;
    integrate_until(s3, x3, 0.0, t_end, dt);
    const dense_summary r4 = integrate_dense(s4, x4, 0.0, t_end, dt, times, [](const S2&, double) {});
    CHECK(x4.q == x3.q);
    CHECK(x4.p == x3.p);
    CHECK(r4.extra_force_evaluations == r4.steps + 1);
    // 141 steps: chunks of 64, 64, 12 and the shortened one: 63 + 63 + 11 replayed.
    CHECK(r4.steps == 141);
    CHECK(r4.replayed_steps == 137);
}

TEST_CASE("dense output: one output costs the two ends of its step only") {
    const std::vector<double> one{1.234};
    for (const hermite_order order : {hermite_order::cubic, hermite_order::quintic}) {
        auto s = make_stepper<S2>(oscillator, method("leapfrog_kdk"));
        S2 x = oscillator_start;
        double at = 0;
        const dense_summary r = integrate_dense(s, x, 0.0, 10.0, 0.1, one, [&](const S2&, double t) { at = t; }, order);
        CHECK(at == 1.234);
        CHECK(r.extra_force_evaluations == 2);
        // 1.234 is in step 13 of the first chunk: 12 steps in one call, then one step,
        // on a copy of the stepper (leapfrog: 12 + 1 forces, then 1: the step reuses
        // the force the 12 steps ended with).
        CHECK(r.replayed_steps == 13);
        CHECK(r.replay_force_evaluations == 14);
        if (order == hermite_order::cubic) {
            CHECK(r.extra_velocity_evaluations == 2);
        } else {
            // 2 velocities, 2 M^-1 F, and at most 2 for M (q1 - q0) when M is the identity.
            CHECK(r.extra_velocity_evaluations >= 4);
            CHECK(r.extra_velocity_evaluations <= 6);
        }
    }
}

TEST_CASE("dense output: a mass other than 1: the quintic's p = M dq/dt through M (q1 - q0)") {
    // H = p^2/(2m) + m w^2 q^2/2 with m = 3: velocity = p/3, so p = 3 dq/dt,
    // and M (q1 - q0) comes from conjugate gradients on velocity(). The
    // quintic's error e(t) = q^(6)/720 (t - ta)^3 (t - tb)^3 differentiated:
    // |dp| <= m max|q^(6)| dt^5 max|3 s^2 (1 - s)^2 (1 - 2 s)| / 720, the max
    // 0.0536 (s = 0.28), and 0.0527 at s = 1/4 where it is sampled.
    const hamiltonians::harmonic_oscillator heavy{3.0, 1.0};
    const S2 x0(Eigen::Vector2d(1, 0.2), Eigen::Vector2d(0.3, 1.5));
    const auto exact = [&](double t) { return heavy.exact(x0, t); };
    const double a6 = std::max(std::hypot(1.0, 0.3 / 3), std::hypot(0.2, 1.5 / 3));  // amplitude of q's components
    for (std::size_t n : {100, 200}) {
        const double dt = two_pi / double(n);
        const errors e = interpolation_error(exact_stepper{exact}, heavy, exact, two_pi, n, hermite_order::quintic);
        const double bound = 3 * a6 * std::pow(dt, 5) * 0.0536 / 720;
        CAPTURE(n);
        CHECK(e.p <= 1.05 * bound);
        CHECK(e.p >= 0.5 * bound);  // the sampled points see the leading term (s = 1/4: 0.0527)
        CHECK(e.q <= 1.05 * a6 * std::pow(dt, 6) / 46080 + 1e-15);
    }
}

TEST_CASE("dense output: bad output times and orders are refused, naming the value") {
    auto s = make_stepper<S2>(oscillator, method("leapfrog_kdk"));
    S2 x = oscillator_start;
    const auto none = [](const S2&, double) {};
    const std::vector<double> unsorted{1.0, 0.5}, late{12.0}, early{-1.0}, nan{std::nan("")}, unsorted_not{0.5, 1.0};
    CHECK_THROWS_WITH_AS(integrate_dense(s, x, 0.0, 10.0, 0.1, unsorted, none),
                         doctest::Contains("output_times[1] = 0.5 is before output_times[0] = 1"), invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_dense(s, x, 0.0, 10.0, 0.1, late, none), doctest::Contains("output_times[0] = 12"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_dense(s, x, 0.0, 10.0, 0.1, early, none), doctest::Contains("output_times[0] = -1"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_dense(s, x, 0.0, 10.0, 0.1, nan, none), doctest::Contains("output_times[0] = nan"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_dense(s, x, 0.0, 10.0, 0.0, late, none), doctest::Contains("dt = 0"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_dense(s, x, 5.0, 1.0, 0.1, late, none), doctest::Contains("t_end = 1"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_dense(s, x, 0.0, 10.0, 0.1, unsorted_not, none, static_cast<hermite_order>(4)),
                         doctest::Contains("order = 4"), invalid_argument);
    CHECK(x.q == oscillator_start.q);  // nothing ran
}

TEST_CASE("dense output: a dynamic-size state gives the fixed-size state's values") {
    using SD = phase_space<double>;
    const std::vector<double> times{0.05, 1.234, 2.5, 3.0};
    for (const hermite_order order : {hermite_order::cubic, hermite_order::quintic}) {
        std::vector<S2> fixed;
        std::vector<SD> dynamic;
        auto s1 = make_stepper<S2>(kepler, method("leapfrog_kdk"));
        S2 x1 = kepler_exact(0);
        integrate_dense(s1, x1, 0.0, 3.0, 0.1, times, [&](const S2& y, double) { fixed.push_back(y); }, order);
        auto s2 = make_stepper<SD>(kepler, method("leapfrog_kdk"));
        SD x2 = kepler_exact(0).cast<double, Eigen::Dynamic>();
        integrate_dense(s2, x2, 0.0, 3.0, 0.1, times, [&](const SD& y, double) { dynamic.push_back(y); }, order);
        REQUIRE(dynamic.size() == fixed.size());
        for (std::size_t i = 0; i < fixed.size(); ++i) {
            CHECK(dynamic[i].size() == 2);
            CHECK((dynamic[i].q - fixed[i].q).cwiseAbs().maxCoeff() <= 1e-14);
            CHECK((dynamic[i].p - fixed[i].p).cwiseAbs().maxCoeff() <= 1e-14);
        }
    }
}

namespace {
using P1 = phase_space<double, 1>;
using L1 = phase_space<long double, 1>;
constexpr double pendulum_span = 20;  // about two periods from q = 2.5 at rest

// 1000 times in [0, 20], uniform, fixed seed, sorted.
std::vector<double> random_times() {
    std::mt19937_64 generator(37);
    std::uniform_real_distribution<double> uniform(0, pendulum_span);
    std::vector<double> t(1000);
    for (double& v : t) v = uniform(generator);
    std::sort(t.begin(), t.end());
    return t;
}

// The reference: dprkn12 in long double at tolerance 1e-18, run to land
// exactly on each time (no interpolation), from q = 2.5, p = 0.
std::vector<L1> pendulum_reference(const std::vector<double>& times) {
    auto s = make_rkn_stepper<dprkn12, L1>(hamiltonians::pendulum{});
    L1 x(1);
    x.q[0] = 2.5L;
    x.p[0] = 0;
    control_options c;
    c.absolute_tolerance = c.relative_tolerance = 1e-18;
    std::vector<L1> out;
    long double t = 0;
    for (double tau : times) {
        if (tau > t) integrate_controlled(s, x, t, static_cast<long double>(tau), c);
        t = tau;
        out.push_back(x);
    }
    return out;
}

template <class Pair>
void check_pair_dense(double tol, const std::vector<double>& times, const std::vector<L1>& reference) {
    auto s = make_rkn_stepper<Pair, P1>(hamiltonians::pendulum{});
    P1 x(1);
    x.q[0] = 2.5;
    x.p[0] = 0;
    control_options c;
    c.absolute_tolerance = c.relative_tolerance = tol;
    double worst = 0;
    std::size_t i = 0;
    const auto r = integrate_dense(s, x, 0.0, pendulum_span, c, std::span<const double>(times), [&](const P1& y, double) {
        worst = std::max({worst, double(std::fabs(y.q[0] - reference[i].q[0])),
                          double(std::fabs(y.p[0] - reference[i].p[0]))});
        ++i;
    });
    MESSAGE(std::string(Pair::name), " at tolerance ", tol, ": ", r.accepted, " steps, dense output off by ", worst, " = ",
            worst / tol, " tol, ", r.extra_force_evaluations, " extra forces");
    CHECK(i == times.size());
    CHECK(r.outputs == times.size());
    // A dense value carries the run's error at the step's start, within 10
    // tolerances by the pairs' tolerance proportionality (test_rkn_pairs.cpp,
    // band_high), plus the interpolation's own: the continuous extension's
    // (dprkn6, order 6 in q, 5 in p) or a partial step's local error, both at
    // most the step's, which the control holds below one tolerance.
    CHECK(worst <= 10 * tol);
    // Partial steps (dprkn8, dprkn12) cost s - 1 forces per value; dprkn6's extension none.
    const std::uint64_t per_value = rkn_dense_table<Pair> ? 0 : Pair::stages - 1;
    CHECK(r.extra_force_evaluations <= per_value * times.size());
}
}  // namespace

TEST_CASE("dense output over a controlled run: dprkn6, dprkn8, dprkn12 on the pendulum within 10 tolerances at 1000 times") {
    const std::vector<double> times = random_times();
    const std::vector<L1> reference = pendulum_reference(times);
    for (double tol : {1e-8, 1e-10}) {
        check_pair_dense<dprkn6>(tol, times, reference);
        check_pair_dense<dprkn8>(tol, times, reference);
        check_pair_dense<dprkn12>(tol, times, reference);
    }
}

TEST_CASE("dense output over a controlled run: a stepper without its own interpolation gets the Hermite interpolant") {
    // Euler-Richardson through richardson_adaptive, on the oscillator: the
    // cubic Hermite's error dt^4/384 max|x^(4)| (dt <= 0.1, |x^(4)| <= 1) is
    // added to the run's own error, bounded by the steps' local errors summed
    // (a rotation does not grow them): accepted * tolerance.
    auto er = make_classic<euler_richardson, S2>(oscillator);
    S2 x = oscillator_start;
    auto adaptive = richardson_adaptive(er);
    control_options o = adaptive.default_control();
    o.absolute_tolerance = 1e-7;
    o.dt_max = 0.1;
    const std::vector<double> times{0.0, 0.05, 1.234, 3.0, two_pi};
    double worst = 0;
    std::size_t i = 0;
    const auto r = integrate_dense(adaptive, oscillator, x, 0.0, two_pi, o, std::span<const double>(times),
                                   [&](const S2& y, double t) {
                                       CHECK(t == times[i++]);
                                       worst = std::max(worst, max_difference(y, oscillator_exact(t)));
                                   });
    CHECK(i == times.size());
    CHECK(r.extra_force_evaluations > 0);
    CHECK(worst <= double(r.accepted) * o.absolute_tolerance + std::pow(0.1, 4) / 384);
}

}  // namespace test_drivers_test_dense_output
