#pragma once
// A Hamiltonian H(q, p) that need not split as T(p) + V(q): a charged
// particle in a magnetic field, a double pendulum, H = (1 + q^2)(1 + p^2)/2.
// Hamilton's equations dq/dt = dH/dp, dp/dt = -dH/dq (Gould & Tobochnik,
// eq. 3.73, without the separation) are built from a templated
//     energy(q, p)                 -> H(q, p)
// and, where the user gives them, the analytic gradients
//     dH_dq(q, p, out), dH_dp(q, p, out)   writing the gradient into out;
// whatever is missing comes from forward-mode dual numbers (dual.hpp), about
// n evaluations of H per gradient. A generic energy(q, p) is evaluated once
// more at a stepper's first call with a new dimension, on vectors that refuse
// a read past the state (checked_reads.hpp).
//
// A kick-drift table needs H = T(p) + V(q) (hamiltonian.hpp): a general
// Hamiltonian is run by the extended-phase-space methods
// (methods/extended_phase_space.hpp, semiexplicit.hpp) or the implicit Gauss-Legendre
// collocation (methods/gauss/gauss_collocation.hpp).
#include <concepts>
#include <utility>

#include <Eigen/Core>

#include "hamiltonian.hpp"

namespace sympl {

template <class H, class Vec>
concept general_hamiltonian = requires(const H& h, const Vec& q, const Vec& p) {
    { h.energy(q, p) } -> std::convertible_to<scalar_of<Vec>>;
};

template <class H, class Vec>
concept has_analytic_dH_dq = requires(const H& h, const Vec& q, const Vec& p, Vec& out) { h.dH_dq(q, p, out); };
template <class H, class Vec>
concept has_analytic_dH_dp = requires(const H& h, const Vec& q, const Vec& p, Vec& out) { h.dH_dp(q, p, out); };

// out = dH/dq at (q, p); analytic when H provides it.
template <class H, class Vec>
    requires general_hamiltonian<H, Vec>
void dH_dq(const H& h, const Vec& q, const Vec& p, Vec& out) {
    if constexpr (has_analytic_dH_dq<H, Vec>) {
        h.dH_dq(q, p, out);
    } else {
        detail::gradient(
            [&h, &p](const auto& x) {
                using X = std::decay_t<decltype(x)>;
                return h.energy(x, X(p.template cast<typename X::Scalar>()));
            },
            q, out);
    }
}

// out = dH/dp at (q, p); analytic when H provides it.
template <class H, class Vec>
    requires general_hamiltonian<H, Vec>
void dH_dp(const H& h, const Vec& q, const Vec& p, Vec& out) {
    if constexpr (has_analytic_dH_dp<H, Vec>) {
        h.dH_dp(q, p, out);
    } else {
        detail::gradient(
            [&h, &q](const auto& x) {
                using X = std::decay_t<decltype(x)>;
                return h.energy(X(q.template cast<typename X::Scalar>()), x);
            },
            p, out);
    }
}

// H(q, p) of a state.
template <class H, class S, int D>
    requires general_hamiltonian<H, typename phase_space<S, D>::vector>
S energy(const H& h, const phase_space<S, D>& x) {
    return S(h.energy(x.q, x.p));
}

// A general Hamiltonian from one generic lambda H(q, p):
//   auto h = sympl::make_general_hamiltonian([](const auto& q, const auto& p) {
//       return 0.5 * (1 + q.squaredNorm()) * (1 + p.squaredNorm()); });
template <class Fn>
struct lambda_general_hamiltonian {
    Fn H;
    // Constrained as lambda_hamiltonian's members (hamiltonian.hpp).
    template <class Vec> requires std::invocable<const Fn&, const Vec&, const Vec&>
    auto energy(const Vec& q, const Vec& p) const { return H(q, p); }
};
template <class Fn>
lambda_general_hamiltonian<Fn> make_general_hamiltonian(Fn H) {
    return {std::move(H)};
}

}  // namespace sympl
