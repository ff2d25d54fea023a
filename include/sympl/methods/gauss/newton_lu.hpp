#pragma once
// The LU factorisation with partial pivoting of the simplified Newton matrix
// I - dt (A (x) J) of an implicit Runge-Kutta method (Hairer & Wanner, Solving
// ODEs II, sec. IV.8), in place, and the solve with its factors on stage
// vectors of any scalar (dual numbers too): sized once, no allocation after.
#include <cmath>
#include <utility>

#include <Eigen/Core>

namespace sympl::detail {

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
    // v <- matrix^-1 v, with the factors of factor(). The row swaps moved the
    // multipliers of L along with the rows (P A = L U), so every swap is applied
    // to v before the forward substitution.
    template <class Vec>
    void solve(Vec& v) const {
        const Eigen::Index N = v.size();
        for (Eigen::Index k = 0; k < N; ++k)
            if (pivot[k] != k) std::swap(v[k], v[pivot[k]]);
        for (Eigen::Index k = 0; k < N; ++k)
            for (Eigen::Index r = k + 1; r < N; ++r)
                if (matrix(r, k) != Real(0)) v[r] -= matrix(r, k) * v[k];
        for (Eigen::Index k = N - 1; k >= 0; --k) {
            for (Eigen::Index c = k + 1; c < N; ++c) v[k] -= matrix(k, c) * v[c];
            v[k] = v[k] / matrix(k, k);
        }
    }
};
}  // namespace sympl::detail
