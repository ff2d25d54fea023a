// Sandvik's oscillator test (Sandvik's lecture notes, "Test: same oscillator as before"):
// Euler, the leapfrog (velocity Verlet) and RK4 on x'' = -x from x = 1, v = 0,
// at dt = 0.1 and 0.01, printing the relative energy error at t = 10, 100, 1000.
// Euler's error grows exponentially, RK4's drifts linearly in time, the
// leapfrog's stays bounded (about dt^2/4) however long the run.
#include <cmath>
#include <cstdio>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>

using State = sympl::phase_space<double, 1>;

template <template <class, class> class Method>
void report(const char* name, double dt) {
    const sympl::hamiltonians::harmonic_oscillator h{};
    auto stepper = sympl::make_classic<Method, State>(h);
    State x(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.0));
    const double e0 = sympl::energy(h, x);
    std::printf("%-16s dt = %-5g", name, dt);
    double t0 = 0;
    for (const double t : {10.0, 100.0, 1000.0}) {
        sympl::integrate_until(stepper, x, t0, t, dt);
        t0 = t;
        std::printf("   %10.3e", std::fabs(sympl::energy(h, x) - e0) / e0);
    }
    std::printf("\n");
}

int main() {
    std::printf("relative energy error |E(t) - E(0)| / E(0) of the harmonic oscillator\n");
    std::printf("%-16s %-10s   %10s   %10s   %10s\n", "method", "", "t = 10", "t = 100", "t = 1000");
    for (const double dt : {0.1, 0.01}) {
        report<sympl::euler>("Euler", dt);
        report<sympl::velocity_verlet>("leapfrog", dt);
        report<sympl::rk4>("RK4", dt);
    }
}
