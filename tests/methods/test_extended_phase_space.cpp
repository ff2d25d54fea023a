// Tao's explicit and Jayawardana & Ohsawa's semiexplicit methods for
// non-separable H(q, p): measured orders, invariant over a long span,
// symplecticity (extended and original phase space), a lost binding, refusals.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include <sympl/sympl.hpp>
#include <sympl/core/general_hamiltonian.hpp>
#include <sympl/hamiltonians/product_hamiltonian.hpp>
#include <sympl/methods/extended_phase_space.hpp>
#include <sympl/methods/semiexplicit.hpp>

#include "nonseparable_problems.hpp"

namespace test_methods_test_extended_phase_space {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using namespace sympl::nonseparable_testing;

namespace {
using V1 = Eigen::Matrix<double, 1, 1>;
using State = phase_space<double, 1>;
using StateL = phase_space<long double, 1>;

// A long-double reference by the 8th-order semiexplicit method at 4000 steps
// (its error is below 1e-18 there).
template <class H>
StateL reference_at(const H& h, const StateL& start, double t_end) {
    return run<long double>(make_semiexplicit_stepper<StateL>(h, method("yoshida_8")), start, t_end, 4000);
}

// Global error at t_end against the reference.
template <class H>
double error_at(const H& h, const StateL& start, const StateL& reference, double t_end, bool tao, const table& t,
                int n) {
    const State x0 = start.cast<double>();
    const State x = tao ? run<double>(make_tao_stepper<State>(h, t), x0, t_end, n)
                        : run<double>(make_semiexplicit_stepper<State>(h, t), x0, t_end, n);
    return double(max_difference(x.cast<long double>(), reference));
}

// Order from the errors at n and 2n steps.
template <class H>
double measured_order(const H& h, const StateL& start, const StateL& reference, double t_end, bool tao,
                      const table& t, int n) {
    const double e1 = error_at(h, start, reference, t_end, tao, t, n);
    const double e2 = error_at(h, start, reference, t_end, tao, t, 2 * n);
    const double order = std::log2(e1 / e2);
    std::printf("  %-12s %-26s n = %4d: error %.3e -> %.3e, order %.3f\n", tao ? "tao" : "semiexplicit",
                t.name().c_str(), n, e1, e2, order);
    return order;
}

}  // namespace

TEST_CASE("extended phase space: measured orders 2, 4, 6 of both methods on two non-separable H") {
    // Pairs (n, 2n) where the error is in its asymptotic range and far above
    // rounding. Tao's error carries a factor omega (Tao 2016: O(T dt^l omega)),
    // so its asymptotic range starts at smaller steps.
    struct row { const table* t; int expected; int n_tao, n_semiexplicit; };
    const row rows[] = {{&leapfrog, 2, 500, 500}, {&order4, 4, 500, 200}, {&order6, 6, 250, 100}};
    std::printf("orders, H = (1 + q^2)(1 + p^2)/2 from (-3, 0), T = 5:\n");
    const StateL a(Eigen::Matrix<long double, 1, 1>(-3.0L), Eigen::Matrix<long double, 1, 1>(0.0L));
    const StateL ra = reference_at(product, a, 5.0);
    for (const row& r : rows)
        for (bool tao : {true, false}) {
            CAPTURE(r.t->name());
            CAPTURE(tao);
            CHECK(std::fabs(measured_order(product, a, ra, 5.0, tao, *r.t, tao ? r.n_tao : r.n_semiexplicit) - r.expected) <= 0.15);
        }
    std::printf("orders, H = p^2/(2(1 + q^2/2)) + 1 - cos q from (2.5, 0), T = 10:\n");
    const StateL b(Eigen::Matrix<long double, 1, 1>(2.5L), Eigen::Matrix<long double, 1, 1>(0.0L));
    const StateL rb = reference_at(varying_mass, b, 10.0);
    for (const row& r : rows)
        for (bool tao : {true, false}) {
            CAPTURE(r.t->name());
            CAPTURE(tao);
            CHECK(std::fabs(measured_order(varying_mass, b, rb, 10.0, tao, *r.t, tao ? r.n_tao : r.n_semiexplicit) - r.expected) <= 0.15);
        }
}

TEST_CASE("extended phase space: suzuki_fractal and a catalog composition are accepted at their order") {
    const StateL a(Eigen::Matrix<long double, 1, 1>(-3.0L), Eigen::Matrix<long double, 1, 1>(0.0L));
    const StateL ra = reference_at(product, a, 5.0);
    CHECK(std::fabs(measured_order(product, a, ra, 5.0, false, suzuki_fractal(leapfrog), 100) - 4) <= 0.15);
    CHECK(std::fabs(measured_order(product, a, ra, 5.0, true, method("forest_ruth_4"), 500) - 4) <= 0.15);
    // The drift-kick-drift leapfrog composes the same second-order map.
    CHECK(error_at(product, a, ra, 5.0, true, method("leapfrog_dkd"), 300) ==
          error_at(product, a, ra, 5.0, true, leapfrog, 300));
}

TEST_CASE("extended phase space: the energy error stays bounded over 1000 time units, shrinking at the order") {
    // A symplectic method keeps a modified energy within O(dt^l) over
    // exponentially long times (Hairer, Lubich & Wanner, GNI Thm. IX.8.1): the
    // largest error over the whole span is that of its first tenth (no drift:
    // a drift would make it ~10 times larger), and halving dt divides it by
    // about 2^l (asserted: by at least 2^(l - 1)).
    std::printf("max |H/H0 - 1| over t in [0, 1000], H = (1 + q^2)(1 + p^2)/2 from (-3, 0):\n");
    for (const table* t : {&leapfrog, &order4, &order6}) {
        const int l = t->order();
        for (bool tao : {true, false}) {
            double worst[2] = {0, 0};
            for (int k = 0; k < 2; ++k) {
                const double dt = 0.05 / (1 << k);
                const int n = int(std::lround(1000 / dt));
                State x(V1(-3.0), V1(0.0));
                const double e0 = energy(product, x);
                double first_tenth = 0;
                auto step = [&](auto& s) {
                    for (int i = 0; i < n; ++i) {
                        s.step(x, dt);
                        worst[k] = std::max(worst[k], std::fabs(energy(product, x) / e0 - 1));
                        if (i < n / 10) first_tenth = worst[k];
                    }
                };
                if (tao) {
                    auto s = make_tao_stepper<State>(product, *t);
                    step(s);
                } else {
                    auto s = make_semiexplicit_stepper<State>(product, *t);
                    step(s);
                }
                std::printf("  %-12s %-26s dt = %.4f: %.3e (first tenth %.3e)\n", tao ? "tao" : "semiexplicit",
                            t->name().c_str(), dt, worst[k], first_tenth);
                CAPTURE(t->name());
                CAPTURE(tao);
                CHECK(worst[k] <= 1.5 * first_tenth);
            }
            CHECK(std::log2(worst[0] / worst[1]) >= l - 1);
        }
    }
}

TEST_CASE("extended phase space: Tao's map is symplectic in the extended space, near-symplectic in the original one") {
    // Extended space: the Jacobian M of 100 steps (dual numbers in q, p, x, y)
    // satisfies M^T J M = J to rounding: each partial flow is an exact flow.
    using D4 = dual<double, 4>;
    using S4 = phase_space<D4, 1>;
    using V4 = Eigen::Matrix<D4, 1, 1>;
    auto s = make_tao_stepper<S4>(product, order6);
    extended_state<D4, 1> z;
    z.q = V4(D4::variable(-3.0, 0));
    z.p = V4(D4::variable(0.1, 1));
    z.x = V4(D4::variable(-2.9, 2));
    z.y = V4(D4::variable(0.05, 3));
    for (int i = 0; i < 100; ++i) s.step_extended(z, D4(0.01));
    Eigen::Matrix4d M;  // rows and columns in the order (q, x, p, y)
    const D4* rows[4] = {&z.q[0], &z.x[0], &z.p[0], &z.y[0]};
    const int column_of[4] = {0, 2, 1, 3};  // variable k (q, p, x, y) -> column
    for (int r = 0; r < 4; ++r)
        for (int k = 0; k < 4; ++k) M(r, column_of[k]) = rows[r]->grad[k];
    Eigen::Matrix4d J = Eigen::Matrix4d::Zero();
    J.block<2, 2>(0, 2) = Eigen::Matrix2d::Identity();
    J.block<2, 2>(2, 0) = -Eigen::Matrix2d::Identity();
    const double extended_defect = (M.transpose() * J * M - J).norm();
    std::printf("Tao, extended space, 100 steps of yoshida_6: ||M^T J M - J|| = %.2e (||M|| = %.2f)\n",
                extended_defect, M.norm());
    CHECK(extended_defect <= 1e-12);

    // Original space: the map (q0, p0) -> (q, p) at t = 1 (both copies start at
    // the point) is not symplectic; its defect is part of the global error of
    // the Jacobian, O(dt^l): halving dt divides it by 2^l.
    using D2 = dual<double, 2>;
    using S2 = phase_space<D2, 1>;
    using V2 = Eigen::Matrix<D2, 1, 1>;
    for (const table* t : {&leapfrog, &order4, &order6}) {
        double defect[2];
        for (int k = 0; k < 2; ++k) {
            const int n = 100 << k;
            S2 x(V2(D2::variable(-3.0, 0)), V2(D2::variable(0.0, 1)));
            x = run<D2>(make_tao_stepper<S2>(product, *t), x, 1.0, n);
            defect[k] = area_defect(x);
        }
        const double order = std::log2(defect[0] / defect[1]);
        std::printf("Tao, original space, t = 1, %-26s: |det M - 1| = %.2e (dt = 0.01), %.2e (dt = 0.005), order %.2f\n",
                    t->name().c_str(), defect[0], defect[1], order);
        CAPTURE(t->name());
        CHECK(defect[0] > 1e-12);  // really not symplectic there
        CHECK(std::fabs(order - t->order()) <= 0.3);
    }
}

TEST_CASE("extended phase space: copies that come apart stop the run with integration_error") {
    // omega = 0.1 is far below the problem's frequencies (up to ~10): the
    // copies separate within a few time units; omega = 20 keeps them bound
    // over the same run (largest divergence ~2e-3).
    const State start(V1(-3.0), V1(0.0));
    {
        auto s = make_tao_stepper<State>(product, leapfrog, {.omega = 0.1});
        State x = start;
        bool thrown = false;
        try {
            for (int i = 0; i < 2000; ++i) s.step(x, 0.01);
        } catch (const integration_error& e) {
            thrown = true;
            const std::string what = e.what();
            std::printf("omega = 0.1: %s\n", e.what());
            CHECK(what.find("omega = 0.1") != std::string::npos);
            CHECK(what.find("step ") != std::string::npos);
            CHECK(what.find("|q - x| + |p - y| (in the binding's units) = ") != std::string::npos);
            CHECK(e.step > 1);
            CHECK(e.step == s.steps_taken() + 1);
            CHECK(std::isfinite(x.q[0]));
        }
        CHECK(thrown);
    }
    {
        auto s = make_tao_stepper<State>(product, leapfrog);
        State x = start;
        CHECK_NOTHROW(for (int i = 0; i < 2000; ++i) s.step(x, 0.01));
        std::printf("omega = 20: largest divergence %.2e over 2000 steps\n", double(s.max_divergence()));
        CHECK(s.max_divergence() < 1e-2);
        CHECK(s.max_divergence() > 0);
    }
    // Too large a step for omega = 20: the copies separate in the first step,
    // and the state is left where it was.
    {
        auto s = make_tao_stepper<State>(product, leapfrog);
        State x = start;
        CHECK_THROWS_AS(s.step(x, 0.2), integration_error);
        CHECK(x.q[0] == -3.0);
        CHECK(x.p[0] == 0.0);
    }
    // Through the driver: the error reaches the caller, with the absolute time.
    {
        auto s = make_tao_stepper<State>(product, leapfrog, {.omega = 0.1});
        State x = start;
        try {
            integrate_until(s, x, 100.0, 120.0, 0.01);
            FAIL("expected integration_error");
        } catch (const integration_error& e) {
            CHECK(e.time > 100.0);
            CHECK(e.time < 103.0);
        }
    }
}

TEST_CASE("extended phase space: the drivers run both steppers and count evaluations") {
    const State start(V1(-3.0), V1(0.0));
    auto tao = make_tao_stepper<State>(product, order4);
    State x = start;
    const run_summary r = integrate_until(tao, x, 0.0, 1.0, 0.01);
    State y = run<double>(make_tao_stepper<State>(product, order4), start, 1.0, 100);
    CHECK(r.steps == 100);
    CHECK(max_difference(x, y) <= 1e-14);
    // 3 weights, A's merged and carried over to the next step: 3 gradient
    // pairs per weight, 9 a step, and one more for the very first A.
    CHECK(r.force_evaluations == 9 * 100 + 1);
    CHECK(r.velocity_evaluations == 9 * 100 + 1);

    auto semi = make_semiexplicit_stepper<State>(product, order4);
    State z = start;
    const run_summary rs = integrate_until(semi, z, 0.0, 1.0, 0.01);
    // 7 gradient pairs per sweep of the map (4 A, 3 B), one sweep per projection iteration.
    CHECK(rs.force_evaluations == 7 * semi.projection_iterations());
    std::printf("semiexplicit triple jump, dt = 0.01: %.2f projection iterations per step\n",
                double(semi.projection_iterations()) / 100);
    CHECK(semi.projection_iterations() >= 100);
    CHECK(std::fabs(energy(product, z) / energy(product, start) - 1) < 1e-6);
}

TEST_CASE("extended phase space: bad step sizes, tables and options are refused by name") {
    State x(V1(-3.0), V1(0.0));
    auto tao = make_tao_stepper<State>(product, leapfrog);
    auto semi = make_semiexplicit_stepper<State>(product, leapfrog);
    for (double dt : {0.0, std::nan(""), double(INFINITY)}) {
        CAPTURE(dt);
        CHECK_THROWS_AS(tao.step(x, dt), invalid_argument);
        CHECK_THROWS_AS(semi.step(x, dt), invalid_argument);
        try {
            tao.step(x, dt);
        } catch (const invalid_argument& e) {
            const std::string what = e.what();
            CHECK(what.find("dt = ") != std::string::npos);
        }
    }
    CHECK(x.q[0] == -3.0);
    // Not compositions of leapfrog steps: a splitting with free coefficients,
    // an RKN table, a force-gradient one, a non-symmetric one.
    for (const table& t : {method("pefrl_4"), method("blanes_moan_s6"), method("euler_cromer"),
                           force_gradient_method("chin_4a")}) {
        CAPTURE(t.name());
        try {
            (void)make_tao_stepper<State>(product, t);
            FAIL("expected invalid_argument");
        } catch (const invalid_argument& e) {
            const std::string what = e.what();
            CHECK(what.find("'" + t.name() + "'") != std::string::npos);
        }
        CHECK_THROWS_AS((void)make_semiexplicit_stepper<State>(product, t), invalid_argument);
    }
    CHECK_THROWS_AS((void)make_tao_stepper<State>(product, leapfrog, {.omega = 0}), invalid_argument);
    CHECK_THROWS_AS((void)make_tao_stepper<State>(product, leapfrog, {.omega = std::nan("")}), invalid_argument);
    CHECK_THROWS_AS((void)make_tao_stepper<State>(product, leapfrog, {.divergence_limit = -1}), invalid_argument);
    CHECK_THROWS_AS((void)make_semiexplicit_stepper<State>(product, leapfrog, {.max_iterations = 0}), invalid_argument);
    // Accepted: the catalog's leapfrog compositions, whatever their form.
    for (const char* name : {"leapfrog_kdk", "leapfrog_dkd", "yoshida_4", "suzuki_4", "mclachlan_ss5", "yoshida_6",
                             "kahan_li_8", "forest_ruth_4"}) {
        CAPTURE(name);
        CHECK_NOTHROW((void)make_tao_stepper<State>(product, method(name)));
    }
}

TEST_CASE("extended phase space: a general H reading past the state is refused at the first step") {
    using SX = phase_space<double>;
    auto h = make_general_hamiltonian(
        [](const auto& q, const auto& p) { return 0.5 * (1 + q[2] * q[2]) * (1 + p.squaredNorm()); });
    SX x(2);
    const std::string read = " the Hamiltonian's H(q, p) read q[2] of a state of dimension 2; expected indices 0..1";
    for (bool tao : {true, false}) {
        CAPTURE(tao);
        try {
            if (tao) make_tao_stepper<SX>(h, leapfrog).step(x, 0.1);
            else make_semiexplicit_stepper<SX>(h, leapfrog).step(x, 0.1);
            FAIL("expected invalid_argument");
        } catch (const invalid_argument& e) {
            CHECK(std::string(e.what()) == (tao ? "tao_stepper:" : "semiexplicit_stepper:") + read);
        }
    }
    SX y(3);
    CHECK_NOTHROW(make_tao_stepper<SX>(h, leapfrog).step(y, 0.1));
}

TEST_CASE("extended phase space: Tao's stepper restored from carried() goes on bit for bit, and without it not") {
    const State start(V1(-3.0), V1(0.0));
    const auto observe = [](const State&, double) {};
    auto whole = make_tao_stepper<State>(product, order4);
    State a = start;
    integrate_steps(whole, a, 0.0, 0.01, 200, observe);
    run_options resume;
    resume.first_step = 77;  // stopped there, as a checkpoint stops a run, and resumed by another stepper
    for (const bool restored : {true, false}) {
        auto first = make_tao_stepper<State>(product, order4), second = make_tao_stepper<State>(product, order4);
        State b = start;
        integrate_steps(first, b, 0.0, 0.01, 77, observe);
        if (restored) second.restore_carried(first.carried());
        integrate_steps(second, b, 0.0, 0.01, 200, observe, resume);
        CAPTURE(restored);
        CHECK((max_difference(a, b) == 0) == restored);
        if (restored) CHECK(second.max_divergence() == whole.max_divergence());
    }
    std::vector<double> bad = whole.carried();
    bad.pop_back();
    CHECK_THROWS_WITH_AS(whole.restore_carried(bad), doctest::Contains("ends early"), invalid_argument);
}

}  // namespace test_methods_test_extended_phase_space
