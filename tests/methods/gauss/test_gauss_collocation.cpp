// Gauss-Legendre collocation (methods/gauss/gauss_collocation.hpp) on the three
// non-separable systems of hamiltonians/: their analytic gradients, the orders
// 2s, symplecticity of the step map to rounding, bounded energy error, and bad input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/core/general_hamiltonian.hpp>
#include <sympl/methods/gauss/gauss_collocation.hpp>
#include <sympl/hamiltonians/charged_particle.hpp>
#include <sympl/hamiltonians/double_pendulum.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/product_hamiltonian.hpp>

namespace test_methods_test_gauss_collocation {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using State = phase_space<double, 2>;
using V2 = Eigen::Vector2d;
constexpr double eps = std::numeric_limits<double>::epsilon();

const hamiltonians::charged_particle charged{};
const hamiltonians::double_pendulum pendulum2{};
const hamiltonians::product_hamiltonian product{};

// One start per system: nonlinear motion well away from equilibria.
const State charged_start(V2(0.5, 0.2), V2(0.1, 0.4));
const State pendulum2_start(V2(1.0, 0.5), V2(0.2, -0.1));
const State product_start(V2(0.6, -0.3), V2(0.4, 0.2));

// The same energy with no analytic gradients: dH_dq and dH_dp by dual numbers.
template <class H>
auto by_duals(const H& h) {
    return make_general_hamiltonian([h](const auto& q, const auto& p) { return h.energy(q, p); });
}

template <class S, class H>
phase_space<S, 2> run(const H& h, int stages, phase_space<S, 2> x, S t_end, long n) {
    auto stepper = make_gauss_collocation<phase_space<S, 2>>(h, stages);
    const S dt = t_end / S(n);
    for (long i = 0; i < n; ++i) stepper.step(x, dt);
    return x;
}

// max |M^T J M - J| for the one-step map x -> x1 with M = dx1/dx, read off
// dual numbers carried through the step; also returns max |M_ij| and max |M - I|.
template <class H>
std::tuple<double, double, double> symplecticity_defect(const H& h, int stages, const State& x0, double dt,
                                               gauss_options options = {}) {
    using D = dual<double, 4>;
    using DState = phase_space<D, 2>;
    DState x;
    for (int i = 0; i < 2; ++i) {
        x.q[i] = D::variable(x0.q[i], i);
        x.p[i] = D::variable(x0.p[i], 2 + i);
    }
    auto stepper = make_gauss_collocation<DState>(h, stages, options);
    stepper.step(x, D(dt));
    Eigen::Matrix4d M, J = Eigen::Matrix4d::Zero();
    for (int i = 0; i < 2; ++i)
        for (int k = 0; k < 4; ++k) {
            M(i, k) = x.q[i].grad[k];
            M(2 + i, k) = x.p[i].grad[k];
        }
    J.topRightCorner<2, 2>().setIdentity();
    J.bottomLeftCorner<2, 2>() = -Eigen::Matrix2d::Identity();
    return {(M.transpose() * J * M - J).cwiseAbs().maxCoeff(), M.cwiseAbs().maxCoeff(),
            (M - Eigen::Matrix4d::Identity()).cwiseAbs().maxCoeff()};
}

// max |H - H0| over the first n1 and over all n steps of size dt.
template <class Stepper, class H>
std::pair<double, double> energy_errors(Stepper stepper, const H& h, State x, double dt, int n1, int n) {
    const double e0 = energy(h, x);
    double early = 0, all = 0;
    for (int i = 1; i <= n; ++i) {
        stepper.step(x, dt);
        const double e = std::fabs(energy(h, x) - e0);
        all = std::max(all, e);
        if (i <= n1) early = e > early ? e : early;
    }
    return {early, all};
}
}  // namespace

