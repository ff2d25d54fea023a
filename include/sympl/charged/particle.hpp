#pragma once
// A particle of mass m and charge e in an electromagnetic field
// (charged/fields.hpp). The pushers (boris.hpp, relativistic_pusher.hpp) step
// its kinetic state, a phase_space<S, 3> holding the position x in q and the
// velocity v (relativistic: u = gamma v) in p, as Newton's form x'' = a(x, v, t)
// does elsewhere in sympl. The canonical splitting (canonical_splitting.hpp)
// steps the canonical state (q, p = m v + e A(q)) of
//     H(q, p) = |p - e A(q)|^2 / 2m + e phi(q)
// (Goldstein, Poole & Safko, Classical Mechanics, 3rd ed., sec. 8.1). Both
// forms, the conversions between them, the Lorentz force and the energies are
// here.
#include <cmath>
#include <string>

#include "../core/error.hpp"
#include "../core/phase_space.hpp"
#include "fields.hpp"

namespace sympl::charged {

template <class S = double>
using kinetic_state = phase_space<S, 3>;  // q: position x, p: velocity v (or u = gamma v)
template <class S = double>
using canonical_state = phase_space<S, 3>;  // q, p = m v + e A(q)

struct particle {
    double mass = 1.0;
    double charge = 1.0;
    double speed_of_light = 299792458.0;  // relativistic pusher only, in the units of v; infinity: Newton's motion

    // e/m, the only combination the non-relativistic motion sees.
    double charge_to_mass() const { return charge / mass; }

    void check(const char* who) const {
        using std::isfinite;
        if (!isfinite(mass) || !(mass > 0))
            throw invalid_argument(std::string(who) + ": mass = " + std::to_string(mass) + "; expected a finite mass > 0");
        if (!isfinite(charge))
            throw invalid_argument(std::string(who) + ": charge = " + std::to_string(charge) + "; expected a finite charge");
        if (!(speed_of_light > 0))
            throw invalid_argument(std::string(who) + ": speed_of_light = " + std::to_string(speed_of_light) +
                                   "; expected a speed > 0 (infinity for Newton's motion)");
    }
};

// e (E + v x B) / m at (x, t).
template <electromagnetic_field F>
vec3<> lorentz_acceleration(const particle& a, const F& f, const vec3<>& x, const vec3<>& v, double t) {
    return a.charge_to_mass() * (vec3<>(f.E(x, t)) + v.cross(vec3<>(f.B(x, t))));
}

// The canonical momentum p = m v + e A(x) of a static field, and back.
template <solvable_potentials F>
canonical_state<> to_canonical(const particle& a, const F& f, const kinetic_state<>& k) {
    return canonical_state<>(k.q, vec3<>(a.mass * k.p + a.charge * vec3<>(f.A(k.q))));
}
template <solvable_potentials F>
kinetic_state<> to_kinetic(const particle& a, const F& f, const canonical_state<>& c) {
    return kinetic_state<>(c.q, vec3<>((c.p - a.charge * vec3<>(f.A(c.q))) / a.mass));
}

// m |v|^2 / 2 + e phi(x): conserved in a static field.
template <solvable_potentials F>
double energy(const particle& a, const F& f, const kinetic_state<>& k) {
    return a.mass * k.p.squaredNorm() / 2 + a.charge * f.phi(k.q);
}

// gamma = sqrt(1 + |u|^2 / c^2) of u = gamma v.
inline double lorentz_factor(const particle& a, const vec3<>& u) {
    return std::sqrt(1 + u.squaredNorm() / (a.speed_of_light * a.speed_of_light));
}

}  // namespace sympl::charged
