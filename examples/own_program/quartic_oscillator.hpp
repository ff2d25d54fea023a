#pragma once
// A system of one's own, written as sympl's hamiltonians/ are: the quartic
// oscillator H = p^2 / 2 + k q^4 / 4, anharmonic (its period depends on the
// amplitude), so no method is exact on it.
#include <sympl/core/phase_space.hpp>

namespace my {

struct quartic_oscillator {
    double stiffness = 1.0;  // k

    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> auto potential(const V& q) const {
        typename V::Scalar v(0);
        for (Eigen::Index i = 0; i < q.size(); ++i) v += q[i] * q[i] * q[i] * q[i];
        return stiffness * v / 4;
    }
    template <class V> auto velocity(const V& p) const { return p; }
    template <class V> void force(const V& q, V& f) const {
        f.resize(q.size());
        for (Eigen::Index i = 0; i < q.size(); ++i) f[i] = -stiffness * q[i] * q[i] * q[i];
    }
};

}  // namespace my
