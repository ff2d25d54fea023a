// Boost.Odeint interop, both ways: sympl Hamiltonians in Odeint's steppers, and
// sympl steppers in Odeint's integrate functions.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/interop/odeint.hpp>
#include <sympl/methods/extrapolation.hpp>
#include <sympl/methods/time_transformation.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

namespace test_interop_test_odeint {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
namespace odeint = boost::numeric::odeint;

namespace {
using K = phase_space<double, 2>;
const hamiltonians::kepler kepler{};
}  // namespace

TEST_CASE("odeint: a sympl Hamiltonian runs in runge_kutta4, dopri5 (controlled and dense) and fehlberg78") {
    const K x0 = hamiltonians::kepler::initial_state(0.5);
    const K exact = hamiltonians::kepler::exact_state(0.5, 2 * M_PI);
    const auto system = make_odeint_system<2>(kepler);
    using Vec = std::vector<double>;
    {
        Vec y = stacked(x0);
        odeint::integrate_n_steps(odeint::runge_kutta4<Vec>(), system, y, 0.0, 2 * M_PI / 2000, 2000);
        CHECK(max_difference(from_stacked<K>(y), exact) < 1e-7);
    }
    {
        Vec y = stacked(x0);
        odeint::integrate_adaptive(odeint::make_controlled(1e-12, 1e-12, odeint::runge_kutta_dopri5<Vec>()), system, y,
                                   0.0, 2 * M_PI, 0.01);
        CHECK(max_difference(from_stacked<K>(y), exact) < 1e-9);
    }
    {
        Vec y = stacked(x0);
        odeint::integrate_const(odeint::make_dense_output(1e-12, 1e-12, odeint::runge_kutta_dopri5<Vec>()), system, y,
                                0.0, 2 * M_PI, 2 * M_PI / 8);
        CHECK(max_difference(from_stacked<K>(y), exact) < 1e-9);
    }
    {
        Vec y = stacked(x0);
        odeint::integrate_adaptive(odeint::make_controlled(1e-13, 1e-13, odeint::runge_kutta_fehlberg78<Vec>()), system,
                                   y, 0.0, 2 * M_PI, 0.01);
        CHECK(max_difference(from_stacked<K>(y), exact) < 1e-10);
    }
    // A dynamic-size system reads the dimension from the state.
    Vec y = stacked(x0), dydt(4);
    make_odeint_system(kepler)(y, dydt, 0.0);
    CHECK(dydt[0] == 0.0);
    CHECK(dydt[2] == doctest::Approx(-1 / (0.5 * 0.5)));
}

TEST_CASE("odeint: the symplectic pair form drives Odeint's own symplectic steppers") {
    const K x0 = hamiltonians::kepler::initial_state(0.5);
    std::vector<double> q = {x0.q[0], x0.q[1]}, p = {x0.p[0], x0.p[1]};
    auto qp = std::make_pair(std::ref(q), std::ref(p));
    odeint::integrate_n_steps(odeint::symplectic_rkn_sb3a_mclachlan<std::vector<double>>(),
                              odeint_symplectic_system<2>(kepler), qp, 0.0, 2 * M_PI / 1000, 1000);
    // The same table in sympl, converted by role: the same trajectory.
    K x = x0;
    auto s = make_stepper<K>(kepler, method("odeint_sb3a_mclachlan"));
    s.steps(x, 2 * M_PI / 1000, 1000);
    CHECK(std::fabs(q[0] - x.q[0]) < 1e-12);
    CHECK(std::fabs(p[1] - x.p[1]) < 1e-12);
}

TEST_CASE("odeint: sympl steppers run in integrate_const and integrate_n_steps with an Odeint observer") {
    const K x0 = hamiltonians::kepler::initial_state(0.5);
    auto stepper = make_odeint_stepper(make_stepper<K>(kepler, method("blanes_moan_s6")));
    CHECK(stepper.order() == 4);
    K x = x0;
    std::vector<double> times;
    // dt = 1/512 divides t_end = 2 exactly: Odeint's integrate_const stops at the
    // last t0 + k dt <= t_end (with 2 pi / 500 rounding would cost a step).
    const std::size_t steps = odeint::integrate_const(stepper, odeint_stepper_system{}, x, 0.0, 2.0, 1.0 / 512,
                                                      [&](const K&, double t) { times.push_back(t); });
    CHECK(steps == 1024);
    CHECK(times.size() == 1025);
    CHECK(times.back() == 2.0);
    CHECK(max_difference(x, hamiltonians::kepler::exact_state(0.5, 2.0)) < 1e-9);

    // A classic (time-aware) stepper too, and the same trajectory as sympl's own driver.
    odeint_stepper classic(make_classic<rk4, K>(kepler), 4);
    K y = x0, z = x0;
    odeint::integrate_n_steps(classic, odeint_stepper_system{}, y, 0.0, 0.01, 300);
    auto own = make_classic<rk4, K>(kepler);
    integrate_steps(own, z, 0.0, 0.01, 300);
    CHECK(max_difference(y, z) == 0);
}

TEST_CASE("odeint: state conversions check their sizes") {
    CHECK_THROWS_WITH_AS(from_stacked<K>(std::vector<double>(3)), doctest::Contains("3 numbers"), invalid_argument);
    CHECK_THROWS_WITH_AS(from_stacked<K>(std::vector<double>(6)), doctest::Contains("expected q and p stacked, 4 numbers"),
                         invalid_argument);
}

TEST_CASE("odeint: LogH and extrapolated steppers run in Odeint's drivers, in fictitious time") {
    using KX = phase_space<double, 3>;
    const hamiltonians::kepler h{};
    const KX X0 = to_extended(h, hamiltonians::kepler::initial_state(0.9));
    const double ds = 2 * M_PI / 256;  // Odeint's "time" is the fictitious time s
    auto logh_leapfrog = splitting_stepper<logh<hamiltonians::kepler>, KX>({h}, method("blanes_moan_s6"));
    auto bridged = make_odeint_stepper(logh_leapfrog);
    KX X = X0, Y = X0;
    odeint::integrate_n_steps(bridged, odeint_stepper_system{}, X, 0.0, ds, 256);
    for (int i = 0; i < 256; ++i) logh_leapfrog.step(Y, ds);
    CHECK(max_difference(X, Y) == 0);
    // One fictitious period 2 pi / a is one physical period: back at pericentre, t = 2 pi.
    CHECK(physical_time(X) == doctest::Approx(2 * M_PI).epsilon(1e-8));
    CHECK(max_difference(physical_state(X), hamiltonians::kepler::initial_state(0.9)) < 1e-6);

    odeint_stepper extrapolated(extrapolation_stepper(splitting_stepper<logh<hamiltonians::kepler>, KX>(
                                                          {h}, method("leapfrog_dkd")), 4), 8);
    KX Z = X0;
    odeint::integrate_n_steps(extrapolated, odeint_stepper_system{}, Z, 0.0, 2 * M_PI / 32, 32);
    CHECK(physical_time(Z) == doctest::Approx(2 * M_PI).epsilon(1e-8));
    CHECK(max_difference(physical_state(Z), hamiltonians::kepler::initial_state(0.9)) < 1e-6);
}

}  // namespace test_interop_test_odeint
