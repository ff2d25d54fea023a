#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <new>
#include <limits>
#include <string>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

namespace test_core_test_splitting_stepper {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

TEST_CASE("splitting_stepper: fixed-size and dynamic states give identical trajectories") {
    using Fixed = phase_space<double, 2>;
    using Dynamic = phase_space<double>;
    for (const char* name : {"leapfrog_kdk", "pefrl_4", "blanes_moan_srkn11b"}) {
        CAPTURE(name);
        splitting_stepper<hamiltonians::kepler, Fixed> fixed({}, method(name));
        splitting_stepper<hamiltonians::kepler, Dynamic> dynamic({}, method(name));
        Fixed a = hamiltonians::kepler::initial_state(0.6);
        Dynamic b(a.q, a.p);
        fixed.steps(a, 0.01, 2000);
        dynamic.steps(b, 0.01, 2000);
        CHECK(a.q[0] == b.q[0]);
        CHECK(a.q[1] == b.q[1]);
        CHECK(a.p[0] == b.p[0]);
        CHECK(a.p[1] == b.p[1]);
    }
}

TEST_CASE("splitting_stepper: a fixed-size state's unused residuals are handed on as zeros, not stray bits") {
    // The stepper built in memory filled with 0xff bytes (a NaN in every
    // double): a residual left uninitialised would reach memory(), and a
    // checkpoint, as NaN.
    using Fixed = phase_space<double, 2>;
    using stepper = splitting_stepper<hamiltonians::kepler, Fixed>;
    alignas(stepper) unsigned char bytes[sizeof(stepper)];
    std::memset(bytes, 0xff, sizeof bytes);
    for (const table& t : {method("leapfrog_kdk"), force_gradient_method("chin_4a")}) {
        CAPTURE(t.name());
        stepper* s = new (bytes) stepper({}, t);
        Fixed x = hamiltonians::kepler::initial_state(0.6);
        s->steps(x, 0.01, 10);
        const auto m = s->memory();
        CHECK(m.q_error.isZero());
        CHECK(m.p_error.isZero());
        s->~stepper();
        std::memset(bytes, 0xff, sizeof bytes);
    }
}

TEST_CASE("splitting_stepper: force and velocity evaluations are counted, the last force reused") {
    using State = phase_space<double, 1>;
    splitting_stepper<hamiltonians::pendulum, State> lf({}, method("leapfrog_kdk"));
    State x(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.0));
    lf.steps(x, 0.1, 1000);
    CHECK(lf.force_evaluations() == 1001);  // one per step plus the very first
    CHECK(lf.velocity_evaluations() == 1000);
    splitting_stepper<hamiltonians::pendulum, State> y6({}, method("yoshida_6"));
    y6.steps(x, 0.1, 100);
    CHECK(y6.force_evaluations() == 7 * 100 + 1);
    // x was moved by y6 since lf returned it: lf's first step() evaluates its
    // force afresh, and each later one reuses the force the previous one ended with.
    lf.reset_counters();
    for (int i = 0; i < 10; ++i) lf.step(x, 0.1);
    CHECK(lf.force_evaluations() == 11);
    CHECK(lf.velocity_evaluations() == 10);
}

