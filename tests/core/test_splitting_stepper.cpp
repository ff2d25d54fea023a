#include <doctest/doctest.h>

#include <cmath>
#include <limits>

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
    // step() never trusts a force from an earlier call.
    lf.reset_counters();
    for (int i = 0; i < 10; ++i) lf.step(x, 0.1);
    CHECK(lf.force_evaluations() == 20);
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
// The table walked sub-step by sub-step, n times, a fresh force at every kick:
// the definition the stepper's loop must reproduce.
template <class H, class State>
void walk(const H& h, const table& t, State& x, double dt, int n, std::uint64_t& forces) {
    typename State::vector f(x.q.size()), v(x.q.size());
    for (int s = 0; s < n; ++s)
        for (const substep& o : t.substeps()) {
            const double w = double(o.weight) * dt;
            if (o.kind == substep::kick) {
                force(h, x.q, f);
                ++forces;
                x.p += w * f;
            } else {
                velocity(h, x.p, v);
                x.q += w * v;
            }
        }
}
}  // namespace

namespace {
// steps(n) and resume_steps against the walk, for one state type.
template <class State>
void check_against_walk(const char* name) {
    const hamiltonians::henon_heiles h;
    const table t = method(name);
    const auto ops = t.substeps();
    const bool joined = ops.front().kind == ops.back().kind;
    const auto start = hamiltonians::henon_heiles::initial_state(0.125, 0.1, 0.0);
    State a(start.q, start.p), b = a;
    auto s = make_stepper<State>(h, t);
    std::uint64_t walked = 0;
    const int n = 500;
    s.steps(a, 0.05, n);
    walk(h, t, b, 0.05, n, walked);
    const double gap = max_difference(a, b);
    if (!joined) CHECK(gap == 0);
    else CHECK(gap < 1e-13);
    // A force per kick, less one per step boundary when a kick ends the step and starts the next.
    const bool reuse = ops.back().kind == substep::kick && ops.front().kind == substep::kick;
    CHECK(s.force_evaluations() == walked - (reuse ? n - 1 : 0));
    // In chunks with resume_steps: the same counts; bit for bit where nothing is joined.
    State c(start.q, start.p);
    auto r = make_stepper<State>(h, t);
    r.steps(c, 0.05, 1);
    r.resume_steps(c, 0.05, 199);
    r.resume_steps(c, 0.05, 300);
    CHECK(r.force_evaluations() == s.force_evaluations());
    if (!joined) CHECK(max_difference(c, a) == 0);
    else CHECK(max_difference(c, a) < 1e-13);
}
}  // namespace

TEST_CASE("splitting_stepper: the loop runs the table's sub-steps in order, the last force reused, ends joined") {
    // ruth_3 and mclachlan_atela_4 start and end with different kinds: nothing
    // is joined, so steps(n) is the walk bit for bit. leapfrog_kdk and
    // blanes_moan_s6 end with the kind they start with: one sub-step joined per
    // step boundary, a rounding apart. Kick-first and drift-first tables both,
    // on a small fixed-size state (run as drift-kick pairs) and a dynamic one
    // (kick-drift pairs): each shape meets a body it has to rotate.
    for (const char* name : {"ruth_3", "mclachlan_atela_4", "leapfrog_kdk", "blanes_moan_s6", "odeint_sb3a_mclachlan"}) {
        CAPTURE(name);
        check_against_walk<phase_space<double, 2>>(name);
        check_against_walk<phase_space<double>>(name);
    }
}

namespace {
// FPU-beta with velocity(p, v) writing v = p: the drift is a pass of its own.
struct fpu_velocity_into : hamiltonians::fpu_beta {
    template <class V> void velocity(const V& p, V& v) const { v = p; }
};
}  // namespace

TEST_CASE("splitting_stepper: a kick and its drift fused in one pass (velocity(p) = p) give the numbers of two passes") {
    using State = phase_space<double>;
    const int n = 37;
    State a(n);
    for (int i = 0; i < n; ++i) a.q[i] = 0.3 * std::sin(0.7 * i + 0.2), a.p[i] = 0.1 * std::cos(1.3 * i);
    State b = a;
    for (const char* name : {"leapfrog_kdk", "odeint_sb3a_mclachlan", "blanes_moan_s10", "ruth_3"}) {
        CAPTURE(name);
        auto fused = make_stepper<State>(hamiltonians::fpu_beta{1.0}, method(name));
        auto separate = make_stepper<State>(fpu_velocity_into{{1.0}}, method(name));
        fused.steps(a, 0.02, 300);
        separate.steps(b, 0.02, 300);
        CHECK(max_difference(a, b) == 0);
    }
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
