// Quickstart: a pendulum written as two lambdas, integrated by a 4th-order
// table for 1000 periods; prints the largest relative energy error.
#include <cmath>
#include <cstdio>

#include <sympl/sympl.hpp>

int main() {
    auto pendulum = sympl::make_hamiltonian(
        [](const auto& p) { return 0.5 * p.squaredNorm(); },                // T(p)
        [](const auto& q) { using std::cos; return 1.0 - cos(q[0]); });     // V(q); forces by autodiff
    using State = sympl::phase_space<double, 1>;
    State x(Eigen::Matrix<double, 1, 1>(2.0), Eigen::Matrix<double, 1, 1>(0.0));
    auto stepper = sympl::make_stepper<State>(pendulum, sympl::method("blanes_moan_s6"));
    const double e0 = sympl::energy(pendulum, x);
    double worst = 0;
    const auto summary = sympl::integrate_until(stepper, x, 0.0, 8000.0, 0.1,
        [&](const State& s, double) { worst = std::max(worst, std::fabs(sympl::energy(pendulum, s) / e0 - 1)); });
    std::printf("%zu steps, %llu force evaluations, max relative energy error %.3e\n", summary.steps,
                static_cast<unsigned long long>(summary.force_evaluations), worst);
    return worst < 1e-5 ? 0 : 1;
}
