// Automatic differentiation of kinetic/potential against the analytic
// gradients of every ready-made system, to 1e-14 relative.
#include <doctest/doctest.h>

#include <cmath>

#include <sympl/methods/catalog.hpp>
#include <sympl/core/general_hamiltonian.hpp>
#include <sympl/core/hamiltonian.hpp>
#include <sympl/core/splitting_stepper.hpp>
#include <sympl/hamiltonians/double_well.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/morse.hpp>
#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/relativistic_pendulum.hpp>
#include <sympl/hamiltonians/stiff_fpu.hpp>
#include <sympl/hamiltonians/toda.hpp>
#include <sympl/hamiltonians/two_particle_spring.hpp>

namespace test_core_test_hamiltonian {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
// Wraps H and hides its analytic gradients, so the library must derive them.
template <class H>
struct energies_only {
    H h;
    template <class V> auto kinetic(const V& p) const { return h.kinetic(p); }
    template <class V> auto potential(const V& q) const { return h.potential(q); }
};

template <class H, class Vec>
void check_gradients(const H& h, const Vec& q, const Vec& p) {
    static_assert(has_analytic_force<H, Vec> && has_analytic_velocity<H, Vec>);
    static_assert(!has_analytic_force<energies_only<H>, Vec> && !has_analytic_velocity<energies_only<H>, Vec>);
    Vec f_exact, f_auto, v_exact, v_auto;
    force(h, q, f_exact);
    force(energies_only<H>{h}, q, f_auto);
    velocity(h, p, v_exact);
    velocity(energies_only<H>{h}, p, v_auto);
    CHECK((f_auto - f_exact).norm() <= 1e-14 * f_exact.norm());
    CHECK((v_auto - v_exact).norm() <= 1e-14 * v_exact.norm());
}
}  // namespace

TEST_CASE("hamiltonian: autodiff gradients equal analytic ones on every ready-made system") {
    SUBCASE("harmonic oscillator, fixed size 3") {
        check_gradients(hamiltonians::harmonic_oscillator{2.0, 1.5}, Eigen::Vector3d(0.3, -1, 2), Eigen::Vector3d(1, 2, -0.5));
    }
    SUBCASE("pendulum") {
        check_gradients(hamiltonians::pendulum{1.5, 0.8, 9.81}, Eigen::Matrix<double, 1, 1>(2.1), Eigen::Matrix<double, 1, 1>(-0.7));
    }
    SUBCASE("kepler") {
        check_gradients(hamiltonians::kepler{}, Eigen::Vector2d(0.4, -0.9), Eigen::Vector2d(1.2, 0.3));
    }
    SUBCASE("relativistic pendulum, dynamic size") {
        Eigen::VectorXd q(3), p(3);
        q << 0.5, -2.0, 1.0;
        p << 3.0, -0.2, 0.7;
        check_gradients(hamiltonians::relativistic_pendulum{2.0, 1.5, 0.7}, q, p);
    }
    SUBCASE("two particles joined by a spring (Gould & Tobochnik eq. 3.72)") {
        Eigen::Vector4d q(0.3, -1.0, 2.0, 0.5), p(1.0, 2.0, -0.5, 0.25);
        check_gradients(hamiltonians::two_particle_spring{1.5, 2.5}, q, p);
    }
    SUBCASE("Henon-Heiles") {
        check_gradients(hamiltonians::henon_heiles{}, Eigen::Vector2d(0.3, -0.4), Eigen::Vector2d(0.1, 0.2));
    }
    SUBCASE("stiff FPU, m = 3") {
        Eigen::Matrix<double, 6, 1> q, p;
        q << 0.3, -0.2, 0.5, 0.1, -0.4, 0.25;
        p << 1, 2, 3, 4, 5, 6;
        check_gradients(hamiltonians::stiff_fpu{}, q, p);
    }
    SUBCASE("outer solar system") {
        const hamiltonians::outer_solar_system s{};
        const auto x = s.initial_state();
        check_gradients(s, x.q, x.p);
    }
    SUBCASE("Kepler in 3-D") {
        check_gradients(hamiltonians::kepler{}, Eigen::Vector3d(0.4, -0.9, 0.3), Eigen::Vector3d(1.2, 0.3, -0.1));
    }
    SUBCASE("Morse, double well, Toda") {
        const Eigen::Vector3d q(0.3, -0.5, 1.7), p(0.2, -1.0, 0.4);
        check_gradients(hamiltonians::morse{2.0, 1.5, 0.8, 0.2}, q, p);
        check_gradients(hamiltonians::double_well{0.7}, q, p);
        check_gradients(hamiltonians::toda{}, q, p);
    }
    SUBCASE("FPU-beta chain, 21 particles (reverse mode)") {
        Eigen::VectorXd q(21), p(21);
        for (int i = 0; i < 21; ++i) {
            q[i] = std::sin(0.7 * i);
            p[i] = std::cos(1.3 * i);
        }
        check_gradients(hamiltonians::fpu_beta{0.8}, q, p);
    }
}

