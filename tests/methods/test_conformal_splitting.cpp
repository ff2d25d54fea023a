// Damped and driven systems by splitting tables (methods/conformal_splitting.hpp):
// orders measured on a nonlinear problem, conformal symplecticity measured
// against Odeint RK4, bad input named.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <new>
#include <string>

#include <Eigen/LU>
#include <boost/numeric/odeint.hpp>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>
#include <sympl/hamiltonians/damped_driven_oscillator.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

namespace test_methods_test_conformal_splitting {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using V1 = Eigen::Matrix<double, 1, 1>;
using State = phase_space<double, 1>;
using Q1 = Eigen::Matrix<quad, 1, 1>;
using QState = phase_space<quad, 1>;

constexpr double gamma_ = 0.3, drive_amplitude = 0.5, drive_frequency = 0.7;

// The damped, driven pendulum q'' = -sin q - gamma q' + A cos(Omega t): nonlinear, so a kick/drift swap or a
// kick that sees the wrong time shows in the measured order.
struct cosine_drive {
    template <class T> T operator()(T t) const {
        using std::cos;
        return T(drive_amplitude) * cos(T(drive_frequency) * t);
    }
};
auto damped_pendulum() { return damped_driven_by(hamiltonians::pendulum{}, gamma_, cosine_drive{}); }

// The same with T = sqrt(1 + p^2) (relativistic), undamped: any T may be driven.
struct relativistic_pendulum {
    template <class V> auto kinetic(const V& p) const {
        using std::sqrt;
        return sqrt(1 + p.squaredNorm());
    }
    template <class V> auto potential(const V& q) const {
        using std::cos;
        return 1 - cos(q[0]);
    }
    template <class V> void velocity(const V& p, V& v) const {
        using std::sqrt;
        v = p / sqrt(1 + p.squaredNorm());
    }
    template <class V> void force(const V& q, V& f) const {
        using std::sin;
        f.resize(1);
        f[0] = -sin(q[0]);
    }
};

// Measured order of `t` on `system` from (1.2, 0.3) over [0, 3] in 113-bit precision.
template <class System>
order_measurement order_of(const System& system, const table& t) {
    auto stepper = make_conformal_stepper<QState>(system, t);
    const QState x0(Q1(quad(1.2)), Q1(quad(0.3)));
    return measure_order(
        [&](std::size_t n) {
            QState x = x0;
            const quad dt = quad(3) / quad(n);
            for (std::size_t i = 0; i < n; ++i) stepper.step(x, quad(i) * dt, dt);
            return x;
        },
        3.0);
}
}  // namespace

TEST_CASE("conformal_splitting: leapfrog, Forest-Ruth, Blanes-Moan keep orders 2, 4, 4, 6 with damping and driving") {
    // blanes_moan_s6 is Blanes & Moan's 6-stage method of order 4; their SRKN_11^b is of order 6.
    for (const char* name : {"leapfrog_kdk", "forest_ruth_4", "blanes_moan_s6", "blanes_moan_srkn11b"}) {
        CAPTURE(name);
        const order_measurement m = order_of(damped_pendulum(), method(name));
        CAPTURE(m.order);
        CHECK(std::fabs(m.order - method(name).order()) <= 0.15);
    }
}

TEST_CASE("conformal_splitting: every catalog table keeps its order on the damped, driven pendulum") {
    // The drift stays linear in p and the kick independent of p, so
    // [B,[B,[B,A]]] = 0 and the Runge-Kutta-Nystrom tables keep theirs too.
    for (const table& t : catalog()) {
        if (t.order() > 6) continue;  // orders 8 and 10 need spans the 113-bit floor cuts short; see test_catalog
        CAPTURE(t.name());
        const order_measurement m = order_of(damped_pendulum(), t);
        CAPTURE(m.order);
        CHECK(std::fabs(m.order - t.order()) <= 0.15);
    }
}

TEST_CASE("conformal_splitting: undamped but driven, a table keeps its general order for non-quadratic T") {
    const auto driven = damped_driven_by(relativistic_pendulum{}, 0.0, cosine_drive{});
    for (const auto& entry : {std::pair{"leapfrog_kdk", 2}, {"forest_ruth_4", 4}, {"yoshida_6", 6}}) {
        const char* name = entry.first;  // not a structured binding: CAPTURE takes none before clang 16
        const int order = entry.second;
        CAPTURE(name);
        const order_measurement m = order_of(driven, method(name));
        CAPTURE(m.order);
        CHECK(std::fabs(m.order - order) <= 0.15);
    }
}

