#pragma once
// Henon-Heiles system (Henon & Heiles 1964, Astron. J. 69, 73):
//     H = (p1^2 + p2^2)/2 + (q1^2 + q2^2)/2 + q1^2 q2 - q2^3/3.
// Bounded motion for H < 1/6; at H = 1/6 most orbits are chaotic (GNI ch. I.3).
#include <cmath>
#include <string>

#include <sympl/core/error.hpp>
#include <sympl/core/phase_space.hpp>

namespace sympl::hamiltonians {

struct henon_heiles {
    static constexpr int dimension = 2;  // q = (x, y)
    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> auto potential(const V& q) const {
        return (q[0] * q[0] + q[1] * q[1]) / 2 + q[0] * q[0] * q[1] - q[1] * q[1] * q[1] / 3;
    }
    template <class V> const V& velocity(const V& p) const { return p; }
    template <class V> void force(const V& q, V& f) const {
        f.resize(2);
        f[0] = -q[0] - 2 * q[0] * q[1];
        f[1] = -q[1] - q[0] * q[0] + q[1] * q[1];
    }
    // df = J_F(q) u for force-gradient tables: J_F = [[-1 - 2y, -2x], [-2x, -1 + 2y]].
    template <class V> void force_derivative(const V& q, const V& u, V& df) const {
        df[0] = -(1 + 2 * q[1]) * u[0] - 2 * q[0] * u[1];
        df[1] = -2 * q[0] * u[0] + (2 * q[1] - 1) * u[1];
    }

    // A state of the given energy on the section q1 = 0: (q2, p2) chosen, p1 >= 0 from H.
    template <class S = double>
    static phase_space<S, 2> initial_state(double energy = 1.0 / 6, double q2 = 0.1, double p2 = 0.0) {
        const double rest = 2 * energy - p2 * p2 - q2 * q2 + 2 * q2 * q2 * q2 / 3;
        if (!(rest >= 0))
            throw invalid_argument("henon_heiles: energy = " + std::to_string(energy) + " is below the potential at q2 = " +
                                   std::to_string(q2) + ", p2 = " + std::to_string(p2) + "; expected p1^2 >= 0");
        return phase_space<S, 2>(Eigen::Matrix<S, 2, 1>(S(0), S(q2)), Eigen::Matrix<S, 2, 1>(S(std::sqrt(rest)), S(p2)));
    }
};

}  // namespace sympl::hamiltonians