TEST_CASE("hamiltonian: a pair of lambdas, energy, and Hamilton's equations (Gould & Tobochnik eq. 3.73)") {
    auto h = make_hamiltonian([](const auto& p) { return 0.5 * p.squaredNorm(); },
                              [](const auto& q) { using std::cos; return 1.0 - cos(q[0]); });
    const phase_space<double, 1> x(Eigen::Matrix<double, 1, 1>(0.8), Eigen::Matrix<double, 1, 1>(-0.3));
    CHECK(energy(h, x) == doctest::Approx(0.045 + 1 - std::cos(0.8)).epsilon(1e-15));
    phase_space<double, 1> dxdt;
    hamilton_rhs(h, x, dxdt);
    CHECK(dxdt.q[0] == doctest::Approx(-0.3).epsilon(1e-15));          // dq/dt = dT/dp
    CHECK(dxdt.p[0] == doctest::Approx(-std::sin(0.8)).epsilon(1e-15));  // dp/dt = -dV/dq
}

TEST_CASE("hamiltonians: exact solutions agree with a 10th-order run (Kepler 3-D, Morse)") {
    {
        using S3 = phase_space<double, 3>;
        const double e = 0.6, i = 0.4, node = 1.1, w = -0.7;
        S3 x = hamiltonians::kepler::initial_state_3d(e, i, node, w);
        auto s = make_stepper<S3>(hamiltonians::kepler{}, method("sofroniou_spaletta_10"));
        s.steps(x, 0.005, 1000);
        CHECK(max_difference(x, hamiltonians::kepler::exact_state_3d(e, i, node, w, 5.0)) < 1e-11);
        // the orbit lies in the plane normal to the angular momentum
        const Eigen::Vector3d L = x.q.cross(x.p);
        CHECK(std::fabs(L.normalized().z() - std::cos(i)) < 1e-12);
    }
    {
        using S2 = phase_space<double, 2>;
        const hamiltonians::morse m{1.3, 2.0, 0.9, 0.5};
        const S2 x0(Eigen::Vector2d(0.2, 1.4), Eigen::Vector2d(0.8, -0.3));
        S2 x = x0;
        auto s = make_stepper<S2>(m, method("sofroniou_spaletta_10"));
        s.steps(x, 0.005, 2000);
        CHECK(max_difference(x, m.exact(x0, 10.0)) < 1e-11);
        CHECK_THROWS_AS(m.exact(S2(Eigen::Vector2d(0.5, 0.5), Eigen::Vector2d(5.0, 0.0)), 1.0), invalid_argument);
    }
}

TEST_CASE("hamiltonians: initial data of the cited problems") {
    // Henon-Heiles at energy 1/6 on the section q1 = 0.
    const auto hh = hamiltonians::henon_heiles::initial_state(1.0 / 6, 0.1, 0.05);
    CHECK(energy(hamiltonians::henon_heiles{}, hh) == doctest::Approx(1.0 / 6).epsilon(1e-15));
    CHECK_THROWS_AS(hamiltonians::henon_heiles::initial_state(0.001, 0.5), invalid_argument);
    // Stiff FPU (GNI I.5.1): the stiff spring's energy is (omega x_{1,1})^2/2 + y_{1,1}^2/2 = 1.
    const hamiltonians::stiff_fpu fpu{};
    const auto x = fpu.initial_state();
    const double d = x.q[1] - x.q[0], dp = x.p[1] - x.p[0];
    CHECK(0.5 * dp * dp / 2 + fpu.omega * fpu.omega / 4 * d * d == doctest::Approx(1.0));
    // Outer solar system: total momentum small, energy negative (a bound system).
    const hamiltonians::outer_solar_system sun{};
    const auto y = sun.initial_state();
    CHECK(energy(sun, y) < 0);
    CHECK(y.p.segment<3>(3).norm() == doctest::Approx(0.000954786104043 * Eigen::Vector3d(0.00565429, -0.00412490, -0.00190589).norm()));
}

namespace {
// FPU-beta without its gradients: everything from the potential by dual numbers.
struct fpu_potential_only {
    double beta = 1.0;
    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> auto potential(const V& q) const { return hamiltonians::fpu_beta{beta}.potential(q); }
};
}  // namespace

