#pragma once
// An explicit symplectic method for a charged particle in a static field
// symmetric about the z axis (A = A_theta(r, z) e_theta, phi(r, z)): in the
// cylindrical coordinates (r, theta, z), a canonical transformation,
//     H = (p_r^2 + p_z^2) / 2m + U(r, z),   U = (p_theta / r - e A_theta)^2 / 2m + e phi,
// theta is cyclic, so p_theta = x p_y - y p_x is exact, and what remains is a
// kinetic energy quadratic in (p_r, p_z) plus a potential: any kick-drift table
// of the catalog runs it at its full order, Runge-Kutta-Nystrom tables
// included ([U, [U, [U, T]]] = 0 holds with theta: nothing depends on it).
// A kick of weight b h is the exact flow of U: p_r, p_z kicked by -b h grad U,
// theta advanced by b h dU/dp_theta; a drift moves r and z. Symplectic in the
// Cartesian (q, p) (Goldstein, Poole & Safko, Classical Mechanics, 3rd ed.,
// sec. 8.2 for the reduction; Hairer, Lubich & Wanner, GNI, sec. III.3 for
// the tables). It needs the orbit away from the axis: a drift that takes r
// through the centrifugal barrier p_theta^2 / 2 m r^2 is a step too large.
// Dim = 2 runs a planar motion in a field along z. docs/charged-particles.md.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/phase_space.hpp"
#include "../core/table.hpp"
#include "particle.hpp"

namespace sympl::charged {

template <class F>
concept axisymmetric_potentials = requires(const F& f, double r, double z) {
    { f.axial(r, z) } -> std::convertible_to<axial_values>;
};

// The cylindrical canonical state: r, z, theta and their momenta.
struct cylindrical_state {
    double r = 0, z = 0, theta = 0, p_r = 0, p_z = 0, p_theta = 0;
};

template <axisymmetric_potentials F, int Dim = 3>
class axisymmetric_splitting_stepper {
    static_assert(Dim == 2 || Dim == 3, "a charged particle moves in the plane (Dim = 2) or in space (Dim = 3)");

public:
    using state_type = phase_space<double, Dim>;  // Cartesian canonical q, p
    using scalar = double;

    axisymmetric_splitting_stepper(particle a, F field, const table& t)
        : particle_(a), field_(std::move(field)), name_(t.name()), order_(t.order()) {
        particle_.check("axisymmetric_splitting_stepper");
        if (t.has_force_gradient())
            throw invalid_argument("axisymmetric_splitting_stepper: table '" + t.name() +
                                   "' has force-gradient kicks; expected a kick-drift table");
        for (const substep& s : t.substeps()) ops_.push_back({s.kind == substep::kick, double(s.weight)});
        merge_ends_ = ops_.size() > 1 && ops_.front().kick == ops_.back().kick;
    }

    const particle& charged_particle() const { return particle_; }
    const F& field() const { return field_; }
    int order() const { return order_; }
    // Evaluations of the field's potentials (one per kick).
    std::uint64_t force_evaluations() const { return kicks_; }

    void step(state_type& s, double dt) { steps(s, dt, 1); }
    // n steps, converted to cylindrical coordinates and back once; the last
    // sub-step of one step merged with the first of the next where they are
    // of one kind.
    void steps(state_type& s, double dt, std::size_t n) {
        cylindrical_state c = to_cylindrical(s);
        for (std::size_t k = 0; k < n; ++k) {
            const std::size_t first = (merge_ends_ && k > 0) ? 1 : 0;
            const std::size_t last = (merge_ends_ && k + 1 < n) ? ops_.size() - 1 : ops_.size();
            for (std::size_t i = first; i < last; ++i) apply(ops_[i].kick, ops_[i].weight * dt, c);
            if (last < ops_.size()) apply(ops_.back().kick, (ops_.back().weight + ops_.front().weight) * dt, c);
        }
        s = to_cartesian(c);
    }

    // The exact flow of U over time t: a kick of p_r, p_z and a turn of theta.
    void kick(double t, cylindrical_state& c) {
        const axial_values a = field_.axial(c.r, c.z);
        const double e = particle_.charge, m = particle_.mass, inv_r = 1 / c.r, l = c.p_theta * inv_r;
        const double w = (l - e * a.A) / m;  // the angular velocity times r
        c.p_r -= t * (w * (-l * inv_r - e * a.dA_dr) + e * a.dphi_dr);
        if constexpr (Dim == 3) c.p_z -= t * (-w * e * a.dA_dz + e * a.dphi_dz);
        c.theta += t * w * inv_r;
        ++kicks_;
    }
    void drift(double t, cylindrical_state& c) const {
        c.r += t * c.p_r / particle_.mass;
        if constexpr (Dim == 3) c.z += t * c.p_z / particle_.mass;
    }

    static cylindrical_state to_cylindrical(const state_type& s) {
        cylindrical_state c;
        const double x = s.q[0], y = s.q[1];
        c.r = std::hypot(x, y);
        if (c.r == 0)
            throw invalid_argument("axisymmetric_splitting_stepper: the particle is on the axis (r = 0), where "
                                   "cylindrical coordinates are singular; expected r > 0");
        c.theta = std::atan2(y, x);
        c.p_r = (x * s.p[0] + y * s.p[1]) / c.r;
        c.p_theta = x * s.p[1] - y * s.p[0];
        if constexpr (Dim == 3) {
            c.z = s.q[2];
            c.p_z = s.p[2];
        }
        return c;
    }
    static state_type to_cartesian(const cylindrical_state& c) {
        state_type s;
        const double cs = std::cos(c.theta), sn = std::sin(c.theta), l = c.p_theta / c.r;
        s.q[0] = c.r * cs;
        s.q[1] = c.r * sn;
        s.p[0] = c.p_r * cs - l * sn;
        s.p[1] = c.p_r * sn + l * cs;
        if constexpr (Dim == 3) {
            s.q[2] = c.z;
            s.p[2] = c.p_z;
        }
        return s;
    }

private:
    struct op {
        bool kick;
        double weight;
    };
    void apply(bool is_kick, double t, cylindrical_state& c) {
        if (is_kick)
            kick(t, c);
        else
            drift(t, c);
    }

    particle particle_;
    F field_;
    std::string name_;
    int order_ = 0;
    std::vector<op> ops_;
    bool merge_ends_ = false;
    std::uint64_t kicks_ = 0;
};

}  // namespace sympl::charged
