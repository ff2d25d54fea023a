// The claims Gould & Tobochnik (ch. 3) and Sandvik's lecture notes make about their classic algorithms, measured:
// orders, bounded or growing energy error, time reversal, the error estimate,
// the self-starting steps, and clear errors on bad input.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/damped_driven_oscillator.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

namespace test_methods_test_classic_steppers {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using State = phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;

const State start(V1(1.2), V1(0.3));
const hamiltonians::harmonic_oscillator oscillator{};
const hamiltonians::pendulum pendulum{};
// Damped and driven (Sandvik's friction case, with time dependence).
const hamiltonians::damped_driven_oscillator damped{1.0, 1.0, 0.3, 0.5, 0.7};
// The undamped oscillator in Newton's form, and the pendulum in Newton's form.
const hamiltonians::damped_driven_oscillator newton_oscillator{};
const auto newton_pendulum = make_newtonian([](const auto& x, auto) { return (-x.array().sin()).matrix().eval(); });

// A damped pendulum with the split m a = F(x) - G(v) of Sandvik's lecture notes.
struct damped_pendulum {
    double mass = 1.0, b = 0.4;
    static constexpr bool p_is_velocity = true;
    template <class V, class T> void dq_dt(const V&, const V& v, T, V& out) const { out = v; }
    template <class V, class T> void dp_dt(const V& x, const V& v, T, V& out) const {
        out = (-x.array().sin()).matrix() - b * v;
    }
    template <class V, class T> void force(const V& x, T, V& out) const { out = (-x.array().sin()).matrix(); }
    template <class V> void drag(const V& v, V& out) const { out = b * v; }
};

// Runs n steps of t_end/n from `start` with a fresh stepper made by `make`.
template <class Make>
double order_of(Make make, double t_end = 3.0) {
    order_options o;
    o.min_steps = 8;
    o.max_steps = std::size_t(1) << 15;
    o.floor = 1e-10;  // double precision
    return measure_order(
               [&](std::size_t n) {
                   auto s = make();
                   State x = start;
                   const double dt = t_end / double(n);
                   for (std::size_t i = 0; i < n; ++i) s.step(x, double(i) * dt, dt);
                   return x;
               },
               t_end, o)
        .order;
}

template <template <class, class> class Method, class System, class... Options>
double order_on(const System& system, Options... options) {
    return order_of([&] { return make_classic<Method, State>(system, options...); });
}

// Largest relative error of the oscillator's energy (q^2 + p^2)/2 over n steps from (1, 0).
template <template <class, class> class Method, class System>
double max_energy_error(const System& system, double dt, std::size_t n) {
    auto s = make_classic<Method, State>(system);
    State x(V1(1.0), V1(0.0));
    double worst = 0;
    for (std::size_t i = 0; i < n; ++i) {
        s.step(x, double(i) * dt, dt);
        worst = std::max(worst, std::fabs(x.q[0] * x.q[0] + x.p[0] * x.p[0] - 1));
    }
    return worst;
}
}  // namespace

