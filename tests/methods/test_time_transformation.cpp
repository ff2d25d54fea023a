// LogH: any table in fictitious time keeps its order, Kepler's energy to
// rounding, and the driver lands on the requested times.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include <sympl/methods/catalog.hpp>
#include <sympl/analysis/convergence.hpp>
#include <sympl/core/splitting_stepper.hpp>
#include <sympl/methods/time_transformation.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/kepler.hpp>

namespace test_methods_test_time_transformation {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using K = phase_space<double, 2>;
using KX = phase_space<double, 3>;  // (q, t), (p, p_t)

namespace {
const double pi = std::numbers::pi;

// Kepler orbit of eccentricity e from pericentre, one period, in n fictitious steps.
K kepler_period(const table& t, double e, std::size_t n, stepper_options options = {}) {
    const hamiltonians::kepler h{};
    KX X = to_extended(h, hamiltonians::kepler::initial_state(e));
    splitting_stepper<logh<hamiltonians::kepler>, KX> s({h}, t, options);
    integrate_to_time(s, X, 2 * pi, 2 * pi / double(n));  // the fictitious length of one period is 2 pi / a
    return physical_state(X);
}
}  // namespace

TEST_CASE("logh: a table keeps its order in fictitious time (Kepler e = 0.9, final position)") {
    for (const auto& entry : std::vector<std::pair<const char*, double>>{
             {"leapfrog_kdk", 2}, {"forest_ruth_4", 4}, {"blanes_moan_s6", 4}, {"yoshida_6", 6}}) {
        const char* name = entry.first;  // not a structured binding: lambdas take none before clang 16
        const double order = entry.second;
        CAPTURE(name);
        order_options o;
        o.min_steps = 64;
        o.max_steps = 1 << 15;
        o.floor = 1e-11;
        const auto m = measure_order([&](std::size_t n) { return kepler_period(method(name), 0.9, n); }, 2 * pi, o);
        CHECK(m.converged);
        CHECK(m.order == doctest::Approx(order).epsilon(0.15 / order));
    }
}

TEST_CASE("logh: the final error against the exact orbit falls at the table's order") {
    const K exact = hamiltonians::kepler::exact_state(0.9, 2 * pi);
    const double coarse = max_difference(kepler_period(method("blanes_moan_s6"), 0.9, 200), exact);
    const double fine = max_difference(kepler_period(method("blanes_moan_s6"), 0.9, 400), exact);
    CHECK(std::log2(coarse / fine) == doctest::Approx(4).epsilon(0.15 / 4));
}

TEST_CASE("logh: drift-first leapfrog keeps Kepler's energy to rounding, e = 0.99, 100 orbits at 100 steps per orbit") {
    // Mikkola & Tanikawa 1999: the LogH leapfrog moves on the exact Kepler orbit. Measured, that holds for the
    // drift-kick-drift form; kick-drift-kick has an ordinary second-order energy error (5.3 here).
    const hamiltonians::kepler h{};
    const K x0 = hamiltonians::kepler::initial_state(0.99);
    const double e0 = energy(h, x0), eps = std::numeric_limits<double>::epsilon();
    const auto worst_energy_error = [&](const char* name, bool compensated) {
        KX X = to_extended(h, x0);
        splitting_stepper<logh<hamiltonians::kepler>, KX> s({h}, method(name), stepper_options{compensated});
        double worst = 0;
        const auto r = integrate_to_time(s, X, 200 * pi, 2 * pi / 100, [&](const KX& y, double) {
            worst = std::max(worst, std::fabs(energy(h, physical_state(y)) - e0) / std::fabs(e0));
        });
        CHECK(r.steps == doctest::Approx(10000).epsilon(0.01));
        return worst;
    };
    // Rounding alone: each step adds ~eps * T/|E| (T/|E| = 199 at pericentre), a random walk over 1e4 steps.
    CHECK(worst_energy_error("leapfrog_dkd", false) < 2 * eps * 199 * std::sqrt(1e4));
    CHECK(worst_energy_error("leapfrog_dkd", true) < 1e-12);  // compensated summation: below the random walk
    CHECK(worst_energy_error("leapfrog_kdk", true) > 1e-3);
    // A fixed-step leapfrog with as many forces per orbit is not close at pericentre.
    K x = x0;
    double fixed_worst = 0;
    auto fixed = make_stepper<K>(h, method("leapfrog_kdk"));
    integrate_until(fixed, x, 0.0, 2 * pi, 2 * pi / 100, [&](const K& y, double) {
        fixed_worst = std::max(fixed_worst, std::fabs(energy(h, y) - e0) / std::fabs(e0));
    });
    CHECK(fixed_worst > 1e3);
}

TEST_CASE("logh: the driver lands on t_end and on every observation time") {
    const hamiltonians::kepler h{};
    KX X = to_extended(h, hamiltonians::kepler::initial_state(0.7));
    splitting_stepper<logh<hamiltonians::kepler>, KX> s({h}, method("blanes_moan_s6"));
    const std::vector<double> wanted = {0.1, 1.0, 2.5, 2.5000001, 7.0};
    std::vector<double> seen;
    const double t_end = 10.123;
    const auto r = integrate_to_time(s, X, t_end, 0.05, [&](const KX&, double t) { seen.push_back(t); }, wanted);
    CHECK(std::fabs(physical_time(X) - t_end) <= 4 * std::numeric_limits<double>::epsilon() * t_end);
    CHECK(r.t == t_end);
    for (double t : wanted) CHECK(std::find(seen.begin(), seen.end(), t) != seen.end());
    CHECK(r.force_evaluations >= r.steps);
    // Landing does not spoil accuracy: the state at t_end is the exact orbit's to the method's error.
    const K exact = hamiltonians::kepler::exact_state(0.7, t_end);
    CHECK(max_difference(physical_state(X), exact) < 1e-6);
}

TEST_CASE("logh: fixed and dynamic states, compensated summation and the extended energy") {
    const hamiltonians::kepler h{};
    const K x0 = hamiltonians::kepler::initial_state(0.5);
    using DX = phase_space<double>;
    DX Y = to_extended(h, x0.cast<double, Eigen::Dynamic>());
    splitting_stepper<logh<hamiltonians::kepler>, DX> dynamic({h}, method("blanes_moan_s6"));
    integrate_to_time(dynamic, Y, 2 * pi, 0.01);
    const K fixed = kepler_period(method("blanes_moan_s6"), 0.5, std::size_t(std::ceil(2 * pi / 0.01)));
    CHECK(max_difference(physical_state(Y).cast<double, 2>(), fixed) < 1e-12);
    const K compensated = kepler_period(method("blanes_moan_s6"), 0.5, 629, stepper_options{true});
    CHECK(max_difference(compensated, fixed) < 1e-9);
    // Lambda = ln(T + p_t) - ln(-V) is 0 on the orbit and stays 0 to the method's error.
    CHECK(std::fabs(energy(logh<hamiltonians::kepler>{h}, to_extended(h, x0))) < 1e-15);
}

TEST_CASE("logh: a potential that is not negative, or a bad step, is an error naming the value") {
    const hamiltonians::harmonic_oscillator h{};
    using X1 = phase_space<double, 2>;
    X1 X = to_extended(h, phase_space<double, 1>(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.0)));
    splitting_stepper<logh<hamiltonians::harmonic_oscillator>, X1> s({h}, method("leapfrog_kdk"));
    CHECK_THROWS_WITH_AS(integrate_to_time(s, X, 1.0, 0.1), doctest::Contains("V(q) = 0.5 at t = 0"), invalid_argument);
    const hamiltonians::kepler k{};
    KX Y = to_extended(k, hamiltonians::kepler::initial_state(0.5));
    splitting_stepper<logh<hamiltonians::kepler>, KX> t({k}, method("leapfrog_kdk"));
    CHECK_THROWS_WITH_AS(integrate_to_time(t, Y, 1.0, -0.1), doctest::Contains("ds = -0.1"), invalid_argument);
    CHECK_THROWS_WITH_AS(integrate_to_time(t, Y, 1.0, 1e-3, no_observer{}, {}, {10}), doctest::Contains("max_steps is 10"),
                         invalid_argument);
    // An unbound start (H0 > 0 makes T + p_t = -V, still > 0) runs; a state with T + p_t <= 0 does not.
    KX Z = Y;
    Z.p[2] = -10;  // p_t far below -T
    CHECK_THROWS_WITH_AS(integrate_to_time(t, Z, 1.0, 0.1), doctest::Contains("T(p) + p_t = "), invalid_argument);
}

