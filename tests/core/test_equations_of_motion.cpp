// Equations of motion in pair form: Newton's x'' = a(x, v, t), Hamilton's
// equations, and the non-Hamiltonian damped, driven oscillator with its exact
// solution in every regime.
#include <doctest/doctest.h>

#include <cmath>
#include <type_traits>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/damped_driven_oscillator.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/two_particle_spring.hpp>

namespace test_core_test_equations_of_motion {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using State = phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;
}  // namespace

TEST_CASE("equations_of_motion: make_newtonian tells a(x, t) from a(x, v, t)") {
    const auto free_fall = make_newtonian([](const auto& x, auto) { return (0 * x).eval(); });
    const auto drag = make_newtonian([](const auto&, const auto& v, auto) { return (-v).eval(); });
    static_assert(!force_depends_on_velocity<decltype(free_fall)>());
    static_assert(force_depends_on_velocity<decltype(drag)>());
    static_assert(newtonian_form<decltype(drag)> && equations_of_motion<decltype(drag), State>);
    V1 out;
    drag.dp_dt(V1(1.0), V1(2.0), 0.0, out);
    CHECK(out[0] == -2.0);
    drag.dq_dt(V1(1.0), V1(2.0), 0.0, out);
    CHECK(out[0] == 2.0);
}

TEST_CASE("equations_of_motion: a separable Hamiltonian gives Hamilton's equations (eq. 3.73)") {
    const hamiltonians::pendulum h{1.5, 0.8, 9.81};
    const auto e = equations_of<State>(h);
    static_assert(!force_depends_on_velocity<decltype(e)>() && !newtonian_form<decltype(e)>);
    const State x(V1(0.4), V1(-1.1));
    State rhs;
    hamilton_rhs(h, x, rhs);
    V1 dq, dp;
    e.dq_dt(x.q, x.p, 0.0, dq);
    e.dp_dt(x.q, x.p, 0.0, dp);
    CHECK(dq[0] == rhs.q[0]);
    CHECK(dp[0] == rhs.p[0]);
}

TEST_CASE("equations_of_motion: a generic quadratic T gives dq/dt = M^-1 p, recognised once per dimension") {
    // T = sum p_i^2 / (2 m_i) written generically: recognised as diagonal, so
    // dq/dt is the product p_i / m_i, equal to the gradient of T to rounding.
    // A T that is not quadratic (sqrt(1 + |p|^2)) stays a gradient.
    using Vec = Eigen::VectorXd;
    using DState = phase_space<double>;
    const auto masses = [](const auto& p) {
        using S = typename std::decay_t<decltype(p)>::Scalar;
        S t(0);
        for (Eigen::Index i = 0; i < p.size(); ++i) t += p[i] * p[i] / (2.0 * (1.0 + 0.5 * double(i)));
        return t;
    };
    const auto cosine = [](const auto& q) { using std::cos; return 1.0 - cos(q[0]); };
    const auto quadratic = equations_of<DState>(make_hamiltonian(masses, cosine));
    const auto relativistic = equations_of<DState>(
        make_hamiltonian([](const auto& p) { using std::sqrt; return sqrt(1.0 + p.squaredNorm()); }, cosine));
    for (Eigen::Index n : {3, 40}) {
        Vec q = Vec::Constant(n, 0.3), p(n), v, expected(n), w;
        for (Eigen::Index i = 0; i < n; ++i) p[i] = 0.7 * std::sin(1.3 * double(i + 1));
        for (Eigen::Index i = 0; i < n; ++i) expected[i] = p[i] / (1.0 + 0.5 * double(i));
        quadratic.dq_dt(q, p, 0.0, v);
        CAPTURE(n);
        CHECK(quadratic.kinetic.recognised() == quadratic_kinetic<Vec>::form::diagonal);
        CHECK(quadratic.kinetic.dimension() == n);
        CHECK((v - expected).norm() <= 4e-16 * expected.norm());
        relativistic.dq_dt(q, p, 0.0, w);
        CHECK(relativistic.kinetic.recognised() == quadratic_kinetic<Vec>::form::not_quadratic);
        CHECK((w - p / std::sqrt(1.0 + p.squaredNorm())).norm() <= 1e-15 * w.norm());
    }
}

TEST_CASE("damped_driven_oscillator: the exact solution solves m x'' + b x' + k x = F0 cos(W t) in every regime") {
    struct regime {
        const char* name;
        hamiltonians::damped_driven_oscillator o;
    };
    const regime regimes[] = {
        {"underdamped, driven", {1.3, 2.0, 0.4, 0.7, 1.1}},
        {"overdamped, driven", {1.0, 1.0, 3.0, 0.5, 0.7}},
        {"critically damped", {1.0, 1.0, 2.0, 0.5, 0.3}},
        {"undamped, driven off resonance", {1.0, 4.0, 0.0, 1.0, 1.0}},
        {"undamped at resonance", {1.0, 4.0, 0.0, 1.0, 2.0}},
        {"free particle with drag", {1.0, 0.0, 0.5, 0.0, 0.0}},
    };
    const State x0(V1(0.8), V1(-0.4));
    for (const regime& r : regimes) {
        CAPTURE(r.name);
        const auto& o = r.o;
        CHECK(max_difference(o.exact(x0, 0.0), x0) < 1e-15);
        const double h = 1e-4;
        for (const double t : {0.5, 2.0, 7.0}) {
            const double xm = o.exact(x0, t - h).q[0], xc = o.exact(x0, t).q[0], xp = o.exact(x0, t + h).q[0];
            const double v = o.exact(x0, t).p[0];
            const double acceleration = (xp - 2 * xc + xm) / (h * h);
            CHECK(std::fabs(v - (xp - xm) / (2 * h)) < 1e-7);
            const double residual = o.mass * acceleration + o.damping * v + o.stiffness * xc -
                                    o.drive_amplitude * std::cos(o.drive_frequency * t);
            CHECK(std::fabs(residual) < 1e-5);
        }
    }
}

TEST_CASE("two_particle_spring: the exact solution (centre of mass + relative oscillator) matches a 10th-order run") {
    const hamiltonians::two_particle_spring h{1.3, 2.1};
    using S4 = phase_space<double, 4>;
    const S4 x0 = hamiltonians::two_particle_spring::initial_state();
    S4 x = x0;
    auto s = make_stepper<S4>(h, method("sofroniou_spaletta_10"));
    s.steps(x, 0.01, 1000);
    CHECK(max_difference(x, h.exact(x0, 10.0)) < 1e-12);
    CHECK(std::fabs(energy(h, h.exact(x0, 10.0)) - energy(h, x0)) < 1e-14);
}

}  // namespace test_core_test_equations_of_motion
