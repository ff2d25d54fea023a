#pragma once
// Periodic Toda lattice (Toda 1967, J. Phys. Soc. Japan 22, 431): N unit
// masses on a ring, H = |p|^2/2 + sum_i exp(q_i - q_{i+1}), q_{N+1} = q_1.
// Integrable (Henon 1974; Flaschka 1974): the traces of powers of the Lax
// matrix are conserved; the exact motion is not elementary.
#include <cmath>

#include <Eigen/Core>

namespace sympl::hamiltonians {

struct toda {
    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> auto potential(const V& q) const {
        using std::exp;
        const Eigen::Index n = q.size();
        typename V::Scalar v(0);
        for (Eigen::Index i = 0; i < n; ++i) v += exp(q[i] - q[(i + 1) % n]);
        return v;
    }
    template <class V> const V& velocity(const V& p) const { return p; }
    template <class V> void force(const V& q, V& f) const {
        using std::exp;
        const Eigen::Index n = q.size();
        f.setZero(n);
        for (Eigen::Index i = 0; i < n; ++i) {
            const auto e = exp(q[i] - q[(i + 1) % n]);  // bond (i, i+1) pushes i back, i+1 forward
            f[i] -= e;
            f[(i + 1) % n] += e;
        }
    }
};

}  // namespace sympl::hamiltonians
