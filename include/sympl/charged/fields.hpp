#pragma once
// Electromagnetic fields for charged particles in 3D: the concept the pushers
// read (E(x, t), B(x, t), any callables), and three ready fields that also
// give the potentials phi and A the canonical H = |p - e A|^2 / 2m + e phi
// needs (Goldstein, Poole & Safko, Classical Mechanics, 3rd ed., sec. 8.1),
// with the x_i-primitives of A_i that make the splitting of
// charged/canonical_splitting.hpp exact (Zhou, He, Sun, Liu & Qin 2017, Phys.
// Plasmas 24, 052507):
//   uniform_field:       constant E and B, A = B x q / 2, phi = -E . q;
//   radial_mirror_field: B = B0 (1 + (x^2 + y^2)/L^2) e_z, A = g(r^2) (-y, x, 0),
//                        g = (B0/2)(1 + r^2/(2 L^2)), E = -k (x, y, 0)
//                        (hamiltonians/charged_particle.hpp in 3D);
//   magnetic_mirror:     the paraxial mirror B_z = B0 (1 + z^2/L^2),
//                        B_r = -(r/2) dB_z/dz, A = (B0/2)(1 + z^2/L^2)(-y, x, 0).
// Formulas and which method needs what: docs/charged-particles.md.
#include <concepts>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace sympl::charged {

template <class S = double>
using vec3 = Eigen::Matrix<S, 3, 1>;

// E(x, t) and B(x, t): what the Boris and relativistic pushers need.
template <class F>
concept electromagnetic_field = requires(const F& f, const vec3<>& x, double t) {
    { f.E(x, t) } -> std::convertible_to<vec3<>>;
    { f.B(x, t) } -> std::convertible_to<vec3<>>;
};

// A static field given by its potentials, with what makes each part
// H_i = (p_i - e A_i(q))^2 / 2m of the canonical H exactly solvable: the
// gradient of the primitive P_i(q) = integral of A_i d q_i in the directions
// j != i (primitive_gradient(i, q)[j]; its i-th component is not read).
template <class F>
concept solvable_potentials = electromagnetic_field<F> && requires(const F& f, const vec3<>& q, int i) {
    { f.A(q) } -> std::convertible_to<vec3<>>;
    { f.phi(q) } -> std::convertible_to<double>;
    { f.primitive_gradient(i, q) } -> std::convertible_to<vec3<>>;
};

// A_theta and phi with their r and z derivatives at (r, z), for a field
// symmetric about the z axis, A = A_theta(r, z) e_theta (axisymmetric_splitting.hpp).
struct axial_values {
    double A = 0, dA_dr = 0, dA_dz = 0;
    double phi = 0, dphi_dr = 0, dphi_dz = 0;
};

// Uniform E and B. With A = B x q / 2, A_i does not depend on q_i, so
// P_i = q_i A_i and dP_i/dq_j = q_i dA_i/dq_j = q_i (B x e_j)_i / 2.
struct uniform_field {
    vec3<> electric = vec3<>::Zero();
    vec3<> magnetic = vec3<>(0, 0, 1);

    template <class S> vec3<S> E(const vec3<S>&, double = 0) const { return electric.cast<S>(); }
    template <class S> vec3<S> B(const vec3<S>&, double = 0) const { return magnetic.cast<S>(); }
    template <class S> vec3<S> A(const vec3<S>& q) const { return magnetic.cast<S>().cross(q) / S(2); }
    template <class S> S phi(const vec3<S>& q) const { return -electric.cast<S>().dot(q); }
    vec3<> primitive_gradient(int i, const vec3<>& q) const {
        vec3<> g;
        for (int j = 0; j < 3; ++j) g[j] = q[i] * magnetic.cross(vec3<>::Unit(j))[i] / 2;
        return g;
    }
};

// The field of hamiltonians/charged_particle.hpp in 3D: B_z grows with the
// distance r from the z axis, and e phi = (k e / 2) r^2 confines radially
// (E = -k (x, y, 0); `confinement` is k).
struct radial_mirror_field {
    double field = 1.0;         // B0: B_z on the axis
    double field_length = 1.0;  // L: B_z doubles at r = L
    double confinement = 0.0;   // k