TEST_CASE("conformal_splitting: the damped, driven oscillator against its exact solution") {
    // Newton's form with b = 0.6, m = 2: gamma = b/m = 0.3. Error at t = 10
    // from dt to dt/2 falls by 2^p.
    const hamiltonians::damped_driven_oscillator o{2.0, 1.5, 0.6, 0.5, 0.7};
    const State x0(V1(1.0), V1(0.0));
    const State exact = o.exact(x0, 10.0);
    for (const char* name : {"leapfrog_kdk", "forest_ruth_4", "blanes_moan_s6", "blanes_moan_srkn11b"}) {
        CAPTURE(name);
        const int order = method(name).order();
        auto stepper = make_conformal_stepper<State>(o, method(name));
        const auto error_at = [&](double dt) {
            State x = x0;
            integrate_until(stepper, x, 0.0, 10.0, dt);
            return std::hypot(x.q[0] - exact.q[0], x.p[0] - exact.p[0]);
        };
        const double coarse = error_at(0.2), fine = error_at(0.1);
        CAPTURE(coarse);
        CAPTURE(fine);
        CHECK(std::fabs(std::log2(coarse / fine) - order) <= 0.15);
    }
}

TEST_CASE("conformal_splitting: M^T J M = exp(-gamma t) J at rounding, where Odeint RK4 misses it") {
    // Each kick is a shear and each damped drift scales dq ^ dp by exp(-gamma h): the map is conformal
    // symplectic with factor exp(-gamma n dt), to a few ulps per sub-step.
    const auto system = damped_pendulum();
    const State x0(V1(1.2), V1(0.3));
    const double dt = 0.1;
    const std::size_t n = 500;
    const double factor = std::exp(-gamma_ * dt * double(n));
    const auto flow = [&](auto& x) {
        auto s = make_conformal_stepper<std::decay_t<decltype(x)>>(system, method("blanes_moan_s6"));
        using T = typename std::decay_t<decltype(x)>::scalar;
        for (std::size_t i = 0; i < n; ++i) s.step(x, T(double(i) * dt), T(dt));
    };
    const phase_matrix<double> M = flow_jacobian(flow, x0);
    const phase_matrix<double> J = symplectic_form(1);
    const double defect = (M.transpose() * J * M - factor * J).norm() / M.squaredNorm();
    const double eps = std::numeric_limits<double>::epsilon();
    CAPTURE(defect);
    CHECK(defect <= double(n) * double(method("blanes_moan_s6").substeps().size()) * eps);
    CHECK(std::fabs(M.determinant() - factor) <= double(n) * eps * M.squaredNorm());

    // Odeint's RK4 on the same equations: its determinant is off by its local error, far above rounding.
    namespace odeint = boost::numeric::odeint;
    const auto rk4_flow = [&](auto& x) {
        using T = typename std::decay_t<decltype(x)>::scalar;
        std::array<T, 2> y{x.q[0], x.p[0]};
        const auto rhs = [&](const std::array<T, 2>& s, std::array<T, 2>& d, double t) {
            using std::cos;
            using std::sin;
            d[0] = s[1];
            d[1] = -sin(s[0]) - T(gamma_) * s[1] + T(drive_amplitude) * cos(drive_frequency * t);
        };
        odeint::runge_kutta4<std::array<T, 2>, double, std::array<T, 2>, double> rk4;
        for (std::size_t i = 0; i < n; ++i) rk4.do_step(rhs, y, double(i) * dt, dt);
        x.q[0] = y[0];
        x.p[0] = y[1];
    };
    const phase_matrix<double> R = flow_jacobian(rk4_flow, x0);
    const double rk_defect = (R.transpose() * J * R - factor * J).norm() / R.squaredNorm();
    CAPTURE(rk_defect);
    CHECK(rk_defect > 1000 * std::max(defect, eps));
}

