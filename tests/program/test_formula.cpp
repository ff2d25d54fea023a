// Formulas of scenes read and evaluated (src/formulas/): values against the
// same H written in C++, the errors a scene's author sees, bounded depth.
#include <doctest/doctest.h>

#include <string>

#include <Eigen/Dense>

#include "formulas/formula.hpp"
#include "formulas/formula_eval.hpp"

namespace test_program_test_formula {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app::formulas;

const names plane{{"k", "n"}, {"x", "y"}, {"px", "py"}, 2};

std::string error_of(const std::string& text) {
    try {
        parse(text, plane);
    } catch (const formula_error& e) {
        return std::to_string(e.column) + ": " + e.what();
    }
    return "accepted";
}

TEST_CASE("formula: Henon-Heiles and an FPU chain written as formulas give the values of the same H in C++") {
    Eigen::VectorXd q(2), p(2);
    q << 0.3, -0.2;
    p << 0.1, 0.5;
    const formula hh = parse("(px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2*y - y^3/3", plane);
    const double x = q[0], y = q[1];
    const double by_hand = (p.squaredNorm()) / 2 + (x * x + y * y) / 2 + x * x * y - y * y * y / 3;
    CHECK(evaluate<double>(hh, {1, 2}, q, p) == doctest::Approx(by_hand).epsilon(4e-16));
    // An indexed sum over neighbours: n = 2 gives the one spring between q[0] and q[1].
    const formula chain = parse("sum(i, 0, n - 2, (q[i+1] - q[i])^2/2 + k*(q[i+1] - q[i])^4/4)", plane);
    const double d = q[1] - q[0];
    CHECK(evaluate<double>(chain, {1, 2}, q, p) == doctest::Approx(d * d / 2 + d * d * d * d / 4).epsilon(4e-16));
    // '^' binds right and above unary minus: -2^2 = -4, 2^3^2 = 512.
    CHECK(evaluate<double>(parse("-2^2", plane), {1, 2}, q, p) == -4);
    CHECK(evaluate<double>(parse("2^3^2", plane), {1, 2}, q, p) == 512);
}

TEST_CASE("formula: every error names its column and what was expected") {
    CHECK(error_of("x +") == "4: the formula ends where a value was expected");
    CHECK(error_of("sin(x") == "6: the end after sin's argument (functions take one); expected ')'");
    CHECK(error_of("foo(x)").rfind("1: unknown function 'foo'; expected one of: sin, cos", 0) == 0);
    CHECK(error_of("xx + 1").rfind("1: unknown name 'xx'; did you mean 'x' or 'px'?", 0) == 0);
    CHECK(error_of("1e999") == "1: '1e999' is not a finite number");
    CHECK(error_of("x ^^ 2") == "4: '^' where a value was expected; expected a number, a name, a function or '('");
    CHECK(error_of("sum(1, 0, 1, x)").rfind("5: sum's first argument must be the index's name", 0) == 0);
    CHECK(error_of("x y") == "3: 'y' after a complete formula; expected an operator (+ - * / ^) or the end");
    // An index outside the state, found when evaluated.
    Eigen::VectorXd q(2), p(2);
    q << 1, 2;
    p << 3, 4;
    CHECK_THROWS_WITH_AS(evaluate<double>(parse("q[n]", plane), {1, 2}, q, p), "q[2] outside 0..1", formula_error);
    // Nesting is bounded: 5000 brackets are refused, not a stack overflow.
    CHECK(error_of(std::string(5000, '(') + "x").find("nested more than 1000 deep") != std::string::npos);
}

}  // namespace test_program_test_formula

// The scene's way in: [system] tables read, run, and refused with file:line:col.
#include <cmath>

#include <sympl/core/hamiltonian.hpp>

#include "formulas/formula_code.hpp"
#include "formulas/formula_entry.hpp"
#include "formulas/machine_code.hpp"
#include "reading/scene.hpp"
#include "running/systems.hpp"

