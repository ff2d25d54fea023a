// The one controlled driver: any error-estimating stepper (here a Heun-Euler
// pair written in the test, as a new controlled method would be), the
// controller's options checked with the value named, the underflow error.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <sympl/drivers/controlled.hpp>
#include <sympl/methods/adaptive.hpp>
#include <sympl/methods/classic_steppers.hpp>
#include <sympl/methods/rkn_pairs.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/kepler.hpp>

namespace test_drivers_test_controlled {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using S1 = phase_space<double, 1>;

// Heun's method (order 2) with Euler's step as the embedded one: the
// difference of the two, h/2 (f(y1) - f(y0)), estimates Euler's local error,
// O(h^2). On q' = p, p' = -q; the run goes on with Heun (local extrapolation).
struct heun_euler {
    using state_type = S1;
    using scalar = double;
    static constexpr int error_order = 2;
    S1 trial{1};
    std::uint64_t forces = 0;

    double attempt(const S1& x, double, double h, const control_options& o) {
        const double q1 = x.q[0] + h * x.p[0], p1 = x.p[0] - h * x.q[0];  // Euler
        ++forces;
        trial.q[0] = x.q[0] + h / 2 * (x.p[0] + p1);
        trial.p[0] = x.p[0] - h / 2 * (x.q[0] + q1);
        const double eq = trial.q[0] - q1, ep = trial.p[0] - p1;
        const double sq = o.absolute_tolerance + o.relative_tolerance * std::max(std::fabs(x.q[0]), std::fabs(trial.q[0]));
        const double sp = o.absolute_tolerance + o.relative_tolerance * std::max(std::fabs(x.p[0]), std::fabs(trial.p[0]));
        return std::sqrt((eq / sq * eq / sq + ep / sp * ep / sp) / 2);
    }
    void accept(S1& x) { std::swap(x, trial); }
    std::uint64_t force_evaluations() const { return forces; }
};
static_assert(error_estimating_stepper<heun_euler>);
}  // namespace

TEST_CASE("controlled: a stepper written outside the library runs under the one driver and meets its tolerance") {
    heun_euler s;
    S1 x(1);
    x.q[0] = 1;
    control_options o;
    o.absolute_tolerance = 1e-8;
    o.relative_tolerance = 0;
    const double t_end = 2 * M_PI;
    std::size_t observed = 0;
    const control_summary r = integrate_controlled(s, x, 0.0, t_end, o, [&](const S1&, double) { ++observed; });
    CHECK(r.t == t_end);
    CHECK(observed == r.accepted + 1);
    CHECK(r.largest_error <= 1);
    CHECK(r.force_evaluations == r.accepted + r.rejected);
    // The oscillator's flow is a rotation: local errors add up without growing,
    // so the global error is at most the sum of the accepted steps' errors.
    // Heun's local error is O(h^3), below the estimate (Euler's, O(h^2)) that
    // is held to sqrt(2) * tolerance in the Euclidean norm.
    const double error = std::hypot(x.q[0] - std::cos(t_end), x.p[0] + std::sin(t_end));
    MESSAGE("Heun-Euler, tolerance 1e-8: ", r.accepted, " steps, ", r.rejected, " rejected, error ", error);
    CHECK(error <= double(r.accepted) * std::sqrt(2.0) * o.absolute_tolerance);
}

TEST_CASE("controlled: the stepper's own defaults when no options are given") {
    using K = phase_space<double, 2>;
    auto er = make_classic<euler_richardson, K>(hamiltonians::kepler{});
    const control_options d = default_control_of<richardson_adaptive<decltype(er)>>();
    CHECK(d.absolute_tolerance == 1e-6);
    CHECK(d.relative_tolerance == 0);
    CHECK(d.beta == 0);
    auto pair = make_rkn_stepper<dprkn8, K>(hamiltonians::kepler{});
    CHECK(default_control_of<decltype(pair)>().absolute_tolerance == control_options{}.absolute_tolerance);
    K x = hamiltonians::kepler::initial_state(0.5);
    const control_summary r = integrate_controlled(richardson_adaptive(er), x, 0.0, 1.0);
    CHECK(r.largest_error <= 1);
}

TEST_CASE("controlled: bad options name the value, and an unreachable tolerance stops with a step size underflow") {
    heun_euler s;
    S1 x(1);
    x.q[0] = 1;
    const auto message = [&](control_options o, double t0 = 0, double t_end = 1) {
        try {
            integrate_controlled(s, x, t0, t_end, o);
        } catch (const invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no invalid_argument");
    };
    control_options o;
    o.absolute_tolerance = -1;
    CHECK(message(o).find("absolute_tolerance = -1") != std::string::npos);
    o = {};
    o.safety = 1.5;
    CHECK(message(o).find("safety = 1.5") != std::string::npos);
    o = {};
    o.min_factor = 1;
    CHECK(message(o).find("min_factor = 1;") != std::string::npos);
    o = {};
    o.dt_min = 1;
    o.dt_max = 0.5;
    CHECK(message(o).find("dt_min = 1,") != std::string::npos);
    CHECK(message({}, 1, 1).find("t_end = 1 with t0 = 1; expected finite times with t_end > t0") != std::string::npos);

    o = {};
    o.absolute_tolerance = 1e-30;
    o.relative_tolerance = 0;
    o.dt_min = 1e-6;
    const S1 x0 = x;
    try {
        integrate_controlled(s, x, 0.0, 1.0, o);
        FAIL("expected integration_error");
    } catch (const integration_error& e) {
        CHECK(std::string(e.what()).find("integrate_controlled: step size underflow at t = 0") != std::string::npos);
        CHECK(max_difference(x, x0) == 0);
    }
}

}  // namespace test_drivers_test_controlled