TEST_CASE("conformal_splitting: a carried loop's area contracts by exp(-gamma t), Odeint RK4's does not") {
    // A circle of radius 0.15 around (0.3, 0) of the weakly damped, driven
    // pendulum, 1e4 steps of dt = 0.3 (t = 3000): the area falls by
    // exp(-gamma t) = exp(-0.6); the polygon's resolution bounds the error.
    const double gamma = 2e-4, r = 0.15, dt = 0.3;
    const std::size_t n = 10000;
    const auto system = damped_driven_by(hamiltonians::pendulum{}, gamma, [](double t) { return 0.05 * std::cos(0.7 * t); });
    const double expected = M_PI * r * r * std::exp(-gamma * dt * double(n));
    const auto circle = [&](double s) { return State(V1(0.3 + r * std::cos(2 * M_PI * s)), V1(r * std::sin(2 * M_PI * s))); };
    const auto leapfrog = [&](State& x) {
        auto s = make_conformal_stepper<State>(system, method("leapfrog_kdk"));
        for (std::size_t i = 0; i < n; ++i) s.step(x, double(i) * dt, dt);
    };
    namespace odeint = boost::numeric::odeint;
    const auto rk4 = [&](State& x) {
        std::array<double, 2> y{x.q[0], x.p[0]};
        const auto rhs = [&](const std::array<double, 2>& s, std::array<double, 2>& d, double t) {
            d[0] = s[1];
            d[1] = -std::sin(s[0]) - gamma * s[1] + 0.05 * std::cos(0.7 * t);
        };
        odeint::runge_kutta4<std::array<double, 2>> stepper;
        for (std::size_t i = 0; i < n; ++i) stepper.do_step(rhs, y, double(i) * dt, dt);
        x.q[0] = y[0];
        x.p[0] = y[1];
    };
    loop_options o;
    o.initial_points = 32;
    o.max_gap = 0.02;
    const auto lf = carry_loop(circle, leapfrog, o);
    const auto rk = carry_loop(circle, rk4, o);
    REQUIRE(lf.resolved);
    REQUIRE(rk.resolved);
    const double lf_error = std::fabs(loop_area(lf, 0) - expected), rk_error = std::fabs(loop_area(rk, 0) - expected);
    MESSAGE("damped loop area error: leapfrog ", lf_error, " (resolution ", loop_area_resolution(lf, 0), "), Odeint RK4 ",
            rk_error, " (resolution ", loop_area_resolution(rk, 0), ")");
    CHECK(lf_error <= loop_area_resolution(lf, 0));
    CHECK(rk_error > 3 * loop_area_resolution(rk, 0));
}

TEST_CASE("conformal_splitting: bad input is named") {
    const hamiltonians::pendulum h{};
    CHECK_THROWS_WITH_AS(make_conformal_stepper<State>(damped_driven_by(h, -0.1), method("leapfrog_kdk")),
                         doctest::Contains("gamma = -0.1"), invalid_argument);
    CHECK_THROWS_WITH_AS(make_conformal_stepper<State>(damped_driven_by(h, 0.1), force_gradient_method("chin_4a")),
                         doctest::Contains("force-gradient"), invalid_argument);
    State x(V1(1.0), V1(0.0));
    auto nan_drive = make_conformal_stepper<State>(damped_driven_by(h, 0.1, [](double t) { return t > 0.5 ? NAN : 0.0; }),
                                                   method("leapfrog_kdk"));
    CHECK_THROWS_WITH_AS(integrate_until(nan_drive, x, 0.0, 1.0, 0.1), doctest::Contains("is nan"), invalid_argument);
    auto relativistic = make_conformal_stepper<State>(damped_driven_by(relativistic_pendulum{}, 0.1), method("leapfrog_kdk"));
    State y(V1(1.0), V1(0.0));
    CHECK_THROWS_WITH_AS(relativistic.step(y, 0.0, 0.1), doctest::Contains("linear in p"), invalid_argument);
    auto fine = make_conformal_stepper<State>(damped_driven_by(h, 0.1), method("leapfrog_kdk"));
    CHECK_THROWS_WITH_AS(fine.step(y, 0.0, NAN), doctest::Contains("dt = nan"), invalid_argument);
}