namespace {
// A pendulum that counts the forces it is asked for, and whose length the caller may change.
struct counted_pendulum {
    std::uint64_t* calls;
    const double* length;
    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> auto potential(const V& q) const { using std::cos; return -cos(q[0]) / *length; }
    template <class V> void force(const V& q, V& f) const {
        ++*calls;
        for (Eigen::Index i = 0; i < q.size(); ++i) f[i] = -std::sin(q[i]) / *length;
    }
};

template <class State>
State pendulum_state(Eigen::Index n) {
    State x(n);
    for (Eigen::Index i = 0; i < n; ++i) x.q[i] = 0.3 + 0.1 * double(i), x.p[i] = 0.2 - 0.05 * double(i);
    return x;
}

// n steps by step(), with the force dropped before each (state_changed()) or kept.
template <class H, class State>
State step_loop(const H& h, const table& t, State x, int n, bool drop) {
    auto s = make_stepper<State>(h, t);
    for (int i = 0; i < n; ++i) {
        if (drop) s.state_changed();
        s.step(x, 0.05);
    }
    return x;
}

template <class State>
void check_kept_force(Eigen::Index dim) {
    std::uint64_t calls = 0;
    const double length = 1.0;
    const counted_pendulum h{&calls, &length};
    const int n = 200;
    for (const std::string name : {"leapfrog_kdk", "blanes_moan_s6", "ruth_3", "odeint_sb3a_mclachlan"}) {
        CAPTURE(name);
        const table t = method(name);
        const auto ops = t.substeps();
        const bool kept = ops.front().kind == substep::kick && ops.back().kind == substep::kick;
        const bool joined = ops.front().kind == ops.back().kind;
        const State x0 = pendulum_state<State>(dim);
        // The kept force is the force a fresh evaluation gives: bit for bit
        // (where the kicks are not joined across calls).
        const State fresh = step_loop(h, t, x0, n, true), loop = step_loop(h, t, x0, n, false);
        if (!kept || State::dimension == Eigen::Dynamic) CHECK(max_difference(fresh, loop) == 0);
        else CHECK(max_difference(fresh, loop) < 1e-13);
        // steps(n) joins a step's last sub-step with the next step's first. A
        // small state of a kick-first table does so across calls too (it keeps
        // p before its last kick): bit for bit. Otherwise a rounding apart.
        State whole = x0;
        auto s = make_stepper<State>(h, t);
        s.steps(whole, 0.05, n);
        const bool joins_across_calls = kept && State::dimension != Eigen::Dynamic;
        if (joined && !joins_across_calls) CHECK(max_difference(whole, loop) < 1e-13);
        else CHECK(max_difference(whole, loop) == 0);
        // Counted truthfully, and as steps(n) counts: one force per kick, less one per step boundary reused.
        State y = x0;
        auto r = make_stepper<State>(h, t);
        calls = 0;
        for (int i = 0; i < n; ++i) r.step(y, 0.05);
        // A dynamic state's force is tried once, uncounted, for its output size.
        const std::uint64_t trial = State::dimension == Eigen::Dynamic ? 1 : 0;
        CHECK(r.force_evaluations() + trial == calls);
        const std::uint64_t kicks = ops.size() / 2 + (ops.front().kind == substep::kick && joined);
        CHECK(calls - trial == n * kicks - (kept ? n - 1 : 0));
        if (kept) CHECK(r.force_evaluations() == s.force_evaluations());
    }
}
}  // namespace

TEST_CASE("splitting_stepper: a loop of step() reuses the last force, bit for bit what fresh forces give") {
    check_kept_force<phase_space<double, 2>>(2);
    check_kept_force<phase_space<double>>(5);
}

