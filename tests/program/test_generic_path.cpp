// The generic path (src/running/generic_path.hpp): every (system, kind) pair of the
// built-in scenes is compiled for its system; a pair that is not runs through
// the type-erased system, is marked, and gives what the compiled path gives
// for the same method and steps.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include <sympl/hamiltonians/double_pendulum.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

#include "running/erased_system.hpp"
#include "running/generic_path.hpp"
#include "reading/scene.hpp"
#include "running/systems.hpp"

namespace test_program_test_generic_path {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;

namespace {
run_request request(double dt) {
    run_request rq;
    rq.dt = dt;
    rq.tolerance = 1e-9;
    rq.energy = true;
    rq.timing_repeats = 0;
    return rq;
}
}  // namespace

TEST_CASE("every method of every built-in scene runs compiled for its system") {
    std::size_t pairs = 0;
    for (const bool quick : {true, false})
        for (const scene& s : default_scenes(quick)) {
            const runnable_system p = make_system(s.system, s.parameters, s.q0, s.p0, s.source);
            for (const scene_method& m : s.methods) {
                INFO(s.name << ": " << m.name);
                CHECK(compiled_has(p.compiled, m));
                ++pairs;
            }
        }
    CHECK(pairs > 100);
}

TEST_CASE("a kind not compiled for a system runs on the generic path and is marked") {
    // Nothing is compiled for the Morse oscillator (no built-in scene runs it).
    const runnable_system morse = make_system("morse", {}, {}, {}, "test");
    for (const char* name : {"leapfrog_kdk", "blanes_moan_s6", "rk4", "dprkn8", "gauss_4", "odeint_rk4"}) {
        INFO(name);
        const method_spec m = *resolve_method(name, {});
        CHECK_FALSE(morse.compiled.has(m.kind, m.classic));
        const run_result r = morse.run(m, request(0.01), 0.0, 10.0, morse.x0);
        CHECK(r.generic);
        REQUIRE(r.stable);
        CHECK(r.steps == 1000);
        CHECK(r.max_energy_error < 1e-3);  // second order or better at dt = 0.01
    }
    // The pendulum's compiled kinds are not marked.
    const runnable_system pendulum = make_system("pendulum", {}, {}, {}, "test");
    CHECK_FALSE(pendulum.run(*resolve_method("leapfrog_kdk", {}), request(0.01), 0.0, 1.0, pendulum.x0).generic);
    // An extrapolated table is compiled where a built-in scene runs one (Kepler),
    // generic elsewhere, at the order extrapolation gives it either way:
    // leapfrog with 3 columns is sixth order. At dt = 0.05 on the pendulum,
    // leapfrog's energy error is 5.4e-4 and 2 columns' (fourth order) 6.1e-8;
    // a sixth-order error is below the fourth order's by about dt^2 = 2.5e-3
    // (4.8e-12 measured).
    const method_spec extrapolated = *resolve_method("extrapolated(leapfrog_kdk, 3)", {});
    CHECK(compiled_has(make_system("kepler", {}, {}, {}, "test").compiled, extrapolated));
    REQUIRE_FALSE(compiled_has(pendulum.compiled, extrapolated));
    const run_result r = pendulum.run(extrapolated, request(0.05), 0.0, 10.0, pendulum.x0);
    CHECK(r.generic);
    REQUIRE(r.stable);
    CHECK(r.steps == 200);
    CHECK(r.max_energy_error < 6.1e-8 * 2.5e-3);
}

// The same method and steps, compiled against generic: the same step count and
// the final state to a few rounding units (the generic path's states are of
// dynamic size where the compiled pendulum's are fixed, which may change the
// order of a sum, never an operation).
TEST_CASE("the generic path gives what the compiled path gives") {
    const auto compare = [](const runnable_system& p, const run_function& generic, const char* name, double dt) {
        INFO(name);
        const method_spec m = *resolve_method(name, {});
        REQUIRE(compiled_has(p.compiled, m));
        const run_result a = p.run(m, request(dt), 0.0, 20.0, p.x0);
        const run_result b = generic(m, request(dt), 0.0, 20.0, p.x0);
        REQUIRE(a.stable);
        REQUIRE(b.stable);
        CHECK_FALSE(a.generic);
        CHECK(a.steps == b.steps);
        CHECK(a.force_evaluations == b.force_evaluations);
        CHECK(relative_difference(b.final_state, a.final_state) < 64 * 2.2e-16);
        CHECK(std::abs(b.max_energy_error - a.max_energy_error) <= 64 * 2.2e-16);
    };
    const runnable_system pendulum = make_system("pendulum", {}, {}, {}, "test");
    const run_function pendulum_generic =
        detail::generic_run(erased_separable::of(sympl::hamiltonians::pendulum{1, 1, 1}), pendulum.energy);
    for (const char* name : {"leapfrog_kdk", "blanes_moan_s6", "rk4", "dprkn8", "dprkn8_controlled", "odeint_dopri5"})
        compare(pendulum, pendulum_generic, name, 0.05);

    const runnable_system chain = make_system("fpu_beta", {}, {}, {}, "test");
    const run_function chain_generic =
        detail::generic_run(erased_separable::of(sympl::hamiltonians::fpu_beta{1}), chain.energy);
    for (const char* name : {"yoshida_6", "dprkn12"}) compare(chain, chain_generic, name, 0.1);

    const runnable_system dp = make_system("double_pendulum", {}, {}, {}, "test");
    const run_function dp_generic =
        detail::generic_run(erased_general::of(sympl::hamiltonians::double_pendulum{1, 1, 1, 1, 1}), dp.energy);
    for (const char* name : {"gauss_6", "tao(yoshida_6)", "semiexplicit(yoshida_4)"})
        compare(dp, dp_generic, name, 0.02);
}

// The RKN pairs on a state of one number run on fixed-size states
// (generic_path.cpp): the same operations as the compiled pendulum's pairs,
// so the same bits, where dynamic-size states may sum in another order.
TEST_CASE("the generic path's RKN pairs on one degree of freedom give the compiled bits") {
    const runnable_system pendulum = make_system("pendulum", {}, {}, {}, "test");
    const run_function generic =
        detail::generic_run(erased_separable::of(sympl::hamiltonians::pendulum{1, 1, 1}), pendulum.energy);
    for (const char* name : {"dprkn6", "dprkn8", "dprkn12", "dprkn8_controlled", "dprkn12_controlled"}) {
        INFO(name);
        const method_spec m = *resolve_method(name, {});
        const run_result a = pendulum.run(m, request(0.05), 0.0, 20.0, pendulum.x0);
        const run_result b = generic(m, request(0.05), 0.0, 20.0, pendulum.x0);
        REQUIRE(a.stable);
        REQUIRE(b.stable);
        CHECK_FALSE(a.generic);  // the pendulum's own pairs, compiled
        CHECK(b.generic);
        CHECK(a.steps == b.steps);
        CHECK(a.force_evaluations == b.force_evaluations);
        CHECK(a.final_state == b.final_state);
        CHECK(a.max_energy_error == b.max_energy_error);
    }
}

namespace {
// A system whose force, called through a fixed-size view, makes a call
// through the same view inside it (a Python force that runs sympl does).
const erased_fixed_size<1>* nested_view = nullptr;
int nested_depth = 0;
double nested_inner_force = 0;
// H = |p|^2 / 2 + |q|^2 / 2, for the test systems below to give their own force.
struct oscillator_energy {
    template <class V>
    sympl::scalar_of<V> kinetic(const V& p) const {
        return p.squaredNorm() / 2;
    }
    template <class V>
    sympl::scalar_of<V> potential(const V& q) const {
        return q.squaredNorm() / 2;
    }
};
struct nesting_system : oscillator_energy {
    void force(const erased_vector& q, erased_vector& f) const {
        f.resize(q.size());
        if (nested_depth++ == 0) {
            Eigen::Matrix<double, 1, 1> other(7.0), g;
            nested_view->force(other, g);
            nested_inner_force = g[0];
        }
        --nested_depth;
        f = -q;  // read after the inner call
    }
};
}  // namespace

TEST_CASE("a fixed-size call made inside another keeps the outer call's input") {
    const erased_fixed_size<1> view(erased_separable::of(nesting_system{}));
    nested_view = &view;
    Eigen::Matrix<double, 1, 1> q(3.0), f;
    view.force(q, f);
    CHECK(nested_inner_force == -7.0);
    CHECK(f[0] == -3.0);
    view.force(q, f);  // and the scratch vectors are free again after it
    CHECK(f[0] == -3.0);
    nested_view = nullptr;
}

namespace {
// A force of two numbers for a state of one.
struct wrong_size_force : oscillator_energy {
    void force(const erased_vector& q, erased_vector& f) const { f = erased_vector::Constant(q.size() + 1, 1.0); }
};
}  // namespace

TEST_CASE("a fixed-size view refuses a force of another size, not reading past it") {
    const erased_fixed_size<1> view(erased_separable::of(wrong_size_force{}));
    Eigen::Matrix<double, 1, 1> q(3.0), f;
    CHECK_THROWS_WITH_AS(view.force(q, f),
                         doctest::Contains("the system's force or velocity gave 2 numbers for a state of 1 degrees "
                                           "of freedom"),
                         sympl::invalid_argument);
}

}  // namespace test_program_test_generic_path
