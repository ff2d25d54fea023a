#pragma once
// What the Gauss-Legendre stepper (gauss_collocation.hpp) is told and what it
// iterates on: its options (iteration, tolerances, compensated update), the
// constants of its stopping rule and iteration choice, a separable H seen as
// a general one, the options' check, and the componentwise measure of a
// correction its convergence test reads (on dual numbers too).
// The rules and their reasons: docs/nonseparable.md.
#include <cmath>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "../../core/dual.hpp"
#include "../../core/error.hpp"
#include "../../core/general_hamiltonian.hpp"
#include "../../core/hamiltonian.hpp"

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
    template <class V>
        requires separable_hamiltonian<H, V>
    auto energy(const V& q, const V& p) const {
        return h.kinetic(p) + h.potential(q);
    }
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

// The options checked (named in the error as the stepper's) and the relative
// tolerance they ask: theirs, or `eps` (one machine epsilon of the state's scalar).
inline double checked_relative_tolerance(const gauss_options& o, double eps) {
    using std::isfinite;
    const double rtol = o.tolerance ? *o.tolerance : eps;
    if (!isfinite(rtol) || !(rtol > 0))
        throw invalid_argument("gauss_collocation_stepper: tolerance = " + number_text(rtol) +
                               "; expected a finite tolerance > 0");
    if (o.absolute_tolerance && (!isfinite(*o.absolute_tolerance) || *o.absolute_tolerance < 0))
        throw invalid_argument("gauss_collocation_stepper: absolute_tolerance = " + number_text(*o.absolute_tolerance) +
                               "; expected a finite tolerance >= 0 (or none: rtol times the largest component)");
    if (o.max_iterations < 1)
        throw invalid_argument("gauss_collocation_stepper: max_iterations = " + std::to_string(o.max_iterations) +
                               "; expected at least 1");
    return rtol;
}

// The convergence test's measure: max over stages i and components k of
// |dZ_ik| / (atol + rtol y_k), y_k the largest |component k| of y0 and the
// stages y0 + Z_i (kept in ymax), in units of rtol; a NaN kept. No atol:
// rtol times the largest y_k of the component's half (q or p) instead.
template <class State, class Stages, class RealColumn, class Real>
Real scaled_correction(const State& x, const Stages& z, const Stages& dz, RealColumn& ymax, Real rtol,
                       const std::optional<double>& atol) {
    const Eigen::Index s = z.cols(), n = x.q.size();
    Real block[2] = {0, 0};
    for (Eigen::Index k = 0; k < 2 * n; ++k) {
        const auto& y0 = k < n ? x.q[k] : x.p[k - n];
        Real y = Real(magnitude(y0));
        for (Eigen::Index i = 0; i < s; ++i) y = nan_max(y, Real(magnitude(y0 + z(k, i))));
        ymax[k] = y;
        block[k >= n] = nan_max(block[k >= n], y);
    }
    Real worst = 0;
    for (Eigen::Index k = 0; k < 2 * n; ++k) {
        const Real scale = atol ? Real(*atol) + rtol * ymax[k] : rtol * (ymax[k] + block[k >= n]);
        Real v = 0;
        for (Eigen::Index i = 0; i < s; ++i) v = nan_max(v, Real(magnitude(dz(k, i))));
        worst = nan_max(worst, scale > 0 ? v / scale : (v == 0 ? Real(0) : v / scale));
    }
    return worst;
}

}  // namespace detail

}  // namespace sympl