namespace test_program_test_formula_scene {

using namespace sympl::app;
using namespace sympl::app::formulas;

const std::string henon_heiles_scene = R"toml(name = "hh"
methods = ["leapfrog_kdk"]
dt = 0.05
t_end = 50
[system]
name = "hh_of_formulas"
coordinates = ["x", "y"]
T = "(px^2 + py^2) / 2"
V = "(x^2 + y^2) / 2 + x^2*y - y^3/3"
period = "2 * 3.141592653589793"
[initial]
q = [0, 0.1]
p = [0.5692099788303082, 0]
)toml";

std::string scene_error_of(const std::string& text) {
    try {
        parse_scene(text, "f.toml");
    } catch (const std::exception& e) {
        return e.what();
    }
    return "accepted";
}

run_request request(double dt) {
    run_request rq;
    rq.dt = dt;
    rq.tolerance = 1e-10;
    rq.energy = true;
    rq.timing_repeats = 0;
    return rq;
}

TEST_CASE("formula code: compiled values are the interpreter's bits, gradients the library's AD to rounding") {
    const names known{{"a", "n"}, {}, {}, 5};
    const std::vector<double> k{0.7, 5};
    Eigen::VectorXd q(5), p(5);
    q << 0.3, -0.2, 0.5, 0.11, -0.4;
    p << 0.1, 0.5, -0.3, 0.2, 0.05;
    // Every function, powers of each kind, divisions, nested sums with a bound from the outer index.
    const auto T = std::make_shared<formula>(parse("sum(i, 0, n - 1, p[i]^2 / (2 + i)) + a * p[0]^4 / 4", known));
    const auto V = std::make_shared<formula>(parse(
        "sum(i, 0, n - 2, sum(j, i + 1, n - 1, a / sqrt(1 + (q[i] - q[j])^2))) + sin(q[0]) * cos(q[1]) + "
        "tan(q[2]/3) + sinh(q[3]) - cosh(q[4]) * tanh(q[0]) + exp(-q[1]^2) + log(2 + q[2]) + abs(q[3]) + "
        "atan(q[4]) + q[0]^-2 + (1.5 + q[1])^2.5 + 2^q[2] - -q[3]",
        known));
    std::vector<double> x0(q.data(), q.data() + 5);
    x0.insert(x0.end(), p.data(), p.data() + 5);
    const auto prepared = prepare(T, V, nullptr, k, x0);
    REQUIRE_MESSAGE(prepared->code, prepared->interpreted_because);
    const separable_formulas sys(prepared);
    CHECK(sys.kinetic(p) == evaluate<double>(*T, k, q, p));
    CHECK(sys.potential(q) == evaluate<double>(*V, k, q, p));
    // The library's reverse mode through the interpreter, against the machine code's adjoints.
    Eigen::VectorXd f(5), f_ad(5), v(5), v_ad(5);
    sys.force(q, f);
    sympl::detail::gradient([&](const auto& x) { return evaluate<sympl::scalar_of<std::decay_t<decltype(x)>>>(*V, k, x, x); },
                            q, f_ad, -1.0);
    sys.velocity(p, v);
    sympl::detail::gradient([&](const auto& x) { return evaluate<sympl::scalar_of<std::decay_t<decltype(x)>>>(*T, k, x, x); },
                            p, v_ad);
    // Both are the exact gradient rounded along different orders: a few ulps of the largest terms.
    CHECK((f - f_ad).norm() <= 64 * 2.2e-16 * (1 + f_ad.norm()));
    CHECK((v - v_ad).norm() <= 16 * 2.2e-16 * (1 + v_ad.norm()));
    // The long-double functions too.
    using VL = Eigen::Matrix<long double, Eigen::Dynamic, 1>;
    const VL ql = q.cast<long double>();
    VL fl(5);
    sys.force(ql, fl);
    CHECK((fl.cast<double>() - f_ad).norm() <= 64 * 2.2e-16 * (1 + f_ad.norm()));
    // That T has masses 2 + i: drifts need its velocity.
    CHECK_FALSE(prepared->velocity_is_p);
}

