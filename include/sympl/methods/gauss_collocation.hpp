#pragma once
// The implicit Gauss-Legendre collocation Runge-Kutta methods with s = 1, 2, 3
// stages (orders 2s = 2, 4, 6; s = 1 is the implicit midpoint rule):
// symplectic for any H(q, p), separable or not, and symmetric (Butcher 1964;
// Hairer, Lubich & Wanner, Geometric Numerical Integration, 2nd ed. 2006,
// sec. II.1.3, Table II.1.1, Thm. VI.4.3). One step solves the stage equations
//     Z_i = dt sum_j a_ij f(y0 + Z_j),   f(y) = (dH/dp, -dH/dq),
// by simplified Newton iterations with the Jacobian of f at y0 from dual
// numbers (GNI sec. VIII.6.2; Hairer & Wanner, Solving ODEs II, sec. IV.8),
// and takes y1 = y0 + sum_i d_i Z_i, d^T = b^T A^-1 (GNI sec. VIII.6).
// Convergence test, dual-number states and cost: docs/nonseparable.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "../core/dual.hpp"
#include "../core/error.hpp"
#include "../core/general_hamiltonian.hpp"
#include "../core/hamiltonian.hpp"
#include "../drivers/fixed_step.hpp"
#include "../core/phase_space.hpp"

namespace sympl {

// The Butcher tableau of the s-stage Gauss-Legendre method, and d = A^-T b.
// Nodes c_i are the zeros of the shifted Legendre polynomial P_s(2c - 1)
// (Butcher 1964; GNI Table II.1.1), every entry in closed form.
struct gauss_tableau {
    int stages = 0;
    int order = 0;
    std::array<long double, 3> c{};
    std::array<std::array<long double, 3>, 3> a{};
    std::array<long double, 3> b{};
    std::array<long double, 3> d{};  // y1 = y0 + sum d_i Z_i (GNI sec. VIII.6)
};

inline gauss_tableau gauss_legendre_tableau(int stages) {
    const long double r3 = std::numbers::sqrt3_v<long double>, r15 = std::sqrt(15.0L);
    gauss_tableau t;
    t.stages = stages;
    t.order = 2 * stages;
    switch (stages) {
    case 1:  // the implicit midpoint rule
        t.c = {0.5L};
        t.a[0] = {0.5L};
        t.b = {1.0L};
        t.d = {2.0L};
        break;
    case 2:
        t.c = {0.5L - r3 / 6, 0.5L + r3 / 6};
        t.a[0] = {0.25L, 0.25L - r3 / 6};
        t.a[1] = {0.25L + r3 / 6, 0.25L};
        t.b = {0.5L, 0.5L};
        t.d = {-r3, r3};
        break;
    case 3:
        t.c = {0.5L - r15 / 10, 0.5L, 0.5L + r15 / 10};
        t.a[0] = {5.0L / 36, 2.0L / 9 - r15 / 15, 5.0L / 36 - r15 / 30};
        t.a[1] = {5.0L / 36 + r15 / 24, 2.0L / 9, 5.0L / 36 - r15 / 24};
        t.a[2] = {5.0L / 36 + r15 / 30, 2.0L / 9 + r15 / 15, 5.0L / 36};
        t.b = {5.0L / 18, 4.0L / 9, 5.0L / 18};
        t.d = {5.0L / 3, -4.0L / 3, 5.0L / 3};
        break;
    default:
        throw invalid_argument("gauss_legendre_tableau: stages = " + std::to_string(stages) +
                               "; expected 1, 2 or 3 (orders 2, 4, 6)");
    }
    return t;
}

struct gauss_options {
    // Largest Newton correction accepted, relative to the largest |component|
    // of y0 and of the stages. Unset: 8 machine epsilons of the state's scalar
    // (a few ulps: what the iteration reaches when dt |J| is below about 1).
    std::optional<double> tolerance;
    // Iterations before the step gives up with integration_error.
    int max_iterations = 50;
};

// A correction that stops shrinking (the next one no smaller) while within this
// many tolerances is at the rounding floor of the stage equations, and accepted.
inline constexpr double rounding_allowance = 16;

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

// The LU factorisation with partial pivoting of the Newton matrix
// I - dt (A (x) J) (Hairer & Wanner, Solving ODEs II, sec. IV.8), in place,
// and the solve with its factors on stage vectors of any scalar.
template <class Real>
struct newton_lu {
    Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> matrix;
    Eigen::Matrix<Eigen::Index, Eigen::Dynamic, 1> pivot;

