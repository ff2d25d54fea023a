#pragma once
// The planar double pendulum: masses m1, m2 on massless rods l1, l2, angles
// theta1, theta2 from the downward vertical, in canonical coordinates
// q = (theta1, theta2) and their conjugate momenta p = M(q) dq/dt. From the
// Lagrangian L = (1/2) dq^T M(q) dq - V(q) with
//     M = [[(m1 + m2) l1^2, m2 l1 l2 cos d], [m2 l1 l2 cos d, m2 l2^2]],   d = theta1 - theta2,
// the Legendre transform gives T = (1/2) p^T M^-1 p (Goldstein, Poole & Safko,
// Classical Mechanics, 3rd ed., sec. 8.1), det M = m2 l1^2 l2^2 (m1 + m2 sin^2 d):
//     H = [m2 l2^2 p1^2 + (m1 + m2) l1^2 p2^2 - 2 m2 l1 l2 p1 p2 cos d]
//         / [2 m2 l1^2 l2^2 (m1 + m2 sin^2 d)]
//       + (m1 + m2) g l1 (1 - cos theta1) + m2 g l2 (1 - cos theta2)
// (the same H as Stachowiak & Okada, Chaos Solitons Fractals 29, 417 (2006),
// with V shifted to vanish at rest). Not separable: T depends on d; chaotic
// at energies of the order of the potential's range.
#include <cmath>

#include <Eigen/Core>

namespace sympl::hamiltonians {

struct double_pendulum {
    double mass1 = 1.0;
    double mass2 = 1.0;
    double length1 = 1.0;
    double length2 = 1.0;
    double gravity = 1.0;
    static constexpr int dimension = 2;

    template <class V> auto energy(const V& q, const V& p) const {
        using S = typename V::Scalar;
        using std::cos;
        using std::sin;
        const S d = q[0] - q[1], c = cos(d), s = sin(d);
        const S numerator = kinetic_numerator(p, c);
        const S denominator = S(2 * mass2 * length1 * length1 * length2 * length2) * (S(mass1) + S(mass2) * s * s);
        return S(numerator / denominator + S((mass1 + mass2) * gravity * length1) * (1 - cos(q[0])) +
                 S(mass2 * gravity * length2) * (1 - cos(q[1])));
    }
    // dH/dp = M^-1 p.
    template <class V> void dH_dp(const V& q, const V& p, V& out) const {
        using S = typename V::Scalar;
        using std::cos;
        using std::sin;
        const S d = q[0] - q[1], c = cos(d), s = sin(d);
        const S denominator = S(2 * mass2 * length1 * length1 * length2 * length2) * (S(mass1) + S(mass2) * s * s);
        const S k12(mass2 * length1 * length2);
        out.resize(2);
        out[0] = 2 * (S(mass2 * length2 * length2) * p[0] - k12 * c * p[1]) / denominator;
        out[1] = 2 * (S((mass1 + mass2) * length1 * length1) * p[1] - k12 * c * p[0]) / denominator;
    }
    // dH/dtheta1 = dT/dd + (m1 + m2) g l1 sin theta1, dH/dtheta2 = -dT/dd + m2 g l2 sin theta2,
    // dT/dd = (N' D - N D') / D^2 with N' = 2 m2 l1 l2 p1 p2 sin d, D' = 4 m2^2 l1^2 l2^2 sin d cos d.
    template <class V> void dH_dq(const V& q, const V& p, V& out) const {
        using S = typename V::Scalar;
        using std::cos;
        using std::sin;
        const S d = q[0] - q[1], c = cos(d), s = sin(d);
        const S k(2 * mass2 * length1 * length1 * length2 * length2);
        const S denominator = k * (S(mass1) + S(mass2) * s * s);
        const S numerator = kinetic_numerator(p, c);
        const S dN = S(2 * mass2 * length1 * length2) * p[0] * p[1] * s;
        const S dD = k * S(2 * mass2) * s * c;
        const S dT = (dN * denominator - numerator * dD) / (denominator * denominator);
        out.resize(2);
        out[0] = dT + S((mass1 + mass2) * gravity * length1) * sin(q[0]);
        out[1] = -dT + S(mass2 * gravity * length2) * sin(q[1]);
    }

private:
    template <class V, class S> S kinetic_numerator(const V& p, const S& c) const {
        return S(mass2 * length2 * length2) * p[0] * p[0] + S((mass1 + mass2) * length1 * length1) * p[1] * p[1] -
               S(2 * mass2 * length1 * length2) * p[0] * p[1] * c;
    }
};

}  // namespace sympl::hamiltonians