TEST_CASE("classic: measured global orders match the textbooks' theory on oscillator, pendulum and damped oscillator") {
    // Damped oscillator: the plain treatment of a velocity-dependent force,
    // a_n at v_{n-1/2} (half-step, two-step leapfrog, plain damped leapfrog),
    // loses an order (Sandvik's lecture notes).
    struct expectation {
        const char* name;
        double oscillator, pendulum, damped;
    };
    const expectation e[] = {{"euler", 1, 1, 1},          {"euler_cromer", 1, 1, 1},     {"half_step", 2, 2, 1},
                             {"euler_richardson", 2, 2, 2}, {"rk4", 4, 4, 4},             {"velocity_verlet", 2, 2, 2},
                             {"predictor_corrector", 2, 2, 2}};
    const predictor_corrector_options tight{1e-15, 100};
    for (const expectation& x : e) {
        CAPTURE(x.name);
        const std::string n = x.name;
        double o[3] = {0, 0, 0};
        if (n == "euler") o[0] = order_on<euler>(oscillator), o[1] = order_on<euler>(pendulum), o[2] = order_on<euler>(damped);
        if (n == "euler_cromer")
            o[0] = order_on<euler_cromer>(oscillator), o[1] = order_on<euler_cromer>(pendulum),
            o[2] = order_on<euler_cromer>(damped);
        if (n == "half_step")
            o[0] = order_on<half_step>(oscillator), o[1] = order_on<half_step>(pendulum), o[2] = order_on<half_step>(damped);
        if (n == "euler_richardson")
            o[0] = order_on<euler_richardson>(oscillator), o[1] = order_on<euler_richardson>(pendulum),
            o[2] = order_on<euler_richardson>(damped);
        if (n == "rk4") o[0] = order_on<rk4>(oscillator), o[1] = order_on<rk4>(pendulum), o[2] = order_on<rk4>(damped);
        if (n == "velocity_verlet")
            o[0] = order_on<velocity_verlet>(oscillator), o[1] = order_on<velocity_verlet>(pendulum),
            o[2] = order_on<velocity_verlet>(damped);
        if (n == "predictor_corrector")
            o[0] = order_on<predictor_corrector>(oscillator, tight), o[1] = order_on<predictor_corrector>(pendulum, tight),
            o[2] = order_on<predictor_corrector>(damped, tight);
        CHECK(std::fabs(o[0] - x.oscillator) <= 0.15);
        CHECK(std::fabs(o[1] - x.pendulum) <= 0.15);
        CHECK(std::fabs(o[2] - x.damped) <= 0.15);
    }
}

TEST_CASE("classic: two-step leapfrog (eq. 3.47) is second order, plain velocity dependence costs an order") {
    CHECK(std::fabs(order_on<leapfrog_two_step>(newton_oscillator) - 2) <= 0.15);
    CHECK(std::fabs(order_on<leapfrog_two_step>(newton_pendulum) - 2) <= 0.15);
    CHECK(std::fabs(order_on<leapfrog_two_step>(damped) - 1) <= 0.15);
}

TEST_CASE("classic: damped leapfrog, plain loses an order and the corrected procedure keeps 2 (Sandvik's lecture notes)") {
    const auto plain = damping_treatment::plain, corrected = damping_treatment::corrected;
    CHECK(std::fabs(order_on<damped_leapfrog>(damped, plain) - 1) <= 0.15);
    CHECK(std::fabs(order_on<damped_leapfrog>(damped, corrected) - 2) <= 0.15);
    CHECK(std::fabs(order_on<damped_leapfrog>(damped_pendulum{}, plain) - 1) <= 0.15);
    CHECK(std::fabs(order_on<damped_leapfrog>(damped_pendulum{}, corrected) - 2) <= 0.15);
    // Without damping both are the leapfrog.
    CHECK(std::fabs(order_on<damped_leapfrog>(newton_oscillator, plain) - 2) <= 0.15);
    CHECK(std::fabs(order_on<damped_leapfrog>(newton_oscillator, corrected) - 2) <= 0.15);
}

TEST_CASE("classic: damped leapfrog converges to the exact damped, driven solution") {
    auto s = make_classic<damped_leapfrog, State>(damped);
    State x = start;
    const double dt = 1e-3;
    for (int i = 0; i < 5000; ++i) s.step(x, i * dt, dt);
    const State exact = damped.exact(start, 5.0);
    CHECK(max_difference(x, exact) < 1e-5);
    CHECK(s.force_evaluations() == 5001);  // one F per step, plus the start
}

