#pragma once
// The outer solar system: the Sun (with the inner planets' mass added),
// Jupiter, Saturn, Uranus, Neptune and Pluto as point masses in 3-D,
//     H = sum_i |p_i|^2 / (2 m_i) - G sum_{i<j} m_i m_j / |q_i - q_j|,
// q = (x_0, y_0, z_0, x_1, ...). Data of Hairer, Lubich & Wanner, Geometric
// Numerical Integration (2nd ed. 2006), ch. I.2.4, Table 2.2: masses relative to
// the Sun, distances in AU, time in days, G = 2.95912208286e-4; positions and
// velocities at 5 September 1994, 0h00 GST. No exact solution.
#include <array>
#include <cmath>

#include <sympl/core/phase_space.hpp>

namespace sympl::hamiltonians {

struct outer_solar_system {
    static constexpr int bodies = 6;
    static constexpr int dimension = 3 * bodies;
    double G = 2.95912208286e-4;
    std::array<double, bodies> mass{1.00000597682,       // Sun (+ inner planets)
                                    0.000954786104043,   // Jupiter
                                    0.000285583733151,   // Saturn
                                    0.0000437273164546,  // Uranus
                                    0.0000517759138449,  // Neptune
                                    1.0 / 1.3e8};        // Pluto

    template <class V> auto kinetic(const V& p) const {
        typename V::Scalar t(0);
        for (int i = 0; i < bodies; ++i) t += p.template segment<3>(3 * i).squaredNorm() / (2 * mass[i]);
        return t;
    }
    template <class V> auto potential(const V& q) const {
        using std::sqrt;
        typename V::Scalar v(0);
        for (int i = 0; i < bodies; ++i)
            for (int j = i + 1; j < bodies; ++j)
                v -= G * mass[i] * mass[j] / sqrt((q.template segment<3>(3 * i) - q.template segment<3>(3 * j)).squaredNorm());
        return v;
    }
    template <class V> void velocity(const V& p, V& v) const {
        v.resize(dimension);  // products with reciprocals: no division on the step's chain
        for (int i = 0; i < bodies; ++i) v.template segment<3>(3 * i) = p.template segment<3>(3 * i) * (1 / mass[i]);
    }
    template <class V> void force(const V& q, V& f) const {
        using S = typename V::Scalar;
        using std::sqrt;
        f.setZero(dimension);
        for (int i = 0; i < bodies; ++i)
            for (int j = i + 1; j < bodies; ++j) {
                const Eigen::Matrix<S, 3, 1> d = q.template segment<3>(3 * i) - q.template segment<3>(3 * j);
                const S r2 = d.squaredNorm();
                const Eigen::Matrix<S, 3, 1> g = d * (S(G * mass[i] * mass[j]) / (r2 * sqrt(r2)));
                f.template segment<3>(3 * i) -= g;
                f.template segment<3>(3 * j) += g;
            }
    }

    // GNI Table 2.2 (momenta p_i = m_i v_i).
    template <class S = double>
    phase_space<S, dimension> initial_state() const {
        static constexpr double q0[bodies][3] = {{0, 0, 0},
                                                 {-3.5023653, -3.8169847, -1.5507963},
                                                 {9.0755314, -3.0458353, -1.6483708},
                                                 {8.3101420, -16.2901086, -7.2521278},
                                                 {11.4707666, -25.7294829, -10.8169456},
                                                 {-15.5387357, -25.2225594, -3.1902382}};
        static constexpr double v0[bodies][3] = {{0, 0, 0},
                                                 {0.00565429, -0.00412490, -0.00190589},
                                                 {0.00168318, 0.00483525, 0.00192462},
                                                 {0.00354178, 0.00137102, 0.00055029},
                                                 {0.00288930, 0.00114527, 0.00039677},
                                                 {0.00276725, -0.00170702, -0.00136504}};
        phase_space<S, dimension> x;
        for (int i = 0; i < bodies; ++i)
            for (int k = 0; k < 3; ++k) {
                x.q[3 * i + k] = S(q0[i][k]);
                x.p[3 * i + k] = S(mass[i]) * S(v0[i][k]);
            }
        return x;
    }
};

}  // namespace sympl::hamiltonians
