#pragma once
// The simplified Newton iteration's frozen part for the stage equations of an
// s-stage implicit Runge-Kutta method on y' = f(y), f = (dH/dp, -dH/dq): the
// Jacobian J = df/dy at one point, from H's gradients carried on dual numbers
// (exact for analytic gradients templated on their scalar), and the LU factors
// of I - dt (A (x) J), kept across iterations and steps until the step size
// changes or the caller marks them stale (Hairer & Wanner, Solving ODEs II,
// sec. IV.8; Hairer, Lubich & Wanner, GNI sec. VIII.6.2). The matrix is
// equilibrated by the components' scales D (|y_k| plus the largest |y| of its
// half, q or p): factored as D^-1 (I - dt A (x) J) D, so that partial
// pivoting is not misled by units (momenta 1e-11 beside positions of 30).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include <Eigen/Core>

#include "../../core/dual.hpp"
#include "../../core/general_hamiltonian.hpp"
#include "newton_lu.hpp"

namespace sympl::detail {

// A matrix in a carried list as the vector of its elements, column by
// column: the list holds no shape. Read back, the elements wait here until
// shape() gives them the rows and columns the list was found to fit.
template <class Matrix>
class carried_elements {
public:
    using value_type = typename std::remove_const_t<Matrix>::Scalar;

    explicit carried_elements(Matrix& m) : m_(m) {}
    Eigen::Index size() const {
        if constexpr (std::is_const_v<Matrix>) return m_.size();
        else return read_.size();
    }
    const value_type* data() const {
        if constexpr (std::is_const_v<Matrix>) return m_.data();
        else return read_.data();
    }
    value_type* data() { return read_.data(); }
    void resize(std::size_t n) { read_.resize(Eigen::Index(n)); }
    void shape(Eigen::Index rows, Eigen::Index cols) {
        m_ = Eigen::Map<const Eigen::Matrix<value_type, Eigen::Dynamic, Eigen::Dynamic>>(read_.data(), rows, cols);
    }

private:
    Matrix& m_;
    Eigen::Matrix<value_type, Eigen::Dynamic, 1> read_;
};

template <class Real, int Dim>
class frozen_newton {
public:
    // The Jacobian's dual numbers: all 2n directions at once for small fixed sizes.
    static constexpr int width = (Dim != Eigen::Dynamic && 2 * Dim <= 16) ? 2 * Dim : 8;
    using jacobian_dual = dual<Real, width>;
    using dual_vector = Eigen::Matrix<jacobian_dual, Dim, 1>;

    void resize(Eigen::Index n, int stages) {
        n_ = n;
        stages_ = stages;
        jacobian_.setZero(2 * n, 2 * n);  // zeros only for carried() before any Jacobian
        scale_.setZero(2 * n);
        lu_.resize(2 * n * stages);
        q_.resize(n);
        p_.resize(n);
        gq_.resize(n);
        gp_.resize(n);
        have_jacobian_ = factored_ = false;
    }

    bool has_jacobian() const { return have_jacobian_; }
    bool factored_for(Real h) const { return factored_ && h == h_; }
    void mark_stale() { have_jacobian_ = factored_ = false; }
    std::uint64_t jacobian_evaluations() const { return jacobians_; }
    std::uint64_t factorizations() const { return factorizations_; }
    void reset_counters() { jacobians_ = factorizations_ = 0; }