TEST_CASE("classic: leapfrog energy stays bounded over 1e6 steps while Euler's grows and RK4's drifts (Sandvik's lecture notes)") {
    for (const double h : {0.1, 0.01}) {
        CAPTURE(h);
        // Leapfrog on the oscillator conserves p^2 + (1 - h^2/4) q^2 exactly, so
        // the energy error never exceeds (h^2/4) / (1 - h^2/4).
        const double bound = (h * h / 4) / (1 - h * h / 4) * (1 + 1e-6) + 1e-13;
        CHECK(max_energy_error<velocity_verlet>(oscillator, h, 1000000) <= bound);
        CHECK(max_energy_error<half_step>(oscillator, h, 1000000) <= bound);
        CHECK(max_energy_error<leapfrog_two_step>(newton_oscillator, h, 1000000) <= bound);

        // Euler multiplies the energy by 1 + h^2 every step; RK4 by 1 - h^6/72 + h^8/576.
        auto euler_s = make_classic<euler, State>(oscillator);
        auto rk4_s = make_classic<rk4, State>(oscillator);
        State xe(V1(1.0), V1(0.0)), xr = xe;
        const std::size_t n = h == 0.1 ? 2000 : 1000000;
        for (std::size_t i = 0; i < n; ++i) euler_s.step(xe, i * h, h);
        for (std::size_t i = 0; i < 1000000; ++i) rk4_s.step(xr, i * h, h);
        const double euler_growth = std::pow(1 + h * h, double(n));
        CHECK(energy(oscillator, xe) / 0.5 == doctest::Approx(euler_growth).epsilon(1e-9));
        CHECK(energy(oscillator, xe) / 0.5 > 1.5);
        const double rk4_drift = 1 - std::pow(1 - std::pow(h, 6) / 72 + std::pow(h, 8) / 576, 1e6);
        CHECK(std::fabs((1 - energy(oscillator, xr) / 0.5) - rk4_drift) <= 1e-3 * rk4_drift);
    }
}

TEST_CASE("classic: the leapfrogs are time-reversible, RK4 is not") {
    const double dt = 0.1;
    auto back_and_forth = [&](auto s) {
        State x = start;
        for (int i = 0; i < 100; ++i) s.step(x, i * dt, dt);
        for (int i = 100; i > 0; --i) s.step(x, i * dt, -dt);
        return max_difference(x, start);
    };
    CHECK(back_and_forth(make_classic<velocity_verlet, State>(pendulum)) < 1e-13);
    CHECK(back_and_forth(make_classic<half_step, State>(pendulum)) < 1e-13);
    CHECK(back_and_forth(make_classic<leapfrog_two_step, State>(newton_pendulum)) < 1e-12);
    CHECK(back_and_forth(make_classic<predictor_corrector, State>(pendulum, predictor_corrector_options{1e-15, 100})) < 1e-12);
    CHECK(back_and_forth(make_classic<rk4, State>(pendulum)) > 1e-8);
    CHECK(back_and_forth(make_classic<euler_richardson, State>(pendulum)) > 1e-6);
}

TEST_CASE("classic: the half-step algorithm starts with the Euler half step (eq. 3.37c)") {
    auto s = make_classic<half_step, State>(pendulum);
    State x = start;
    const double dt = 0.1;
    s.step(x, 0.0, dt);
    const double a0 = -std::sin(start.q[0]);
    CHECK(s.half_step_momentum()[0] == start.p[0] + dt / 2 * a0);
    CHECK(x.q[0] == start.q[0] + dt * s.half_step_momentum()[0]);  // eq. 3.37b
    // Continuing: one force per step (eq. 3.37a reuses the force of the last step).
    s.reset_counters();
    for (int i = 1; i < 11; ++i) s.step(x, i * dt, dt);
    CHECK(s.force_evaluations() == 10);
    // Handing it another state restarts it with eq. 3.37c.
    State y = start;
    s.step(y, 0.0, dt);
    CHECK(s.half_step_momentum()[0] == start.p[0] + dt / 2 * a0);
}