TEST_CASE("splitting_stepper: a state changed between calls gives what a fresh stepper gives, bit for bit") {
    using State = phase_space<double>;
    std::uint64_t calls = 0;
    double length = 1.0;
    const counted_pendulum h{&calls, &length};
    State a = pendulum_state<State>(4);
    auto s = make_stepper<State>(h, method("leapfrog_kdk"));
    s.steps(a, 0.05, 10);
    const auto fresh_step = [&](State x) {
        auto f = make_stepper<State>(h, method("leapfrog_kdk"));
        f.step(x, 0.05);
        return x;
    };
    // One bit of one component of q: a fresh force.
    a.q[3] = std::nextafter(a.q[3], 1.0);
    State expected = fresh_step(a);
    calls = 0;
    s.step(a, 0.05);
    CHECK(calls == 2);
    CHECK(max_difference(a, expected) == 0);
    // +0 and -0 are equal numbers but different bits: a fresh force.
    a.q[1] = 0.0;
    s.step(a, 0.05);
    a.q[1] = -0.0;
    expected = fresh_step(a);
    calls = 0;
    s.step(a, 0.05);
    CHECK(calls == 2);
    CHECK(max_difference(a, expected) == 0);
    // p alone changed (a thermostat, a rescaling): the force of q still holds.
    a.p *= 0.5;
    expected = fresh_step(a);
    calls = 0;
    s.step(a, 0.05);
    CHECK(calls == 1);
    CHECK(max_difference(a, expected) == 0);
    // The same on a small fixed-size state, which joins the kicks across calls.
    using Small = phase_space<double, 2>;
    Small z = pendulum_state<Small>(2);
    auto sz = make_stepper<Small>(h, method("leapfrog_kdk"));
    sz.steps(z, 0.05, 10);
    z.p[1] *= 0.5;
    Small z_expected = z;
    make_stepper<Small>(h, method("leapfrog_kdk")).step(z_expected, 0.05);
    sz.step(z, 0.05);
    CHECK(max_difference(z, z_expected) == 0);
    z.q[0] = std::nextafter(z.q[0], 0.0);
    z_expected = z;
    make_stepper<Small>(h, method("leapfrog_kdk")).step(z_expected, 0.05);
    sz.step(z, 0.05);
    CHECK(max_difference(z, z_expected) == 0);
    // Handed back with another dt (here -dt: retracing the step), no kick is
    // joined: the same as a stepper that keeps nothing.
    Small back = z, back_expected = z;
    sz.step(back, -0.05);
    auto plain = make_stepper<Small>(h, method("leapfrog_kdk"));
    plain.step(back_expected, -0.05);
    CHECK(max_difference(back, back_expected) == 0);
    // Another state of another size, then the first again: fresh forces both times.
    State b = pendulum_state<State>(3), b_expected = fresh_step(b);
    s.step(b, 0.05);
    CHECK(max_difference(b, b_expected) == 0);
    expected = fresh_step(a);
    calls = 0;
    s.step(a, 0.05);
    CHECK(calls == 3);  // and the uncounted trial of the force's size, for the size is new again
    CHECK(max_difference(a, expected) == 0);
    // The force changed while q did not: state_changed() says so.
    length = 2.0;
    expected = fresh_step(a);
    s.state_changed();
    s.step(a, 0.05);
    CHECK(max_difference(a, expected) == 0);
    // A non-finite p handed back is refused before the state is touched.
    State c = a;
    c.p[2] = INFINITY;
    CHECK_THROWS_WITH_AS(s.step(c, 0.05), doctest::Contains("component 2"), invalid_argument);
    CHECK(c.q[2] == a.q[2]);
    // A step() that produced a non-finite q keeps no force; the next call refuses the state.
    splitting_stepper<hamiltonians::harmonic_oscillator, phase_space<double, 1>> ho({}, method("leapfrog_kdk"));
    phase_space<double, 1> big(Eigen::Matrix<double, 1, 1>(1e300), Eigen::Matrix<double, 1, 1>(1e300));
    ho.step(big, 1e10);
    CHECK(!is_finite(big));
    CHECK_THROWS_WITH_AS(ho.step(big, 0.1), doctest::Contains("not finite"), invalid_argument);
}

TEST_CASE("splitting_stepper: a user table runs and a zero or non-finite dt is refused") {
    using State = phase_space<double, 1>;
    splitting_stepper<hamiltonians::harmonic_oscillator, State> s({}, table("mine", {0.5L, 0.5L}, {1, 0}));
    State x(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.0));
    CHECK_THROWS_AS(s.step(x, 0.0), invalid_argument);
    CHECK_THROWS_AS(s.step(x, std::nan("")), invalid_argument);
    CHECK(x.q[0] == 1.0);  // nothing moved
    // Leapfrog on the oscillator: exact closed form of one step, q1 = q0 (1 - h^2/2) + h p0.
    s.step(x, 0.1);
    CHECK(x.q[0] == doctest::Approx(1 - 0.005).epsilon(1e-15));
}

