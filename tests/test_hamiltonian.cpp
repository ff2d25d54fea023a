// Automatic differentiation of kinetic/potential against the analytic
// gradients of every ready-made system, to 1e-14 relative.
#include <doctest/doctest.h>

#include <cmath>

#include <sympl/hamiltonian.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/relativistic_pendulum.hpp>
#include <sympl/hamiltonians/two_particle_spring.hpp>

using namespace sympl;

namespace {
// Wraps H and hides its analytic gradients, so the library must derive them.
template <class H>
struct energies_only {
    H h;
    template <class V> auto kinetic(const V& p) const { return h.kinetic(p); }
    template <class V> auto potential(const V& q) const { return h.potential(q); }
};

template <class H, class Vec>
void check_gradients(const H& h, const Vec& q, const Vec& p) {
    static_assert(has_analytic_force<H, Vec> && has_analytic_velocity<H, Vec>);
    static_assert(!has_analytic_force<energies_only<H>, Vec> && !has_analytic_velocity<energies_only<H>, Vec>);
    Vec f_exact, f_auto, v_exact, v_auto;
    force(h, q, f_exact);
    force(energies_only<H>{h}, q, f_auto);
    velocity(h, p, v_exact);
    velocity(energies_only<H>{h}, p, v_auto);
    CHECK((f_auto - f_exact).norm() <= 1e-14 * f_exact.norm());
    CHECK((v_auto - v_exact).norm() <= 1e-14 * v_exact.norm());
}
}  // namespace

TEST_CASE("hamiltonian: autodiff gradients equal analytic ones on every ready-made system") {
    SUBCASE("harmonic oscillator, fixed size 3") {
        check_gradients(hamiltonians::harmonic_oscillator{2.0, 1.5}, Eigen::Vector3d(0.3, -1, 2), Eigen::Vector3d(1, 2, -0.5));
    }
    SUBCASE("pendulum") {
        check_gradients(hamiltonians::pendulum{1.5, 0.8, 9.81}, Eigen::Matrix<double, 1, 1>(2.1), Eigen::Matrix<double, 1, 1>(-0.7));
    }
    SUBCASE("kepler") {
        check_gradients(hamiltonians::kepler{}, Eigen::Vector2d(0.4, -0.9), Eigen::Vector2d(1.2, 0.3));
    }
    SUBCASE("relativistic pendulum, dynamic size") {
        Eigen::VectorXd q(3), p(3);
        q << 0.5, -2.0, 1.0;
        p << 3.0, -0.2, 0.7;
        check_gradients(hamiltonians::relativistic_pendulum{2.0, 1.5, 0.7}, q, p);
    }
    SUBCASE("two particles joined by a spring (seed eq. 3.72)") {
        Eigen::Vector4d q(0.3, -1.0, 2.0, 0.5), p(1.0, 2.0, -0.5, 0.25);
        check_gradients(hamiltonians::two_particle_spring{1.5, 2.5}, q, p);
    }
    SUBCASE("FPU-beta chain, 21 particles (chunked autodiff)") {
        Eigen::VectorXd q(21), p(21);
        for (int i = 0; i < 21; ++i) {
            q[i] = std::sin(0.7 * i);
            p[i] = std::cos(1.3 * i);
        }
        check_gradients(hamiltonians::fpu_beta{0.8}, q, p);
    }
}

TEST_CASE("hamiltonian: a pair of lambdas, energy, and Hamilton's equations (seed eq. 3.73)") {
    auto h = make_hamiltonian([](const auto& p) { return 0.5 * p.squaredNorm(); },
                              [](const auto& q) { using std::cos; return 1.0 - cos(q[0]); });
    const phase_space<double, 1> x(Eigen::Matrix<double, 1, 1>(0.8), Eigen::Matrix<double, 1, 1>(-0.3));
    CHECK(energy(h, x) == doctest::Approx(0.045 + 1 - std::cos(0.8)).epsilon(1e-15));
    phase_space<double, 1> dxdt;
    hamilton_rhs(h, x, dxdt);
    CHECK(dxdt.q[0] == doctest::Approx(-0.3).epsilon(1e-15));          // dq/dt = dT/dp
    CHECK(dxdt.p[0] == doctest::Approx(-std::sin(0.8)).epsilon(1e-15));  // dp/dt = -dV/dq
}