TEST_CASE("conformal_splitting: a harmonic drive by angle addition equals the cosine per kick, to rounding") {
    // The same pendulum driven by harmonic_drive (one cosine and sine per step) and by a lambda (one cosine per
    // kick): the kicks see the same forces up to rounding, so the runs agree to a few ulps per step.
    const harmonic_drive drive{drive_amplitude, drive_frequency, 0.4};
    const auto by_angles = damped_driven_by(hamiltonians::pendulum{}, gamma_, drive);
    const auto by_cosines = damped_driven_by(hamiltonians::pendulum{}, gamma_, [&](double t) { return drive(t); });
    static_assert(harmonically_driven<decltype(by_angles), State::vector>);
    static_assert(!harmonically_driven<decltype(by_cosines), State::vector>);
    const std::size_t n = 1000;
    for (const char* name : {"leapfrog_kdk", "blanes_moan_srkn11b", "forest_ruth_4"}) {
        CAPTURE(name);
        auto a = make_conformal_stepper<State>(by_angles, method(name));
        auto b = make_conformal_stepper<State>(by_cosines, method(name));
        State x(V1(1.2), V1(0.3)), y = x;
        integrate_until(a, x, 0.0, 0.1 * double(n), 0.1);
        integrate_until(b, y, 0.0, 0.1 * double(n), 0.1);
        const double difference = std::hypot(x.q[0] - y.q[0], x.p[0] - y.p[0]);
        CAPTURE(difference);
        CHECK(difference <= double(n) * double(method(name).substeps().size()) * std::numeric_limits<double>::epsilon());
    }
}

TEST_CASE("conformal_splitting: a table that ends and starts with a kick reuses the force across steps") {
    // leapfrog_kdk: one force per step and one to start, when each step starts where the last one ended (t = i dt
    // exactly: dt = 1/4); a state handed in from elsewhere gets a fresh force.
    const hamiltonians::damped_driven_oscillator o{1.0, 1.0, 0.3, 0.5, 0.7};
    auto s = make_conformal_stepper<State>(o, method("leapfrog_kdk"));
    State x(V1(1.0), V1(0.0));
    integrate_until(s, x, 0.0, 100.0, 0.25);
    CHECK(s.force_evaluations() == 401);
    State moved = x;
    moved.q[0] += 1e-3;
    s.step(moved, 100.0, 0.25);
    CHECK(s.force_evaluations() == 403);
    // Reuse changes no bit: the same run one step at a time from fresh steppers (no carried force).
    State y(V1(1.0), V1(0.0));
    for (int i = 0; i < 400; ++i) {
        auto fresh = make_conformal_stepper<State>(o, method("leapfrog_kdk"));
        fresh.step(y, 0.25 * i, 0.25);
    }
    CHECK(y.q[0] == x.q[0]);
    CHECK(y.p[0] == x.p[0]);
}

TEST_CASE("conformal_splitting: a new stepper on a fixed-size state kept no last kick, whatever its bytes held") {
    // The kept kick was marked by its vectors' size, which a fixed-size state
    // has from the start, and its time starts at 0: a stepper built where
    // another had kept a kick at t = 0 reused that force at its first step
    // from t = 0 (the report's damped rows counted one force too few). Built
    // in place in the same bytes, from where the first one stopped, the new
    // one evaluates both kicks of its first step.
    const hamiltonians::damped_driven_oscillator o{1.0, 1.0, 0.3, 0.5, 0.7};
    using stepper = conformal_stepper<hamiltonians::damped_driven_oscillator, State>;
    alignas(stepper) unsigned char bytes[sizeof(stepper)];
    auto* first = new (bytes) stepper(make_conformal_stepper<State>(o, method("leapfrog_kdk")));
    State x(V1(1.0), V1(0.0));
    first->step(x, -0.25, 0.25);  // its last kick at t = 0
    first->~stepper();
    auto* second = new (bytes) stepper(make_conformal_stepper<State>(o, method("leapfrog_kdk")));
    second->step(x, 0.0, 0.25);
    CHECK(second->force_evaluations() == 2);
    second->~stepper();
}

TEST_CASE("conformal: a Hamiltonian reading past the state is refused at the first step") {
    using SX = phase_space<double>;
    auto h = make_hamiltonian([](const auto& p) { return 0.5 * p.squaredNorm(); },
                              [](const auto& q) { return 0.5 * (q[0] * q[0] + q[1] * q[1]); });
    conformal_stepper<decltype(damped_driven_by(h, 0.1)), SX> s(damped_driven_by(h, 0.1), method("leapfrog_kdk"));
    SX x(1);
    CHECK_THROWS_WITH_AS(
        s.step(x, 0.0, 0.1),
        "conformal_stepper: the Hamiltonian's V(q) read q[1] of a state of dimension 1; expected indices 0..0",
        invalid_argument);
    SX y(2);
    CHECK_NOTHROW(s.step(y, 0.0, 0.1));
}

}  // namespace test_methods_test_conformal_splitting