TEST_CASE("formula code: a chain's neighbours carried from term to term give the gradient of the interpreter's AD") {
    const names known{{"a", "n"}, {}, {}, 6};
    const std::vector<double> k{0.7, 6};
    Eigen::VectorXd q(6);
    q << 0.3, -0.2, 0.5, 0.11, -0.4, 0.25;
    // Offsets (1, 0) and (-1, 0) are carried; (-1, 1) and a sum inside a sum are not.
    for (const char* text : {"sum(i, 0, n - 2, (q[i+1] - q[i])^2 / 2 + a * (q[i+1] - q[i])^4 / 4)",
                             "q[0]^2 + sum(i, 1, n - 1, cos(q[i] - q[i-1])) + q[n-1]^4",
                             "sum(i, 1, n - 2, q[i-1] * q[i+1])",
                             "sum(i, 0, n - 2, sum(j, i + 1, n - 1, a / sqrt(1 + (q[i] - q[j])^2)))"}) {
        CAPTURE(text);
        const auto T = std::make_shared<formula>(parse("sum(i, 0, n - 1, p[i]^2 / 2)", known));
        const auto V = std::make_shared<formula>(parse(text, known));
        const bool chain = std::string(text).find("q[i+1] - q[i]") != std::string::npos ||
                           std::string(text).find("q[i] - q[i-1]") != std::string::npos;
        CHECK((separable_source(*T, *V).find("if (h") != std::string::npos) == chain);
        std::vector<double> x0(q.data(), q.data() + 6);
        x0.resize(12, 0.1);
        const auto prepared = prepare(T, V, nullptr, k, x0);
        REQUIRE_MESSAGE(prepared->code, prepared->interpreted_because);
        Eigen::VectorXd f(6), f_ad(6);
        separable_formulas(prepared).force(q, f);
        sympl::detail::gradient(
            [&](const auto& x) { return evaluate<sympl::scalar_of<std::decay_t<decltype(x)>>>(*V, k, x, x); }, q, f_ad,
            -1.0);
        CHECK((f - f_ad).norm() <= 64 * 2.2e-16 * (1 + f_ad.norm()));
    }
}

TEST_CASE("formula code: T = sum p_i^2 / 2 is found to drift by p itself, and no other T") {
    const names known{{"m", "n"}, {}, {}, 3};
    const std::vector<double> x0{0.1, 0.2, 0.3, 0.4, 0.5, 0.6};
    const auto V = std::make_shared<formula>(parse("sum(i, 0, n - 1, q[i]^2) / 2", known));
    const auto with = [&](const char* t, double m) {
        return prepare(std::make_shared<formula>(parse(t, known)), V, nullptr, {m, 3}, x0)->velocity_is_p;
    };
    CHECK(with("sum(i, 0, n - 1, p[i]^2 / 2)", 1));
    CHECK(with("(p[0]^2 + p[1]^2 + p[2]^2) / (2 * m)", 1));
    CHECK_FALSE(with("(p[0]^2 + p[1]^2 + p[2]^2) / (2 * m)", 2));             // masses 2
    CHECK_FALSE(with("(p[0]^2 + p[1]^2 + p[2]^2 + p[0]*p[1]) / 2", 1));       // not diagonal
    CHECK_FALSE(with("(p[0]^2 + p[1]^2) / 2 + sqrt(1 + p[2]^2)", 1));         // not quadratic
}

TEST_CASE("formula code: nothing of the formula's text reaches the compiler") {
    const names known{{"rm_rf_home"}, {"system_call"}, {"evil_momentum"}, 1};
    const formula T = parse("evil_momentum^2 / 2", known), V = parse("rm_rf_home * system_call^2 / 2", known);
    const std::string source = separable_source(T, V);
    for (const char* name : {"rm_rf_home", "system_call", "evil_momentum"}) CHECK(source.find(name) == std::string::npos);
    // A function a scene names that is not one of the list never gets that far.
    CHECK_THROWS_WITH_AS(parse("system(1)", known), doctest::Contains("unknown function 'system'"), formula_error);
    // A broken source is refused with the compiler's words, not loaded.
    const compiled_or_reason broken = compile_c("this is not C");
    CHECK(broken.code == nullptr);
    CHECK(broken.reason.find("failed") != std::string::npos);
}

