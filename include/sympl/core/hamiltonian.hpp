#pragma once
// A separable Hamiltonian H(q, p) = T(p) + V(q) and Hamilton's equations
// dq/dt = dT/dp, dp/dt = -dV/dq (Gould & Tobochnik, eqs. 3.71 and 3.73).
//
// A user type provides templated kinetic(p) and potential(q). It may also
// provide the analytic gradients
//     velocity(p)      -> dT/dp  (returning a vector or an Eigen expression), or
//     velocity(p, v)   writing dT/dp into v;
//     force(q, f)      writing -dV/dq into f, or
//     force(q)         -> -dV/dq.
// Whatever is missing is derived by automatic differentiation of
// kinetic/potential: forward mode (dual.hpp) for up to 8 components (16 of a
// fixed size), reverse mode (reverse_mode.hpp) above, whose cost per gradient does
// not grow with n (docs/speed.md has the figures). Generic kinetic/potential
// are evaluated once more at a stepper's first call with a new dimension, on
// vectors that refuse a read past the state (checked_reads.hpp).
#include <cmath>
#include <concepts>
#include <string>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "reverse_mode.hpp"
#include "checked_reads.hpp"
#include "dual.hpp"
#include "error.hpp"
#include "phase_space.hpp"

namespace sympl {

// Scalar of an Eigen vector type.
template <class Vec>
using scalar_of = typename Vec::Scalar;

// The same vector shape with another scalar (used for dual numbers).
template <class Vec, class S>
using rebind_vector = Eigen::Matrix<S, Vec::RowsAtCompileTime, 1>;

template <class H, class Vec>
concept separable_hamiltonian = requires(const H& h, const Vec& x) {
    { h.kinetic(x) } -> std::convertible_to<scalar_of<Vec>>;
    { h.potential(x) } -> std::convertible_to<scalar_of<Vec>>;
};

template <class H, class Vec>
concept has_force_into = requires(const H& h, const Vec& q, Vec& f) { h.force(q, f); };
template <class H, class Vec>
concept has_force_value = requires(const H& h, const Vec& q, Vec& f) { f = h.force(q); };
template <class H, class Vec>
concept has_velocity_into = requires(const H& h, const Vec& p, Vec& v) { h.velocity(p, v); };
template <class H, class Vec>
concept has_velocity_value = requires(const H& h, const Vec& p, Vec& v) { v.noalias() = h.velocity(p); };

template <class H, class Vec>
concept has_analytic_force = has_force_into<H, Vec> || has_force_value<H, Vec>;
template <class H, class Vec>
concept has_analytic_velocity = has_velocity_into<H, Vec> || has_velocity_value<H, Vec>;

// A Hamiltonian written for one dimension may say so, as a constant
// `static constexpr int dimension` or a member `dimension()`; the steppers then
// refuse a state of another size before the first force reads past its end.
template <class H>
concept declares_dimension = requires(const H& h) {
    { h.dimension() } -> std::convertible_to<Eigen::Index>;
} || requires {
    { H::dimension } -> std::convertible_to<Eigen::Index>;
};

template <class H>
Eigen::Index declared_dimension(const H& h) {
    if constexpr (requires { h.dimension(); }) return h.dimension();
    else return H::dimension;
}

// What a stepper checks once per call, before it touches the state: q and p of
// one size, the size the Hamiltonian declares (if it does), every component
// finite; and, once per dimension, that the Hamiltonian's generic code reads
// no component past the state's end (checked_reads.hpp).
template <class H, class State>
void check_state(const H& h, const State& x, const char* who) {
    if (x.q.size() != x.p.size())
        throw invalid_argument(std::string(who) + ": q has " + std::to_string(x.q.size()) + " components but p has " +
                               std::to_string(x.p.size()) + "; expected equal dimensions");
    if constexpr (declares_dimension<H>)
        if (x.q.size() != declared_dimension(h))
            throw invalid_argument(std::string(who) + ": the state has dimension " + std::to_string(x.q.size()) +
                                   " but the Hamiltonian is written for dimension " +
                                   std::to_string(declared_dimension(h)) + "; expected equal dimensions");
    using std::isfinite;
    for (Eigen::Index i = 0; i < x.q.size(); ++i)
        if (!isfinite(x.q[i]) || !isfinite(x.p[i]))
            throw invalid_argument(std::string(who) + ": the state is not finite (component " + std::to_string(i) +
                                   " of q or p); expected finite q and p");
    check_reads_once(h, x, who);
}

namespace detail {
// Width of the dual numbers used to differentiate an n-dimensional function:
// all directions at once for small fixed sizes, chunks of 8 otherwise.
template <class Vec>
constexpr int autodiff_width() {
    constexpr int n = Vec::RowsAtCompileTime;
    return (n != Eigen::Dynamic && n <= 16) ? n : 8;
}

// out = factor * d fn / d x (factor -1 for a force: exactly the negated
// gradient, without a pass of its own; 1 for scalars that are not plain
// floating-point numbers): by reverse mode where forward mode would take more than
// one pass of W directions (one recording and one sweep, whatever n), else by
// forward mode in chunks of W. Scalars that are not plain floating-point types
// (dual numbers, SIMD batches) stay in forward mode. Workspaces are reused
// across calls (no heap allocation once sized).
template <class Vec, class Fn>
void gradient(const Fn& fn, const Vec& x, Vec& out, scalar_of<Vec> factor = scalar_of<Vec>(1)) {
    using S = scalar_of<Vec>;
    constexpr int W = autodiff_width<Vec>();
    if constexpr (std::is_floating_point_v<S>) {
        if (x.size() > W) {
            reverse_gradient(fn, x, out, factor);
            return;
        }
    }
    using D = dual<S, W>;
    using DVec = rebind_vector<Vec, D>;
    thread_local DVec xd;
    const Eigen::Index n = x.size();
    if (xd.size() != n) xd.resize(n);
    if (out.size() != n) out.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) xd[i] = D(x[i]);
    for (Eigen::Index start = 0; start < n; start += W) {
        for (int k = 0; k < W; ++k)
            if (start + k < n) xd[start + k].grad[k] = S(1);
        const D y = fn(xd);
        for (int k = 0; k < W; ++k)
            if (start + k < n) {
                if constexpr (std::is_floating_point_v<S>) out[start + k] = factor * y.grad[k];
                else out[start + k] = y.grad[k];  // factor 1: force() negates these itself
                xd[start + k].grad[k] = S(0);
            }
    }
}
}  // namespace detail