    template <class S> S gauge(const S& r2) const { return S(field / 2) * (1 + r2 / S(2 * field_length * field_length)); }
    template <class S> vec3<S> E(const vec3<S>& q, double = 0) const {
        return vec3<S>(-S(confinement) * q[0], -S(confinement) * q[1], S(0));
    }
    template <class S> vec3<S> B(const vec3<S>& q, double = 0) const {
        const S r2 = q[0] * q[0] + q[1] * q[1];
        return vec3<S>(S(0), S(0), S(field) * (1 + r2 / S(field_length * field_length)));
    }
    template <class S> vec3<S> A(const vec3<S>& q) const {
        const S g = gauge(S(q[0] * q[0] + q[1] * q[1]));
        return vec3<S>(-g * q[1], g * q[0], S(0));
    }
    template <class S> S phi(const vec3<S>& q) const { return S(confinement / 2) * (q[0] * q[0] + q[1] * q[1]); }
    // P_x = -(B0/2)(x y + (x^3 y / 3 + x y^3) / (2 L^2)), P_y = (B0/2)(x y + (x^3 y + x y^3 / 3) / (2 L^2)), P_z = 0.
    vec3<> primitive_gradient(int i, const vec3<>& q) const {
        const double x = q[0], y = q[1], b = field / 2, c = 1 / (2 * field_length * field_length);
        if (i == 0) return {0, -b * (x + (x * x * x / 3 + 3 * x * y * y) * c), 0};
        if (i == 1) return {b * (y + (3 * x * x * y + y * y * y / 3) * c), 0, 0};
        return vec3<>::Zero();
    }
    // A_theta = g(r^2) r, phi = (k/2) r^2 (charged/axisymmetric_splitting.hpp).
    axial_values axial(double r, double) const {
        const double c = 1 / (2 * field_length * field_length);
        return {.A = field / 2 * r * (1 + r * r * c), .dA_dr = field / 2 * (1 + 3 * r * r * c),
                .phi = confinement / 2 * r * r, .dphi_dr = confinement * r};
    }
};

// A paraxial magnetic mirror about the z axis: B_z = B0 (1 + z^2/L^2),
// B_x = -B0 x z / L^2, B_y = -B0 y z / L^2 (divergence-free), no E. A particle
// whose pitch angle is large enough bounces between z = -L.. and z = +L..;
// its magnetic moment is the adiabatic invariant.
struct magnetic_mirror {
    double field = 1.0;         // B0: B_z at the centre
    double field_length = 1.0;  // L: B_z doubles at |z| = L

    template <class S> S strength(const S& z) const { return S(field) * (1 + z * z / S(field_length * field_length)); }
    template <class S> vec3<S> E(const vec3<S>&, double = 0) const { return vec3<S>::Zero(); }
    template <class S> vec3<S> B(const vec3<S>& q, double = 0) const {
        const S s = -S(field / (field_length * field_length)) * q[2];
        return vec3<S>(s * q[0], s * q[1], strength(q[2]));
    }
    template <class S> vec3<S> A(const vec3<S>& q) const {
        const S h = strength(q[2]) / S(2);
        return vec3<S>(-h * q[1], h * q[0], S(0));
    }
    template <class S> S phi(const vec3<S>&) const { return S(0); }
    // P_x = -h x y, P_y = h x y with h = B_z(z)/2, P_z = 0.
    vec3<> primitive_gradient(int i, const vec3<>& q) const {
        const double h = strength(q[2]) / 2, dh = field * q[2] / (field_length * field_length);
        if (i == 0) return {0, -h * q[0], -dh * q[0] * q[1]};
        if (i == 1) return {h * q[1], 0, dh * q[0] * q[1]};
        return vec3<>::Zero();
    }
    // A_theta = r B_z(z) / 2 (charged/axisymmetric_splitting.hpp).
    axial_values axial(double r, double z) const {
        return {.A = r * strength(z) / 2, .dA_dr = strength(z) / 2, .dA_dz = r * field * z / (field_length * field_length)};
    }
};

}  // namespace sympl::charged
