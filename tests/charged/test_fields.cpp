// The ready fields: B = curl A, E = -grad phi, div B = 0, the primitives'
// gradients against A's derivatives, and the axial potentials against A.
#include <doctest/doctest.h>

#include <cmath>

#include <sympl/charged/fields.hpp>

namespace test_charged_test_fields {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::charged;

// Central differences of a vector function's component i in direction j: error O(h^2) ~ 1e-10.
template <class G>
double derivative(const G& g, vec3<> q, int i, int j) {
    const double h = 1e-5;
    vec3<> a = q, b = q;
    a[j] += h;
    b[j] -= h;
    return (vec3<>(g(a))[i] - vec3<>(g(b))[i]) / (2 * h);
}

template <class F>
void check_field(const F& f, const vec3<>& q) {
    const auto A = [&](const vec3<>& x) { return f.A(x); };
    const auto B = [&](const vec3<>& x) { return f.B(x, 0.0); };
    const vec3<> curl(derivative(A, q, 2, 1) - derivative(A, q, 1, 2), derivative(A, q, 0, 2) - derivative(A, q, 2, 0),
                      derivative(A, q, 1, 0) - derivative(A, q, 0, 1));
    CHECK((curl - vec3<>(f.B(q, 0.0))).norm() < 1e-8);
    CHECK(std::abs(derivative(B, q, 0, 0) + derivative(B, q, 1, 1) + derivative(B, q, 2, 2)) < 1e-8);
    const auto phi = [&](const vec3<>& x) { return vec3<>(f.phi(x), 0, 0); };
    for (int j = 0; j < 3; ++j) CHECK(std::abs(derivative(phi, q, 0, j) + vec3<>(f.E(q, 0.0))[j]) < 1e-8);
    // d/dq_i of dP_i/dq_j is dA_i/dq_j (j != i): the primitive's gradient is A's.
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            if (j == i) continue;
            const auto P = [&](const vec3<>& x) { return f.primitive_gradient(i, x); };
            CHECK(std::abs(derivative(P, q, j, i) - derivative(A, q, i, j)) < 1e-8);
        }
}

TEST_CASE("fields: B = curl A, div B = 0, E = -grad phi, primitives") {
    const vec3<> q(0.7, -0.4, 0.3);
    check_field(uniform_field{.electric = vec3<>(0.2, -0.1, 0.3), .magnetic = vec3<>(0.5, -1.2, 0.8)}, q);
    check_field(radial_mirror_field{.field = 1.3, .field_length = 0.8, .confinement = 0.4}, q);
    check_field(magnetic_mirror{.field = 1.3, .field_length = 0.8}, q);
}

TEST_CASE("fields: the axial potentials are A . e_theta and phi, with their derivatives") {
    const auto check_axial = [](const auto& f) {
        const double r = 0.6, z = 0.3, h = 1e-5;
        const auto A_theta = [&](double rr, double zz) { return vec3<>(f.A(vec3<>(rr, 0, zz)))[1]; };
        const axial_values a = f.axial(r, z);
        CHECK(std::abs(a.A - A_theta(r, z)) < 1e-14);
        CHECK(std::abs(a.dA_dr - (A_theta(r + h, z) - A_theta(r - h, z)) / (2 * h)) < 1e-8);
        CHECK(std::abs(a.dA_dz - (A_theta(r, z + h) - A_theta(r, z - h)) / (2 * h)) < 1e-8);
        CHECK(std::abs(a.phi - f.phi(vec3<>(r, 0, z))) < 1e-14);
        CHECK(std::abs(a.dphi_dr + vec3<>(f.E(vec3<>(r, 0, z), 0.0))[0]) < 1e-14);
        CHECK(std::abs(a.dphi_dz + vec3<>(f.E(vec3<>(r, 0, z), 0.0))[2]) < 1e-14);
    };
    check_axial(radial_mirror_field{.field = 1.3, .field_length = 0.8, .confinement = 0.4});
    check_axial(magnetic_mirror{.field = 1.3, .field_length = 0.8});
}

}  // namespace test_charged_test_fields
