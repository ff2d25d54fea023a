// A tour of the public API, built by the consumer test with CMake's defaults
// (no build type, GNU extensions on): every entry point is called once and
// checked against what theory says, so a link or behaviour problem in an
// installed sympl shows here. Exit code 0 when every check holds.
#include <cmath>
#include <cstdio>
#include <numbers>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>
#include <sympl/hamiltonians/kepler.hpp>

namespace {
int failures = 0;
void expect(bool ok, const char* what, double value) {
    std::printf("%-60s %-4s %.3e\n", what, ok ? "ok" : "FAIL", value);
    failures += ok ? 0 : 1;
}
}  // namespace

int main() {
    using State = sympl::phase_space<double, 1>;
    using V1 = Eigen::Matrix<double, 1, 1>;
    // A pendulum from two lambdas; forces by automatic differentiation.
    auto pendulum = sympl::make_hamiltonian([](const auto& p) { return 0.5 * p.squaredNorm(); },
                                            [](const auto& q) { using std::cos; return 1.0 - cos(q[0]); });

    // A table composed from published ones, its order measured in 113-bit precision.
    const sympl::table leapfrog = sympl::concatenate(sympl::method("euler_cromer"), sympl::method("euler_cromer_dk"));
    const sympl::table fourth = sympl::triple_jump(leapfrog);
    expect(std::fabs(sympl::measure_order(fourth).order - 4) <= 0.15, "triple jump of Euler-Cromer + adjoint: order 4",
           sympl::measure_order(fourth).order);

    // The generic stepper and its driver: energy error bounded, O(dt^4).
    State x(V1(2.0), V1(0.0));
    auto stepper = sympl::make_stepper<State>(pendulum, fourth);
    const double e0 = sympl::energy(pendulum, x);
    double worst = 0;
    sympl::integrate_until(stepper, x, 0.0, 1000.0, 0.05,
                           [&](const State& s, double) { worst = std::max(worst, std::fabs(sympl::energy(pendulum, s) / e0 - 1)); });
    expect(worst < 1e-5, "pendulum, 1000 time units: max relative energy error", worst);

    // Extrapolation of the leapfrog: order 2 + 2(3 - 1) = 6.
    sympl::extrapolation_stepper extrapolated(sympl::make_stepper<State>(pendulum, sympl::method("leapfrog_kdk")), 3);
    expect(extrapolated.order() == 6, "extrapolated leapfrog, 3 columns: order", extrapolated.order());

    // LogH on an eccentric Kepler orbit: lands on t = 2 pi, back at pericentre.
    const sympl::hamiltonians::kepler kepler{};
    using K = sympl::phase_space<double, 2>;
    using KX = sympl::phase_space<double, 3>;
    KX X = sympl::to_extended(kepler, sympl::hamiltonians::kepler::initial_state(0.9));
    sympl::splitting_stepper<sympl::logh<sympl::hamiltonians::kepler>, KX> logh({kepler}, sympl::method("blanes_moan_s6"));
    const double pi = std::numbers::pi;
    sympl::integrate_to_time(logh, X, 2 * pi, 2 * pi / 1000);
    const K back = sympl::physical_state(X);
    const double miss = sympl::max_difference(back, sympl::hamiltonians::kepler::initial_state(0.9));
    expect(miss < 1e-6, "LogH Kepler e = 0.9, one period: distance from the start", miss);

    // A classic stepper of the seed texts (RK4) and the adaptive Euler-Richardson driver.
    State y(V1(2.0), V1(0.0));
    auto rk4 = sympl::make_classic<sympl::rk4, State>(pendulum);
    sympl::integrate_until(rk4, y, 0.0, 10.0, 0.01);
    expect(std::fabs(sympl::energy(pendulum, y) / e0 - 1) < 1e-7, "RK4, 10 time units at dt = 0.01: relative energy error",
           std::fabs(sympl::energy(pendulum, y) / e0 - 1));
    auto er = sympl::make_classic<sympl::euler_richardson, K>(kepler);
    K z = sympl::hamiltonians::kepler::initial_state(0.5);
    sympl::control_options options = sympl::richardson_adaptive(er).default_control();
    options.absolute_tolerance = 1e-7;
    const auto adaptive = sympl::integrate_controlled(sympl::richardson_adaptive(er), z, 0.0, 2 * pi, options);
    const double adaptive_miss = sympl::max_difference(z, sympl::hamiltonians::kepler::initial_state(0.5));
    expect(adaptive_miss < 1e-3 && adaptive.accepted > 10, "adaptive Euler-Richardson, one Kepler period: miss", adaptive_miss);

    // The flow map of a table is symplectic: M^T J M = J to rounding.
    const auto flow = [&](auto& s) {
        using S = typename std::decay_t<decltype(s)>;
        auto st = sympl::make_stepper<S>(pendulum, sympl::method("blanes_moan_s6"));
        st.steps(s, 0.1, 50);
    };
    const double defect = sympl::symplecticity_defect(sympl::flow_jacobian(flow, State(V1(1.0), V1(0.3))));
    expect(defect < 1e-13, "symplecticity defect of 50 steps of blanes_moan_s6", defect);

    // Bad input is an error that names the value.
    try {
        stepper.step(x, -0.0);
        expect(false, "dt = 0 refused", 0);
    } catch (const sympl::invalid_argument&) {
        expect(true, "dt = 0 refused", 0);
    }
    return failures == 0 ? 0 : 1;
}
