#pragma once
// The total energy of N point masses with the user's own masses and G,
//     H = sum_i |p_i|^2 / (2 m_i) - sum_{i<j} G m_i m_j / |q_i - q_j|,
// the Hamiltonian the Wisdom-Holman stepper conserves to O(eps h^2) (Wisdom
// & Holman 1991, AJ 102, 1528), beside the built-in
// hamiltonians/outer_solar_system.hpp. The state is the stepper's: inertial
// positions q and momenta p_i = m_i v_i (not velocities), 3 per body, laid
// out as in coordinates.hpp.
#include <cmath>
#include <cstddef>
#include <span>
#include <string>

#include "../core/error.hpp"
#include "../core/phase_space.hpp"
#include "coordinates.hpp"

namespace sympl {

// Masses finite and > 0 (star first, at least two bodies), a state of 3
// degrees of freedom per body and G finite and > 0, else an invalid_argument
// naming the value. Bodies at one position give an infinite energy.
template <class S, int D>
S nbody_energy(std::span<const double> mass, double G, const phase_space<S, D>& x) {
    using std::sqrt;
    const std::size_t n = detail::checked_bodies(x, mass, "nbody_energy");
    if (!(std::isfinite(G) && G > 0))
        throw invalid_argument("nbody_energy: G = " + detail::number_text(G) + "; expected a finite G > 0");
    S kinetic(0), potential(0);
    for (std::size_t i = 0; i < n; ++i)
        kinetic += x.p.template segment<3>(Eigen::Index(3 * i)).squaredNorm() / (2 * mass[i]);
    for (std::size_t i = 0; i < n; ++i)
        for (std::size_t j = i + 1; j < n; ++j)
            potential -= G * mass[i] * mass[j] / sqrt((x.q.template segment<3>(Eigen::Index(3 * i)) -
                                                       x.q.template segment<3>(Eigen::Index(3 * j)))
                                                          .squaredNorm());
    return kinetic + potential;
}

}  // namespace sympl
