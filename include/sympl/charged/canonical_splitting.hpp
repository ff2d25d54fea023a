#pragma once
// An explicit symplectic method for a charged particle in a static field, of
// any even order: the canonical H(q, p) = |p - e A(q)|^2 / 2m + e phi(q) split
// into the parts
//     H_i = (p_i - e A_i(q))^2 / 2m   (i = x, y[, z]),   H_phi = e phi(q),
// each exactly solvable (Zhou, He, Sun, Liu & Qin 2017, Phys. Plasmas 24,
// 052507; He, Zhou, Sun, Liu & Qin 2017, Phys. Lett. A 381, 568). Under H_i
// only q_i moves and pi_i = p_i - e A_i is constant, so for a time t
//     q_i' = q_i + t pi_i / m,  p_i' = pi_i + e A_i(q'),
//     p_j' = p_j + e (dP_i/dq_j (q') - dP_i/dq_j (q))  (j != i),
// P_i the primitive of A_i in q_i (fields.hpp: solvable_potentials); under
// H_phi, p' = p + t e E(q). The base step X(h/2) Y(h/2) [Z(h/2)] Phi(h)
// [Z(h/2)] Y(h/2) X(h/2) is symmetric and of order 2; any table that composes
// leapfrog steps (leapfrog_kdk, triple_jump(...), suzuki_fractal(...),
// yoshida_6, kahan_li_8, ...) composes it to its order (Yoshida 1990; Suzuki
// 1990), neighbouring X flows merged into one. Symplectic in (q, p).
// Dim = 2 runs a planar motion (q_z = p_z = 0) in a field whose B is along z.
#include <cstdint>
#include <string>
#include <utility>

#include "../core/error.hpp"
#include "../core/phase_space.hpp"
#include "../core/table.hpp"
#include "../methods/catalog_forms.hpp"
#include "particle.hpp"

namespace sympl::charged {

template <solvable_potentials F, int Dim = 3>
class canonical_splitting_stepper {
    static_assert(Dim == 2 || Dim == 3, "a charged particle moves in the plane (Dim = 2) or in space (Dim = 3)");

public:
    using state_type = phase_space<double, Dim>;  // canonical q, p
    using scalar = double;

    canonical_splitting_stepper(particle a, F field, const table& composition)
        : particle_(a), field_(std::move(field)),
          weights_(detail::leapfrog_composition_weights(composition, "canonical_splitting_stepper")) {
        particle_.check("canonical_splitting_stepper");
    }

    const particle& charged_particle() const { return particle_; }
    const F& field() const { return field_; }
    int order() const { return weights_.order; }
    // Exact partial flows run (each reads the field's potentials twice, or E once).
    std::uint64_t force_evaluations() const { return flows_; }

    void step(state_type& s, double dt) {
        vec3<> q = padded(s.q), p = padded(s.p);
        const auto& g = weights_.gamma;
        double pending = double(g.front()) / 2 * dt;  // the X flow carried to the next base step
        for (std::size_t k = 0; k < g.size(); ++k) {
            const double h = double(g[k]) * dt;
            flow_part(0, pending, q, p);
            for (int i = 1; i < Dim; ++i) flow_part(i, h / 2, q, p);
            flow_phi(h, q, p);
            for (int i = Dim - 1; i >= 1; --i) flow_part(i, h / 2, q, p);
            pending = h / 2 + (k + 1 < g.size() ? double(g[k + 1]) / 2 * dt : 0.0);
        }
        flow_part(0, pending, q, p);
        s.q = q.template head<Dim>();
        s.p = p.template head<Dim>();
    }

    // The exact flow of H_i over time t.
    void flow_part(int i, double t, vec3<>& q, vec3<>& p) {
        const double e = particle_.charge;
        const vec3<> before = field_.primitive_gradient(i, q);
        const double pi = p[i] - e * vec3<>(field_.A(q))[i];
        q[i] += t * pi / particle_.mass;
        const vec3<> after = field_.primitive_gradient(i, q);
        for (int j = 0; j < Dim; ++j) p[j] += e * (after[j] - before[j]);
        p[i] = pi + e * vec3<>(field_.A(q))[i];
        ++flows_;
    }
    // The exact flow of e phi(q) over time t: a kick by e E(q).
    void flow_phi(double t, const vec3<>& q, vec3<>& p) {
        const vec3<> E = field_.E(q, 0.0);
        p.template head<Dim>() += (t * particle_.charge) * E.template head<Dim>();
        ++flows_;
    }

private:
    static vec3<> padded(const typename state_type::vector& v) {
        vec3<> w = vec3<>::Zero();
        w.template head<Dim>() = v;
        return w;
    }

    particle particle_;
    F field_;
    composition_weights weights_;
    std::uint64_t flows_ = 0;
};

}  // namespace sympl::charged
