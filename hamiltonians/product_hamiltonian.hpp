#pragma once
// H = (1 + |q|^2)(1 + |p|^2) / 2 in any dimension: the standard non-separable
// test problem of Tao, Phys. Rev. E 94, 043303 (2016) (there with one degree
// of freedom), also used by Jayawardana & Ohsawa, Math. Comp. 92 (2023).
// Hamilton's equations
//     dq/dt = (1 + |q|^2) p,   dp/dt = -(1 + |p|^2) q
// turn (q, p) around the origin, faster at larger amplitude (the period
// depends on H: a nonlinear oscillator); H itself is the invariant a method
// should keep, and with one degree of freedom the orbits are its closed level
// curves.
#include <Eigen/Core>

namespace sympl::hamiltonians {

struct product_hamiltonian {
    template <class V> auto energy(const V& q, const V& p) const {
        using S = typename V::Scalar;
        return S((1 + q.squaredNorm()) * (1 + p.squaredNorm()) / 2);
    }
    template <class V> void dH_dq(const V& q, const V& p, V& out) const {
        using S = typename V::Scalar;
        out = q * S(1 + p.squaredNorm());
    }
    template <class V> void dH_dp(const V& q, const V& p, V& out) const {
        using S = typename V::Scalar;
        out = p * S(1 + q.squaredNorm());
    }
};

}  // namespace sympl::hamiltonians