TEST_CASE("force_derivative: the analytic FPU-beta one and the potential's Hessian by dual numbers agree") {
    // J_F u three ways: fpu_beta's analytic force_derivative, forward over
    // forward mode on its potential alone, and central differences of the force.
    const hamiltonians::fpu_beta analytic{1.0};
    const fpu_potential_only by_duals{1.0};
    const int n = 21;  // more than two chunks of 8 directions
    Eigen::VectorXd q(n), u(n), a, d, f1, f2;
    for (int i = 0; i < n; ++i) q[i] = 0.4 * std::sin(0.9 * i + 0.3), u[i] = std::cos(1.7 * i);
    force_derivative(analytic, q, u, a);
    force_derivative(by_duals, q, u, d);
    const double e = 1e-5;
    const Eigen::VectorXd qa = q + e * u, qb = q - e * u;
    force(analytic, qa, f1);
    force(analytic, qb, f2);
    const Eigen::VectorXd differences = (f1 - f2) / (2 * e);
    CHECK((a - d).cwiseAbs().maxCoeff() <= 1e-13 * a.cwiseAbs().maxCoeff());
    // Central differences: truncation ~ e^2 |F'''| ~ 1e-10, rounding ~ 1e-16 / e ~ 1e-11.
    CHECK((a - differences).cwiseAbs().maxCoeff() <= 1e-8);
    // Fixed-size state, Kepler (analytic force, the potential differentiated twice).
    const hamiltonians::kepler k;
    Eigen::Vector2d q2(0.7, -0.3), u2(0.2, 0.5), df2;
    force_derivative(k, q2, u2, df2);
    const double r2 = q2.squaredNorm(), r3 = r2 * std::sqrt(r2);
    const Eigen::Vector2d exact = (3 * q2.dot(u2) / (r2 * r3)) * q2 - u2 / r3;
    CHECK((df2 - exact).cwiseAbs().maxCoeff() <= 1e-14);
    // Henon-Heiles' analytic J_F u against the Hessian of its potential by dual numbers.
    struct henon_heiles_potential_only {
        double kinetic(const Eigen::Vector2d& p) const { return p.squaredNorm() / 2; }
        auto potential(const detail::hessian_vector<Eigen::Vector2d>& q) const {
            return hamiltonians::henon_heiles{}.potential(q);
        }
        double potential(const Eigen::Vector2d& q) const { return hamiltonians::henon_heiles{}.potential(q); }
    };
    Eigen::Vector2d hh_analytic, hh_duals;
    force_derivative(hamiltonians::henon_heiles{}, q2, u2, hh_analytic);
    force_derivative(henon_heiles_potential_only{}, q2, u2, hh_duals);
    CHECK((hh_analytic - hh_duals).cwiseAbs().maxCoeff() <= 1e-15);
}

TEST_CASE("check_reads: generic code reading past the state is refused at the first call") {
    using SX = phase_space<double>;
    const table lf = method("leapfrog_kdk");
    const auto kinetic = [](const auto& p) { return 0.5 * p.squaredNorm(); };

    // V reads q[1] of a one-dimensional dynamic state: without the check every
    // force of a Release build would read memory the state does not own.
    auto two_d = make_hamiltonian(kinetic, [](const auto& q) { return 0.5 * (q[0] * q[0] + q[1] * q[1]); });
    auto s = make_stepper<SX>(two_d, lf);
    SX x(1);
    x.q[0] = 0.3;
    const char* expected = "splitting_stepper: the Hamiltonian's V(q) read q[1] of a state of dimension 1; "
                           "expected indices 0..0";
    CHECK_THROWS_WITH_AS(s.step(x, 0.1), expected, invalid_argument);
    CHECK_THROWS_WITH_AS(s.step(x, 0.1), expected, invalid_argument);  // refused again, not remembered as checked
    CHECK(x.q[0] == 0.3);                                               // and the state untouched
    SX x2(2);
    CHECK_NOTHROW(s.step(x2, 0.1));  // the dimension it is written for runs

    // T reads p[2] of a two-dimensional state, through operator().
    auto three_p = make_hamiltonian([](const auto& p) { return 0.5 * (p(0) * p(0) + p(2) * p(2)); },
                                    [](const auto& q) { return 0.5 * q.squaredNorm(); });
    SX y(2);
    CHECK_THROWS_WITH_AS(make_stepper<SX>(three_p, lf).step(y, 0.1),
                         "splitting_stepper: the Hamiltonian's T(p) read p[2] of a state of dimension 2; "
                         "expected indices 0..1",
                         invalid_argument);

    // A fixed-size state is checked too (Eigen's own check of q[i] is an assert).
    using S1 = phase_space<double, 1>;
    auto fixed_read = make_hamiltonian(kinetic, [](const auto& q) { return q(0) * q[1]; });
    S1 z;
    CHECK_THROWS_WITH_AS(make_stepper<S1>(fixed_read, lf).step(z, 0.1), expected, invalid_argument);
    // q.y() is a read of q[1] (on a dynamic state: on a fixed one Eigen refuses it at compile time).
    auto y_read = make_hamiltonian(kinetic, [](const auto& q) { return q.x() * q.y(); });
    CHECK_THROWS_WITH_AS(check_state(y_read, SX(1), "splitting_stepper"), expected, invalid_argument);

    // Blocks are reads too: two bodies in 3-D read from a state of dimension 4.
    auto bodies = make_hamiltonian(kinetic, [](const auto& q) {
        using std::sqrt;
        return -1 / sqrt((q.template segment<3>(0) - q.template segment<3>(3)).squaredNorm());
    });
    SX b(4);
    b.q << 1, 0, 0, 0;
    CHECK_THROWS_WITH_AS(check_state(bodies, b, "splitting_stepper"),
                         "splitting_stepper: the Hamiltonian's V(q) read q[3..5] of a state of dimension 4; "
                         "expected indices 0..3",
                         invalid_argument);
    auto tail_read = make_hamiltonian([](const auto& p) { return 0.5 * p.tail(3).squaredNorm(); }, kinetic);
    CHECK_THROWS_WITH_AS(check_state(tail_read, SX(2), "splitting_stepper"),
                         "splitting_stepper: the Hamiltonian's T(p) read p[-1..1] of a state of dimension 2; "
                         "expected indices 0..1",
                         invalid_argument);

    // A general H(q, p), evaluated as check_state does at a stepper's first call.
    auto general = make_general_hamiltonian(
        [](const auto& q, const auto& p) { return 0.5 * (1 + q[0] * q[0]) * (1 + p[1] * p[1]); });
    CHECK_THROWS_WITH_AS(check_state(general, SX(1), "gauss_collocation_stepper"),
                         "gauss_collocation_stepper: the Hamiltonian's H(q, p) read p[1] of a state of dimension 1; "
                         "expected indices 0..0",
                         invalid_argument);
    CHECK_NOTHROW(check_state(general, SX(2), "gauss_collocation_stepper"));
}

