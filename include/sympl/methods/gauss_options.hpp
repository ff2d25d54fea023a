#pragma once
// What the Gauss-Legendre stepper (gauss_collocation.hpp) is told and what it
// iterates on: its options (iteration, tolerances, compensated update), the
// constants of its stopping rule and iteration choice, a separable H seen as
// a general one, and the magnitudes of (dual) numbers its convergence test
// reads. The rules and their reasons: docs/nonseparable.md.
#include <optional>
#include <type_traits>
#include <utility>

#include "../core/dual.hpp"
#include "../core/general_hamiltonian.hpp"
#include "../core/hamiltonian.hpp"

namespace sympl {

// How the stage equations are iterated.
enum class gauss_iteration {
    automatic,    // fixed point while it contracts by gauss_newton_switch or better per iteration, else Newton
    fixed_point,  // Z <- dt (A (x) I) F(Z): s evaluations of f per iteration, nothing else
    newton,       // simplified Newton, Jacobian frozen across steps until convergence slows
};

struct gauss_options {
    // rtol: the correction of every component k is measured against
    // atol_k + rtol |y_k| (|y_k| the largest of y0 and the stage values).
    // Unset: one machine epsilon of the state's scalar, with the plateau rule
    // below the iteration then runs to rounding (GNI_IRK2 asks the same).
    std::optional<double> tolerance;
    // atol, the same for every component. Unset: rtol times the largest |y_k|
    // of the component's half of the state (q or p), so that a component near
    // zero is judged on its neighbours' rounding.
    std::optional<double> absolute_tolerance;
    // Iterations of one attempt at a step (a step that fails retries once, from
    // Euler's start by simplified Newton) before it gives up with integration_error.
    int max_iterations = 50;
    gauss_iteration iteration = gauss_iteration::automatic;
    // Sum y1 = y0 + sum_i d_i Z_i with Kahan's compensation carried from step
    // to step (while the state handed in is the one the last step returned).
    bool compensated = false;
};

// A correction that stops shrinking once the relative correction is at most
// this is at the rounding floor of the stage equations (cancellation inside
// f can put it far above a few ulps) and accepted (GNI sec. VIII.6.2: stop
// when the corrections no longer decrease). Above it, a correction that grows
// is a slow or diverging iteration, never taken for convergence.
inline constexpr double gauss_rounding_plateau = 0x1p-36;
// automatic: fixed-point steps that contract by less than this per iteration
// switch the stepper to simplified Newton (measured: docs/nonseparable.md).
inline constexpr double gauss_newton_switch = 0.25;
// Newton: a contraction slower than this marks the frozen Jacobian stale.
inline constexpr double gauss_jacobian_refresh = 0.1;

// A separable Hamiltonian seen as a general one: dH/dq = -dV/dq, dH/dp = dT/dp.
template <class H>
struct separable_as_general {
    H h;
    template <class V> auto energy(const V& q, const V& p) const { return h.kinetic(p) + h.potential(q); }
    template <class V> void dH_dq(const V& q, const V&, V& out) const {
        force(h, q, out);
        out = -out;
    }
    template <class V> void dH_dp(const V&, const V& p, V& out) const { velocity(h, p, out); }
};

template <class H, class Vec>
concept gauss_collocation_system = general_hamiltonian<H, Vec> || separable_hamiltonian<H, Vec>;

namespace detail {
// max(m, v) that keeps a NaN once seen (std::max drops a NaN second argument),
// so that a diverged iteration is never taken for a converged one.
template <class T>
T nan_max(T m, T v) {
    return (m != m || v != v || v > m) ? (m != m ? m : v) : m;
}
// |x| of a (possibly nested) dual number: the largest of its value and all its
// derivatives, so that an iteration on dual numbers converges in both.
template <class X>
auto magnitude(const X& x) {
    using std::fabs;
    if constexpr (is_dual<X>::value) {
        auto m = magnitude(x.value);
        for (const auto& g : x.grad) m = nan_max(m, magnitude(g));
        return m;
    } else {
        return fabs(x);
    }
}
template <class X>
using real_of = decltype(primal(std::declval<X>()));

}  // namespace detail

}  // namespace sympl
