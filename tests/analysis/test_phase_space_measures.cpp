// Phase-space area and the symplecticity of the numerical flow, measured
// against Boost.Odeint's runge_kutta4 on the same Hamiltonian at the same dt.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include <Eigen/LU>  // determinant()

#include <sympl/sympl.hpp>
#include <sympl/interop/odeint.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/two_particle_spring.hpp>

namespace test_analysis_test_phase_space_measures {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using State = phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;
constexpr double eps = std::numeric_limits<double>::epsilon();

template <class H>
auto table_flow(const H& h, const table& t, double dt, std::size_t n) {
    return [&h, &t, dt, n](auto& x) {
        auto s = make_stepper<std::decay_t<decltype(x)>>(h, t);
        s.steps(x, dt, n);
    };
}

template <template <class, class> class Method, class H>
auto classic_flow(const H& h, double dt, std::size_t n) {
    return [&h, dt, n](auto& x) {
        auto s = make_classic<Method, std::decay_t<decltype(x)>>(h);
        for (std::size_t i = 0; i < n; ++i) s.step(x, double(i) * dt, dt);
    };
}

double relative_defect(const phase_matrix<double>& M) { return symplecticity_defect(M) / M.squaredNorm(); }
}  // namespace

TEST_CASE("phase_space_measures: closed forms of det M on the harmonic oscillator") {
    const hamiltonians::harmonic_oscillator h{};
    const State x0(V1(0.7), V1(-0.2));
    for (const double dt : {0.3, 0.1}) {
        CAPTURE(dt);
        // Explicit Euler: det = 1 + h^2 per step; Euler-Cromer: 1; RK4: 1 - h^6/72 + h^8/576.
        CHECK(flow_jacobian(classic_flow<euler>(h, dt, 1), x0).determinant() == doctest::Approx(1 + dt * dt).epsilon(1e-15));
        CHECK(flow_jacobian(classic_flow<euler>(h, dt, 50), x0).determinant() ==
              doctest::Approx(std::pow(1 + dt * dt, 50)).epsilon(1e-13));
        CHECK(std::fabs(flow_jacobian(classic_flow<euler_cromer>(h, dt, 1), x0).determinant() - 1) <= 2 * eps);
        CHECK(std::fabs(flow_jacobian(table_flow(h, method("euler_cromer"), dt, 1000), x0).determinant() - 1) <= 1e-13);
        const double rk4_det = 1 - std::pow(dt, 6) / 72 + std::pow(dt, 8) / 576;
        CHECK(flow_jacobian(odeint_rk4_flow<1>(h, dt, 1), x0).determinant() - 1 == doctest::Approx(rk4_det - 1).epsilon(1e-6));
        CHECK(flow_jacobian(classic_flow<rk4>(h, dt, 1), x0).determinant() - 1 == doctest::Approx(rk4_det - 1).epsilon(1e-6));
        CHECK(flow_jacobian(odeint_rk4_flow<1>(h, dt, 100), x0).determinant() ==
              doctest::Approx(std::pow(rk4_det, 100)).epsilon(1e-12));
    }
}

TEST_CASE("phase_space_measures: the autodiff Jacobian equals the finite-difference one to 1e-7") {
    const hamiltonians::pendulum pendulum{};
    const State x0(V1(1.2), V1(0.3));
    const auto yoshida = table_flow(pendulum, method("yoshida_6"), 0.1, 100);
    const phase_matrix<double> A = flow_jacobian(yoshida, x0), F = finite_difference_jacobian(yoshida, x0);
    CHECK((A - F).cwiseAbs().maxCoeff() <= 1e-7 * A.cwiseAbs().maxCoeff());

    const hamiltonians::henon_heiles hh{};
    const auto x1 = hamiltonians::henon_heiles::initial_state(1.0 / 8);
    const auto rk = odeint_rk4_flow<2>(hh, 0.05, 200);
    const phase_matrix<double> B = flow_jacobian(rk, x1), G = finite_difference_jacobian(rk, x1);
    CHECK((B - G).cwiseAbs().maxCoeff() <= 1e-7 * B.cwiseAbs().maxCoeff());
}

