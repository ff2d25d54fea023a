#pragma once
// A pendulum with relativistic kinetic energy,
//     H = m c^2 sqrt(1 + |p|^2/(m c)^2) + k sum(1 - cos q_i),
// a separable Hamiltonian whose kinetic energy is not quadratic: methods that
// keep their order only for T = p^2/2 (Runge-Kutta-Nystrom methods) lose it here.
#include <cmath>

#include <Eigen/Core>

namespace sympl::hamiltonians {

struct relativistic_pendulum {
    double mass = 1.0;
    double c = 1.0;      // speed of light
    double k = 1.0;      // restoring torque

    template <class V> auto kinetic(const V& p) const {
        using std::sqrt;
        const double mc = mass * c;
        return sqrt(1 + p.squaredNorm() / (mc * mc)) * (mass * c * c);
    }
    template <class V> auto potential(const V& q) const {
        using std::cos;
        typename V::Scalar v(0);
        for (Eigen::Index i = 0; i < q.size(); ++i) v += 1 - cos(q[i]);
        return v * k;
    }
    // dT/dp = p / (m gamma), gamma = sqrt(1 + |p|^2/(m c)^2).
    template <class V> void velocity(const V& p, V& v) const {
        using std::sqrt;
        const double mc = mass * c;
        const auto gamma = sqrt(1 + p.squaredNorm() / (mc * mc));
        v = p / (gamma * mass);
    }
    template <class V> void force(const V& q, V& f) const {
        using std::sin;
        f.resize(q.size());
        for (Eigen::Index i = 0; i < q.size(); ++i) f[i] = -k * sin(q[i]);
    }
};

}  // namespace sympl::hamiltonians
