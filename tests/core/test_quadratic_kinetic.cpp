// A quadratic kinetic energy recognised from generic code: diagonal and dense
// inverse masses found to rounding, and every T that is not quadratic refused.
#include <doctest/doctest.h>

#include <cmath>

#include <sympl/core/quadratic_kinetic.hpp>
#include <sympl/hamiltonians/relativistic_pendulum.hpp>

namespace test_core_test_quadratic_kinetic {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using Vec = Eigen::VectorXd;

namespace {
constexpr double eps = 2.220446049250313e-16;

template <class Kinetic>
struct kinetic_only {
    Kinetic T;
    template <class V> auto kinetic(const V& p) const { return T(p); }
    template <class V> auto potential(const V& q) const { return 0 * q.sum(); }
};
template <class Kinetic>
kinetic_only<Kinetic> with_kinetic(Kinetic T) { return {T}; }

template <class H>
typename quadratic_kinetic<Vec>::form recognised(const H& h, Eigen::Index n) {
    quadratic_kinetic<Vec> k;
    k.recognise(h, n);
    return k.recognised();
}
using form = quadratic_kinetic<Vec>::form;

Vec masses(Eigen::Index n) {
    Vec m(n);
    for (Eigen::Index i = 0; i < n; ++i) m[i] = 1.0 + 0.37 * double(i % 11);
    return m;
}
}  // namespace

TEST_CASE("quadratic_kinetic: diagonal masses found, at any size, and the velocity is the gradient") {
    for (Eigen::Index n : {1, 3, 1000, 100000}) {
        const Vec m = masses(n);
        const auto h = with_kinetic([m](const auto& p) { return 0.5 * (p.array().square() / m.array()).sum(); });
        quadratic_kinetic<Vec> k;
        k.recognise(h, n);
        REQUIRE(k.recognised() == form::diagonal);
        CHECK(((k.inverse_mass_diagonal().array() * m.array()) - 1).abs().maxCoeff() <= 4 * eps);
        Vec p(n), v_found, v_grad;
        for (Eigen::Index i = 0; i < n; ++i) p[i] = std::cos(0.3 * double(i)) * 2.5;
        k.velocity(p, v_found);
        sympl::velocity(h, p, v_grad);
        CHECK((v_found - v_grad).cwiseAbs().maxCoeff() <= 4 * eps * v_grad.cwiseAbs().maxCoeff());
    }
}

TEST_CASE("quadratic_kinetic: a coupled mass matrix is found whole up to dense_limit") {
    Eigen::Matrix4d a;
    a << 2.0, 0.3, 0.1, 0.0,  //
        0.3, 1.5, -0.2, 0.05,  //
        0.1, -0.2, 1.0, 0.4,   //
        0.0, 0.05, 0.4, 3.0;
    const Eigen::MatrixXd inverse_mass = a;
    const auto h = with_kinetic([inverse_mass](const auto& p) {
        using S = typename std::decay_t<decltype(p)>::Scalar;
        S t(0);
        for (Eigen::Index i = 0; i < p.size(); ++i)
            for (Eigen::Index j = 0; j < p.size(); ++j) t += 0.5 * inverse_mass(i, j) * p[i] * p[j];
        return t;
    });
    quadratic_kinetic<Vec> k;
    k.recognise(h, 4);
    REQUIRE(k.recognised() == form::dense);
    CHECK((k.inverse_mass() - inverse_mass).cwiseAbs().maxCoeff() <= 8 * eps * 3.0);
    // Coupled beyond dense_limit: left to automatic differentiation.
    const auto chain = with_kinetic([](const auto& p) {
        const auto n = p.size();
        return 0.5 * p.squaredNorm() + 0.25 * (p.head(n - 1).array() * p.tail(n - 1).array()).sum();
    });
    CHECK(recognised(chain, quadratic_kinetic<Vec>::dense_limit) == form::dense);
    CHECK(recognised(chain, quadratic_kinetic<Vec>::dense_limit + 1) == form::not_quadratic);
}

TEST_CASE("quadratic_kinetic: kinetic energies that are not quadratic are refused") {
    // Relativistic (Gould & Tobochnik's problem of a fast particle): v = p / sqrt(1 + p^2).
    CHECK(recognised(with_kinetic([](const auto& p) {
                         using std::sqrt;
                         return sqrt(1.0 + p.squaredNorm());
                     }),
                     5) == form::not_quadratic);
    // A quartic correction far below the quadratic part's size.
    CHECK(recognised(with_kinetic([](const auto& p) { return 0.5 * p.squaredNorm() + 1e-9 * p.squaredNorm() * p.squaredNorm(); }),
                     5) == form::not_quadratic);
    // Linear in p (a vector potential's shift): dT/dp does not vanish at p = 0.
    CHECK(recognised(with_kinetic([](const auto& p) { return 0.5 * (p.array() - 0.1).square().sum(); }), 5) ==
          form::not_quadratic);
    // Homogeneous of degree 2 but not quadratic: |p|_4^2.
    CHECK(recognised(with_kinetic([](const auto& p) {
                         using std::sqrt;
                         return 0.5 * sqrt(p.array().square().square().sum());
                     }),
                     5) == form::not_quadratic);
    // The library's relativistic pendulum, whose velocity is analytic: never replaced.
    CHECK(recognised(hamiltonians::relativistic_pendulum{}, 3) == form::analytic);
}

}  // namespace test_core_test_quadratic_kinetic