TEST_CASE("gauss_collocation: the tableaus satisfy B(2s), C(s) and the symplecticity condition") {
    // Order 2s needs the quadrature B(2s): sum b_i c_i^(k-1) = 1/k, k <= 2s, and the
    // collocation conditions C(s): sum_j a_ij c_j^(k-1) = c_i^k / k (GNI sec. II.1.3);
    // symplectic: b_i a_ij + b_j a_ji = b_i b_j (GNI Thm. VI.4.3); d^T A = b^T (GNI sec. VIII.6).
    for (int s = 1; s <= max_gauss_stages; ++s) {
        CAPTURE(s);
        // Sums of s products of computed entries, each entry a few roundings
        // off (s >= 4 come from a Newton solve and a linear system): the
        // error grows as s^2 eps (measured 58 eps at s = 6).
        const long double tol = 16 * s * s * std::numeric_limits<long double>::epsilon();
        const gauss_tableau t = gauss_legendre_tableau(s);
        CHECK(t.order == 2 * s);
        for (int k = 1; k <= 2 * s; ++k) {
            long double v = 0;
            for (int i = 0; i < s; ++i) v += t.b[i] * std::pow(t.c[i], (long double)(k - 1));
            CHECK(std::fabs(v - 1.0L / k) <= tol);
        }
        for (int i = 0; i < s; ++i)
            for (int k = 1; k <= s; ++k) {
                long double v = 0;
                for (int j = 0; j < s; ++j) v += t.a[i][j] * std::pow(t.c[j], (long double)(k - 1));
                CHECK(std::fabs(v - std::pow(t.c[i], (long double)k) / k) <= tol);
            }
        for (int i = 0; i < s; ++i)
            for (int j = 0; j < s; ++j) {
                CHECK(std::fabs(t.b[i] * t.a[i][j] + t.b[j] * t.a[j][i] - t.b[i] * t.b[j]) <= tol);
            }
        for (int j = 0; j < s; ++j) {
            long double v = 0;
            for (int i = 0; i < s; ++i) v += t.d[i] * t.a[i][j];
            CHECK(std::fabs(v - t.b[j]) <= tol);
        }
    }
    CHECK_THROWS_AS(gauss_legendre_tableau(0), invalid_argument);
    CHECK_THROWS_AS(gauss_legendre_tableau(max_gauss_stages + 1), invalid_argument);
}

TEST_CASE("gauss_collocation: each analytic gradient equals the dual-number gradient of its energy") {
    // Both are exact derivatives of one formula: they differ by rounding only,
    // a few eps times the size of the terms summed (relative 1e-13 leaves room
    // for the cancellations in dT/dd of the double pendulum).
    const auto agree = [](const auto& h, const State& x) {
        const auto g = by_duals(h);
        State::vector aq, ap, dq, dp;
        h.dH_dq(x.q, x.p, aq);
        h.dH_dp(x.q, x.p, ap);
        dH_dq(g, x.q, x.p, dq);
        dH_dp(g, x.q, x.p, dp);
        const double scale = std::max(dq.cwiseAbs().maxCoeff(), dp.cwiseAbs().maxCoeff());
        CHECK(scale > 0.1);  // a point where the gradient is not small
        CHECK((aq - dq).cwiseAbs().maxCoeff() <= 1e-13 * scale);
        CHECK((ap - dp).cwiseAbs().maxCoeff() <= 1e-13 * scale);
        // and the analytic member is the one the free function picks
        State::vector viaq;
        dH_dq(h, x.q, x.p, viaq);
        CHECK(viaq == aq);
    };
    const State points[] = {State(V2(0.5, 0.2), V2(0.1, 0.4)), State(V2(-1.3, 2.1), V2(0.7, -1.9)),
                            State(V2(2.5, -0.4), V2(-3.0, 0.25))};
    hamiltonians::charged_particle other;
    other.mass = 1.7;
    other.charge = -0.6;
    other.field = 2.3;
    other.field_length = 0.8;
    other.confinement = 0.4;
    hamiltonians::double_pendulum unequal;
    unequal.mass1 = 2.0;
    unequal.mass2 = 0.5;
    unequal.length1 = 1.5;
    unequal.length2 = 0.7;
    unequal.gravity = 9.81;
    for (const State& x : points) {
        agree(charged, x);
        agree(other, x);
        agree(pendulum2, x);
        agree(unequal, x);
        agree(product, x);
    }
    // The product Hamiltonian in any dimension.
    const Eigen::Vector3d q(0.3, -1.2, 0.8), p(1.1, 0.4, -0.6);
    Eigen::Vector3d a, d;
    product.dH_dq(q, p, a);
    dH_dq(by_duals(product), q, p, d);
    CHECK((a - d).cwiseAbs().maxCoeff() <= 1e-13 * d.cwiseAbs().maxCoeff());
}