TEST_CASE("formula systems: Henon-Heiles and the double pendulum as formulas run as the built-in systems do") {
    const scene s = parse_scene(henon_heiles_scene, "hh.toml");
    CHECK(s.system == "hh_of_formulas");
    CHECK(s.period == doctest::Approx(2 * 3.141592653589793).epsilon(1e-15));
    const runnable_system mine = make_system(s.system, s.parameters, s.q0, s.p0, s.source);
    const runnable_system builtin = make_system("henon_heiles", {}, {}, {}, "test");
    CHECK(mine.form.quadratic_kinetic);
    for (const char* name : {"leapfrog_kdk", "blanes_moan_s6", "rk4", "dprkn8", "odeint_dopri5", "gauss_4"}) {
        INFO(name);
        const method_spec m = *resolve_method(name, {});
        const run_result a = mine.run(m, request(0.05), 0, 50, mine.x0);
        const run_result b = builtin.run(m, request(0.05), 0, 50, builtin.x0);
        REQUIRE(a.stable);
        CHECK(a.generic);
        CHECK(a.steps == b.steps);
        // The same steps on forces equal to rounding: states apart by rounding grown over 1000 steps.
        CHECK(relative_difference(a.final_state, b.final_state) < 1e-11);
        CHECK(a.max_energy_error == doctest::Approx(b.max_energy_error).epsilon(1e-6));
    }
    // The double pendulum as one H runs Gauss and Tao with the built-in's energy errors.
    const std::string pendulum = R"toml(methods = ["gauss_4"]
dt = 0.02
t_end = 20
[system]
name = "double_pendulum_of_formulas"
H = "(p[0]^2 + 2*p[1]^2 - 2*p[0]*p[1]*cos(q[0] - q[1])) / (2*(1 + sin(q[0] - q[1])^2)) + 2*(1 - cos(q[0])) + (1 - cos(q[1]))"
[initial]
q = [1.0, 0.5]
p = [0.2, -0.1]
)toml";
    const scene d = parse_scene(pendulum, "dp.toml");
    const runnable_system dp = make_system(d.system, {}, d.q0, d.p0, d.source);
    const runnable_system dp_builtin = make_system("double_pendulum", {}, {}, {}, "test");
    CHECK_FALSE(dp.form.separable_hamiltonian);
    for (const char* name : {"gauss_4", "gauss_6", "tao(yoshida_4)"}) {
        INFO(name);
        const method_spec m = *resolve_method(name, {});
        const run_result a = dp.run(m, request(0.02), 0, 20, dp.x0);
        const run_result b = dp_builtin.run(m, request(0.02), 0, 20, dp_builtin.x0);
        REQUIRE(a.stable);
        CHECK(relative_difference(a.final_state, b.final_state) < 1e-10);
        CHECK(a.max_energy_error == doctest::Approx(b.max_energy_error).epsilon(1e-4));
    }
}