TEST_CASE("splitting_stepper: compensated summation keeps roundoff from growing with the step count") {
    // Float leapfrog on the oscillator, compared with the same method run in
    // double (compensated): the difference is float roundoff alone. Plain
    // summation loses ~eps/2 per update, a random walk growing like sqrt(n);
    // Kahan summation carries each update's rounding error into the next, so
    // the error stays at a few ulps whatever n (Kahan 1965).
    const hamiltonians::harmonic_oscillator h;
    const double dt = 1.0 / 8192;  // exact in float, so both runs use the same step
    const double eps = std::numeric_limits<float>::epsilon();
    auto roundoff = [&](bool compensated, int n) {
        phase_space<double, 1> ref(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.0));
        splitting_stepper<hamiltonians::harmonic_oscillator, phase_space<double, 1>> exact_ish(h, method("leapfrog_kdk"), {true});
        exact_ish.steps(ref, dt, n);
        using F = phase_space<float, 1>;
        splitting_stepper<hamiltonians::harmonic_oscillator, F> s(h, method("leapfrog_kdk"), {compensated});
        F x(Eigen::Matrix<float, 1, 1>(1.0f), Eigen::Matrix<float, 1, 1>(0.0f));
        s.steps(x, float(dt), n);
        return std::max(std::fabs(double(x.q[0]) - ref.q[0]), std::fabs(double(x.p[0]) - ref.p[0]));
    };
    const int short_run = 1 << 16, long_run = 1 << 22;
    const double plain_short = roundoff(false, short_run), plain_long = roundoff(false, long_run);
    const double kahan_short = roundoff(true, short_run), kahan_long = roundoff(true, long_run);
    CAPTURE(plain_short);
    CAPTURE(plain_long);
    CAPTURE(kahan_short);
    CAPTURE(kahan_long);
    CHECK(kahan_short <= 2 * eps);
    CHECK(kahan_long <= 2 * eps);
    CHECK(plain_short >= 10 * eps);   // a random walk of ~sqrt(n) half-ulps
    CHECK(plain_long >= 20 * eps);
    CHECK(100 * kahan_long < plain_long);
}

TEST_CASE("splitting_stepper: the FPU-beta chain conserves energy with a 4th-order table") {
    Eigen::VectorXd q(32), p(32);
    for (int i = 0; i < 32; ++i) {
        q[i] = 0.1 * std::sin(3.14159265358979 * (i + 1) / 33);
        p[i] = 0;
    }
    const hamiltonians::fpu_beta h{1.0};
    phase_space<double> x(q, p);
    const double e0 = energy(h, x);
    splitting_stepper<hamiltonians::fpu_beta, phase_space<double>> s(h, method("forest_ruth_4"));
    double worst = 0;
    for (int i = 0; i < 100; ++i) {
        s.steps(x, 0.05, 10);
        worst = std::max(worst, std::fabs(energy(h, x) - e0) / e0);
    }
    CHECK(worst < 1e-6);
}

namespace {
// A user's Hamiltonian whose force returns three components whatever the state.
struct wrong_size_force {
    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> auto potential(const V& q) const { return q.squaredNorm() / 2; }
    template <class V> void force(const V& q, V& f) const { f = -V::Constant(3, q[0]); }
};
}  // namespace

TEST_CASE("splitting_stepper: sizes and finiteness are checked before the state is touched") {
    using Dynamic = phase_space<double>;
    // Henon-Heiles declares dimension 2: a 1-D state is refused before its force reads q[1].
    splitting_stepper<hamiltonians::henon_heiles, Dynamic> hh({}, method("leapfrog_kdk"));
    Dynamic one(Eigen::VectorXd::Constant(1, 0.1), Eigen::VectorXd::Constant(1, 0.2));
    CHECK_THROWS_WITH_AS(hh.steps(one, 0.1, 10),
                         doctest::Contains("state has dimension 1 but the Hamiltonian is written for dimension 2"),
                         invalid_argument);
    CHECK(one.q[0] == 0.1);
    // A force of the wrong size is caught before the first step.
    splitting_stepper<wrong_size_force, Dynamic> bad({}, method("forest_ruth_4"));
    Dynamic two(Eigen::VectorXd::Constant(2, 0.5), Eigen::VectorXd::Constant(2, 0.0));
    CHECK_THROWS_WITH_AS(bad.steps(two, 0.1, 10),
                         doctest::Contains("force returned 3 components for a state of dimension 2"), invalid_argument);
    CHECK_THROWS_AS(bad.step(two, 0.1), invalid_argument);  // and again on the next call
    CHECK(two.q[0] == 0.5);
    // A non-finite state is refused by step() and steps(), whatever the size.
    splitting_stepper<hamiltonians::harmonic_oscillator, phase_space<double, 1>> ho({}, method("leapfrog_kdk"));
    phase_space<double, 1> nan_state(Eigen::Matrix<double, 1, 1>(NAN), Eigen::Matrix<double, 1, 1>(0.0));
    CHECK_THROWS_WITH_AS(ho.step(nan_state, 0.1), doctest::Contains("not finite"), invalid_argument);
    Dynamic inf_p(Eigen::VectorXd::Constant(2, 0.0), Eigen::VectorXd::Constant(2, INFINITY));
    splitting_stepper<hamiltonians::harmonic_oscillator, Dynamic> hod({}, method("leapfrog_kdk"));
    CHECK_THROWS_WITH_AS(hod.steps(inf_p, 0.1, 3), doctest::Contains("component 0"), invalid_argument);
    // The checks cost no force evaluation that is counted.
    Dynamic fine(Eigen::VectorXd::Constant(2, 0.1), Eigen::VectorXd::Constant(2, 0.0));
    hh.steps(fine, 0.1, 10);
    CHECK(hh.force_evaluations() == 11);
}