TEST_CASE("check_reads: correct Hamiltonians pass and run bit for bit as without the check") {
    const table lf = method("leapfrog_kdk");
    // Whole-vector operations only, on a dynamic state.
    auto whole = make_hamiltonian([](const auto& p) { return 0.5 * p.dot(p); },
                                  [](const auto& q) {
                                      using std::cos;
                                      return 0.5 * q.squaredNorm() + 0.1 * q.sum() * q.sum() +
                                             q.head(2).norm() - cos(q.segment(1, 2).sum());
                                  });
    using SX = phase_space<double>;
    SX x(3);
    x.q << 0.3, -0.2, 0.7;
    x.p << 0.1, 0.4, -0.5;
    const SX x0 = x;
    // The checked vector computes what the state's vector computes, bit for bit.
    using checked = detail::checked_vector<double, Eigen::Dynamic>;
    const detail::read_site site{"test", "V(q)", "q"};
    CHECK(whole.potential(checked(x.q, site)) == whole.potential(x.q));

    // The first run is checked (first call for this Hamiltonian type and dimension),
    // the second is not: their results agree bit for bit.
    auto first = make_stepper<SX>(whole, lf);
    first.steps(x, 0.01, 100);
    SX again = x0;
    auto second = make_stepper<SX>(whole, lf);
    second.steps(again, 0.01, 100);
    CHECK((x.q.array() == again.q.array()).all());
    CHECK((x.p.array() == again.p.array()).all());
    CHECK(x.q != x0.q);

    // Indexed reads within the state, fixed size: pass.
    using S2 = phase_space<double, 2>;
    auto indexed = make_hamiltonian([](const auto& p) { return 0.5 * (p[0] * p[0] + p(1) * p(1)); },
                                    [](const auto& q) { using std::cos; return -cos(q[0]) - cos(q.coeff(1)); });
    const S2 z0(Eigen::Vector2d(0.5, -0.2), Eigen::Vector2d(0.0, 0.3));
    S2 z = z0, z_again = z0;
    CHECK_NOTHROW(make_stepper<S2>(indexed, lf).steps(z, 0.01, 100));  // checked
    make_stepper<S2>(indexed, lf).steps(z_again, 0.01, 100);            // not checked again
    CHECK(z.q == z_again.q);
    CHECK(z.p == z_again.p);
    CHECK(z.q != z0.q);

    // A lambda whose signature takes only the concrete vector still runs (unchecked).
    auto concrete = make_hamiltonian([](const Eigen::VectorXd& p) { return 0.5 * p.squaredNorm(); },
                                     [](const Eigen::VectorXd& q) { return 0.5 * q.squaredNorm(); });
    SX w(2);
    w.q[0] = 1;
    CHECK_NOTHROW(check_state(concrete, w, "splitting_stepper"));
}

}  // namespace test_core_test_hamiltonian
