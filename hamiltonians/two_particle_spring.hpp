#pragma once
// Gould & Tobochnik's two particles A and B in the plane joined by a spring (Gould & Tobochnik ch. 3,
// eq. 3.72): q = (x_A, y_A, x_B, y_B),
//     H = |p|^2/(2m) + k/2 [(q1 - q3)^2 + (q2 - q4)^2],
// with its exact solution: the centre of mass moves uniformly and the relative
// coordinate q_A - q_B oscillates with omega = sqrt(2k/m) (reduced mass m/2).
#include <cmath>

#include <sympl/core/phase_space.hpp>

namespace sympl::hamiltonians {

struct two_particle_spring {
    static constexpr int dimension = 4;  // q = (x1, y1, x2, y2)
    double mass = 1.0;       // each particle (Gould & Tobochnik take unit mass)
    double stiffness = 1.0;  // k

    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / (2 * mass); }
    template <class V> auto potential(const V& q) const {
        const auto dx = q[0] - q[2], dy = q[1] - q[3];
        return (0.5 * stiffness) * (dx * dx + dy * dy);
    }
    template <class V> auto velocity(const V& p) const { return p * (1 / mass); }  // no division on the step's chain
    template <class V> void force(const V& q, V& f) const {
        using S = typename V::Scalar;
        const S fx = S(-stiffness) * (q[0] - q[2]), fy = S(-stiffness) * (q[1] - q[3]);
        f.resize(4);
        f << fx, fy, -fx, -fy;
    }

    // A default state: B at rest at the origin, A stretched along x and moving
    // along y, so the spring both oscillates and rotates while the pair drifts.
    template <class S = double>
    static phase_space<S, 4> initial_state() {
        return phase_space<S, 4>(Eigen::Matrix<S, 4, 1>(S(1.5), S(0), S(0), S(0)),
                                 Eigen::Matrix<S, 4, 1>(S(0), S(0.6), S(0), S(0)));
    }

    template <class S, int D>
    phase_space<S, D> exact(const phase_space<S, D>& x0, S t) const {
        using std::cos; using std::sin; using std::sqrt;
        using V2 = Eigen::Matrix<S, 2, 1>;
        const S m(mass), mu = m / 2, w = sqrt(2 * S(stiffness) / m), c = cos(w * t), s = sin(w * t);
        const V2 qa = x0.q.template head<2>(), qb = x0.q.template tail<2>();
        const V2 pa = x0.p.template head<2>(), pb = x0.p.template tail<2>();
        const V2 P = pa + pb, R = (qa + qb) / 2 + P * (t / (2 * m));  // centre of mass
        const V2 r0 = qa - qb, pi0 = (pa - pb) / 2;                   // relative coordinate and momentum
        const V2 r = r0 * c + pi0 * (s / (mu * w)), pi = pi0 * c - r0 * (mu * w * s);
        phase_space<S, D> x = x0;
        x.q << R + r / 2, R - r / 2;
        x.p << P / 2 + pi, P / 2 - pi;
        return x;
    }
};

}  // namespace sympl::hamiltonians
