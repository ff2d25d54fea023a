#pragma once
// The Boris pusher (Boris 1970, Proc. 4th Conf. Numer. Simul. Plasmas, 3;
// Birdsall & Langdon, Plasma Physics via Computer Simulation, sec. 4-3) for
// m dv/dt = e (E + v x B), in its synchronised drift-kick-drift form:
//     x_h = x + v dt/2,   E, B at (x_h, t + dt/2),
//     v-  = v + (e dt / 2m) E,   v+ = R v-,   v' = v+ + (e dt / 2m) E,
//     x'  = x_h + v' dt/2,
// with R the rotation about B by 2 atan(e |B| dt / 2m) (Boris's tangent form,
// no trigonometry). Second order, explicit, symmetric and volume-preserving
// (Qin, Zhang, Xiao, Liu, Sun & Tang 2013, Phys. Plasmas 20, 084503), but not
// symplectic in general; in uniform B it keeps |v| to rounding and its
// gyration centre exactly (in exact arithmetic). docs/charged-particles.md.
#include <cstdint>
#include <string>

#include "../core/error.hpp"
#include "particle.hpp"

namespace sympl::charged {

// v+ of Boris's rotation: v+ - v- = (v+ + v-) x tau with tau = (e dt / 2m) B,
// solved as v' = v- + v- x tau, v+ = v- + v' x 2 tau / (1 + |tau|^2).
inline vec3<> boris_rotation(const vec3<>& v_minus, const vec3<>& tau) {
    const vec3<> v_prime = v_minus + v_minus.cross(tau);
    return v_minus + v_prime.cross((2 / (1 + tau.squaredNorm())) * tau);
}

template <electromagnetic_field F>
class boris_stepper {
public:
    using state_type = kinetic_state<>;  // q: x, p: v
    using scalar = double;

    boris_stepper(particle a, F field) : particle_(a), field_(std::move(field)) { particle_.check("boris_stepper"); }

    const particle& charged_particle() const { return particle_; }
    const F& field() const { return field_; }
    // Evaluations of the pair (E, B), one per step.
    std::uint64_t force_evaluations() const { return evaluations_; }

    void step(state_type& s, double dt) { step(s, 0.0, dt); }
    void step(state_type& s, double t, double dt) {
        const double half = dt / 2, k = particle_.charge_to_mass() * half;
        const vec3<> x_half = s.q + half * s.p;
        const vec3<> E = field_.E(x_half, t + half), B = field_.B(x_half, t + half);
        ++evaluations_;
        const vec3<> v_minus = s.p + k * E;
        s.p = boris_rotation(v_minus, k * B) + k * E;
        s.q = x_half + half * s.p;
    }

private:
    particle particle_;
    F field_;
    std::uint64_t evaluations_ = 0;
};

}  // namespace sympl::charged