TEST_CASE("gauss_collocation: s = 1, 2, 3 converge with orders 2, 4, 6 on each system") {
    // Global error at t = 3 against s = 3 in long double at 1024 steps (which
    // differs from 2048 steps by ~1e-18: a reference 1e6 below the smallest
    // error read). The step counts put the errors between 1e-3 and 1e-12, in
    // the asymptotic range (measured slopes at the next coarser pair are within
    // 0.05 of 2s, except s = 3 on the double pendulum at 16 -> 32, 5.7) and
    // 1000 times above the rounding floor of a double run (~1e-15).
    const auto order = [](const auto& h, const State& x0, int s, long n) {
        const auto ref = run<long double>(h, 3, x0.cast<long double>(), 3.0L, 1024);
        const auto e = [&](long m) {
            return double(max_difference(run<double>(h, s, x0, 3.0, m).template cast<long double>(), ref));
        };
        const double e1 = e(n), e2 = e(2 * n);
        CHECK(e2 > 1e3 * eps);  // above rounding
        return std::log2(e1 / e2);
    };
    for (int s = 1; s <= 3; ++s) {
        CAPTURE(s);
        const long n = s == 3 ? 32 : 64;
        const double p1 = order(charged, charged_start, s, n);
        const double p2 = order(pendulum2, pendulum2_start, s, n);
        const double p3 = order(product, product_start, s, n);
        MESSAGE("s = " << s << ": orders " << p1 << ", " << p2 << ", " << p3);
        CHECK(std::fabs(p1 - 2 * s) <= 0.15);
        CHECK(std::fabs(p2 - 2 * s) <= 0.15);
        CHECK(std::fabs(p3 - 2 * s) <= 0.15);
    }
}

TEST_CASE("gauss_collocation: the step map is symplectic to rounding (dual numbers through one step)") {
    // M^T J M = J holds exactly for the exact stage solution (GNI Thm. VI.4.3).
    // With the iteration converged to rounding on values and derivatives, each
    // entry of M carries an error of a few eps |M| (amplified at most by
    // sum |d_i| = 14/3 in y1 = y0 + sum d_i Z_i); each entry of M^T J M sums
    // 2n = 4 products of two entries: bound 4 * 2 * 16 eps |M|^2.
    const auto check = [](const auto& h, const State& x0, double dt) {
        for (int s = 1; s <= 3; ++s) {
            CAPTURE(s);
            const auto [defect, m, moved] = symplecticity_defect(h, s, x0, dt);
            const double bound = 4 * 2 * 16 * eps * m * m;
            MESSAGE("s = " << s << ", dt = " << dt << ": defect " << defect << ", |M| " << m << ", |M - I| " << moved
                           << ", bound " << bound);
            CHECK(defect <= bound);
            // The map is far from the identity, so the check sees the method's terms.
            CHECK(moved > 0.1);
        }
    };
    check(charged, charged_start, 0.4);
    check(pendulum2, pendulum2_start, 0.4);
    check(product, product_start, 0.4);
    // The same check fails for a solve stopped early: symplecticity needs the
    // converged stages (a tolerance of 1e-5 leaves a defect far above rounding).
    gauss_options loose;
    loose.tolerance = 1e-5;
    const auto [defect, m, moved] = symplecticity_defect(pendulum2, 2, pendulum2_start, 0.4, loose);
    (void)moved;
    MESSAGE("tolerance 1e-5: defect " << defect);
    CHECK(defect > 4 * 2 * 16 * eps * m * m);
}

