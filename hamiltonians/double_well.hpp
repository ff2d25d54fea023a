#pragma once
// Symmetric double well, per component: H = p^2/2 + barrier (q^2 - 1)^2, wells
// at q = +-1 separated by a barrier of height `barrier` at q = 0 (the quartic
// Duffing potential with negative linear stiffness). Its motion is given by
// Jacobi elliptic functions; sympl uses numerical references for it.
#include <cmath>

#include <Eigen/Core>

namespace sympl::hamiltonians {

struct double_well {
    double barrier = 1.0;

    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> auto potential(const V& q) const {
        typename V::Scalar v(0);
        for (Eigen::Index i = 0; i < q.size(); ++i) {
            const auto s = q[i] * q[i] - 1;
            v += barrier * s * s;
        }
        return v;
    }
    template <class V> const V& velocity(const V& p) const { return p; }
    template <class V> void force(const V& q, V& f) const {
        f.resize(q.size());
        for (Eigen::Index i = 0; i < q.size(); ++i) f[i] = -4 * barrier * q[i] * (q[i] * q[i] - 1);
    }
};

}  // namespace sympl::hamiltonians