namespace {
// Written for doubles only: nothing to differentiate a force-gradient kick with.
struct double_only_oscillator {
    double kinetic(const Eigen::Vector2d& p) const { return p.squaredNorm() / 2; }
    double potential(const Eigen::Vector2d& q) const { return q.squaredNorm() / 2; }
    void force(const Eigen::Vector2d& q, Eigen::Vector2d& f) const { f = -q; }
};
}  // namespace

TEST_CASE("splitting_stepper: force-gradient tables, counted, chunked bit for bit, refused without a derivative") {
    using State = phase_space<double>;
    const table& chin = force_gradient_method("chin_4a");
    const int n = 64;
    State a(n);
    for (int i = 0; i < n; ++i) a.q[i] = 0.3 * std::sin(0.7 * i + 0.2), a.p[i] = 0.1 * std::cos(1.3 * i);
    State b = a;
    auto whole = make_stepper<State>(hamiltonians::fpu_beta{1.0}, chin);
    whole.steps(a, 0.05, 300);
    // A force per kick with the last one reused across steps; one derivative per step.
    CHECK(whole.force_evaluations() == 2 * 300 + 1);
    CHECK(whole.force_derivative_evaluations() == 300);
    auto chunked = make_stepper<State>(hamiltonians::fpu_beta{1.0}, chin);
    chunked.steps(b, 0.05, 100);
    chunked.resume_steps(b, 0.05, 200);
    CHECK(max_difference(a, b) == 0);
    CHECK(chunked.force_evaluations() == whole.force_evaluations());
    // Fourth order in the energy on the chain: dt halved, the error / 16.
    const auto energy_error = [&](double dt) {
        State x(n);
        for (int i = 0; i < n; ++i) x.q[i] = 0.3 * std::sin(0.7 * i + 0.2), x.p[i] = 0.1 * std::cos(1.3 * i);
        auto s = make_stepper<State>(hamiltonians::fpu_beta{1.0}, chin);
        const double e0 = energy(s.hamiltonian(), x);
        double worst = 0;
        for (int k = 0; k < 20; ++k) {
            s.steps(x, dt, std::size_t(std::lround(0.5 / dt)));
            worst = std::max(worst, std::fabs(energy(s.hamiltonian(), x) - e0));
        }
        return worst;
    };
    const double slope = std::log2(energy_error(0.1) / energy_error(0.05));
    CAPTURE(slope);
    CHECK(std::fabs(slope - 4) <= 0.3);
    // Compensated summation runs the same method: a rounding apart.
    State c(n);
    for (int i = 0; i < n; ++i) c.q[i] = 0.3 * std::sin(0.7 * i + 0.2), c.p[i] = 0.1 * std::cos(1.3 * i);
    auto compensated = make_stepper<State>(hamiltonians::fpu_beta{1.0}, chin, stepper_options{.compensated = true});
    compensated.steps(c, 0.05, 300);
    CHECK(max_difference(a, c) < 1e-12);
    // No derivative to be had: refused at construction, naming the table.
    using S2 = phase_space<double, 2>;
    CHECK_THROWS_WITH_AS((splitting_stepper<double_only_oscillator, S2>({}, chin)),
                         doctest::Contains("table 'chin_4a' has force-gradient kicks"), invalid_argument);
    CHECK_NOTHROW((splitting_stepper<double_only_oscillator, S2>({}, method("leapfrog_kdk"))));
}

