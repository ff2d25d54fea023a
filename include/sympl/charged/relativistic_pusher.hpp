#pragma once
// The relativistic pusher of Higuera & Cary (2017, Phys. Plasmas 24, 052104)
// for du/dt = (e/m)(E + u x B / gamma), u = gamma v, gamma = sqrt(1 + |u|^2/c^2),
// in the drift-kick-drift form of boris.hpp:
//     x_h = x + (dt/2) u / gamma(u),   E, B at (x_h, t + dt/2),
//     u-  = u + (e dt / 2m) E,   tau = (e dt / 2m) B,
//     gamma_bar^2 = (sigma + sqrt(sigma^2 + 4 (|tau|^2 + (u- . tau / c)^2))) / 2,
//                   sigma = gamma(u-)^2 - |tau|^2,
//     t = tau / gamma_bar,   w = (u- + (u- . t) t + u- x t) / (1 + |t|^2),
//     u' = w + w x t + (e dt / 2m) E,   x' = x_h + (dt/2) u' / gamma(u').
// Its magnetic rotation uses the gamma of the average momentum w, so it is
// volume-preserving and drifts at the exact E x B velocity at any speed
// (Boris's uses gamma(u-), Vay 2008 a mixture); explicit, second order,
// symmetric, not symplectic. At |u| << c it is Boris's pusher (w is Boris's
// midpoint, w + w x t his v+). docs/charged-particles.md.
#include <cmath>
#include <cstdint>

#include "particle.hpp"

namespace sympl::charged {

template <electromagnetic_field F>
class relativistic_pusher {
public:
    using state_type = kinetic_state<>;  // q: x, p: u = gamma v
    using scalar = double;

    relativistic_pusher(particle a, F field) : particle_(a), field_(std::move(field)) {
        particle_.check("relativistic_pusher");
    }

    const particle& charged_particle() const { return particle_; }
    const F& field() const { return field_; }
    // Evaluations of the pair (E, B), one per step.
    std::uint64_t force_evaluations() const { return evaluations_; }

    void step(state_type& s, double dt) { step(s, 0.0, dt); }
    void step(state_type& s, double t, double dt) {
        const double half = dt / 2, k = particle_.charge_to_mass() * half, c = particle_.speed_of_light;
        const vec3<> x_half = s.q + (half / lorentz_factor(particle_, s.p)) * s.p;
        const vec3<> E = field_.E(x_half, t + half), B = field_.B(x_half, t + half);
        ++evaluations_;
        const vec3<> u_minus = s.p + k * E, tau = k * B;
        const double tau2 = tau.squaredNorm(), u_star = u_minus.dot(tau) / c;
        const double sigma = 1 + u_minus.squaredNorm() / (c * c) - tau2;
        const double gamma_bar = std::sqrt((sigma + std::sqrt(sigma * sigma + 4 * (tau2 + u_star * u_star))) / 2);
        const vec3<> tt = tau / gamma_bar;
        const vec3<> w = (u_minus + u_minus.dot(tt) * tt + u_minus.cross(tt)) / (1 + tt.squaredNorm());
        s.p = w + w.cross(tt) + k * E;
        s.q = x_half + (half / lorentz_factor(particle_, s.p)) * s.p;
    }

private:
    particle particle_;
    F field_;
    std::uint64_t evaluations_ = 0;
};

}  // namespace sympl::charged
