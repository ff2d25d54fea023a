// Richardson extrapolation (Gould & Tobochnik, eq. 3.68): of a derivative, step by step
// around any fixed-step method, and of whole runs.
#include <doctest/doctest.h>

#include <cmath>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

namespace test_methods_test_richardson {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using State = phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;
const State start(V1(1.2), V1(0.3));
const hamiltonians::pendulum pendulum{};

order_options double_precision() {
    order_options o;
    o.min_steps = 8;
    o.max_steps = std::size_t(1) << 15;
    o.floor = 1e-10;
    return o;
}

template <class Stepper>
State run(Stepper s, std::size_t n, double t_end = 3.0) {
    State x = start;
    const double dt = t_end / double(n);
    for (std::size_t i = 0; i < n; ++i) s.step(x, double(i) * dt, dt);
    return x;
}
}  // namespace

TEST_CASE("richardson: the extrapolated central difference is fourth order (eq. 3.68)") {
    const auto f = [](double t) { return std::sin(t) * std::exp(t / 3); };
    const double t = 0.7, exact = std::cos(t) * std::exp(t / 3) + std::sin(t) * std::exp(t / 3) / 3;
    const double e1 = std::fabs(richardson_derivative(f, t, 0.1) - exact);
    const double e2 = std::fabs(richardson_derivative(f, t, 0.05) - exact);
    const double e3 = std::fabs(richardson_derivative(f, t, 0.025) - exact);
    CHECK(std::fabs(std::log2(e1 / e2) - 4) <= 0.15);
    CHECK(std::fabs(std::log2(e2 / e3) - 4) <= 0.15);
    CHECK_THROWS_AS(richardson_derivative(f, t, 0.0), invalid_argument);
}

TEST_CASE("richardson: step-by-step extrapolation raises the order by one, by two for a symmetric method") {
    const auto order = [&](auto make) {
        return measure_order([&](std::size_t n) { return run(make(), n); }, 3.0, double_precision()).order;
    };
    CHECK(std::fabs(order([] { return richardson_stepper(make_classic<euler, State>(pendulum), 1); }) - 2) <= 0.15);
    CHECK(std::fabs(order([] { return richardson_stepper(make_classic<rk2, State>(pendulum), 2); }) - 3) <= 0.15);
    CHECK(std::fabs(order([] { return richardson_stepper(make_classic<velocity_verlet, State>(pendulum), 2); }) - 4) <= 0.15);
    // Works around a splitting stepper too (step(x, dt), no time).
    CHECK(std::fabs(order([] { return richardson_stepper(make_stepper<State>(pendulum, method("euler_cromer")), 1); }) - 2) <= 0.15);
    CHECK_THROWS_AS(richardson_stepper(make_classic<euler, State>(pendulum), 0), invalid_argument);
}

TEST_CASE("richardson: combining whole runs of a symmetric method gains two orders") {
    // Velocity Verlet's global error expands in even powers of dt.
    const auto vv = [](std::size_t n) { return run(make_classic<velocity_verlet, State>(pendulum), n); };
    const double combined =
        measure_order([&](std::size_t n) { return richardson_combine(vv(n), vv(2 * n), 2); }, 3.0, double_precision()).order;
    CHECK(std::fabs(combined - 4) <= 0.15);
    // Euler's expansion has every power: one order only.
    const auto eu = [](std::size_t n) { return run(make_classic<euler, State>(pendulum), n); };
    const double euler_combined =
        measure_order([&](std::size_t n) { return richardson_combine(eu(n), eu(2 * n), 1); }, 3.0, double_precision()).order;
    CHECK(std::fabs(euler_combined - 2) <= 0.15);
}

}  // namespace test_methods_test_richardson