    void resize(Eigen::Index n) {
        matrix.resize(n, n);
        pivot.resize(n);
    }
    // Factors `matrix`; returns the index of a zero or non-finite pivot, or -1.
    Eigen::Index factor() {
        const Eigen::Index N = matrix.rows();
        using std::fabs;
        for (Eigen::Index k = 0; k < N; ++k) {
            Eigen::Index best = k;
            for (Eigen::Index r = k + 1; r < N; ++r)
                if (fabs(matrix(r, k)) > fabs(matrix(best, k))) best = r;
            pivot[k] = best;
            if (best != k) matrix.row(k).swap(matrix.row(best));
            const Real piv = matrix(k, k);
            if (!(fabs(piv) > Real(0)) || !std::isfinite(double(piv))) return k;
            for (Eigen::Index r = k + 1; r < N; ++r) {
                const Real l = matrix(r, k) / piv;
                matrix(r, k) = l;
                if (l != Real(0)) matrix.row(r).tail(N - k - 1) -= l * matrix.row(k).tail(N - k - 1);
            }
        }
        return -1;
    }
    // v <- matrix^-1 v, with the factors of factor().
    template <class Vec>
    void solve(Vec& v) const {
        const Eigen::Index N = v.size();
        for (Eigen::Index k = 0; k < N; ++k) {
            if (pivot[k] != k) std::swap(v[k], v[pivot[k]]);
            for (Eigen::Index r = k + 1; r < N; ++r)
                if (matrix(r, k) != Real(0)) v[r] -= matrix(r, k) * v[k];
        }
        for (Eigen::Index k = N - 1; k >= 0; --k) {
            for (Eigen::Index c = k + 1; c < N; ++c) v[k] -= matrix(k, c) * v[c];
            v[k] = v[k] / matrix(k, k);
        }
    }
};
}  // namespace detail

template <class H, class State>
    requires phase_space_state<State> && gauss_collocation_system<H, typename State::vector>
class gauss_collocation_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    using real = detail::real_of<scalar>;  // the plain floating-point type under scalar
    using system_type =
        std::conditional_t<general_hamiltonian<H, vector>, H, separable_as_general<H>>;

    gauss_collocation_stepper(H hamiltonian, int stages, gauss_options options = {})
        : h_(wrap(std::move(hamiltonian))), tableau_(gauss_legendre_tableau(stages)), options_(options) {
        using std::isfinite;
        tolerance_ = options_.tolerance ? *options_.tolerance : 8 * double(std::numeric_limits<real>::epsilon());
        if (!isfinite(tolerance_) || !(tolerance_ > 0))
            throw invalid_argument("gauss_collocation_stepper: tolerance = " + detail::number_text(tolerance_) +
                                   "; expected a finite tolerance > 0");
        if (options_.max_iterations < 1)
            throw invalid_argument("gauss_collocation_stepper: max_iterations = " +
                                   std::to_string(options_.max_iterations) + "; expected at least 1");
        for (int i = 0; i < 3; ++i) {
            c_[i] = real(tableau_.c[i]);
            d_[i] = real(tableau_.d[i]);
            for (int j = 0; j < 3; ++j) a_[i][j] = real(tableau_.a[i][j]);
        }
        if constexpr (State::dimension != Eigen::Dynamic) size_workspace(State::dimension);
    }

    // One step of size dt (dt < 0 runs backwards). On integration_error x is unchanged.
    void step(State& x, scalar dt) { advance(x, std::numeric_limits<double>::quiet_NaN(), dt); }
    // The same with the time of the step's start, which only the error reports:
    // integrate.hpp's driver calls this one and adds the step's index.
    void step(State& x, scalar t, scalar dt) { advance(x, double(primal(t)), dt); }

    int stages() const { return tableau_.stages; }
    int order() const { return tableau_.order; }
    const gauss_tableau& tableau() const { return tableau_; }
    double tolerance() const { return tolerance_; }
    int max_iterations() const { return options_.max_iterations; }
    // Newton iterations of the last step and the largest relative correction reached.
    int last_iterations() const { return last_iterations_; }
    double last_residual() const { return last_residual_; }

    std::uint64_t force_evaluations() const { return dH_dq_evaluations_; }     // dH/dq
    std::uint64_t velocity_evaluations() const { return dH_dp_evaluations_; }  // dH/dp
    std::uint64_t jacobian_evaluations() const { return jacobian_evaluations_; }
    void reset_counters() { dH_dq_evaluations_ = dH_dp_evaluations_ = jacobian_evaluations_ = 0; }
    const system_type& system() const { return h_; }

