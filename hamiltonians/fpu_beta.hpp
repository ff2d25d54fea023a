#pragma once
// Fermi-Pasta-Ulam-Tsingou beta chain with fixed ends (Fermi, Pasta & Ulam 1955,
// Los Alamos report LA-1940): N unit masses, q_0 = q_{N+1} = 0,
//     H = |p|^2/2 + sum_{i=0}^{N} [ r_i^2/2 + beta r_i^4/4 ],  r_i = q_{i+1} - q_i.
#include <cmath>

#include <Eigen/Core>

namespace sympl::hamiltonians {

struct fpu_beta {
    double beta = 1.0;

    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> auto potential(const V& q) const {
        using S = typename V::Scalar;
        const Eigen::Index n = q.size();
        S v(0);
        for (Eigen::Index i = 0; i <= n; ++i) {
            const S r = (i < n ? q[i] : S(0)) - (i > 0 ? q[i - 1] : S(0));
            const S r2 = r * r;
            v += r2 / 2 + r2 * r2 * (beta / 4);
        }
        return v;
    }
    template <class V> const V& velocity(const V& p) const { return p; }  // unit mass
    // f_i = phi'(r_i) - phi'(r_{i-1}) with phi'(r) = r + beta r^3, r_i = q_{i+1} - q_i.
    template <class V> void force(const V& q, V& f) const {
        using S = typename V::Scalar;
        const Eigen::Index n = q.size();
        f.resize(n);
        if (n == 0) return;
        S left = q[0] + S(beta) * q[0] * q[0] * q[0];  // spring to the left wall: r = q_1 - 0
        for (Eigen::Index i = 0; i + 1 < n; ++i) {
            const S r = q[i + 1] - q[i];
            const S right = r + S(beta) * r * r * r;
            f[i] = right - left;
            left = right;
        }
        const S r = -q[n - 1];  // spring to the right wall
        f[n - 1] = (r + S(beta) * r * r * r) - left;
    }
    // df = J_F(q) u for force-gradient tables, one pass as the force:
    // df_i = phi''(r_i) (u_{i+1} - u_i) - phi''(r_{i-1}) (u_i - u_{i-1}), phi''(r) = 1 + 3 beta r^2.
    template <class V> void force_derivative(const V& q, const V& u, V& df) const {
        using S = typename V::Scalar;
        const Eigen::Index n = q.size();
        df.resize(n);
        if (n == 0) return;
        S left = (1 + 3 * S(beta) * q[0] * q[0]) * u[0];
        for (Eigen::Index i = 0; i + 1 < n; ++i) {
            const S r = q[i + 1] - q[i];
            const S right = (1 + 3 * S(beta) * r * r) * (u[i + 1] - u[i]);
            df[i] = right - left;
            left = right;
        }
        const S r = -q[n - 1];
        df[n - 1] = (1 + 3 * S(beta) * r * r) * (-u[n - 1]) - left;
    }
};

}  // namespace sympl::hamiltonians
