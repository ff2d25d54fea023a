#pragma once
// Osculating orbital elements to positions and velocities (Murray & Dermott
// 1999, "Solar System Dynamics", sec. 2.8, eq. 2.122 with Kepler's equation
// 2.52), and a population of test particles (test_particles.hpp) made of
// them: a grid over a and e, or any list, each about the star of a planetary
// state. Elliptic orbits only (0 <= e < 1, a > 0); angles in radians.
#include <array>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "../../core/error.hpp"
#include "../coordinates.hpp"
#include "../test_particles/test_particles.hpp"

namespace sympl {

struct orbital_elements {
    double a = 1, e = 0;
    double inclination = 0, node = 0, pericentre = 0;  // i, Omega, omega
    double mean_anomaly = 0;                            // M
};

// Position and velocity relative to the central mass GM of the orbit `o`.
inline std::pair<std::array<double, 3>, std::array<double, 3>> to_cartesian(const orbital_elements& o, double gm) {
    const std::string who = "to_cartesian: ";
    if (!(std::isfinite(o.a) && o.a > 0))
        throw invalid_argument(who + "a = " + detail::number_text(o.a) + "; expected a finite a > 0");
    if (!(o.e >= 0 && o.e < 1))
        throw invalid_argument(who + "e = " + detail::number_text(o.e) + "; expected 0 <= e < 1 (elliptic)");
    for (double angle : {o.inclination, o.node, o.pericentre, o.mean_anomaly})
        if (!std::isfinite(angle))
            throw invalid_argument(who + "an angle = " + detail::number_text(angle) + "; expected finite angles");
    if (!(std::isfinite(gm) && gm > 0))
        throw invalid_argument(who + "GM = " + detail::number_text(gm) + "; expected a finite GM > 0");
    // Kepler's equation E - e sin E = M by Newton from E = M + e sin M (M in [-pi, pi]).
    const double pi = std::numbers::pi;
    const double M = std::remainder(o.mean_anomaly, 2 * pi);
    double E = o.e < 0.8 ? M + o.e * std::sin(M) : (M < 0 ? -pi : pi);
    for (int k = 0; k < 50; ++k) {
        const double d = (E - o.e * std::sin(E) - M) / (1 - o.e * std::cos(E));
        E -= d;
        if (std::fabs(d) <= 4e-16 * std::max(1.0, std::fabs(E))) break;
    }
    // In the orbit's plane (x to pericentre), then rotated by omega, i, Omega (MD99 eq. 2.122).
    const double b = o.a * std::sqrt(1 - o.e * o.e), n = std::sqrt(gm / (o.a * o.a * o.a));
    const double cE = std::cos(E), sE = std::sin(E), r = o.a * (1 - o.e * cE);
    const double x = o.a * (cE - o.e), y = b * sE;
    const double vx = -o.a * n * sE * o.a / r, vy = b * n * cE * o.a / r;
    const double cw = std::cos(o.pericentre), sw = std::sin(o.pericentre), cO = std::cos(o.node),
                 sO = std::sin(o.node), ci = std::cos(o.inclination), si = std::sin(o.inclination);
    const double P[3] = {cO * cw - sO * sw * ci, sO * cw + cO * sw * ci, sw * si};
    const double Q[3] = {-cO * sw - sO * cw * ci, -sO * sw + cO * cw * ci, cw * si};
    std::pair<std::array<double, 3>, std::array<double, 3>> rv;
    for (int c = 0; c < 3; ++c) rv.first[c] = x * P[c] + y * Q[c], rv.second[c] = vx * P[c] + vy * Q[c];
    return rv;
}

// Test particles on the orbits `orbits` about the star (body 0) of the
// planetary state x (masses star first, G): heliocentric Keplerian orbits
// about G m_0, placed at the star's inertial position and velocity.
template <class State>
test_particle_set<double> particles_on(const std::vector<orbital_elements>& orbits, const State& x,
                                       const std::vector<double>& mass, double G) {
    detail::checked_finite_bodies(x, mass, "particles_on");
    test_particle_set<double> p;
    for (const orbital_elements& o : orbits) {
        auto [r, v] = to_cartesian(o, G * mass[0]);
        for (int c = 0; c < 3; ++c) r[std::size_t(c)] += x.q[c], v[std::size_t(c)] += x.p[c] / mass[0];
        p.add(r, v);
    }
    return p;
}

// A grid of orbits, a over [a0, a1] (na values) times e over [e0, e1] (ne
// values), a varying fastest; the other elements as in `rest`, the mean
// anomaly spread by the golden angle so that neighbours start apart.
inline std::vector<orbital_elements> element_grid(double a0, double a1, std::size_t na, double e0, double e1,
                                                  std::size_t ne, orbital_elements rest = {}) {
    if (na == 0 || ne == 0)
        throw invalid_argument("element_grid: " + std::to_string(na) + " x " + std::to_string(ne) +
                               " points; expected at least one value of a and of e");
    std::vector<orbital_elements> g;
    const auto at = [](double from, double to, std::size_t k, std::size_t n) {
        return n == 1 ? from : from + (to - from) * double(k) / double(n - 1);
    };
    for (std::size_t j = 0; j < ne; ++j)
        for (std::size_t i = 0; i < na; ++i) {
            orbital_elements o = rest;
            o.a = at(a0, a1, i, na), o.e = at(e0, e1, j, ne);
            o.mean_anomaly = rest.mean_anomaly + 2.399963229728653 * double(g.size());
            g.push_back(o);
        }
    return g;
}

}  // namespace sympl