TEST_CASE("classic: two-step leapfrog self-starts by eq. 3.45 and gives eqs. 3.47b and 3.50 velocities") {
    auto s = make_classic<leapfrog_two_step, State>(newton_pendulum);
    auto vv = make_classic<velocity_verlet, State>(newton_pendulum);
    State x = start, y = start;
    const double dt = 0.05;
    for (int i = 0; i < 60; ++i) {
        const State before = x;
        s.step(x, i * dt, dt);
        vv.step(y, i * dt, dt);
        // The two forms are one algorithm (Gould & Tobochnik, after eq. 3.48): equal to roundoff.
        CHECK(max_difference(x, y) < 1e-12);
        if (i == 0) CHECK(x.q[0] == doctest::Approx(before.q[0] + dt * before.p[0] - dt * dt / 2 * std::sin(before.q[0])).epsilon(1e-15));
    }
    // eq. 3.47b is the central difference at t_n, one step behind: second order.
    CHECK(s.central_difference_time() == doctest::Approx(59 * dt));
    const double v_ref = [&] {
        auto r = make_classic<rk4, State>(newton_pendulum);
        State z = start;
        for (int i = 0; i < 59 * 20; ++i) r.step(z, i * dt / 20, dt / 20);
        return z.p[0];
    }();
    CHECK(std::fabs(s.central_difference_velocity()[0] - v_ref) < 5 * dt * dt);
}

TEST_CASE("classic: Euler-Richardson's estimate tracks the true error of the half-step pair within 2x") {
    // |x2 - x1| estimates the error of x2 (two Euler half steps); checked
    // against the exact step (RK4 with 1000 sub-steps) as dt shrinks.
    for (const double dt : {0.1, 0.05, 0.025, 0.0125}) {
        CAPTURE(dt);
        auto er = make_classic<euler_richardson, State>(pendulum);
        State x = start;
        er.step(x, 0.0, dt);
        State x2 = start;
        auto eu = make_classic<euler, State>(pendulum);
        eu.step(x2, 0.0, dt / 2);
        eu.step(x2, dt / 2, dt / 2);
        State exact = start;
        auto r = make_classic<rk4, State>(pendulum);
        for (int i = 0; i < 1000; ++i) r.step(exact, i * dt / 1000, dt / 1000);
        const double true_q = std::fabs(x2.q[0] - exact.q[0]), true_p = std::fabs(x2.p[0] - exact.p[0]);
        const auto& e = er.last_error_estimate();
        CHECK(e.position / true_q > 0.5);
        CHECK(e.position / true_q < 2);
        CHECK(e.momentum / true_p > 0.5);
        CHECK(e.momentum / true_p < 2);
        // and it bounds the Euler-Richardson step's own error
        CHECK(std::fabs(x.q[0] - exact.q[0]) < e.position);
        CHECK(std::fabs(x.p[0] - exact.p[0]) < e.momentum);
    }
}

TEST_CASE("classic: predictor-corrector that does not converge stops with a clear error, nothing is lost") {
    const hamiltonians::harmonic_oscillator stiff{1.0, 100.0};
    auto s = make_classic<predictor_corrector, State>(stiff, predictor_corrector_options{1e-12, 5});
    State x = start;
    const State before = x;
    try {
        s.step(x, 0.0, 0.1);
        FAIL("expected integration_error");
    } catch (const integration_error& e) {
        CHECK(std::string(e.what()).find("no convergence in 5 iterations") != std::string::npos);
        CHECK(max_difference(x, before) == 0);
    }
    // Through the driver the error names the step.
    State y = start;
    auto t = make_classic<predictor_corrector, State>(stiff, predictor_corrector_options{1e-12, 5});
    try {
        integrate_steps(t, y, 0.0, 0.1, 10);
        FAIL("expected integration_error");
    } catch (const integration_error& e) {
        CHECK(e.step == 1);
        CHECK(std::string(e.what()).find("(step 1)") != std::string::npos);
    }
    const auto make = [&](predictor_corrector_options o) { return make_classic<predictor_corrector, State>(stiff, o); };
    CHECK_THROWS_WITH_AS(make({0.0, 5}), doctest::Contains("tolerance = 0"), invalid_argument);
    CHECK_THROWS_WITH_AS(make({1e-9, 0}), doctest::Contains("max_iterations = 0"), invalid_argument);
}

