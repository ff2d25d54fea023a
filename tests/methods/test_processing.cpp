// Processed methods: the effective order of every catalog entry, measured on
// nonlinear problems with quadratic and non-quadratic kinetic energy; outputs
// at the true state; the kernel's state carried between calls.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>

namespace test_methods_test_processing {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using HH = hamiltonians::henon_heiles;
using X2 = phase_space<double, 2>;

// Largest relative energy error over n steps of dt, looked at every `every` steps.
template <class Stepper>
double max_energy_error(Stepper& s, const X2& x0, double dt, std::size_t n, std::size_t every) {
    const HH h;
    const double e0 = energy(h, x0);
    double worst = 0;
    X2 x = x0;
    integrate_steps(s, x, 0.0, dt, n,
                    [&](const X2& y, double) { worst = std::max(worst, std::fabs(energy(h, y) - e0) / std::fabs(e0)); },
                    run_options{every});
    return worst;
}
}  // namespace

TEST_CASE("processing: every processed method reaches its effective order, its kernel alone only 4") {
    for (const processed_method& m : processed_catalog()) {
        CAPTURE(m.name);
        // Kepler (quadratic T) and the pendulum with T = sqrt(1 + p^2). Not the
        // plain pendulum: there bcm_2006_p8's slopes are still pre-asymptotic
        // (10.6, 9.9) when the differences reach 1e-17, below which the
        // 15-digit published coefficients set the error.
        for (order_problem problem : {order_problem::kepler, order_problem::nonquadratic_kinetic}) {
            const std::string problem_name = to_string(problem);
            CAPTURE(problem_name);
            const order_measurement processed_order = measure_order(m, problem);
            CAPTURE(processed_order.order);
            CHECK(std::fabs(processed_order.order - m.order) <= 0.15);
        }
        // Without the processor the kernel is a plain order-4 composition: the
        // processor, not the kernel, makes the order.
        const double kernel_order = measure_order(m.kernel, order_problem::pendulum).order;
        CAPTURE(kernel_order);
        CHECK(std::fabs(kernel_order - 4) <= 0.15);
        CHECK(m.citation.size() > 10);
    }
}

TEST_CASE("processing: the processor is a change of variables (kicks and drifts each sum to 0)") {
    for (const processed_method& m : processed_catalog()) {
        CAPTURE(m.name);
        coefficient kicks = 0, drifts = 0;
        for (const substep& s : m.processor) (s.kind == substep::kick ? kicks : drifts) += s.weight;
        CHECK(std::fabs(static_cast<double>(kicks)) <= 1e-15);
        CHECK(std::fabs(static_cast<double>(drifts)) <= 1e-15);
    }
}

TEST_CASE("processing: the energy seen by an observer converges at the effective order, the kernel's at 4") {
    // Henon-Heiles at E = 1/8 over t = 40, looked at every 8 steps: the
    // processed outputs' energy error falls as dt^8 (bcm_2006_p8); the kernel's
    // own state, which the processor maps to the output, carries O(dt^4).
    const processed_method& m = processed("bcm_2006_p8");
    const X2 x0 = HH::initial_state(1.0 / 8);
    std::vector<double> processed_error, kernel_error;
    for (double dt : {0.4, 0.2}) {
        processed_stepper<HH, X2> s({}, m);
        processed_error.push_back(max_energy_error(s, x0, dt, static_cast<std::size_t>(std::lround(40 / dt)), 8));
        splitting_stepper<HH, X2> k({}, m.kernel);
        kernel_error.push_back(max_energy_error(k, x0, dt, static_cast<std::size_t>(std::lround(40 / dt)), 8));
    }
    const double processed_slope = std::log2(processed_error[0] / processed_error[1]);
    const double kernel_slope = std::log2(kernel_error[0] / kernel_error[1]);
    CAPTURE(processed_error[1]);
    CAPTURE(kernel_error[1]);
    CHECK(processed_slope >= 8 - 0.5);
    CHECK(std::fabs(kernel_slope - 4) <= 0.5);
    CHECK(processed_error[1] < kernel_error[1] / 100);
}

