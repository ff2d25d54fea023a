// The system registry: every entry builds with its defaults, keeps its
// promises (exact solution, energy) and agrees with what actually runs.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <sympl/methods/catalog.hpp>

#include "methods/method_kinds.hpp"
#include "running/systems.hpp"

namespace test_program_test_systems {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;

namespace {
// One method of each kind and every classic stepper.
std::vector<method_spec> every_method() {
    std::vector<method_spec> all;
    for (const std::string& name : method_names_beside_tables()) all.push_back(*resolve_method(name, {}));
    all.push_back(*resolve_method("blanes_moan_s6", {}));
    all.push_back(*resolve_method("mine", {{"mine", sympl::method("leapfrog_kdk")}}));
    all.push_back(*resolve_method("logh(leapfrog_dkd)", {}));
    all.push_back(*resolve_method("extrapolated(leapfrog_kdk, 3)", {}));
    all.push_back(*resolve_method("extrapolated(logh(leapfrog_dkd), 3)", {}));
    all.push_back(*resolve_method("tao(yoshida_4)", {}));
    all.push_back(*resolve_method("semiexplicit(leapfrog_kdk)", {}));
    return all;
}
}  // namespace

TEST_CASE("systems: every system runs every method the registry says it can, and refuses every other") {
    const auto methods = every_method();
    // 10 classic names, 4 Odeint kinds, 6 Gauss-Legendre, 6 RKN pairs, 2 charged pushers, the force-gradient
    // tables and processed methods, a catalog and an inline table, a logh, two extrapolated, a tao and a semiexplicit
    CHECK(methods.size() == 35 + sympl::force_gradient_catalog().size() + sympl::processed_catalog().size());
    for (const system_entry& entry : systems()) {
        const runnable_system p = make_system(entry.name, {}, {}, {}, "test");
        for (const method_spec& m : methods) {
            CAPTURE(entry.name);
            CAPTURE(m.name);
            const std::string why = why_not(m, p.form);
            run_request rq;
            rq.dt = 1e-3;
            rq.tolerance = 1e-6;
            rq.timing_repeats = 0;
            rq.energy = p.hamiltonian;
            bool ran = false;
            std::string refusal;
            try {
                const run_result r = p.run(m, rq, 0.0, 0.01, p.x0);
                ran = true;
                // Tao's binding is set in each component's own units (issue 39): the outer solar
                // system, whose momenta are 1e-11 of its positions, keeps its copies bound too.
                CHECK(r.stable);
                const bool fixed_step = steps_in_physical_time(m);
                CHECK(r.steps >= (fixed_step ? 10u : 1u));  // logh: dt is a fictitious step
                CHECK(r.final_state.size() == p.x0.size());
            } catch (const sympl::invalid_argument& e) {
                refusal = e.what();
            }
            CHECK(ran == why.empty());
            // The same words as the registry's, also where the registry's values (V < 0, a
            // quadratic T) decide what the system's type cannot.
            if (!ran) CHECK(refusal == why);
        }
    }
}

TEST_CASE("systems: defaults lie in their ranges and a value outside one is refused with the range") {
    for (const system_entry& entry : systems()) {
        CAPTURE(entry.name);
        CHECK_FALSE(entry.description.empty());
        for (const parameter& q : entry.parameters) {
            CAPTURE(q.name);
            CHECK(q.accepts(q.value));
            CHECK_FALSE(q.accepts(std::nan("")));
            CHECK_FALSE(q.meaning.empty());
        }
        const runnable_system p = make_system(entry.name, {}, {}, {}, "test");
        CHECK(p.x0.size() == 2 * p.degrees_of_freedom);
        CHECK(bool(p.exact) == entry.exact);
        CHECK(p.hamiltonian == bool(p.energy));
    }
    CHECK_THROWS_WITH_AS(make_system("pendulum", {{"mass", -1}}, {}, {}, "s.toml"),
                         "s.toml: pendulum mass = -1; expected a finite number > 0", sympl::invalid_argument);
    CHECK_THROWS_WITH_AS(make_system("fpu_beta", {{"n", 2.5}}, {}, {}, "s.toml"),
                         "s.toml: fpu_beta n = 2.5; expected an integer in [1, 1000000]", sympl::invalid_argument);
    CHECK_THROWS_WITH_AS(make_system("kepler", {{"eccentricity", 1}}, {}, {}, "s.toml"),
                         "s.toml: kepler eccentricity = 1; expected a finite number in [0, 1)", sympl::invalid_argument);
    CHECK_THROWS_WITH_AS(make_system("kepler", {{"mu", 2}, {"scale", 3}}, {}, {}, "s.toml"),
                         "s.toml: kepler: mu = 2 and scale = 3; expected one of them left at 1", sympl::invalid_argument);
    CHECK_THROWS_WITH_AS(make_system("pendulum", {}, {1, 2}, {0, 0}, "s.toml"),
                         "s.toml: initial q has 2 and p 2 values; pendulum expects 1 each", sympl::invalid_argument);
}

TEST_CASE("systems: an exact solution is the flow: a 10th-order run at a small step lands on it") {
    for (const system_entry& entry : systems()) {
        if (!entry.exact) continue;
        CAPTURE(entry.name);
        const runnable_system p = make_system(entry.name, {}, {}, {}, "test");
        CHECK(relative_difference(p.exact(0), p.x0) < 1e-15);
        const method_spec m = *resolve_method(p.form.separable_hamiltonian ? "sofroniou_spaletta_10" : "rk4", {});
        run_request rq;
        rq.dt = p.form.separable_hamiltonian ? 0.01 : 0.001;
        rq.timing_repeats = 0;
        const run_result r = p.run(m, rq, 0.0, 2.0, p.x0);
        CHECK(relative_difference(r.final_state, p.exact(2.0)) < 1e-10);
    }
}

TEST_CASE("systems: a scene's own initial state replaces the default and drops the exact solution") {
    const runnable_system p = make_system("harmonic_oscillator", {{"omega", 2}}, {0.5}, {0.25}, "test");
    CHECK(p.x0 == std::vector<double>{0.5, 0.25});
    CHECK_FALSE(p.exact);
    CHECK(p.energy(p.x0) == doctest::Approx(0.25 * 0.25 / 2 + 4 * 0.25 / 2));
}

TEST_CASE("systems: each states its characteristic period, and one period of a periodic orbit closes it") {
    for (const system_entry& entry : systems()) {
        CAPTURE(entry.name);
        CHECK_FALSE(entry.period.meaning.empty());
        const double t = period_of(entry, with_defaults(entry, {}, "test"));
        CHECK(std::isfinite(t));
        CHECK(t > 0);
    }
    // Exact solutions one period on are back at the start (Kepler at two scales, the oscillator at omega = 3).
    const auto closes = [](const std::string& system, const parameter_values& given) {
        const system_entry& entry = *find_system(system);
        const runnable_system p = make_system(system, given, {}, {}, "test");
        return relative_difference(p.exact(period_of(entry, with_defaults(entry, given, "test"))), p.x0);
    };
    CHECK(closes("kepler", {}) < 1e-12);
    CHECK(closes("kepler", {{"scale", 3}, {"eccentricity", 0.9}}) < 1e-12);
    CHECK(closes("harmonic_oscillator", {{"omega", 3}}) < 1e-12);
    // Kepler at mu = 2 has no exact solution here; a 10th-order run over one
    // period (a = mu (1 - e) / (2 mu - 1 - e), vis-viva) closes the orbit.
    const system_entry& kepler = *find_system("kepler");
    const double period = period_of(kepler, with_defaults(kepler, {{"mu", 2}}, "test"));
    CHECK(period == doctest::Approx(two_pi * std::sqrt(0.4 * 0.4 * 0.4 / 2)).epsilon(1e-14));
    const runnable_system p = make_system("kepler", {{"mu", 2}}, {}, {}, "test");
    run_request rq;
    rq.dt = period / 4000;
    rq.timing_repeats = 0;
    const run_result r = p.run(*resolve_method("sofroniou_spaletta_10", {}), rq, 0.0, period, p.x0);
    CHECK(relative_difference(r.final_state, p.x0) < 1e-9);
    // Unbound (mu below (1 + e) / 2 from this start): no period.
    CHECK(period_of(kepler, with_defaults(kepler, {{"mu", 0.5}}, "test")) == 0);
}

TEST_CASE("systems: output columns count from 1, or name the bodies") {
    CHECK(state_columns("henon_heiles", 2) == std::vector<std::string>{"q1", "q2", "p1", "p2"});
    const auto planets = state_columns("outer_solar_system", 18);
    REQUIRE(planets.size() == 36);
    CHECK(planets[0] == "sun_x");
    CHECK(planets[3] == "jupiter_x");
    CHECK(planets[17] == "pluto_z");
    CHECK(planets[18] == "sun_px");
    CHECK(planets[22] == "jupiter_py");
}

TEST_CASE("systems: an unknown system or parameter gets the nearest names") {
    CHECK_THROWS_WITH_AS(make_system("kepplr", {}, {}, {}, "s.toml"),
                         doctest::Contains("s.toml: unknown system 'kepplr'; did you mean 'kepler'? expected one of: "),
                         sympl::invalid_argument);
    CHECK_THROWS_WITH_AS(make_system("pendulum", {{"lenght", 2}}, {}, {}, "s.toml"),
                         "s.toml: pendulum has no parameter 'lenght'; did you mean 'length'? expected one of: mass, "
                         "length, gravity",
                         sympl::invalid_argument);
}

}  // namespace test_program_test_systems
