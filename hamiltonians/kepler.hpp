#pragma once
// Kepler problem H = |p|^2/2 - mu/|q| (Hairer, Lubich & Wanner, Geometric
// Numerical Integration, ch. I.2.3) in the plane or in space (the same H for a
// 2-D or 3-D state), with the exact orbit from Kepler's equation for the
// standard initial data of eccentricity e; in 3-D the orbit is turned by the
// classical angles (argument of pericentre, inclination, ascending node).
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>

#include <sympl/core/dual.hpp>
#include <sympl/core/error.hpp>
#include <sympl/core/phase_space.hpp>

namespace sympl::hamiltonians {

struct kepler {
    double mu = 1.0;

    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> auto potential(const V& q) const {
        using std::sqrt;
        return -mu / sqrt(q.squaredNorm());
    }
    template <class V> const V& velocity(const V& p) const { return p; }  // unit mass
    template <class V> void force(const V& q, V& f) const {
        using std::sqrt;
        const auto r2 = q.squaredNorm();
        const auto inv_r3 = 1 / (r2 * sqrt(r2));
        f = q * (-mu * inv_r3);
    }
    // -dV/dq and V from one square root (time_transformation.hpp's LogH needs both at every kick).
    template <class V> auto force_and_potential(const V& q, V& f) const {
        using std::sqrt;
        const auto inv_r = 1 / sqrt(q.squaredNorm());
        f = q * (-mu * inv_r * inv_r * inv_r);
        return -mu * inv_r;
    }

    // Pericentre of an orbit with semi-major axis 1 and eccentricity e:
    // q = (1 - e, 0), p = (0, sqrt((1 + e)/(1 - e))) (GNI eq. I.2.12), period 2 pi for mu = 1.
    template <class S = double>
    static phase_space<S, 2> initial_state(double e) {
        if (!(e >= 0 && e < 1))
            throw invalid_argument("kepler: eccentricity e = " + std::to_string(e) + "; expected 0 <= e < 1");
        using std::sqrt;
        return phase_space<S, 2>(Eigen::Matrix<S, 2, 1>(S(1 - e), S(0)),
                                 Eigen::Matrix<S, 2, 1>(S(0), sqrt(S(1 + e) / S(1 - e))));
    }

    // Exact state at time t on the orbit started by initial_state(e), mu = 1:
    // E - e sin E = t (Kepler's equation), solved by Newton's method.
    template <class S = double>
    static phase_space<S, 2> exact_state(double e, S t) {
        using std::cos;
        using std::sin;
        using std::sqrt;
        using std::fabs;
        const S ecc(e);
        S E = (e < 0.8) ? t : pi_of<S>();
        for (int i = 0; i < 100; ++i) {
            const S dE = (E - ecc * sin(E) - t) / (1 - ecc * cos(E));
            E -= dE;
            if (fabs(dE) <= 4 * std::numeric_limits<S>::epsilon() * (1 + fabs(E))) break;
        }
        const S c = cos(E), s = sin(E), b = sqrt(1 - ecc * ecc), d = 1 - ecc * c;
        return phase_space<S, 2>(Eigen::Matrix<S, 2, 1>(c - ecc, b * s), Eigen::Matrix<S, 2, 1>(-s / d, b * c / d));
    }

    // The planar orbit turned into space: R = Rz(node) Rx(inclination) Rz(periapsis).
    template <class S = double>
    static phase_space<S, 3> initial_state_3d(double e, double inclination, double node, double periapsis) {
        return to_space(initial_state<S>(e), inclination, node, periapsis);
    }
    template <class S = double>
    static phase_space<S, 3> exact_state_3d(double e, double inclination, double node, double periapsis, S t) {
        return to_space(exact_state<S>(e, t), inclination, node, periapsis);
    }

private:
    template <class S>
    static phase_space<S, 3> to_space(const phase_space<S, 2>& x, double inclination, double node, double periapsis) {
        const Eigen::Matrix3d r = (Eigen::AngleAxisd(node, Eigen::Vector3d::UnitZ()) *
                                   Eigen::AngleAxisd(inclination, Eigen::Vector3d::UnitX()) *
                                   Eigen::AngleAxisd(periapsis, Eigen::Vector3d::UnitZ()))
                                      .toRotationMatrix();
        const Eigen::Matrix<S, 3, 3> R = r.cast<S>();
        return phase_space<S, 3>(R * Eigen::Matrix<S, 3, 1>(x.q[0], x.q[1], S(0)),
                                 R * Eigen::Matrix<S, 3, 1>(x.p[0], x.p[1], S(0)));
    }
};

}  // namespace sympl::hamiltonians