TEST_CASE("processing: the kernel's state carries over between calls, and is rebuilt when the caller changes x or dt") {
    const processed_method& m = processed("bcm_2006_p6_11");
    const X2 x0 = HH::initial_state(1.0 / 8);
    const double dt = 0.1;

    processed_stepper<HH, X2> once({}, m);
    X2 a = x0;
    once.steps(a, dt, 300);

    processed_stepper<HH, X2> chunked({}, m);
    X2 b = x0;
    chunked.steps(b, dt, 100);
    const auto after_first = chunked.force_evaluations();
    chunked.steps(b, dt, 200);
    // Continued from the kernel's state, not from P^-1 of the output: the same
    // 300 kernel steps, with rounding differences only (a join split in two).
    CHECK(max_difference(a, b) < 1e-13);
    // The second call: 200 kernel steps (each step's forces, the first one carried)
    // and the processor once, no P^-1.
    std::size_t processor_kicks = 0;
    for (const substep& s : m.processor) processor_kicks += s.kind == substep::kick;
    CHECK(chunked.force_evaluations() - after_first == 200 * m.kernel.force_evaluations() + processor_kicks);

    // A state changed by the caller starts afresh, exactly as a new stepper would.
    X2 c = b, d = b;
    c.p[0] += 1e-3;
    d.p[0] += 1e-3;
    chunked.steps(c, dt, 50);
    processed_stepper<HH, X2> fresh({}, m);
    fresh.steps(d, dt, 50);
    CHECK(c.q[0] == d.q[0]);
    CHECK(c.p[1] == d.p[1]);

    // So does a new dt (the processor depends on it).
    X2 e = c, f = c;
    chunked.steps(e, dt / 2, 20);
    processed_stepper<HH, X2> fresh2({}, m);
    fresh2.steps(f, dt / 2, 20);
    CHECK(e.q[1] == f.q[1]);
    CHECK(e.p[0] == f.p[0]);
}

TEST_CASE("processing: observed outputs are the true state, whatever the observation cadence") {
    // Outputs every 7 steps through the driver equal one uninterrupted call of
    // the same length: the observer sees P(y), never the kernel's y.
    const processed_method& m = processed("blanes_2001_p6");
    const X2 x0 = HH::initial_state(1.0 / 10);
    processed_stepper<HH, X2> observed({}, m);
    std::vector<X2> seen;
    X2 x = x0;
    integrate_steps(observed, x, 0.0, 0.05, 70, [&](const X2& y, double) { seen.push_back(y); }, run_options{7});
    REQUIRE(seen.size() == 11);
    for (std::size_t k : {1u, 4u, 10u}) {
        processed_stepper<HH, X2> direct({}, m);
        X2 y = x0;
        direct.steps(y, 0.05, 7 * k);
        CAPTURE(k);
        CHECK(max_difference(seen[k], y) < 1e-13);
        // The kernel's state is another point, 10^4 times farther than that tolerance.
        CHECK(max_difference(direct.kernel_state(), y) > 1e-9);
    }
}

TEST_CASE("processing: dynamic-size states (FPU chain) conserve energy and count the processing") {
    const processed_method& m = processed("bcm_2006_p8");
    using FX = phase_space<double>;
    const hamiltonians::fpu_beta h{1.0};
    const int n = 16;
    FX x(Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n));
    for (int i = 0; i < n; ++i) x.q[i] = std::sin(M_PI * (i + 1) / (n + 1));  // lowest mode, amplitude 1
    const double e0 = energy(h, x);
    processed_stepper<hamiltonians::fpu_beta, FX> s(h, m);
    s.steps(x, 0.05, 400);
    CHECK(std::fabs(energy(h, x) - e0) / e0 < 1e-9);
    CHECK(s.force_evaluations() > 400 * m.kernel.force_evaluations());
}

TEST_CASE("processing: a processor whose weights do not sum to 0, or are not finite, is refused with the value") {
    const table& lf = method("leapfrog_kdk");
    const table& kernel = method("yoshida_4");
    CHECK_THROWS_WITH_AS(make_processed("p", kernel, lf, {0.3, -0.2}, 4, "c"),
                         doctest::Contains("processor weights sum to 0.09999"), invalid_table);
    CHECK_THROWS_WITH_AS(make_processed("p", kernel, lf, {NAN, 0.1}, 4, "c"),
                         doctest::Contains("processor weight[0] = nan"), invalid_table);
    CHECK_THROWS_AS(make_processed("p", kernel, lf, {}, 4, "c"), invalid_table);
    // The processor walks plain kicks and drifts: a force-gradient base is refused.
    CHECK_THROWS_WITH_AS(make_processed("p", kernel, force_gradient_method("chin_4a"), {0.1, -0.1}, 4, "c"),
                         doctest::Contains("'chin_4a' has force-gradient kicks"), invalid_table);
    CHECK_THROWS_WITH_AS(processed("no_such"), doctest::Contains("bcm_2006_p8"), invalid_argument);
    processed_stepper<HH, X2> s({}, processed("bcm_2006_p8"));
    X2 x = HH::initial_state(0.1);
    CHECK_THROWS_WITH_AS(s.steps(x, 0.0, 1), doctest::Contains("dt = 0"), invalid_argument);
}

