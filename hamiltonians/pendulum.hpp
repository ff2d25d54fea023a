#pragma once
// Plane pendulum H = p^2/(2 m l^2) + m g l (1 - cos q) per component (q: angle).
// The standard nonlinear test with quadratic kinetic energy.
#include <cmath>

#include <sympl/core/phase_space.hpp>

namespace sympl::hamiltonians {

struct pendulum {
    double mass = 1.0;
    double length = 1.0;
    double gravity = 1.0;

    double inertia() const { return mass * length * length; }
    double stiffness() const { return mass * gravity * length; }

    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / (2 * inertia()); }
    template <class V> auto potential(const V& q) const {
        using std::cos;
        typename V::Scalar v(0);
        for (Eigen::Index i = 0; i < q.size(); ++i) v += 1 - cos(q[i]);
        return v * stiffness();
    }
    // times the reciprocal: the division leaves the chain force -> velocity -> next
    // force that a small system's step waits on (docs/rkn.md)
    template <class V> auto velocity(const V& p) const { return p * (1 / inertia()); }
    template <class V> void force(const V& q, V& f) const {
        using std::sin;
        f.resize(q.size());
        for (Eigen::Index i = 0; i < q.size(); ++i) f[i] = -stiffness() * sin(q[i]);
    }
};

}  // namespace sympl::hamiltonians