// Bound: a step is a chain of s shears (kicks and drifts), each exactly
// symplectic; computed in floating point, sub-step k adds to M^T J M - J at
// most a few ulps times ||M_k||^2, and these add. So after n steps
// ||M^T J M - J|| <= c n s eps max_k ||M_k||^2 with c of order 1; on these
// problems ||M_k|| grows with k, and the test takes c = 1 and ||M||^2 at the end.
TEST_CASE("phase_space_measures: every catalog table keeps the symplecticity defect at roundoff, Odeint RK4 does not") {
    const std::size_t n = 10000;
    const auto check_system = [&](const std::string& system, const auto& h, const auto& x0, double dt) {
        CAPTURE(system);
        double leapfrog_defect = 0;
        for (const std::string& name : catalog_names()) {
            CAPTURE(name);
            const table& t = method(name);
            const double d = relative_defect(flow_jacobian(table_flow(h, t, dt, n), x0));
            CHECK(d <= double(n) * double(t.substeps().size()) * eps);
            if (name == "leapfrog_kdk") leapfrog_defect = d;
        }
        constexpr int D = std::decay_t<decltype(x0)>::dimension;
        const phase_matrix<double> short_run = flow_jacobian(odeint_rk4_flow<D>(h, dt, n / 10), x0);
        const phase_matrix<double> long_run = flow_jacobian(odeint_rk4_flow<D>(h, dt, n), x0);
        const double rk_long = relative_defect(long_run);
        MESSAGE(system, ": relative defect after ", n, " steps: leapfrog ", leapfrog_defect, ", Odeint RK4 ", rk_long,
                "; RK4's ||M^T J M - J|| ", symplecticity_defect(short_run), " after ", n / 10, " steps, ",
                symplecticity_defect(long_run), " after ", n);
        CHECK(rk_long > 1000 * std::max(leapfrog_defect, eps));
        CHECK(symplecticity_defect(long_run) > 2 * symplecticity_defect(short_run));  // grows with time
    };
    const State pendulum_start(V1(1.2), V1(0.3));
    check_system("pendulum", hamiltonians::pendulum{}, pendulum_start, 0.1);
    check_system("two-particle spring", hamiltonians::two_particle_spring{},
                 hamiltonians::two_particle_spring::initial_state(), 0.05);
    check_system("Henon-Heiles", hamiltonians::henon_heiles{}, hamiltonians::henon_heiles::initial_state(1.0 / 8), 0.05);
}

TEST_CASE("phase_space_measures: a carried loop keeps its area within the polygon's resolution, RK4's does not") {
    // A circle of radius 0.15 around (0.3, 0) in the pendulum's phase plane,
    // 1e4 steps of dt = 0.3: the loop winds into a filament 30 times longer.
    const hamiltonians::pendulum h{};
    const double r = 0.15, area = M_PI * r * r, dt = 0.3;
    const auto circle = [&](double s) { return State(V1(0.3 + r * std::cos(2 * M_PI * s)), V1(r * std::sin(2 * M_PI * s))); };
    const auto leapfrog = table_flow(h, method("leapfrog_kdk"), dt, 10000);
    const auto rk4 = odeint_rk4_flow<1>(h, dt, 10000);
    double last_resolution = HUGE_VAL, first_rk_error = 0;
    for (const double gap : {0.04, 0.02}) {
        CAPTURE(gap);
        loop_options o;
        o.initial_points = 32;
        o.max_gap = gap;
        const auto lf = carry_loop(circle, leapfrog, o);
        const auto rk = carry_loop(circle, rk4, o);
        REQUIRE(lf.resolved);
        REQUIRE(rk.resolved);
        const double resolution = loop_area_resolution(lf, 0);
        CHECK(std::fabs(loop_area(lf, 0) - area) <= resolution);
        CHECK(resolution < last_resolution / 3);  // shrinks as gap^2
        CHECK(projected_area_sum(lf) == loop_area(lf, 0));  // one degree of freedom: one plane
        last_resolution = resolution;
        const double rk_error = std::fabs(loop_area(rk, 0) - area);
        if (first_rk_error == 0) first_rk_error = rk_error;
        if (gap == 0.02) {
            MESSAGE("loop area error at gap 0.02: leapfrog ", std::fabs(loop_area(lf, 0) - area), ", Odeint RK4 ", rk_error,
                    ", polygon resolution ", resolution);
            CHECK(rk_error > 3 * loop_area_resolution(rk, 0));  // RK4 lost area, not resolution
            CHECK(rk_error > 0.8 * first_rk_error);             // and refining does not recover it
        }
    }
}

TEST_CASE("phase_space_measures: every catalog table preserves a carried loop's area within its resolution") {
    const hamiltonians::pendulum h{};
    const double r = 0.05, area = M_PI * r * r;
    const auto circle = [&](double s) { return State(V1(0.3 + r * std::cos(2 * M_PI * s)), V1(r * std::sin(2 * M_PI * s))); };
    loop_options o;
    o.initial_points = 16;
    o.max_gap = 0.08;
    for (const std::string& name : catalog_names()) {
        CAPTURE(name);
        const auto loop = carry_loop(circle, table_flow(h, method(name), 0.2, 10000), o);
        CHECK(loop.resolved);
        CHECK(std::fabs(loop_area(loop, 0) - area) <= loop_area_resolution(loop, 0));
    }
}

TEST_CASE("phase_space_measures: bad input is named") {
    CHECK_THROWS_WITH_AS(symplecticity_defect(phase_matrix<double>(phase_matrix<double>::Identity(3, 3))), doctest::Contains("3x3"), invalid_argument);
    const auto circle = [](double s) { return State(V1(std::cos(s)), V1(std::sin(s))); };
    CHECK_THROWS_WITH_AS(carry_loop(circle, [](State&) {}, loop_options{}), doctest::Contains("max_gap = 0"), invalid_argument);
}

}  // namespace test_analysis_test_phase_space_measures
