#pragma once
// Coordinates of planetary systems: a star (body 0, mass m_0) and N planets
// (bodies 1..N), as the Wisdom-Holman splittings need them, and the checks
// of masses and states every planetary header shares.
//
// A state is a phase_space of 3 (N + 1) degrees of freedom laid out as in
// hamiltonians/outer_solar_system.hpp: q = (x_0, y_0, z_0, x_1, ...), p the
// momenta m_i v_i. "Inertial" is any inertial frame (barycentric or not).
//
// Democratic heliocentric coordinates (Duncan, Levison & Lee 1998, AJ 116,
// 2067, eq. 2-3): heliocentric positions with barycentric momenta,
//     Q_0 = sum_j m_j x_j / M   (centre of mass),    Q_i = x_i - x_0,
//     P_0 = sum_j p_j           (total momentum),    P_i = p_i - m_i P_0 / M,
// M = sum_j m_j. Then H = |P_0|^2 / 2M + sum_i |P_i|^2 / 2m_i + |sum_i P_i|^2 / 2m_0 + V(Q).
//
// Jacobi coordinates (Wisdom & Holman 1991, AJ 102, 1528, sec. 3; Plummer 1960):
// eta_i = m_0 + ... + m_i the interior masses, X_i the centre of mass of
// bodies 0..i;
//     Q_0 = X_N,   Q_i = x_i - X_{i-1},   Jacobi masses m'_0 = eta_N, m'_i = m_i eta_{i-1} / eta_i,
//     P_0 = sum_j p_j,   P_i = m'_i dQ_i/dt = p_i - m_i (p_0 + ... + p_i) / eta_i.
// The kinetic energy keeps its form, sum_i |P_i|^2 / 2m'_i.
//
// Masses must be finite and > 0; a mass that is not is an invalid_argument
// naming the body and the value.
#include <cmath>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "../core/error.hpp"
#include "../core/phase_space.hpp"

