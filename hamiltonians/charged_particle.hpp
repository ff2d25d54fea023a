#pragma once
// A charged particle (mass m, charge e) in the plane, in a static non-uniform
// magnetic field B = B_z(x, y) e_z that grows away from the origin,
//     B_z = B0 (1 + (x^2 + y^2) / L^2),
// with the vector potential (symmetric gauge) A = g(r^2) (-y, x),
//     g(r^2) = (B0 / 2) (1 + r^2 / (2 L^2)),   curl A = 2 g + 2 r^2 g' = B_z,
// and an optional electrostatic confinement e phi = (k / 2) (x^2 + y^2).
// With canonical momentum p (Goldstein, Poole & Safko, Classical Mechanics,
// 3rd ed., sec. 8.1: H = |p - e A|^2 / (2m) + e phi)
//     H = |p - e A(q)|^2 / (2 m) + (k / 2) |q|^2,
// which is not separable: the kinetic energy depends on q through A. The
// gyration radius and frequency change along the orbit (a magnetic mirror in
// the radial direction), so the motion is nonlinear; the field is symmetric
// about the origin, so the canonical angular momentum x p_y - y p_x is a
// second invariant (a quadratic one, which Gauss collocation keeps exactly).
#include <cmath>
#include <limits>

#include <Eigen/Core>

#include <sympl/charged/fields.hpp>
#include <sympl/charged/particle.hpp>

namespace sympl::hamiltonians {

struct charged_particle {
    double mass = 1.0;
    double charge = 1.0;
    double field = 1.0;         // B0: B_z at the origin
    double field_length = 1.0;  // L: B_z doubles at r = L
    double confinement = 0.0;   // k: e phi = (k / 2) |q|^2
    static constexpr int dimension = 2;

    // g(r^2) and g' = dg/d(r^2) of A = g (-y, x).
    template <class S> S gauge(const S& r2) const { return S(field / 2) * (1 + r2 / S(2 * field_length * field_length)); }
    double gauge_slope() const { return field / (4 * field_length * field_length); }

    // The particle and its field in 3D, for the pushers and splittings of
    // sympl/charged/ (e phi = (k/2) r^2: the field's E = -(k/e) (x, y, 0)).
    charged::particle particle() const {
        return {.mass = mass, .charge = charge, .speed_of_light = std::numeric_limits<double>::infinity()};
    }
    charged::radial_mirror_field electromagnetic_field() const { return {field, field_length, confinement / charge}; }

    // B_z at q (what the field is; not needed by the dynamics).
    template <class V> auto magnetic_field(const V& q) const {
        using S = typename V::Scalar;
        return S(field) * (1 + q.squaredNorm() / S(field_length * field_length));
    }

    // The kinetic momentum pi = p - e A(q) (= m dq/dt).
    template <class V> V kinetic_momentum(const V& q, const V& p) const {
        using S = typename V::Scalar;
        const S g = gauge(S(q.squaredNorm()));
        V pi(2);
        pi[0] = p[0] + S(charge) * g * q[1];
        pi[1] = p[1] - S(charge) * g * q[0];
        return pi;
    }

    template <class V> auto energy(const V& q, const V& p) const {
        using S = typename V::Scalar;
        return S(kinetic_momentum(q, p).squaredNorm() / S(2 * mass) + S(confinement / 2) * q.squaredNorm());
    }
    // dH/dp = pi / m.
    template <class V> void dH_dp(const V& q, const V& p, V& out) const {
        using S = typename V::Scalar;
        out = kinetic_momentum(q, p) / S(mass);
    }
    // dH/dq_j = -(e / m) sum_i pi_i dA_i/dq_j + k q_j, with
    // dA_x/dx = -2xy g', dA_x/dy = -g - 2y^2 g', dA_y/dx = g + 2x^2 g', dA_y/dy = 2xy g'.
    template <class V> void dH_dq(const V& q, const V& p, V& out) const {
        using S = typename V::Scalar;
        const V pi = kinetic_momentum(q, p);
        const S x = q[0], y = q[1];
        const S g = gauge(S(q.squaredNorm())), g1(gauge_slope()), em(charge / mass), k(confinement);
        out.resize(2);
        out[0] = -em * (-2 * x * y * g1 * pi[0] + (g + 2 * x * x * g1) * pi[1]) + k * x;
        out[1] = -em * ((-g - 2 * y * y * g1) * pi[0] + 2 * x * y * g1 * pi[1]) + k * y;
    }
};

}  // namespace sympl::hamiltonians