TEST_CASE("processing: a kernel solved from the effective conditions alone gets its order from the processor") {
    // A root printed by `derive_nystrom --order 6 --kicks 5 --effective
    // --processor 6 --starts 25`: the 5-kick drift-first kernel solved from the
    // effective-order conditions of quadratic T (order_conditions.hpp), then the
    // processor (6 drift-kick pairs, zero sums) for it. The kernel's roots form
    // a one-parameter family, so runs differ from these digits after the 10th;
    // any root passes. Not a catalog method (on the FPU chain of bench_accuracy
    // it needs 1.5x SRKN11b's forces for 1e-10); a check that the conditions,
    // the processor's order of application and processed_stepper agree.
    const std::vector<coefficient> kick{0.250139655211320533504L, -0.171570944183383322223L, 0.842862577944125577437L,
                                        -0.171570944183383322223L, 0.250139655211320533504L};
    const std::vector<coefficient> drift{-0.119051860411525169416L, 0.770696774993009680753L,
                                         -0.151644914581484511351L, -0.151644914581484511351L,
                                         0.770696774993009680753L,  -0.119051860411525169416L};
    const std::vector<coefficient> processor_drift{0.172270489327773311728L,  -0.279730611906224606853L,
                                                   -0.0120368069760954467771L, 0.221238269640125926086L,
                                                   -0.30586210101172215417L,  0.20412076092614296998L};
    const std::vector<coefficient> processor_kick{-0.354304576908872356338L, 0.483896761008521322577L,
                                                  -0.457422131097906636398L, 0.421533871466774976941L,
                                                  0.170290424009201126878L,  -0.263994348477718433646L};
    std::vector<substep> kernel_ops, processor;
    for (std::size_t i = 0; i < drift.size(); ++i) {
        kernel_ops.push_back({substep::drift, drift[i]});
        if (i < kick.size()) kernel_ops.push_back({substep::kick, kick[i]});
    }
    for (std::size_t i = 0; i < processor_drift.size(); ++i)
        processor.push_back({substep::drift, processor_drift[i]}), processor.push_back({substep::kick, processor_kick[i]});
    const table kernel = table::from_substeps("effective_6_kernel", kernel_ops, 2, "derive_nystrom --effective",
                                              kinetic_requirement::quadratic);
    const processed_method m{"effective_6", kernel, processor, 6, "derive_nystrom --effective"};
    CHECK(effective_order(kernel_ops, 7, kinetic_requirement::quadratic) == 6);
    CHECK(effective_order(kernel_ops, 7, kinetic_requirement::any) == 4);
    for (order_problem problem : {order_problem::pendulum, order_problem::kepler}) {
        const std::string problem_name = to_string(problem);
        CAPTURE(problem_name);
        CHECK(std::fabs(measure_order(m, problem).order - 6) <= 0.15);
        CHECK(std::fabs(measure_order(kernel, problem).order - 2) <= 0.15);  // the kernel alone: order 2
    }
    // Solved for T = p^2/2 only: with T = sqrt(1 + p^2) the general effective
    // condition of degree 5 is unmet and the processed method falls to 4.
    CHECK(std::fabs(measure_order(m, order_problem::nonquadratic_kinetic).order - 4) <= 0.15);
}

TEST_CASE("processing: a stepper restored from carried() goes on bit for bit, and without it not") {
    const processed_method& m = processed("bcm_2006_p6_11");
    const X2 x0 = HH::initial_state(1.0 / 8);
    const double dt = 0.1;
    const auto observe = [](const X2&, double) {};
    processed_stepper<HH, X2> whole({}, m);
    X2 a = x0;
    integrate_steps(whole, a, 0.0, dt, 300, observe);
    run_options resume;
    // Stopped there, as a checkpoint stops a run, and resumed by another
    // stepper; P^-1(P(y)) is y only to rounding (at this step not exactly).
    resume.first_step = 50;
    for (const bool restored : {true, false}) {
        processed_stepper<HH, X2> first({}, m), second({}, m);
        X2 b = x0;
        integrate_steps(first, b, 0.0, dt, 50, observe);
        if (restored) second.restore_carried(first.carried());
        integrate_steps(second, b, 0.0, dt, 300, observe, resume);
        CAPTURE(restored);
        CHECK((max_difference(a, b) == 0) == restored);
    }
    std::vector<double> bad = whole.carried();
    bad[0] = 0.5;
    CHECK_THROWS_WITH_AS(whole.restore_carried(bad), doctest::Contains("neither 0 nor 1"), invalid_argument);
}

}  // namespace test_methods_test_processing
