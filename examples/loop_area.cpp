// Phase-space area of a loop of 200 pendulum initial conditions around
// (q, p) = (0, 1.5), just inside the separatrix (which crosses q = 0 at p = 2),
// where the period varies fastest with energy, carried 10^4 steps of dt = 0.2 by the
// leapfrog, Yoshida's 6th-order method and Boost.Odeint's runge_kutta4.
// CSV on stdout, one row per method and checkpoint:
//   method, step, t, area_200      the polygon of the 200 carried points,
//   area_refined, points           the loop refined until neighbours are within 0.1,
//   area_error                     area_refined - initial area,
//   defect                         ||M^T J M - J|| / ||M||^2 of the flow at (0, 1.5).
// How to read it: README, "Phase-space area".
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <sympl/sympl.hpp>
#include <sympl/interop/odeint.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

using State = sympl::phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;

int main() {
    const sympl::hamiltonians::pendulum h{};
    const double dt = 0.2, r = 0.2, pi = std::numbers::pi;
    const auto circle = [&](double s) { return State(V1(r * std::cos(2 * pi * s)), V1(1.5 + r * std::sin(2 * pi * s))); };
    const double initial_area = sympl::loop_area(sympl::carry_loop(circle, [](State&) {}, {200, 200, 1e9}), 0);
    std::printf("method,step,t,area_200,area_refined,points,area_error,defect\n");
    for (const char* name : {"leapfrog_kdk", "yoshida_6", "odeint_rk4"}) {
        for (std::size_t n = 0; n <= 10000; n += 2500) {
            const auto flow = [&](auto& x) {
                if (std::string(name) == "odeint_rk4") {
                    sympl::odeint_rk4_flow<1>(h, dt, n)(x);
                } else {
                    auto s = sympl::make_stepper<std::decay_t<decltype(x)>>(h, sympl::method(name));
                    if (n > 0) s.steps(x, dt, n);
                }
            };
            const auto coarse = sympl::carry_loop(circle, flow, {200, 200, 1e9});
            const auto fine = sympl::carry_loop(circle, flow, {200, std::size_t(1) << 14, 0.1});
            const auto M = sympl::flow_jacobian(flow, State(V1(0.0), V1(1.5)));
            std::printf("%s,%zu,%g,%.10f,%.10f,%zu%s,%.3e,%.3e\n", name, n, n * dt, sympl::loop_area(coarse, 0),
                        sympl::loop_area(fine, 0), fine.points.size(), fine.resolved ? "" : "(max)",
                        sympl::loop_area(fine, 0) - initial_area, sympl::symplecticity_defect(M) / M.squaredNorm());
        }
    }
}