TEST_CASE("gauss_collocation: the energy error stays bounded over 10^4 steps (no drift)") {
    // A symplectic method keeps H within O(dt^2s) of H0 over exponentially long
    // times (GNI Thm. IX.8.1): the largest error over 10^4 steps is the largest
    // over the first 10^3 (which span several periods), up to the phase of the
    // oscillation; a factor of 3 allows for that, while a linear drift would give 10.
    // dt = 0.1 puts the energy error (1e-3 .. 4e-12) 100 times above the
    // rounding's random walk over 10^4 steps (~ sqrt(10^4) eps |H0|), which would drift.
    const auto bounded = [](const auto& h, const State& x0, double dt) {
        const double walk = std::sqrt(1e4) * eps * std::fabs(energy(h, x0));
        for (int s = 1; s <= 3; ++s) {
            CAPTURE(s);
            const auto [early, all] =
                energy_errors(make_gauss_collocation<State>(h, s), h, x0, dt, 1000, 10000);
            MESSAGE("s = " << s << ": max |H - H0| " << early << " (10^3 steps), " << all << " (10^4 steps)");
            CHECK(early > 100 * walk);
            CHECK(all <= 3 * early);
        }
    };
    bounded(charged, charged_start, 0.1);
    bounded(pendulum2, pendulum2_start, 0.1);
    bounded(product, product_start, 0.1);

    // The same measure catches the drift of a non-symplectic method of order 4:
    // the classical Runge-Kutta method, written out here for a general H.
    struct rk4 {
        void step(State& x, double dt) const {
            const auto f = [](const State& y) {
                State d;
                dH_dp(product, y.q, y.p, d.q);
                dH_dq(product, y.q, y.p, d.p);
                d.p = -d.p;
                return d;
            };
            const auto add = [](const State& y, const State& k, double c) {
                return State(y.q + c * k.q, y.p + c * k.p);
            };
            const State k1 = f(x), k2 = f(add(x, k1, dt / 2)), k3 = f(add(x, k2, dt / 2)), k4 = f(add(x, k3, dt));
            x.q += dt / 6 * (k1.q + 2 * k2.q + 2 * k3.q + k4.q);
            x.p += dt / 6 * (k1.p + 2 * k2.p + 2 * k3.p + k4.p);
        }
    };
    const auto [early, all] = energy_errors(rk4{}, product, product_start, 0.1, 1000, 10000);
    MESSAGE("rk4: max |H - H0| " << early << " (10^3 steps), " << all << " (10^4 steps)");
    CHECK(all > 3 * early);
}

TEST_CASE("gauss_collocation: quadratic invariants are kept to rounding (canonical angular momentum)") {
    // Gauss collocation conserves every quadratic invariant exactly (GNI Thm.
    // IV.2.2); the field of charged_particle is symmetric about the origin, so
    // x p_y - y p_x is one. What remains is rounding: per step a few eps |q||p|,
    // summed over 2000 steps as a random walk (<= sqrt(2000) ~ 45, bound 200).
    const auto L = [](const State& x) { return x.q[0] * x.p[1] - x.q[1] * x.p[0]; };
    for (int s = 1; s <= 3; ++s) {
        CAPTURE(s);
        auto stepper = make_gauss_collocation<State>(charged, s);
        State x = charged_start;
        const double l0 = L(x);
        double worst = 0, size = 0;
        for (int i = 0; i < 2000; ++i) {
            stepper.step(x, 0.1);
            worst = std::max(worst, std::fabs(L(x) - l0));
            size = std::max(size, x.q.norm() * x.p.norm());
        }
        MESSAGE("s = " << s << ": max |L - L0| " << worst);
        CHECK(worst <= 200 * eps * size);
    }
}

TEST_CASE("gauss_collocation: separable Hamiltonians, the driver, counters, time reversal") {
    using S1 = phase_space<double, 1>;
    using V1 = Eigen::Matrix<double, 1, 1>;
    const hamiltonians::pendulum pendulum{};
    // T(p) + V(q) through the adapter and the same H written as one general H(q, p):
    // the same iteration, the same result to rounding.
    auto a = make_gauss_collocation<S1>(pendulum, 3);
    auto b = make_gauss_collocation<S1>(make_general_hamiltonian([](const auto& q, const auto& p) {
                                            using std::cos;
                                            return 0.5 * p.squaredNorm() + (1 - cos(q[0]));
                                        }),
                                        3);
    S1 xa(V1(1.2), V1(0.3)), xb = xa;
    for (int i = 0; i < 100; ++i) {
        a.step(xa, 0.1);
        b.step(xb, 0.1);
    }
    CHECK(max_difference(xa, xb) <= 1e3 * eps);
    CHECK(std::fabs(energy(pendulum, xa) - energy(pendulum, S1(V1(1.2), V1(0.3)))) < 1e-8);

    // integrate_until drives it; each iteration costs s evaluations of dH/dq and of dH/dp.
    auto g = make_gauss_collocation<State>(product, 2);
    State x = product_start;
    const auto r = integrate_until(g, x, 0.0, 1.0, 0.1);
    CHECK(r.steps == 10);
    // The first step starts from Euler's polynomial (one evaluation), the others
    // from the last step's; the fixed-point iteration needs no Jacobian here.
    CHECK(r.force_evaluations == r.velocity_evaluations);
    CHECK(r.force_evaluations == 1 + 2 * g.iterations());
    CHECK(g.iterations() >= 10 * 2);
    CHECK(g.jacobian_evaluations() == 0);
    CHECK_FALSE(g.iterating_by_newton());
    CHECK(g.last_iterations() >= 2);
    CHECK(g.last_residual() <= gauss_rounding_plateau);

    // Symmetric: a step back undoes a step to rounding.
    State y = product_start;
    g.step(y, 0.2);
    g.step(y, -0.2);
    CHECK(max_difference(y, product_start) <= 64 * eps);

    // Dynamic size and long double.
    using SL = phase_space<long double>;
    auto l = make_gauss_collocation<SL>(product, 1);
    SL z(Eigen::Matrix<long double, -1, 1>::Constant(3, 0.5L), Eigen::Matrix<long double, -1, 1>::Constant(3, -0.2L));
    const long double e0 = energy(product, z);
    for (int i = 0; i < 20; ++i) l.step(z, 0.05L);
    CHECK(std::fabs(double(energy(product, z) - e0)) < 1e-3);
    CHECK(l.tolerance() == doctest::Approx(double(std::numeric_limits<long double>::epsilon())));
}