    // J = df/dy at the values (q, p), W of the 2n directions at a time.
    template <class H, class Vec>
    void jacobian_at(const H& h, const Vec& q, const Vec& p) {
        constexpr int W = width;
        const Eigen::Index n = n_, m = 2 * n;
        Real block_q = 0, block_p = 0;
        for (Eigen::Index k = 0; k < n; ++k) {
            q_[k] = jacobian_dual(Real(primal(q[k])));
            p_[k] = jacobian_dual(Real(primal(p[k])));
            block_q = std::max(block_q, Real(std::fabs(q_[k].value)));
            block_p = std::max(block_p, Real(std::fabs(p_[k].value)));
        }
        for (Eigen::Index k = 0; k < n; ++k) {
            scale_[k] = std::fabs(q_[k].value) + block_q;
            scale_[n + k] = std::fabs(p_[k].value) + block_p;
            if (!(scale_[k] > 0)) scale_[k] = 1;
            if (!(scale_[n + k] > 0)) scale_[n + k] = 1;
        }
        auto seed = [&](Eigen::Index dir, int slot, Real v) {
            if (dir < n) q_[dir].grad[slot] = v;
            else p_[dir - n].grad[slot] = v;
        };
        for (Eigen::Index start = 0; start < m; start += W) {
            for (int k = 0; k < W && start + k < m; ++k) seed(start + k, k, Real(1));
            sympl::dH_dq(h, q_, p_, gq_);
            sympl::dH_dp(h, q_, p_, gp_);
            for (int k = 0; k < W && start + k < m; ++k) {
                for (Eigen::Index r = 0; r < n; ++r) {
                    const Real column = scale_[start + k];
                    jacobian_(r, start + k) = gp_[r].grad[k] * column / scale_[r];
                    jacobian_(n + r, start + k) = -gq_[r].grad[k] * column / scale_[n + r];
                }
                seed(start + k, k, Real(0));
            }
        }
        ++jacobians_;
        have_jacobian_ = true;
        factored_ = false;
    }

    // Factors D^-1 (I - h (A (x) J)) D; returns the index of a zero or non-finite pivot, or -1.
    template <class Tableau>
    Eigen::Index factor(const Tableau& a, Real h) {
        ++factorizations_;
        return build_and_factor(a, h);
    }
    Real pivot(Eigen::Index k) const { return lu_.matrix(k, k); }
    // D^-1 J D of the last jacobian_at (J's eigenvalues; D: the components' scales).
    const Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic>& scaled_jacobian() const { return jacobian_; }
    const Eigen::Matrix<Real, Eigen::Dynamic, 1>& scales() const { return scale_; }

    // v <- (I - h A (x) J)^-1 v.
    template <class Vec>
    void solve(Vec& v) const {
        const Eigen::Index m = 2 * n_;
        for (Eigen::Index k = 0; k < v.size(); ++k) v[k] = v[k] / scale_[k % m];
        lu_.solve(v);
        for (Eigen::Index k = 0; k < v.size(); ++k) v[k] = v[k] * scale_[k % m];
    }

    // What the next step reads (a checkpoint): the Jacobian, its scales, the
    // step size factored for; the factors themselves are rebuilt on reading
    // (refactor), the same arithmetic on the same numbers, so bit for bit
    // (counters not carried). Read after resize(n, stages).
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.flag(self.have_jacobian_);
        l.flag(self.factored_);
        l.number(self.h_);
        auto jacobian = carried_elements(self.jacobian_);
        l.numbers(jacobian);
        l.numbers(self.scale_);
        const Eigen::Index m = 2 * self.n_;
        l.check(jacobian.size() == m * m && self.scale_.size() == m && (self.have_jacobian_ || !self.factored_),
                "holds a Newton Jacobian of another size than the state's");
        if constexpr (!std::is_const_v<Self>) jacobian.shape(m, m);
    }
    // The factors of a Jacobian read as factored, for the tableau's A; false if singular.
    template <class Tableau>
    bool refactor(const Tableau& a) {
        return !factored_ || build_and_factor(a, h_) < 0;
    }

private:
    template <class Tableau>
    Eigen::Index build_and_factor(const Tableau& a, Real h) {
        const Eigen::Index m = 2 * n_;
        for (int i = 0; i < stages_; ++i)
            for (int j = 0; j < stages_; ++j)
                lu_.matrix.block(i * m, j * m, m, m) = (-h * Real(a[i][j])) * jacobian_;
        lu_.matrix.diagonal().array() += Real(1);
        const Eigen::Index bad = lu_.factor();
        factored_ = bad < 0;
        h_ = h;
        return bad;
    }

    Eigen::Index n_ = 0;
    int stages_ = 0;
    Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic> jacobian_;  // D^-1 J D
    Eigen::Matrix<Real, Eigen::Dynamic, 1> scale_;                  // D
    newton_lu<Real> lu_;
    dual_vector q_, p_, gq_, gp_;
    Real h_ = 0;
    bool have_jacobian_ = false, factored_ = false;
    std::uint64_t jacobians_ = 0, factorizations_ = 0;
};

}  // namespace sympl::detail