TEST_CASE("logh: a dynamic-size state follows the fixed-size one to rounding, plain and compensated") {
    using KD = phase_space<double, Eigen::Dynamic>;
    const hamiltonians::kepler h{};
    const K x0 = hamiltonians::kepler::initial_state(0.9);
    for (const bool compensated : {false, true}) {
        CAPTURE(compensated);
        KX X = to_extended(h, x0);
        KD Y = to_extended(h, KD(Eigen::VectorXd(x0.q), Eigen::VectorXd(x0.p)));
        REQUIRE(Y.size() == 3);
        splitting_stepper<logh<hamiltonians::kepler>, KX> fixed({h}, method("blanes_moan_s6"), stepper_options{compensated});
        splitting_stepper<logh<hamiltonians::kepler>, KD> dynamic({h}, method("blanes_moan_s6"), stepper_options{compensated});
        const auto rx = integrate_to_time(fixed, X, 4 * pi, 2 * pi / 200);
        const auto ry = integrate_to_time(dynamic, Y, 4 * pi, 2 * pi / 200);
        CHECK(rx.steps == ry.steps);
        CHECK(physical_time(Y) == 4 * pi);
        // The same arithmetic up to the order of operations: a few hundred steps of rounding.
        for (Eigen::Index i = 0; i < 2; ++i) {
            CHECK(std::fabs(X.q[i] - Y.q[i]) < 1e-11);
            CHECK(std::fabs(X.p[i] - Y.p[i]) < 1e-11);
        }
    }
}

TEST_CASE("logh: a run resumed after step k from X and the stepper's memory ends bit for bit as the whole run") {
    const hamiltonians::kepler h{};
    using S = splitting_stepper<logh<hamiltonians::kepler>, KX>;
    const KX start = to_extended(h, hamiltonians::kepler::initial_state(0.9));
    const double t_end = 12.3, ds = 0.05;
    S whole({h}, method("blanes_moan_s6"));
    KX a = start;
    const auto all = integrate_to_time(whole, a, t_end, ds);
    // Stopped after step 97 (the extended state and the memory saved), resumed by another stepper.
    KX b = start, saved = start;
    std::size_t step = 0;
    S first({h}, method("blanes_moan_s6"));
    auto memory = first.memory();
    integrate_to_time(first, b, t_end, ds, [&](const KX& y, double) {
        if (++step == 97) saved = y, memory = first.memory();
    });
    S second({h}, method("blanes_moan_s6"));
    second.restore(memory);
    time_transformed_options resume;
    resume.first_step = 97;
    const auto rest = integrate_to_time(second, saved, t_end, ds, no_observer{}, {}, resume);
    CHECK(max_difference(saved, a) == 0);
    CHECK(rest.steps + 97 == all.steps);
    CHECK(second.force_evaluations() == whole.force_evaluations());
}

}  // namespace test_methods_test_time_transformation