TEST_CASE("gauss_collocation: bad input and a solve that does not converge name the values") {
    auto g = make_gauss_collocation<State>(pendulum2, 2);
    State x = pendulum2_start;
    const auto message = [&](double dt) {
        try {
            g.step(x, dt);
        } catch (const invalid_argument& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(message(std::numeric_limits<double>::quiet_NaN()).find("dt = nan") != std::string::npos);
    CHECK(message(std::numeric_limits<double>::infinity()).find("dt = inf") != std::string::npos);
    CHECK(message(0.0).find("dt = 0;") != std::string::npos);
    CHECK(max_difference(x, pendulum2_start) == 0);
    CHECK_THROWS_AS(make_gauss_collocation<State>(pendulum2, 7), invalid_argument);  // 1 .. 6 stages
    gauss_options bad;
    bad.tolerance = -1;
    CHECK_THROWS_AS(make_gauss_collocation<State>(pendulum2, 2, bad), invalid_argument);
    bad = {};
    bad.max_iterations = 0;
    CHECK_THROWS_AS(make_gauss_collocation<State>(pendulum2, 2, bad), invalid_argument);
    State nan_state = pendulum2_start;
    nan_state.p[1] = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(g.step(nan_state, 0.1), invalid_argument);

    // One iteration cannot reach rounding from the Euler start.
    gauss_options once;
    once.max_iterations = 1;
    auto h = make_gauss_collocation<State>(pendulum2, 3, once);
    try {
        h.step(x, 0.25);
        FAIL("expected integration_error");
    } catch (const integration_error& e) {
        const std::string w = e.what();
        MESSAGE(w);
        CHECK(w.find("dt = 0.25") != std::string::npos);
        CHECK(w.find("after 1 iteration") != std::string::npos);
        CHECK(w.find("max_iterations = 1") != std::string::npos);
        CHECK(w.find("tolerance 2.2204460492503131e-16") != std::string::npos);  // eps
        CHECK(w.find("correction " + detail::number_text(h.last_residual())) != std::string::npos);
    }
    CHECK(max_difference(x, pendulum2_start) == 0);  // x untouched

    // A huge step on the double pendulum: the simplified Newton iteration
    // diverges (or stalls), reported, and through the driver with the step's index.
    auto big = make_gauss_collocation<State>(pendulum2, 2);
    State fast(V2(2.0, -1.0), V2(3.0, 2.0));
    const State before = fast;
    try {
        integrate_steps(big, fast, 0.0, 20.0, 3);
        FAIL("expected integration_error");
    } catch (const integration_error& e) {
        const std::string w = e.what();
        MESSAGE(w);
        CHECK(w.find("dt = 20") != std::string::npos);
        CHECK(w.find("(step 1)") != std::string::npos);
        CHECK(e.step == 1);
    }
    CHECK(max_difference(fast, before) == 0);
}

TEST_CASE("gauss_collocation: converges on a badly scaled state (the outer solar system, dt = 200 .. 1 day)") {
    // Positions of 5 to 40 AU, momenta of 1e-11 to 1e-5: a correction measured
    // against the largest component asked 8 eps of the momenta, which rounding
    // cannot give, and stalled at 1.5e-13 (issue 39). Measured per component
    // against atol + rtol |y| and stopped at the rounding plateau, every step
    // converges: the sweep of the built-in scene (200 .. 5 days, 7 step sizes)
    // and dt = 100, 10, 1, for s = 1, 2, 3, 20 steps each, in every iteration mode.
    using S = phase_space<double, hamiltonians::outer_solar_system::dimension>;
    const hamiltonians::outer_solar_system sun{};
    const S x0 = sun.initial_state();
    const double e0 = energy(sun, x0);
    std::vector<double> steps{100, 10, 1};
    for (int k = 0; k < 7; ++k) steps.push_back(200 * std::pow(5.0 / 200, k / 6.0));
    for (const gauss_iteration mode : {gauss_iteration::automatic, gauss_iteration::fixed_point, gauss_iteration::newton})
        for (int s = 1; s <= 3; ++s)
            for (const double dt : steps) {
                CAPTURE(s);
                CAPTURE(dt);
                CAPTURE(int(mode));
                gauss_options options;
                options.iteration = mode;
                auto g = make_gauss_collocation<S>(sun, s, options);
                S x = x0;
                int most = 0;
                for (int i = 0; i < 20; ++i) {
                    REQUIRE_NOTHROW(g.step(x, dt));
                    most = std::max(most, g.last_iterations());
                    CHECK(g.last_residual() <= gauss_rounding_plateau);
                }
                // At most 30 iterations a step (measured: 2 to 21), and H kept to the
                // method's error (the implicit midpoint's at 100-day steps: 1.6e-3).
                CHECK(most <= 30);
                CHECK(std::fabs(energy(sun, x) / e0 - 1) < (s == 1 ? 1e-2 : 1e-5));
            }
}

TEST_CASE("gauss_collocation: steps across the pericentre of e = 0.99 converge by Newton refreshed at the stages") {
    // The scene kepler_e0.99 sweeps dt = 0.002 .. 2e-5 from the pericentre
    // (r = 0.01, speed 14). A Jacobian at y0 is too far from the stages at the
    // larger steps (s = 2 at 0.002 crawled to 1.4e-11 in 50 iterations); the
    // last attempt refreshes it at the stages' mean every iteration. The
    // implicit midpoint rule at 0.002 (the step moves 3 pericentre distances)
    // still finds no stage value, and says so.
    using S = phase_space<double, 2>;
    const hamiltonians::kepler k{};
    for (int s = 1; s <= 3; ++s)
        for (int j = 0; j < 5; ++j) {
            const double dt = 0.002 * std::pow(0.01, j / 4.0);
            CAPTURE(s);
            CAPTURE(dt);
            auto g = make_gauss_collocation<S>(k, s);
            S x = hamiltonians::kepler::initial_state<double>(0.99);
            const S x0 = x;
            bool failed = false;
            try {
                for (int i = 0; i < 20; ++i) g.step(x, dt);
            } catch (const integration_error& e) {
                failed = true;
                CHECK(std::string(e.what()).find("did not converge") != std::string::npos);
            }
            CHECK(failed == (s == 1 && j == 0));
            // Converged, not accurate: these steps are far too large for the pericentre.
            if (!failed) CHECK(std::isfinite(energy(k, x)));
            CHECK(std::isfinite(energy(k, x0)));
        }
}

TEST_CASE("gauss_collocation: a general H reading past the state is refused at the first step") {
    // H reads p[1] of a one-dimensional dynamic state: refused before the
    // first dH by dual numbers would read past it, naming the index and the dimension.
    using SX = phase_space<double>;
    auto h = make_general_hamiltonian(
        [](const auto& q, const auto& p) { return 0.5 * (1 + q[0] * q[0]) * (1 + p[1] * p[1]); });
    auto g = make_gauss_collocation<SX>(h, 2);
    SX x(1);
    CHECK_THROWS_WITH_AS(g.step(x, 0.1),
                         "gauss_collocation_stepper: the Hamiltonian's H(q, p) read p[1] of a state of dimension 1; "
                         "expected indices 0..0",
                         invalid_argument);
    SX y(2);
    y.q[0] = 0.2;
    CHECK_NOTHROW(g.step(y, 0.1));  // the dimension it is written for
}

namespace {
// N steps, the carried list and the state saved, M more; a fresh stepper given
// the list and the state takes the same M steps bit for bit and with the same
// work, and one not given the list starts from Euler's polynomial (more work).
template <class S, class H>
void check_resumes(const H& h, int stages, gauss_options options, S x, double dt, bool newton_expected) {
    constexpr int N = 23, M = 40;
    auto whole = make_gauss_collocation<S>(h, stages, options);
    for (int i = 0; i < N; ++i) whole.step(x, dt);
    const std::vector<double> saved = whole.carried();
    const S at_save = x;
    CHECK(whole.iterating_by_newton() == newton_expected);
    whole.reset_counters();
    for (int i = 0; i < M; ++i) whole.step(x, dt);
    for (const bool restored : {true, false}) {
        CAPTURE(restored);
        auto resumed = make_gauss_collocation<S>(h, stages, options);
        if (restored) resumed.restore_carried(saved);
        S y = at_save;
        for (int i = 0; i < M; ++i) resumed.step(y, dt);
        if (restored) {
            CHECK(max_difference(x, y) == 0);
            CHECK(resumed.iterations() == whole.iterations());
            CHECK(resumed.factorizations() == whole.factorizations());
        }
        CHECK((resumed.force_evaluations() == whole.force_evaluations()) == restored);
    }
}
}  // namespace

TEST_CASE("gauss_collocation: a stepper restored from carried() goes on bit for bit, in both iteration modes") {
    gauss_options fixed;
    fixed.iteration = gauss_iteration::fixed_point;
    fixed.compensated = true;  // the compensation is carried too
    check_resumes(pendulum2, 3, fixed, pendulum2_start, 0.05, false);
    gauss_options newton;
    newton.iteration = gauss_iteration::newton;  // the frozen Jacobian and its factors carried
    check_resumes(pendulum2, 2, newton, pendulum2_start, 0.05, true);
    // automatic: the outer solar system at 500-day steps switches to Newton at once.
    const hamiltonians::outer_solar_system sun{};
    check_resumes(sun, 2, gauss_options{}, sun.initial_state(), 500.0, true);
}

TEST_CASE("gauss_collocation: a carried list of the wrong length or size is refused by name") {
    auto g = make_gauss_collocation<State>(pendulum2, 2);
    State x = pendulum2_start;
    for (int i = 0; i < 3; ++i) g.step(x, 0.05);
    std::vector<double> list = g.carried();
    list.push_back(0);
    CHECK_THROWS_WITH_AS(g.restore_carried(list), doctest::Contains("gauss_collocation_stepper"), invalid_argument);
    CHECK_THROWS_WITH_AS(g.restore_carried(list), doctest::Contains("longer than"), invalid_argument);
    list.resize(3);
    CHECK_THROWS_WITH_AS(g.restore_carried(list), doctest::Contains("ends early"), invalid_argument);
    // Another stepper's list: a stepper of 3 stages carries more stage values.
    auto g3 = make_gauss_collocation<State>(pendulum2, 3);
    State y = pendulum2_start;
    g3.step(y, 0.05);
    CHECK_THROWS_WITH_AS(g.restore_carried(g3.carried()), doctest::Contains("another size"), invalid_argument);
}

TEST_CASE("gauss_collocation: a list refused after it was read whole leaves the stepper as it was") {
    gauss_options newton;
    newton.iteration = gauss_iteration::newton;  // the Newton part sized and refactored on reading
    auto g = make_gauss_collocation<State>(pendulum2, 2, newton), twin = g;
    State x = pendulum2_start, y = x;
    for (int i = 0; i < 5; ++i) g.step(x, 0.05), twin.step(y, 0.05);
    const std::vector<double> list = g.carried();
    std::vector<double> longer = list;
    longer.push_back(0);
    CHECK_THROWS_WITH_AS(g.restore_carried(longer), doctest::Contains("is longer than"), invalid_argument);
    // A stepper of 3 stages carries more stage values: refused before anything is sized.
    auto g3 = make_gauss_collocation<State>(pendulum2, 3, newton);
    State w = pendulum2_start;
    g3.step(w, 0.05);
    CHECK_THROWS_WITH_AS(g.restore_carried(g3.carried()), doctest::Contains("another size"), invalid_argument);
    CHECK(g.carried() == list);
    for (int i = 0; i < 20; ++i) g.step(x, 0.05), twin.step(y, 0.05);
    CHECK(max_difference(x, y) == 0);
    CHECK(g.iterations() == twin.iterations());
    CHECK(g.factorizations() == twin.factorizations());
}

}  // namespace test_methods_test_gauss_collocation
