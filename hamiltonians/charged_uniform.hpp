#pragma once
// A charged particle (mass m, charge e) in uniform fields E and B in space:
// with A = B x q / 2 and phi = -E . q (Goldstein, Poole & Safko, Classical
// Mechanics, 3rd ed., sec. 8.1),
//     H = |p - e A(q)|^2 / (2m) - e E . q,
// or, with a speed of light c > 0, the relativistic
//     H = m c^2 (gamma - 1) - e E . q,   gamma = sqrt(1 + |p - e A|^2 / (m c)^2).
// The particle gyrates about B at e |B| / (gamma m) and its gyration centre
// drifts at E x B / |B|^2 (Jackson, Classical Electrodynamics, 3rd ed., sec.
// 12.3); H is not separable. The gradients are analytic (and templated, so
// dual numbers differentiate them for Gauss-Legendre's Jacobian).
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include <sympl/charged/fields.hpp>
#include <sympl/charged/particle.hpp>

namespace sympl::hamiltonians {

struct charged_uniform {
    double mass = 1.0;
    double charge = 1.0;
    Eigen::Vector3d electric = Eigen::Vector3d::Zero();
    Eigen::Vector3d magnetic = Eigen::Vector3d(0, 0, 1);
    double speed_of_light = 0.0;  // 0: Newton's motion
    static constexpr int dimension = 3;

    charged::particle particle() const {
        return {.mass = mass, .charge = charge,
                .speed_of_light = speed_of_light > 0 ? speed_of_light : std::numeric_limits<double>::infinity()};
    }
    charged::uniform_field electromagnetic_field() const { return {electric, magnetic}; }
    bool relativistic() const { return speed_of_light > 0; }

    // pi = p - e B x q / 2 (= gamma m dq/dt).
    template <class V> V kinetic_momentum(const V& q, const V& p) const {
        using S = typename V::Scalar;
        const S h(charge / 2);
        V pi(3);
        pi[0] = p[0] - h * (S(magnetic[1]) * q[2] - S(magnetic[2]) * q[1]);
        pi[1] = p[1] - h * (S(magnetic[2]) * q[0] - S(magnetic[0]) * q[2]);
        pi[2] = p[2] - h * (S(magnetic[0]) * q[1] - S(magnetic[1]) * q[0]);
        return pi;
    }
    // gamma m: m, or m sqrt(1 + |pi|^2 / (m c)^2).
    template <class S> S inertia(const S& pi2) const {
        using std::sqrt;
        if (!relativistic()) return S(mass);
        return S(mass) * sqrt(1 + pi2 / S(mass * mass * speed_of_light * speed_of_light));
    }

    template <class V> auto energy(const V& q, const V& p) const {
        using S = typename V::Scalar;
        const S pi2 = kinetic_momentum(q, p).squaredNorm();
        const S potential = -S(charge) * (S(electric[0]) * q[0] + S(electric[1]) * q[1] + S(electric[2]) * q[2]);
        if (!relativistic()) return S(pi2 / S(2 * mass) + potential);
        // m c^2 (gamma - 1) = |pi|^2 / (m (gamma + 1)), without cancellation at small |pi|.
        return S(pi2 / (inertia(pi2) + S(mass)) + potential);
    }
    // dH/dp = pi / (gamma m).
    template <class V> void dH_dp(const V& q, const V& p, V& out) const {
        const V pi = kinetic_momentum(q, p);
        out = pi / inertia(pi.squaredNorm());
    }
    // dH/dq = -(e / 2 gamma m) pi x B - e E (dA_i/dq_j = (B x e_j)_i / 2).
    template <class V> void dH_dq(const V& q, const V& p, V& out) const {
        using S = typename V::Scalar;
        const V pi = kinetic_momentum(q, p);
        const S k = S(charge / 2) / inertia(pi.squaredNorm());
        out.resize(3);
        out[0] = -k * (pi[1] * S(magnetic[2]) - pi[2] * S(magnetic[1])) - S(charge * electric[0]);
        out[1] = -k * (pi[2] * S(magnetic[0]) - pi[0] * S(magnetic[2])) - S(charge * electric[1]);
        out[2] = -k * (pi[0] * S(magnetic[1]) - pi[1] * S(magnetic[0])) - S(charge * electric[2]);
    }
};

}  // namespace sympl::hamiltonians