// f = -dV/dq (Gould & Tobochnik eq. 3.73a), analytic when H provides it.
// Forced inline (as velocity): the steppers' loops call it once per sub-step.
template <class H, class Vec>
    requires separable_hamiltonian<H, Vec>
[[gnu::always_inline]] inline void force(const H& h, const Vec& q, Vec& f) {
    if constexpr (has_force_into<H, Vec>) {
        h.force(q, f);
    } else if constexpr (has_force_value<H, Vec>) {
        f = h.force(q);
    } else {
        if constexpr (std::is_floating_point_v<scalar_of<Vec>>) {
            detail::gradient([&h](const auto& x) { return h.potential(x); }, q, f, scalar_of<Vec>(-1));
        } else {
            detail::gradient([&h](const auto& x) { return h.potential(x); }, q, f);
            f = -f;
        }
    }
}

// v = dT/dp (Gould & Tobochnik eq. 3.73b), analytic when H provides it.
template <class H, class Vec>
    requires separable_hamiltonian<H, Vec>
[[gnu::always_inline]] inline void velocity(const H& h, const Vec& p, Vec& v) {
    if constexpr (has_velocity_into<H, Vec>) {
        h.velocity(p, v);
    } else if constexpr (has_velocity_value<H, Vec>) {
        v.noalias() = h.velocity(p);
    } else {
        detail::gradient([&h](const auto& x) { return h.kinetic(x); }, p, v);
    }
}