TEST_CASE("splitting_stepper: a force-gradient table's stability interval is where the stepper's oscillator turns unstable") {
    // The table computes the interval from its coefficients; the stepper runs the
    // same kicks with J_F u from dual numbers. The one-step matrix of the
    // oscillator (omega = 1) from the stepper, just inside and just outside.
    const table& chin = force_gradient_method("chin_4a");
    const double h = chin.stability_interval();
    CHECK(h > 2.0);  // beyond the leapfrog's
    using State = phase_space<double, 1>;
    const auto trace = [&](double dt) {
        auto s = make_stepper<State>(hamiltonians::harmonic_oscillator{}, chin);
        State e1(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.0));
        State e2(Eigen::Matrix<double, 1, 1>(0.0), Eigen::Matrix<double, 1, 1>(1.0));
        s.step(e1, dt);
        s.step(e2, dt);
        return e1.q[0] + e2.p[0];
    };
    CHECK(std::fabs(trace(0.999 * h)) < 2);
    CHECK(std::fabs(trace(1.001 * h)) > 2);
}

}  // namespace test_core_test_splitting_stepper

namespace test_core_test_splitting_stepper_kinetic {
using namespace sympl;
using State = phase_space<double>;

// A chain of unequal masses whose T and V are generic code only.
struct generic_chain {
    Eigen::VectorXd mass;
    template <class V> auto kinetic(const V& p) const {
        using S = typename V::Scalar;
        S t(0);
        for (Eigen::Index i = 0; i < p.size(); ++i) t += p[i] * p[i] / (2 * mass[i]);
        return t;
    }
    template <class V> auto potential(const V& q) const { return hamiltonians::fpu_beta{0.5}.potential(q); }
};
// The same chain with its velocity p / m written by hand.
struct analytic_chain : generic_chain {
    void velocity(const Eigen::VectorXd& p, Eigen::VectorXd& v) const { v = p.cwiseQuotient(mass); }
};

TEST_CASE("splitting_stepper: a generic quadratic T is recognised and drifts as M^-1 p") {
    const Eigen::Index n = 200;
    Eigen::VectorXd mass(n), q(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        mass[i] = 1.0 + 0.5 * double(i % 3);
        q[i] = 0.3 * std::sin(0.2 * double(i));
    }
    const Eigen::VectorXd p0 = Eigen::VectorXd::Zero(n);
    State generic_x(q, p0), analytic_x = generic_x;
    auto generic = make_stepper<State>(generic_chain{mass}, method("blanes_moan_s6"));
    auto analytic = make_stepper<State>(analytic_chain{{mass}}, method("blanes_moan_s6"));
    CHECK(generic.kinetic_energy_form() == quadratic_kinetic<Eigen::VectorXd>::form::unknown);
    generic.steps(generic_x, 0.05, 2000);
    analytic.steps(analytic_x, 0.05, 2000);
    CHECK(generic.kinetic_energy_form() == quadratic_kinetic<Eigen::VectorXd>::form::diagonal);
    CHECK(analytic.kinetic_energy_form() == quadratic_kinetic<Eigen::VectorXd>::form::analytic);
    // The inverse masses found agree with 1/m to rounding, so the runs differ
    // by rounding only, grown over 2000 steps of a nonlinear chain.
    CHECK((generic_x.q - analytic_x.q).cwiseAbs().maxCoeff() <= 1e-11);
    CHECK((generic_x.p - analytic_x.p).cwiseAbs().maxCoeff() <= 1e-11);
}

TEST_CASE("splitting_stepper: a T that is not quadratic keeps its gradient, and its order") {
    // Relativistic T = sqrt(1 + |p|^2) on a pendulum chain: dT/dp by automatic differentiation.
    const auto h = make_hamiltonian([](const auto& p) { using std::sqrt; return sqrt(1.0 + p.squaredNorm()); },
                                    [](const auto& q) { return double(q.size()) - q.array().cos().sum(); });
    State x0(Eigen::VectorXd::Constant(12, 0.4), Eigen::VectorXd::Constant(12, 0.1));
    auto run = [&](double dt) {
        State x = x0;
        auto s = make_stepper<State>(h, method("forest_ruth_4"));
        s.steps(x, dt, std::size_t(std::lround(2.0 / dt)));
        CHECK(s.kinetic_energy_form() == quadratic_kinetic<Eigen::VectorXd>::form::not_quadratic);
        return x;
    };
    const State a = run(0.02), b = run(0.01), c = run(0.005);
    const double slope = std::log2((a.q - b.q).norm() / (b.q - c.q).norm());
    CHECK(slope == doctest::Approx(4).epsilon(0.15 / 4));
}
}  // namespace test_core_test_splitting_stepper_kinetic