private:
    using real_vector = Eigen::Matrix<real, State::dimension, 1>;
    using real_matrix = Eigen::Matrix<real, Eigen::Dynamic, Eigen::Dynamic>;
    using stage_vector = Eigen::Matrix<scalar, Eigen::Dynamic, 1>;
    // The Jacobian's dual numbers: all 2n directions at once for small fixed sizes.
    static constexpr int jacobian_width =
        (State::dimension != Eigen::Dynamic && 2 * State::dimension <= 16) ? 2 * State::dimension : 8;
    using jacobian_dual = dual<real, jacobian_width>;
    using jacobian_vector = Eigen::Matrix<jacobian_dual, State::dimension, 1>;

    static system_type wrap(H h) {
        if constexpr (std::is_same_v<system_type, H>) return h;
        else return system_type{std::move(h)};
    }

    void size_workspace(Eigen::Index n) {
        n_ = n;
        const Eigen::Index N = 2 * n * tableau_.stages;
        newton_.resize(N);
        jacobian_.resize(2 * n, 2 * n);
        f0_.resize(2 * n);
        z_.resize(N);
        dz_.resize(N);
        f_.resize(N);
        yq_.resize(n);
        yp_.resize(n);
        gq_.resize(n);
        gp_.resize(n);
        jq_.resize(n);
        jp_.resize(n);
        jgq_.resize(n);
        jgp_.resize(n);
    }

    void advance(State& x, double t, scalar dt) {
        using std::isfinite;
        const real h = primal(dt);
        if (!isfinite(h) || h == real(0))
            throw invalid_argument("gauss_collocation_stepper: dt = " + detail::number(dt) +
                                   "; expected a finite non-zero step size");
        check_state(h_, x, "gauss_collocation_stepper");
        if (x.size() != n_) size_workspace(x.size());
        const int s = tableau_.stages;
        const Eigen::Index n = n_, m = 2 * n;

        jacobian_at(x);
        factor_newton_matrix(h, dt, t);

        // Start from the stage values of the explicit Euler polynomial, Z_i = c_i dt f(y0).
        for (int i = 0; i < s; ++i)
            for (Eigen::Index k = 0; k < m; ++k) z_[i * m + k] = scalar(c_[i] * h * f0_[k]);

        real scale0 = 0;
        for (Eigen::Index k = 0; k < n; ++k)
            scale0 = std::max({scale0, real(detail::magnitude(x.q[k])), real(detail::magnitude(x.p[k]))});  // x is finite

        real residual = std::numeric_limits<real>::infinity(), previous = residual;
        int it = 0;
        bool converged = false;
        while (it < options_.max_iterations) {
            ++it;
            // F_i = f(y0 + Z_i).
            for (int i = 0; i < s; ++i) {
                yq_ = x.q + z_.segment(i * m, n);
                yp_ = x.p + z_.segment(i * m + n, n);
                sympl::dH_dq(h_, yq_, yp_, gq_);
                sympl::dH_dp(h_, yq_, yp_, gp_);
                f_.segment(i * m, n) = gp_;
                f_.segment(i * m + n, n) = -gq_;
            }
            dH_dq_evaluations_ += std::uint64_t(s);
            dH_dp_evaluations_ += std::uint64_t(s);
            // Right-hand side -Z + dt (A (x) I) F, then the Newton correction.
            for (int i = 0; i < s; ++i) {
                auto r = dz_.segment(i * m, m);
                r = -z_.segment(i * m, m);
                for (int j = 0; j < s; ++j) r += (dt * scalar(a_[i][j])) * f_.segment(j * m, m);
            }
            newton_.solve(dz_);
            z_ += dz_;
            residual = relative_correction(x, scale0);
            if (!isfinite(residual)) break;
            // At the tolerance; or at the rounding floor of the residual, which
            // cancellation inside dH/dq or dH/dp can put above a few ulps: the
            // corrections stop shrinking (GNI sec. VIII.6.2) while within
            // rounding_allowance tolerances.
            if (residual <= real(tolerance_) ||
                (it >= 3 && residual >= previous && previous <= real(rounding_allowance * tolerance_))) {
                converged = true;
                break;
            }
            previous = residual;
        }
        last_iterations_ = it;
        last_residual_ = double(residual);
        if (!converged)
            throw integration_error(
                "gauss_collocation_stepper: the stage equations of the " + std::to_string(s) +
                    "-stage Gauss-Legendre method did not converge at dt = " + detail::number(dt) +
                    ": relative Newton correction " + detail::number_text(residual) +
                    (isfinite(residual) ? "" : " (the iteration diverged)") + " after " +
                    std::to_string(it) + " iteration" + (it == 1 ? "" : "s") + "; expected at most the tolerance " +
                    detail::number_text(tolerance_) + " within max_iterations = " +
                    std::to_string(options_.max_iterations) + " (reduce dt, or raise max_iterations or the tolerance)",
                0, t);
        // y1 = y0 + sum_i d_i Z_i (GNI sec. VIII.6).
        for (int i = 0; i < s; ++i) {
            x.q += scalar(d_[i]) * z_.segment(i * m, n);
            x.p += scalar(d_[i]) * z_.segment(i * m + n, n);
        }
    }

    // The largest |dZ| relative to the largest of scale0 = max |y0| and |y0 + Z_i|,
    // a NaN kept (a diverged iteration is never taken for a converged one).
    real relative_correction(const State& x, real scale0) const {
        const int s = tableau_.stages;
        const Eigen::Index n = n_, m = 2 * n;
        real correction = 0, scale = scale0;
        for (Eigen::Index k = 0; k < s * m; ++k)
            correction = detail::nan_max(correction, real(detail::magnitude(dz_[k])));
        for (int i = 0; i < s; ++i)
            for (Eigen::Index k = 0; k < n; ++k)
                scale = detail::nan_max(detail::nan_max(scale, real(detail::magnitude(x.q[k] + z_[i * m + k]))),
                                        real(detail::magnitude(x.p[k] + z_[i * m + n + k])));
        return scale > 0 ? correction / scale : (correction == 0 ? real(0) : correction);
    }

    // f(y0) and its Jacobian J = d f / d y at the values of x, by dual numbers
    // carrying W of the 2n directions at a time.
    void jacobian_at(const State& x) {
        constexpr int W = jacobian_width;
        const Eigen::Index n = n_, m = 2 * n;
        auto &q = jq_, &p = jp_, &gq = jgq_, &gp = jgp_;
        for (Eigen::Index k = 0; k < n; ++k) {
            q[k] = jacobian_dual(real(primal(x.q[k])));
            p[k] = jacobian_dual(real(primal(x.p[k])));
        }
        auto seed = [&](Eigen::Index dir, int slot, real v) {
            if (dir < n) q[dir].grad[slot] = v;
            else p[dir - n].grad[slot] = v;
        };
        for (Eigen::Index start = 0; start < m; start += W) {
            for (int k = 0; k < W && start + k < m; ++k) seed(start + k, k, real(1));
            sympl::dH_dq(h_, q, p, gq);
            sympl::dH_dp(h_, q, p, gp);
            for (int k = 0; k < W && start + k < m; ++k) {
                for (Eigen::Index r = 0; r < n; ++r) {
                    jacobian_(r, start + k) = gp[r].grad[k];
                    jacobian_(n + r, start + k) = -gq[r].grad[k];
                }
                seed(start + k, k, real(0));
            }
        }
        for (Eigen::Index r = 0; r < n; ++r) {
            f0_[r] = gp[r].value;
            f0_[n + r] = -gq[r].value;
        }
        ++jacobian_evaluations_;
    }

    // I - dt (A (x) J), factored.
    void factor_newton_matrix(real h, const scalar& dt, double t) {
        const int s = tableau_.stages;
        const Eigen::Index m = 2 * n_;
        for (int i = 0; i < s; ++i)
            for (int j = 0; j < s; ++j)
                newton_.matrix.block(i * m, j * m, m, m) = (-h * a_[i][j]) * jacobian_;
        newton_.matrix.diagonal().array() += real(1);
        const Eigen::Index bad = newton_.factor();
        if (bad >= 0)
            throw integration_error("gauss_collocation_stepper: the Newton matrix I - dt A (x) J is singular or "
                                    "not finite at dt = " + detail::number(dt) +
                                    " (pivot " + detail::number_text(newton_.matrix(bad, bad)) +
                                    "); expected a finite Jacobian of the vector field at the step's start",
                                    0, t);
    }

    system_type h_;
    gauss_tableau tableau_;
    gauss_options options_;
    double tolerance_ = 0;
    std::array<real, 3> c_{}, d_{};
    std::array<std::array<real, 3>, 3> a_{};
    Eigen::Index n_ = -1;
    detail::newton_lu<real> newton_;
    real_matrix jacobian_;
    Eigen::Matrix<real, Eigen::Dynamic, 1> f0_;
    stage_vector z_, dz_, f_;
    vector yq_, yp_, gq_, gp_;
    jacobian_vector jq_, jp_, jgq_, jgp_;
    int last_iterations_ = 0;
    double last_residual_ = 0;
    std::uint64_t dH_dq_evaluations_ = 0, dH_dp_evaluations_ = 0, jacobian_evaluations_ = 0;
};

// Deduction helper: make_gauss_collocation<State>(h, 3) is the 6th-order method.
template <class State, class H>
gauss_collocation_stepper<H, State> make_gauss_collocation(H h, int stages, gauss_options options = {}) {
    return gauss_collocation_stepper<H, State>(std::move(h), stages, options);
}

}  // namespace sympl
