#pragma once
// The non-separable test problems of the extended-phase-space tests
// (test_extended_phase_space.cpp, test_semiexplicit.cpp): J&O 2023's product
// Hamiltonian and a pendulum of varying mass, the composed tables, a plain
// run of n steps, and the area defect of a one-degree-of-freedom map.
#include <cmath>

#include <sympl/sympl.hpp>
#include <sympl/core/general_hamiltonian.hpp>
#include <sympl/hamiltonians/product_hamiltonian.hpp>

namespace sympl::nonseparable_testing {

// Tao's and J&O's test problem, from (q, p) = (-3, 0) as J&O 2023.
inline const hamiltonians::product_hamiltonian product{};
// A pendulum whose mass grows with the angle: H = p^2 / (2 (1 + q^2/2)) + 1 - cos q.
inline const auto varying_mass = make_general_hamiltonian([](const auto& q, const auto& p) {
    using std::cos;
    return p.squaredNorm() / (2 * (1 + q.squaredNorm() / 2)) + 1 - cos(q[0]);
});

inline const table leapfrog = method("leapfrog_kdk");
inline const table order4 = triple_jump(leapfrog);
inline const table order6 = method("yoshida_6");

template <class S, class Stepper>
phase_space<S, 1> run(Stepper s, phase_space<S, 1> x, double t_end, int n) {
    const S dt = S(t_end) / S(n);
    for (int i = 0; i < n; ++i) s.step(x, dt);
    return x;
}

// |det M - 1| of the 2x2 Jacobian of a one-degree-of-freedom map (M^T J M - J = (det M - 1) J).
template <class D>
double area_defect(const phase_space<D, 1>& x) {
    return std::fabs(x.q[0].grad[0] * x.p[0].grad[1] - x.q[0].grad[1] * x.p[0].grad[0] - 1);
}

}  // namespace sympl::nonseparable_testing