TEST_CASE("classic: a run that blows up reports the step and time and keeps the last finite state") {
    // Euler multiplies the oscillator's energy by 1.01 per step at h = 0.1: it
    // overflows after about 1.4e5 steps.
    auto s = make_classic<euler, State>(oscillator);
    State x(V1(1.0), V1(0.0));
    try {
        integrate_steps(s, x, 0.0, 0.1, 200000);
        FAIL("expected integration_error");
    } catch (const integration_error& e) {
        CHECK(e.step > 100000);
        CHECK(e.time == doctest::Approx(0.1 * double(e.step - 1)));
        CHECK(is_finite(x));
        CHECK(energy(oscillator, x) > 1e300);
    }
}

TEST_CASE("classic: steppers run through the driver with time-dependent forces") {
    // The driver passes t = t0 + i dt: the driven oscillator started at t0 = 2
    // on the exact solution stays on it up to t = 4.
    auto s = make_classic<rk4, State>(damped);
    State x = damped.exact(start, 2.0);
    integrate_until(s, x, 2.0, 4.0, 0.01);
    CHECK(max_difference(x, damped.exact(start, 4.0)) < 1e-9);
    // A wrong time (the drive taken from t = 0) would be far off.
    State y = damped.exact(start, 2.0);
    integrate_until(s, y, 0.0, 2.0, 0.01);
    CHECK(max_difference(y, damped.exact(start, 4.0)) > 1e-3);
}

// A run stopped after step k, as a checkpoint stops it, and resumed by another
// stepper from the state and the rule's carried list: bit for bit the whole run,
// with the same evaluation counts; without the list the history restarts (at
// an extra evaluation, the state often the same to the bit).
template <template <class, class> class Method, class System>
void resumes_bit_for_bit(const System& system, const std::string& name) {
    CAPTURE(name);
    const auto observe = [](const State&, double) {};
    auto whole = make_classic<Method, State>(system);
    State a = start;
    integrate_steps(whole, a, 0.0, 0.01, 300, observe);
    run_options resume;
    resume.first_step = 123;
    for (const bool restored : {true, false}) {
        auto first = make_classic<Method, State>(system), second = make_classic<Method, State>(system);
        State b = start;
        integrate_steps(first, b, 0.0, 0.01, 123, observe);
        if (restored) second.restore_carried(first.carried());
        integrate_steps(second, b, 0.0, 0.01, 300, observe, resume);
        CAPTURE(restored);
        const bool same = max_difference(a, b) == 0 &&
                          first.force_evaluations() + second.force_evaluations() == whole.force_evaluations();
        CHECK(same == restored);
    }
}

TEST_CASE("classic: steppers with a history restored from carried() go on bit for bit, and without it not") {
    resumes_bit_for_bit<half_step>(pendulum, "half_step");
    resumes_bit_for_bit<velocity_verlet>(pendulum, "velocity_verlet");
    resumes_bit_for_bit<leapfrog_two_step>(newton_pendulum, "leapfrog_two_step");
    resumes_bit_for_bit<damped_leapfrog>(damped, "damped_leapfrog");
    resumes_bit_for_bit<predictor_corrector>(pendulum, "predictor_corrector");
    auto s = make_classic<velocity_verlet, State>(pendulum);
    State x = start;
    s.step(x, 0.0, 0.01);
    std::vector<double> bad = s.carried();
    bad.push_back(1);
    CHECK_THROWS_WITH_AS(s.restore_carried(bad), doctest::Contains("is longer than"), invalid_argument);
}

}  // namespace test_methods_test_classic_steppers