// The force's derivative along u, df = J_F(q) u with J_F = dF/dq = -Hessian of
// V: what a force-gradient kick needs (table.hpp), with u = M^-1 F. A user type
// may provide it analytically as
//     force_derivative(q, u, df)   writing J_F(q) u into df;
// otherwise it is the Hessian-vector product of the potential by forward mode
// over forward mode (dual numbers whose values are dual numbers carrying u):
// about n/8 evaluations of V for n > 16, so large systems should give it.
template <class H, class Vec>
concept has_force_derivative = requires(const H& h, const Vec& q, const Vec& u, Vec& df) {
    h.force_derivative(q, u, df);
};

namespace detail {
template <class Vec>
using along_vector = rebind_vector<Vec, dual<scalar_of<Vec>, 1>>;  // value q, one tangent u
template <class Vec>
using hessian_vector = rebind_vector<along_vector<Vec>, dual<dual<scalar_of<Vec>, 1>, autodiff_width<Vec>()>>;
}  // namespace detail

// The potential must return the nested dual number itself: a potential written
// for doubles only would take the dual vector by a conversion that drops it.
template <class H, class Vec>
concept differentiable_force = has_force_derivative<H, Vec> || requires(const H& h, const detail::hessian_vector<Vec>& x) {
    { h.potential(x) } -> std::same_as<scalar_of<detail::hessian_vector<Vec>>>;
};

template <class H, class Vec>
    requires separable_hamiltonian<H, Vec> && differentiable_force<H, Vec>
void force_derivative(const H& h, const Vec& q, const Vec& u, Vec& df) {
    if constexpr (has_force_derivative<H, Vec>) {
        h.force_derivative(q, u, df);
    } else {
        using A = detail::along_vector<Vec>;
        thread_local A x, g;
        const Eigen::Index n = q.size();
        if (x.size() != n) x.resize(n);
        for (Eigen::Index i = 0; i < n; ++i) {
            x[i].value = q[i];
            x[i].grad[0] = u[i];
        }
        // g = grad V at q + e u, to first order in e: its tangent is Hessian(V) u = -J_F u.
        detail::gradient([&h](const auto& y) { return h.potential(y); }, x, g);
        if (df.size() != n) df.resize(n);
        for (Eigen::Index i = 0; i < n; ++i) df[i] = -g[i].grad[0];
    }
}

// Total energy H(q, p) = T(p) + V(q) (Gould & Tobochnik eq. 3.71).
template <class H, class S, int D>
    requires separable_hamiltonian<H, typename phase_space<S, D>::vector>
S energy(const H& h, const phase_space<S, D>& x) {
    return S(h.kinetic(x.p)) + S(h.potential(x.q));
}

// Right-hand side of Hamilton's equations (Gould & Tobochnik eq. 3.73) for any other
// integrator: dxdt.q = dT/dp, dxdt.p = -dV/dq.
template <class H, class S, int D>
    requires separable_hamiltonian<H, typename phase_space<S, D>::vector>
void hamilton_rhs(const H& h, const phase_space<S, D>& x, phase_space<S, D>& dxdt) {
    velocity(h, x.p, dxdt.q);
    force(h, x.q, dxdt.p);
}

// A Hamiltonian from two generic lambdas, T(p) and V(q):
//   auto h = sympl::make_hamiltonian([](const auto& p) { return 0.5 * p.squaredNorm(); },
//                                    [](const auto& q) { using std::cos; return -cos(q[0]); });
template <class Kinetic, class Potential>
struct lambda_hamiltonian {
    Kinetic T;
    Potential V;
    // Constrained, so that a lambda whose signature refuses a vector type
    // (e.g. checked_reads.hpp's) is seen to refuse it rather than fail to compile.
    template <class Vec> requires std::invocable<const Kinetic&, const Vec&>
    auto kinetic(const Vec& p) const { return T(p); }
    template <class Vec> requires std::invocable<const Potential&, const Vec&>
    auto potential(const Vec& q) const { return V(q); }
};
template <class Kinetic, class Potential>
lambda_hamiltonian<Kinetic, Potential> make_hamiltonian(Kinetic T, Potential V) {
    return {std::move(T), std::move(V)};
}

}  // namespace sympl