TEST_CASE("formula systems: a scene's mistakes named at file:line:col") {
    const auto with = [](const std::string& from, const std::string& to) {
        std::string text = henon_heiles_scene;
        text.replace(text.find(from), from.size(), to);
        return scene_error_of(text);
    };
    // Column 23 of the formula, after `V = "` (the quote at column 5): column 28 of line 9.
    CHECK(with("x^2*y", "x^2*z") == "f.toml:9:28: system.V: unknown name 'z'; did you mean 'x' or 'y'? expected one "
                                   "of: x, y, px, py, q[i], p[i] (column 23 of the formula)");
    CHECK(with("T = \"(px^2", "T = \"(x^2").find("T uses q; expected T(p) alone") != std::string::npos);
    CHECK(with("y^3/3\"", "y^3/3 + log(x)\"").find("V = -inf at the initial state; expected a finite value") !=
          std::string::npos);
    CHECK(with("name = \"hh_of_formulas\"", "name = \"pendulum\"").find("the name of a built-in system") !=
          std::string::npos);
    CHECK(with("name = \"hh_of_formulas\"", "name = \"a b\"").find("system.name = 'a b'; expected letters") !=
          std::string::npos);
    CHECK(with("T = \"(px^2 + py^2) / 2\"", "H = \"x\"").find("[system] has H and T or V") != std::string::npos);
    CHECK(with("coordinates = [\"x\", \"y\"]", "coordinates = [\"x\"]").find("'system.coordinates' has 1 names for 2") !=
          std::string::npos);
    CHECK(with("coordinates = [\"x\", \"y\"]", "coordinates = [\"x\", \"sin\"]").find("'sin' is already a name") !=
          std::string::npos);
    CHECK(with("[initial]\nq = [0, 0.1]\np = [0.5692099788303082, 0]\n", "").find("without [initial] q and p") !=
          std::string::npos);
    CHECK(with("x^2*y", "q[2]").find("q[2] outside 0..1") != std::string::npos);
    CHECK(with("period = \"2 * 3.141592653589793\"", "period = \"x\"").find("period uses q") != std::string::npos);
    // A second definition under the same name in one run is refused; the same one is taken again.
    CHECK(scene_error_of(henon_heiles_scene) == "accepted");
    CHECK(with("x^2*y", "2*x^2*y").find("defined differently by another scene") != std::string::npos);
}

TEST_CASE("formula systems: an exact solution as formulas of t serves as the reference, and is checked at t = 0") {
    const std::string oscillator = R"toml(methods = ["leapfrog_kdk"]
dt = 0.01
t_end = 10
[system]
name = "oscillator_of_formulas"
parameters = {w = 2.0}
T = "p[0]^2 / 2"
V = "w^2 * q[0]^2 / 2"
exact_q = ["cos(w*t)"]
exact_p = ["-w*sin(w*t)"]
[initial]
q = [1.0]
p = [0.0]
)toml";
    const scene s = parse_scene(oscillator, "osc.toml");
    const runnable_system sys = make_system(s.system, s.parameters, s.q0, s.p0, s.source);
    REQUIRE(sys.exact);
    const std::vector<double> at = sys.exact(0.7);
    CHECK(at[0] == std::cos(2.0 * 0.7));
    CHECK(at[1] == -2.0 * std::sin(2.0 * 0.7));
    // Leapfrog's phase error against the exact solution: second order, so a
    // tenth of the step gives a hundredth of the error (within 0.15 of the order).
    const method_spec m = *resolve_method("leapfrog_kdk", {});
    const auto error_at = [&](double dt) {
        const run_result r = sys.run(m, request(dt), 0, 10, sys.x0);
        return relative_difference(r.final_state, sys.exact(10));
    };
    CHECK(std::log10(error_at(0.01) / error_at(0.001)) == doctest::Approx(2).epsilon(0.075));
    const auto with = [&](const std::string& from, const std::string& to) {
        std::string text = oscillator;
        text.replace(text.find(from), from.size(), to);
        return scene_error_of(text);
    };
    CHECK(with("cos(w*t)", "sin(w*t)") == "f.toml:9:12: exact_q[0] = 0 at t = 0 where the initial q[0] is 1; "
                                          "expected the solution through the initial state");
    CHECK(with("cos(w*t)", "cos(w*s)").find("f.toml:9:19: system.exact_q[0]: unknown name 's'") == 0);
    CHECK(with("cos(w*t)", "cos(q[0]*t)").find("exact_q[0] uses q; expected a formula of t and the parameters") !=
          std::string::npos);
    CHECK(with("exact_p = [\"-w*sin(w*t)\"]", "exact_p = []").find("'system.exact_p' has 0 formulas for 1") !=
          std::string::npos);
    CHECK(with("parameters = {w = 2.0}", "parameters = {w = 2.0, t = 1}").find("'t' free for the time") !=
          std::string::npos);
}

}  // namespace test_program_test_formula_scene