namespace sympl {

namespace detail {
// Every mass finite and > 0, and at least `least` of them (2: a star and a planet).
inline void check_masses(std::span<const double> mass, const std::string& who, std::size_t least = 2) {
    if (mass.size() < least)
        throw invalid_argument(who + ": " + std::to_string(mass.size()) +
                               " masses; expected a star and at least one planet");
    for (std::size_t i = 0; i < mass.size(); ++i)
        if (!(std::isfinite(mass[i]) && mass[i] > 0))
            throw invalid_argument(who + ": mass of body " + std::to_string(i) + " = " + number_text(mass[i]) +
                                   "; expected a finite mass > 0");
}

// A state of 3 degrees of freedom per body for masses that check_masses accepts.
template <class S, int D>
std::size_t checked_bodies(const phase_space<S, D>& x, std::span<const double> mass, const std::string& who) {
    if (mass.size() >= 2 && x.size() != Eigen::Index(3 * mass.size()))
        throw invalid_argument(who + ": a state of " + std::to_string(x.size()) + " degrees of freedom for " +
                               std::to_string(mass.size()) + " bodies; expected 3 per body, " +
                               std::to_string(3 * mass.size()));
    check_masses(mass, who);
    return mass.size();
}

// checked_bodies, and every coordinate finite, no two bodies at one position.
template <class S, int D>
std::size_t checked_finite_bodies(const phase_space<S, D>& x, std::span<const double> mass, const std::string& who) {
    const std::size_t bodies = checked_bodies(x, mass, who);
    const char* axis[] = {"x", "y", "z"};
    for (std::size_t i = 0; i < bodies; ++i)
        for (int k = 0; k < 3; ++k) {
            const Eigen::Index c = Eigen::Index(3 * i) + k;
            if (!std::isfinite(x.q[c]))
                throw invalid_argument(who + ": position " + axis[k] + " of body " + std::to_string(i) + " = " +
                                       number_text(x.q[c]) + "; expected a finite number");
            if (!std::isfinite(x.p[c]))
                throw invalid_argument(who + ": momentum " + axis[k] + " of body " + std::to_string(i) + " = " +
                                       number_text(x.p[c]) + "; expected a finite number");
        }
    for (std::size_t i = 1; i < bodies; ++i)
        for (std::size_t j = 0; j < i; ++j) {
            const Eigen::Index c = Eigen::Index(3 * i);
            const auto d = (x.q.template segment<3>(c) - x.q.template segment<3>(Eigen::Index(3 * j))).eval();
            if (!(d.squaredNorm() > 0))
                throw invalid_argument(who + ": body " + std::to_string(i) + " is at the position of body " +
                                       std::to_string(j) + (j == 0 ? " (the star)" : "") + ", (" +
                                       number_text(x.q[c]) + ", " + number_text(x.q[c + 1]) + ", " +
                                       number_text(x.q[c + 2]) + "); expected distinct positions");
        }
    return bodies;
}

template <class S, int D>
Eigen::Matrix<S, 3, 1> body3(const typename phase_space<S, D>::vector& v, std::size_t i) {
    return v.template segment<3>(Eigen::Index(3 * i));
}
}  // namespace detail

// Interior masses eta_i = m_0 + ... + m_i (Wisdom & Holman 1991, sec. 3).
inline std::vector<double> interior_masses(std::span<const double> mass) {
    std::vector<double> eta(mass.size());
    double sum = 0;
    for (std::size_t i = 0; i < mass.size(); ++i) eta[i] = sum += mass[i];
    return eta;
}

// Jacobi masses m'_0 = eta_N, m'_i = m_i eta_{i-1} / eta_i (Wisdom & Holman 1991, eq. 9).
inline std::vector<double> jacobi_masses(std::span<const double> mass) {
    detail::check_masses(mass, "jacobi_masses", 0);
    const std::vector<double> eta = interior_masses(mass);
    std::vector<double> m(mass.size());
    if (mass.empty()) return m;
    m[0] = eta.back();
    for (std::size_t i = 1; i < mass.size(); ++i) m[i] = mass[i] * (eta[i - 1] / eta[i]);
    return m;
}

// Inertial -> democratic heliocentric (Duncan, Levison & Lee 1998, eq. 2-3).
template <class S, int D>
phase_space<S, D> to_democratic_heliocentric(const phase_space<S, D>& x, std::span<const double> mass) {
    const std::size_t n = detail::checked_bodies(x, mass, "to_democratic_heliocentric");
    S total_mass(0);
    Eigen::Matrix<S, 3, 1> centre = Eigen::Matrix<S, 3, 1>::Zero(), momentum = centre;
    for (std::size_t i = 0; i < n; ++i) {
        total_mass += S(mass[i]);
        centre += S(mass[i]) * detail::body3<S, D>(x.q, i);
        momentum += detail::body3<S, D>(x.p, i);
    }
    phase_space<S, D> y = x;
    const Eigen::Matrix<S, 3, 1> star = detail::body3<S, D>(x.q, 0);
    y.q.template segment<3>(0) = centre / total_mass;
    y.p.template segment<3>(0) = momentum;
    for (std::size_t i = 1; i < n; ++i) {
        y.q.template segment<3>(Eigen::Index(3 * i)) = detail::body3<S, D>(x.q, i) - star;
        y.p.template segment<3>(Eigen::Index(3 * i)) =
            detail::body3<S, D>(x.p, i) - momentum * (S(mass[i]) / total_mass);
    }
    return y;
}

// Democratic heliocentric -> inertial: x_0 = Q_0 - sum_i m_i Q_i / M,
// x_i = Q_i + x_0; p_i = P_i + m_i P_0 / M, p_0 = m_0 P_0 / M - sum_i P_i
// (the barycentric momenta sum to zero).
template <class S, int D>
phase_space<S, D> from_democratic_heliocentric(const phase_space<S, D>& y, std::span<const double> mass) {
    const std::size_t n = detail::checked_bodies(y, mass, "from_democratic_heliocentric");
    S total_mass(0);
    for (std::size_t i = 0; i < n; ++i) total_mass += S(mass[i]);
    Eigen::Matrix<S, 3, 1> shift = Eigen::Matrix<S, 3, 1>::Zero(), planets_momentum = shift;
    for (std::size_t i = 1; i < n; ++i) {
        shift += S(mass[i]) * detail::body3<S, D>(y.q, i);
        planets_momentum += detail::body3<S, D>(y.p, i);
    }
    const Eigen::Matrix<S, 3, 1> star = detail::body3<S, D>(y.q, 0) - shift / total_mass;
    const Eigen::Matrix<S, 3, 1> momentum = detail::body3<S, D>(y.p, 0);
    phase_space<S, D> x = y;
    x.q.template segment<3>(0) = star;
    x.p.template segment<3>(0) = momentum * (S(mass[0]) / total_mass) - planets_momentum;
    for (std::size_t i = 1; i < n; ++i) {
        x.q.template segment<3>(Eigen::Index(3 * i)) = detail::body3<S, D>(y.q, i) + star;
        x.p.template segment<3>(Eigen::Index(3 * i)) =
            detail::body3<S, D>(y.p, i) + momentum * (S(mass[i]) / total_mass);
    }
    return x;
}

// Inertial -> Jacobi (Wisdom & Holman 1991, sec. 3), building the centre of
// mass X_{i-1} and the momentum of bodies 0..i outwards.
template <class S, int D>
phase_space<S, D> to_jacobi(const phase_space<S, D>& x, std::span<const double> mass) {
    const std::size_t n = detail::checked_bodies(x, mass, "to_jacobi");
    phase_space<S, D> y = x;
    S eta(mass[0]);
    Eigen::Matrix<S, 3, 1> centre = detail::body3<S, D>(x.q, 0);      // X_{i-1}
    Eigen::Matrix<S, 3, 1> momentum = detail::body3<S, D>(x.p, 0);    // p_0 + ... + p_{i-1}
    for (std::size_t i = 1; i < n; ++i) {
        const S m(mass[i]), eta_next = eta + m;
        const Eigen::Matrix<S, 3, 1> xi = detail::body3<S, D>(x.q, i), pi = detail::body3<S, D>(x.p, i);
        y.q.template segment<3>(Eigen::Index(3 * i)) = xi - centre;
        momentum += pi;
        y.p.template segment<3>(Eigen::Index(3 * i)) = pi - momentum * (m / eta_next);
        centre = (centre * eta + xi * m) / eta_next;
        eta = eta_next;
    }
    y.q.template segment<3>(0) = centre;
    y.p.template segment<3>(0) = momentum;
    return y;
}

// Jacobi -> inertial, inwards: X_{i-1} = X_i - (m_i / eta_i) Q_i, x_i = Q_i + X_{i-1};
// p_i = P_i + (m_i / eta_i) (p_0 + ... + p_i), the inner sum less p_i.
template <class S, int D>
phase_space<S, D> from_jacobi(const phase_space<S, D>& y, std::span<const double> mass) {
    const std::size_t n = detail::checked_bodies(y, mass, "from_jacobi");
    const std::vector<double> eta = interior_masses(mass);
    phase_space<S, D> x = y;
    Eigen::Matrix<S, 3, 1> centre = detail::body3<S, D>(y.q, 0);    // X_i
    Eigen::Matrix<S, 3, 1> momentum = detail::body3<S, D>(y.p, 0);  // p_0 + ... + p_i
    for (std::size_t i = n - 1; i >= 1; --i) {
        const S w = S(mass[i]) / S(eta[i]);
        const Eigen::Matrix<S, 3, 1> qi = detail::body3<S, D>(y.q, i);
        centre -= qi * w;
        x.q.template segment<3>(Eigen::Index(3 * i)) = qi + centre;
        const Eigen::Matrix<S, 3, 1> pi = detail::body3<S, D>(y.p, i) + momentum * w;
        x.p.template segment<3>(Eigen::Index(3 * i)) = pi;
        momentum -= pi;
    }
    x.q.template segment<3>(0) = centre;
    x.p.template segment<3>(0) = momentum;
    return x;
}

}  // namespace sympl
