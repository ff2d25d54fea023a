#pragma once
// The stiff Fermi-Pasta-Ulam problem of Hairer, Lubich & Wanner, Geometric
// Numerical Integration (2nd ed. 2006), ch. I.5.1: 2m unit masses in a line with
// fixed ends, stiff linear springs (q_{2i-1}, q_{2i}) and soft cubic springs between:
//     H = |p|^2/2 + (omega^2/4) sum_{i=1}^m (q_{2i} - q_{2i-1})^2 + sum_{i=0}^m (q_{2i+1} - q_{2i})^4,
// q_0 = q_{2m+1} = 0. The stiff springs oscillate with angular frequency about
// omega, so an explicit method is stable only for omega dt below its stability
// interval (table::stability_interval(); leapfrog: 2).
#include <cmath>

#include <sympl/core/phase_space.hpp>

namespace sympl::hamiltonians {

struct stiff_fpu {
    double omega = 50.0;

    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> auto potential(const V& q) const {
        using S = typename V::Scalar;
        const Eigen::Index n = q.size();  // 2m
        S v(0);
        for (Eigen::Index i = 0; i + 1 < n; i += 2) {
            const S d = q[i + 1] - q[i];
            v += d * d * (omega * omega / 4);
        }
        for (Eigen::Index i = 0; i <= n; i += 2) {  // soft springs: (q_{2i+1} - q_{2i})^4, 0-based pairs (i-1, i)
            const S d = (i < n ? q[i] : S(0)) - (i > 0 ? q[i - 1] : S(0));
            const S d2 = d * d;
            v += d2 * d2;
        }
        return v;
    }
    template <class V> const V& velocity(const V& p) const { return p; }
    template <class V> void force(const V& q, V& f) const {
        using S = typename V::Scalar;
        const Eigen::Index n = q.size();
        f.setZero(n);
        const S k = S(omega * omega / 2);
        for (Eigen::Index i = 0; i + 1 < n; i += 2) {
            const S g = k * (q[i + 1] - q[i]);  // d/dq of (omega^2/4) d^2 is (omega^2/2) d
            f[i] += g;
            f[i + 1] -= g;
        }
        for (Eigen::Index i = 0; i <= n; i += 2) {
            const S d = (i < n ? q[i] : S(0)) - (i > 0 ? q[i - 1] : S(0));
            const S g = 4 * d * d * d;
            if (i < n) f[i] -= g;
            if (i > 0) f[i - 1] += g;
        }
    }

    // GNI ch. I.5.1, m = 3: in the coordinates x_{0,i} = (q_{2i} + q_{2i-1})/sqrt(2),
    // x_{1,i} = (q_{2i} - q_{2i-1})/sqrt(2): x_{0,1} = 1, y_{0,1} = 1, x_{1,1} = 1/omega,
    // y_{1,1} = 1, all others zero.
    template <class S = double, int D = 6>
    phase_space<S, D> initial_state(int pairs = 3) const {
        phase_space<S, D> x(2 * pairs);
        const S r = 1 / std::sqrt(S(2)), w = S(omega);
        x.q[0] = (1 - 1 / w) * r;
        x.q[1] = (1 + 1 / w) * r;
        x.p[0] = 0;
        x.p[1] = 2 * r;
        return x;
    }
};

}  // namespace sympl::hamiltonians
