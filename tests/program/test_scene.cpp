// Scene files: what they may say, and errors that name file, line and column.
#include <doctest/doctest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <numbers>
#include <vector>
#include <fstream>
#include <string>

#include "methods/run_plan.hpp"
#include "reading/ensemble_points.hpp"
#include "reading/scene.hpp"

namespace test_program_test_scene {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;

namespace {
const std::string good = R"(name = "kepler"
system = "kepler"
parameters = {eccentricity = 0.5}
methods = ["leapfrog_kdk", "mine", "rk4", "odeint_dopri5"]
dt = {from = 0.1, to = 0.001, count = 3}
t_end = 6.283185307179586
[output]
trajectory_every = 10
[[table]]
name = "mine"
kick = [0.5, 0.5]
drift = [1.0, 0.0]
order = 2
)";

std::string error_of(const std::string& text) {
    try {
        parse_scene(text, "scene.toml");
    } catch (const scene_error& e) {
        return e.what();
    }
    return "no error";
}
}  // namespace

TEST_CASE("scene: a valid scene with a sweep, an inline table and outputs") {
    const scene s = parse_scene(good, "scene.toml");
    CHECK(s.system == "kepler");
    CHECK(s.parameters.at("eccentricity") == 0.5);
    REQUIRE(s.methods.size() == 4);
    CHECK(s.methods[1].kind == method_kind::table);
    CHECK(s.methods[1].coefficients->stages() >= 1);
    CHECK(s.methods[2].kind == method_kind::classic);
    CHECK(s.methods[3].kind == method_kind::odeint);
    CHECK(s.methods[3].parameters.stepper == odeint_stepper::dopri5);
    REQUIRE(s.dt.size() == 3);
    CHECK(s.dt[0] == doctest::Approx(0.1));
    CHECK(s.dt[1] == doctest::Approx(0.01));
    CHECK(s.dt[2] == doctest::Approx(0.001));
    CHECK(s.output.trajectory_every == 10);
    CHECK_FALSE(s.output.final_state);
}

TEST_CASE("scene: errors name the file, line and column and what was expected") {
    const auto replace = [](std::string text, const std::string& from, const std::string& to) {
        text.replace(text.find(from), from.size(), to);
        return text;
    };
    CHECK(error_of(replace(good, "t_end = 6.283185307179586", "t_end = 6.2\nstep = 3")) ==
          "scene.toml:7:8: unknown key 'step' in the scene; expected one of: checkpoint, dt, ensemble, initial, methods, name, "
          "output, parameters, quick, system, t0, t_end, table, test_particles, tolerances");
    CHECK(error_of(replace(good, "\"kepler\"\nparameters", "\"kepplr\"\nparameters")).rfind("scene.toml:2:10: unknown system 'kepplr'", 0) == 0);
    CHECK(error_of(replace(good, "\"rk4\"", "\"rk5\"")).rfind("scene.toml:4:36: unknown method 'rk5'", 0) == 0);
    CHECK(error_of(replace(good, "trajectory_every = 10", "trajectory_every = \"often\"")) ==
          "scene.toml:8:20: 'output.trajectory_every' must be an integer >= 1 (every k-th step; leave it out for no "
          "trajectory)");
    // 0 once meant "no trajectory" silently; leaving the key out says that.
    CHECK(error_of(replace(good, "trajectory_every = 10", "trajectory_every = 0")).rfind(
              "scene.toml:8:20: 'output.trajectory_every' must be an integer >= 1", 0) == 0);
    CHECK(error_of(replace(good, "dt = {from = 0.1, to = 0.001, count = 3}", "dt = -0.1")) ==
          "scene.toml:5:6: 'dt' = -0.1; expected a finite number > 0");
    CHECK(error_of(replace(good, "t_end = 6.283185307179586", "t0 = 1.0\nt_end = 0.5")) ==
          "scene.toml:7:9: t_end = 0.5 is not after t0 = 1; expected t_end > t0");
    CHECK(error_of(replace(good, "system = \"kepler\"\n", "")).rfind("scene.toml:1:1: missing 'system'", 0) == 0);
    CHECK(error_of(replace(good, "eccentricity = 0.5", "eccentricty = 0.5")).rfind(
              "scene.toml:3:29: unknown key 'eccentricty' in [parameters] of kepler", 0) == 0);
    CHECK(error_of(replace(good, "drift = [1.0, 0.0]", "drift = [1.0, 0.5]")) ==
          "scene.toml:9:1: table 'mine': sum(drift) = 1.5; expected 1 within 1e-14");
    CHECK(error_of("system = [").rfind("scene.toml:1:11: not valid TOML", 0) == 0);
    // A method name nested 5000 deep is refused before it is resolved (its
    // recursion overflowed the stack), quoted by its start and length.
    std::string deep = "leapfrog_kdk";
    for (int k = 0; k < 5000; ++k) deep = "logh(" + deep + ")";
    const std::string nested = error_of(replace(good, "\"rk4\"", "\"" + deep + "\""));
    CHECK(nested.rfind("scene.toml:4:36: method 'logh(logh(", 0) == 0);
    CHECK(nested.find("...' (30012 characters) nests its parentheses 5000 deep; expected at most 8") !=
          std::string::npos);
    CHECK(nested.size() < 400);
    std::string eight = "leapfrog_kdk", nine;
    for (int k = 0; k < 8; ++k) eight = "compensated(" + eight + ")";
    nine = "compensated(" + eight + ")";
    CHECK(error_of(replace(good, "\"rk4\"", "\"" + eight + "\"")).find("nests") == std::string::npos);
    CHECK(error_of(replace(good, "\"rk4\"", "\"" + nine + "\"")).find("nests its parentheses 9 deep") !=
          std::string::npos);
    CHECK_THROWS_WITH_AS(load_scene("/nonexistent/scene.toml"), doctest::Contains("cannot open"), scene_error);
}

TEST_CASE("scene: a name's control characters, a megabyte name and a thousand unknown keys give short one-line errors") {
    const auto method_error = [](const std::string& toml_name) {
        std::string text = good;
        text.replace(text.find("\"rk4\""), 5, "\"" + toml_name + "\"");
        return error_of(text);
    };
    // TOML escapes for NUL, a newline and a terminal's escape, inside a method name.
    const std::string e = method_error("rk\\u0000x\\nred\\u001b[31m");
    CHECK(e.rfind("scene.toml:4:36: unknown method 'rk\\0x\\nred\\x1b[31m'", 0) == 0);
    CHECK(e.find('\n') == std::string::npos);
    CHECK(e.find('\x1b') == std::string::npos);
    // UTF-8's C1 controls (U+009B is an escape's start on some terminals), beside letters that are not.
    const std::string c1 = method_error("r\\u009b31m\\u0085\\u00e9");
    CHECK(c1.find("unknown method 'r\\u009b31m\\u0085\xc3\xa9'") != std::string::npos);
    // A scene path with a newline and an escape is quoted escaped.
    CHECK_THROWS_WITH_AS(load_scene("/nonexistent/a\nb\x1b.toml"),
                         doctest::Contains("/nonexistent/a\\nb\\x1b.toml: cannot open"), scene_error);
    // A name of a megabyte is quoted by its start and end, with the count cut.
    const std::string m = method_error(std::string(1 << 20, 'q'));
    CHECK(m.size() < 2100);
    CHECK(m.find("characters cut") != std::string::npos);
    CHECK(m.rfind("scene.toml:4:36: unknown method 'qqqq", 0) == 0);
    // A thousand unknown keys: the first 20, then how many more.
    std::string keys = good;
    for (int k = 0; k < 1000; ++k) keys.insert(keys.find("t_end"), "unknown_" + std::to_string(k) + " = 1\n");
    const std::string many = error_of(keys);
    CHECK(std::count(many.begin(), many.end(), '\n') == 20);
    CHECK(many.find("scene.toml: and 980 more unknown names") != std::string::npos);
}

TEST_CASE("scene: the built-in set parses, quick and full") {
    CHECK(default_scenes(true).size() == 17);
    CHECK(default_scenes(false).size() == 17);
    for (const scene& s : default_scenes(true)) {
        CAPTURE(s.name);
        CHECK(s.dt.size() >= (s.ensemble ? 1 : 3));  // an ensemble runs one step size
        CHECK(s.t_end > s.t0);
    }
}

TEST_CASE("scene: an [ensemble] is read in the file's axis order, and its errors are located") {
    const std::string base = "system = \"henon_heiles\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 10\n[ensemble]\n";
    const scene s = parse_scene(base + "grid = {q2 = {from = -0.4, to = 0.6, count = 3}, p2 = {from = 0, to = 1, count = 2}}\n"
                                       "indicator = \"megno\"\n", "e.toml");
    REQUIRE(s.ensemble);
    REQUIRE(s.ensemble->grid.size() == 2);
    CHECK(s.ensemble->grid[0].name == "q2");  // toml++ sorts keys: the order is the file's
    CHECK(s.ensemble->grid[0].value(1) == doctest::Approx(0.1));
    CHECK(s.ensemble->size() == 6);
    CHECK(s.ensemble->megno);
    const auto error_of = [&](const std::string& text) {
        try {
            parse_scene(text, "e.toml");
        } catch (const scene_error& e) {
            return std::string(e.what());
        }
        return std::string("no error");
    };
    CHECK(error_of(base + "grid = {mass = {from = 0, to = 1, count = 2}}\n").find("e.toml:6:16: unknown key 'mass' in ensemble.grid of henon_heiles; expected one of: energy, p2, q2") == 0);
    CHECK(error_of(base + "grid = {q2 = {from = 0, to = 1, count = 0}}\n").find("'q2.count' must be an integer in [1, 1000000]") !=
          std::string::npos);
    CHECK(error_of(base + "grid = {q2 = {from = 0, to = 1, count = 1000000}, p2 = {from = 0, to = 1, count = 1000}}\n")
              .find("the grid has 1e+09 points; expected at most 1e+07") != std::string::npos);
    std::string with_rk4 = base;
    with_rk4.replace(with_rk4.find("leapfrog_kdk"), 12, "rk4");
    CHECK(error_of(with_rk4 + "grid = {q2 = {from = 0, to = 1, count = 2}}\n")
              .find("an ensemble runs one splitting table") != std::string::npos);
    std::string with_gradient = base;
    with_gradient.replace(with_gradient.find("leapfrog_kdk"), 12, "chin_4a");
    CHECK(error_of(with_gradient + "grid = {q2 = {from = 0, to = 1, count = 2}}\n")
              .find("an ensemble runs plain kick-drift tables; 'chin_4a' has force-gradient kicks") != std::string::npos);
    CHECK(error_of(base + "states = \"x.csv\"\ngrid = {q2 = {from = 0, to = 1, count = 2}}\n").find("either grid") !=
          std::string::npos);
}

TEST_CASE("scene: files too large or not files are refused before they are read, NUL bytes named with their line") {
    CHECK_THROWS_WITH_AS(load_scene("/dev/zero"),
                         doctest::Contains("/dev/zero: the scene file is a character device; expected a regular file"),
                         scene_error);
    CHECK_THROWS_WITH_AS(load_scene("/tmp"), doctest::Contains("/tmp: the scene file is a directory"), scene_error);
    const std::string large = "/tmp/sympl_test_large_" + std::to_string(::getpid()) + ".toml";
    { std::ofstream create(large); }
    std::filesystem::resize_file(large, (std::size_t(1) << 20) + 1);  // sparse: no disk used
    CHECK_THROWS_WITH_AS(load_scene(large),
                         doctest::Contains("the scene file is larger than 1048576 bytes; expected at most that"),
                         scene_error);
    std::remove(large.c_str());
    const std::string path = "/tmp/sympl_test_nul_" + std::to_string(::getpid()) + ".toml";
    {
        std::ofstream f(path, std::ios::binary);
        f << "system = \"kepler\"\nname = \"a";
        f.put('\0');
        f << "\"\n";
    }
    CHECK_THROWS_WITH_AS(load_scene(path), doctest::Contains(":2: a NUL byte"), scene_error);
    std::remove(path.c_str());
}

TEST_CASE("scene: output times as a list or {from, to, count}, sorted, inside the span, or refused where they are") {
    const auto with_times = [](const std::string& times) {
        std::string text = good;
        const std::string from = "trajectory_every = 10";
        text.replace(text.find(from), from.size(), "times = " + times);
        return text;
    };
    const scene listed = parse_scene(with_times("[0, 0.5, 0.5, 6.283185307179586]"), "scene.toml");
    CHECK(listed.output.times == std::vector<double>{0, 0.5, 0.5, 6.283185307179586});
    CHECK(listed.output.trajectory_every == 0);
    CHECK(listed.output.writes_trajectory());
    const scene spaced = parse_scene(with_times("{from = 1, to = 2, count = 5}"), "scene.toml");
    CHECK(spaced.output.times == std::vector<double>{1, 1.25, 1.5, 1.75, 2});
    CHECK(parse_scene(with_times("{from = 3, to = 3, count = 1}"), "scene.toml").output.times ==
          std::vector<double>{3});
    // --quick's shorter span leaves out the later times, and only those.
    const scene quick = parse_scene(with_times("[1, 2, 4, 6]") + "[quick]\nt_end = 3\n", "scene.toml", true);
    CHECK(quick.output.times == std::vector<double>{1, 2});
    CHECK(quick.output.times_dropped == 2);
    // When --quick leaves none, the trajectory file is still written (its
    // header; the run's summary says why it has no rows).
    const scene none = parse_scene(with_times("[4, 6]") + "[quick]\nt_end = 3\n", "scene.toml", true);
    CHECK(none.output.times.empty());
    CHECK(none.output.times_dropped == 2);
    CHECK(none.output.writes_trajectory());

    CHECK(error_of(with_times("[0, 2, 1]")) ==
          "scene.toml:8:16: output time 1 comes after 2; expected the times sorted, earliest first");
    CHECK(error_of(with_times("[0, 7]")) == "scene.toml:8:13: output time 7 is outside the run; expected a time in "
                                            "[t0, t_end] = [0, 6.283185307179586]");
    CHECK(error_of(with_times("[-1]")).rfind("scene.toml:8:10: output time -1 is outside the run", 0) == 0);
    CHECK(error_of(with_times("[nan]")).rfind("scene.toml:8:10: output time nan is outside the run", 0) == 0);
    CHECK(error_of(with_times("[]")) == "scene.toml:8:9: 'output.times' is an empty array; expected at least one time");
    CHECK(error_of(with_times("[\"later\"]")) == "scene.toml:8:10: 'output.times' must be a number");
    CHECK(error_of(with_times("5")) ==
          "scene.toml:8:9: 'output.times' must be an array of times or {from, to, count}");
    CHECK(error_of(with_times("{from = 2, to = 1, count = 3}")) ==
          "scene.toml:8:25: 'output.times.to' = 1 is before from = 2; expected to >= from");
    CHECK(error_of(with_times("{from = 0, to = 1, count = 0}")) ==
          "scene.toml:8:36: 'output.times.count' = 0; expected an integer >= 1");
    CHECK(error_of(with_times("{from = 0, to = 1, count = 1.5}")) ==
          "scene.toml:8:36: 'output.times.count' = 1.5; expected an integer >= 1");
    // One time cannot stand for from..to: which end was meant is a guess.
    CHECK(error_of(with_times("{from = 0, to = 1, count = 1}")) ==
          "scene.toml:8:36: 'output.times' count = 1 with from = 0 < to = 1; expected count >= 2, or from = to for a "
          "single time");
    CHECK(error_of(with_times("{from = 0, to = 1, count = 20000000}")) ==
          "scene.toml:8:36: 'output.times' asks for 2e+07 rows; expected at most 1e+07");
    CHECK(error_of(with_times("{from = 1, to = 1, count = 2}")) ==
          "scene.toml:8:36: 'output.times' from = to = 1 with count = 2; expected count = 1 for a single time");
    CHECK(error_of(with_times("{from = 0, to = 1}")) ==
          "scene.toml:8:9: 'output.times' has no 'count'; expected {from = ..., to = ..., count = ...}");
    CHECK(error_of(with_times("{to = 1, count = 3}")) ==
          "scene.toml:8:9: 'output.times' has no 'from'; expected {from = ..., to = ..., count = ...}");
    CHECK(error_of(with_times("[1]\ntrajectory_every = 3")) ==
          "scene.toml:8:9: 'output.times' and 'output.trajectory_every' both choose the trajectory's rows; expected "
          "one of them");
}

TEST_CASE("scene: runs beyond the step limit are refused up front with the figures, and the limit can be raised") {
    const scene s = parse_scene("system = \"harmonic_oscillator\"\nmethods = [\"leapfrog_kdk\", "
                                "\"extrapolated(leapfrog_kdk, 4)\"]\ndt = [0.1, 0.001]\nt_end = 1000\n",
                                "long.toml");
    const runnable_system p = system_of(s);
    // sympl run uses the first dt: 1e4 steps, extrapolated 1e5 inner steps.
    CHECK_NOTHROW(check_run_size(plan_runs(s, p, sweep_use::first), 1e5));
    CHECK_THROWS_WITH_AS(check_run_size(plan_runs(s, p, sweep_use::first), 99999),
                         doctest::Contains("method 'extrapolated(leapfrog_kdk, 4)' at dt = 0.1 over t = 0 .. 1000 takes "
                                           "1e+05 steps; the limit is 1e+05 (raise it with --max-steps)"),
                         scene_error);
    // The report runs the whole sweep: 1e6 steps of leapfrog at dt = 0.001.
    CHECK_THROWS_WITH_AS(check_run_size(plan_runs(s, p, sweep_use::whole), 1e5), doctest::Contains("'leapfrog_kdk' at dt = 0.001"), scene_error);
    // Without an exact solution the reference counts: 1.5 runs at a quarter of the finest step.
    const scene pendulum = parse_scene("system = \"pendulum\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 1000\n",
                                       "pendulum.toml");
    CHECK_THROWS_WITH_AS(check_run_size(plan_runs(pendulum, system_of(pendulum), sweep_use::first), 5e4),
                         doctest::Contains("the reference (its dt is a quarter of the finest step, 0.1) at dt = 0.025"),
                         scene_error);
    CHECK_NOTHROW(check_run_size(plan_runs(pendulum, system_of(pendulum), sweep_use::first), 6e4));
}

TEST_CASE("scene: an initial state of infinite energy is refused, not reported as energy error 0") {
    const auto error_of_initial = [](const std::string& system, const std::string& initial) {
        try {
            system_of(parse_scene("system = \"" + system + "\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 1\n" +
                                       "initial = " + initial + "\n",
                                   "x.toml"));
        } catch (const scene_error& e) {
            return std::string(e.what());
        }
        return std::string("accepted");
    };
    CHECK(error_of_initial("harmonic_oscillator", "{q = [1e308], p = [1e308]}") ==
          "x.toml: the initial state of harmonic_oscillator has energy H = inf; expected a state of finite energy");
    CHECK(error_of_initial("kepler", "{q = [0, 0], p = [0, 1]}") ==
          "x.toml: the initial state of kepler has energy H = -inf; expected a state of finite energy");
    CHECK(error_of_initial("kepler", "{q = [1, 0], p = [0, 1]}") == "accepted");
}

TEST_CASE("scene: a default start the parameters make impossible is refused naming them") {
    // charged_uniform starts at |v0| = sqrt(1.01): below it, a speed of light leaves no momentum for it.
    const std::string head = "system = \"charged_uniform\"\nparameters = {speed_of_light = 0.5}\n"
                             "methods = [\"boris\"]\ndt = 0.1\nt_end = 1\n";
    std::string said;
    try {
        system_of(parse_scene(head, "c.toml"));
    } catch (const std::exception& e) {
        said = e.what();
    }
    // The NaN's sign is the processor's: not part of the message's promise.
    CHECK(said.starts_with("c.toml: charged_uniform's default start is not finite at the parameters given "
                           "(speed_of_light = 0.5): x0 = (1, 0, 0, 0, "));
    CHECK(said.ends_with("nan); expected parameters it can start from (`sympl systems` describes the start) or a "
                         "start of one's own ([initial] in a scene, q0 and p0 in Python)"));
    // Its own start, at rest in the field's gauge (p = e A(q)), runs at that speed of light.
    CHECK_NOTHROW(system_of(parse_scene(head + "initial = {q = [1, 0, 0], p = [0, 0.5, 0]}\n", "c.toml")));
}

TEST_CASE("scene: a checkpoint table for any method kind, a bad interval refused where it is written") {
    const std::string head = "system = \"kepler\"\ndt = 0.1\nt_end = 1\ncheckpoint = {every_steps = 100, file = \"c\"}\n";
    const scene s = parse_scene(head + "methods = [\"leapfrog_kdk\", \"compensated(yoshida_6)\", \"rk4\"]\n", "c.toml");
    CHECK(s.checkpoint.every_steps == 100);
    CHECK(s.methods[1].compensated);
    for (const std::string m : {"velocity_verlet", "logh(leapfrog_dkd)", "odeint_rk4", "extrapolated(leapfrog_kdk, 3)",
                                "odeint_bulirsch_stoer"}) {
        CAPTURE(m);
        CHECK(error_of(head + "methods = [\"rk4\", \"" + m + "\"]\n") == "no error");  // every kind resumes
    }
    CHECK(error_of("system = \"kepler\"\ndt = 0.1\nt_end = 1\nmethods = [\"rk4\"]\ncheckpoint = {every_steps = 0, file = \"c\"}\n") ==
          "scene.toml:5:29: 'checkpoint.every_steps' must be an integer in [1, 1e15]");
    // A different scene text is a different scene for its checkpoints.
    CHECK(parse_scene(head + "methods = [\"rk4\"]\n", "a.toml").text_hash !=
          parse_scene(head + "methods = [\"rk4\"] \n", "a.toml").text_hash);
}

TEST_CASE("scene: every unknown name in one pass, a line each with its place, and the nearest known names") {
    const std::string text = "system = \"kepler\"\n"                                          // 1
                             "parameters = {eccentricty = 0.5}\n"                            // 2
                             "methods = [\"leapfrog_kd\", \"blanes_moan_s6\", \"rk5\"]\n"    // 3
                             "dtt = 0.1\n"                                                   // 4
                             "dt = 0.1\n"                                                    // 5
                             "t_end = 1\n"                                                   // 6
                             "[output]\n"                                                    // 7
                             "energy_eror = true\n";                                         // 8
    const std::string e = error_of(text);
    std::vector<std::string> lines;
    for (std::size_t at = 0; at <= e.size();) {
        const std::size_t end = std::min(e.find('\n', at), e.size());
        lines.push_back(e.substr(at, end - at));
        at = end + 1;
    }
    REQUIRE(lines.size() == 5);
    CHECK(lines[0].rfind("scene.toml:4:7: unknown key 'dtt' in the scene; did you mean 'dt'? expected one of: ", 0) == 0);
    CHECK(lines[1].rfind("scene.toml:2:29: unknown key 'eccentricty' in [parameters] of kepler; did you mean "
                         "'eccentricity'? expected one of: eccentricity, mu, scale", 0) == 0);
    CHECK(lines[2].rfind("scene.toml:3:12: unknown method 'leapfrog_kd'; did you mean 'leapfrog_kdk'", 0) == 0);
    CHECK(lines[3].rfind("scene.toml:3:45: unknown method 'rk5'; did you mean ", 0) == 0);
    CHECK(lines[3].find("'rk4'") != std::string::npos);
    CHECK(lines[4].rfind("scene.toml:8:15: unknown key 'energy_eror' in [output]; did you mean 'energy_error'?", 0) == 0);
    // An unknown system: its parameters cannot be checked, the methods still are.
    const std::string two = error_of("system = \"kepplr\"\nmethods = [\"rk5\"]\ndt = 0.1\nt_end = 1\n");
    CHECK(two.rfind("scene.toml:1:10: unknown system 'kepplr'; did you mean 'kepler'? expected one of: ", 0) == 0);
    CHECK(two.find("\nscene.toml:2:12: unknown method 'rk5'") != std::string::npos);
    // An error that stops the reading still lists the unknown names found before it.
    const std::string stopped = error_of("system = \"kepler\"\nmethods = [\"rk4\"]\ndtt = 0.1\nt_end = 1\n");
    CHECK(stopped.rfind("scene.toml:3:7: unknown key 'dtt' in the scene; did you mean 'dt'?", 0) == 0);
    CHECK(stopped.find("\nscene.toml:1:1: missing 'dt'") != std::string::npos);
}

TEST_CASE("scene: spans and steps in the system's characteristic period") {
    const std::string head = "system = \"kepler\"\nmethods = [\"leapfrog_kdk\"]\n";
    const double orbit = 2 * std::numbers::pi;  // Kepler at mu = 1, any eccentricity and scale
    const scene s = parse_scene(head + "dt = {per_period = [100, 200]}\nt_end = {periods = 1000}\n", "p.toml");
    CHECK(s.period == doctest::Approx(orbit).epsilon(1e-15));
    CHECK(s.t_end == doctest::Approx(1000 * orbit).epsilon(1e-15));
    REQUIRE(s.dt.size() == 2);
    CHECK(s.dt[0] == doctest::Approx(orbit / 100).epsilon(1e-15));
    CHECK(s.dt[1] == doctest::Approx(orbit / 200).epsilon(1e-15));
    // A sweep of steps per period, a method's own, [quick]'s, and t0 counted from.
    const scene q = parse_scene("system = \"kepler\"\nmethods = [{name = \"leapfrog_kdk\", dt = {per_period = 50}}]\n"
                                "dt = {per_period = {from = 10, to = 1000, count = 3}}\nt0 = 1\nt_end = {periods = 2}\n"
                                "[quick]\nt_end = {periods = 1}\n",
                                "q.toml", true);
    CHECK(q.t_end == doctest::Approx(1 + orbit));
    REQUIRE(q.dt.size() == 3);
    CHECK(q.dt[2] == doctest::Approx(orbit / 1000));
    REQUIRE(q.methods[0].dt.size() == 1);
    CHECK(q.methods[0].dt[0] == doctest::Approx(orbit / 50));
    // The period follows the parameters: the oscillator at omega = 4.
    const scene o = parse_scene("system = \"harmonic_oscillator\"\nparameters = {omega = 4}\nmethods = [\"rk4\"]\n"
                                "dt = {per_period = 10}\nt_end = {periods = 3}\n", "o.toml");
    CHECK(o.t_end == doctest::Approx(3 * std::numbers::pi / 2));
    CHECK(o.dt[0] == doctest::Approx(std::numbers::pi / 20));
    // No period (an unbound orbit), a misspelt key, a bad count: located, and said why.
    CHECK(error_of(head + "parameters = {mu = 0.5}\ndt = 0.1\nt_end = {periods = 3}\n").rfind(
              "scene.toml:5:9: 't_end' counts in the system's characteristic period, and it has none at these "
              "parameters (orbital period", 0) == 0);
    CHECK(error_of(head + "dt = {per_priod = 10}\nt_end = 1\n").rfind(
              "scene.toml:3:19: unknown key 'per_priod' in 'dt'; did you mean 'per_period'?", 0) == 0);
    CHECK(error_of(head + "dt = 0.1\nt_end = {periods = -2}\n") ==
          "scene.toml:4:20: 't_end.periods' = -2; expected a finite number > 0");
    // A count of periods past a double's range: refused at its key, with what it was made of.
    CHECK(error_of(head + "dt = 0.1\nt_end = {periods = 1e308}\n").rfind(
              "scene.toml:4:9: 't_end': 1e+308 periods of 6.283185307179586 after t0 = 0 give t_end = inf; expected "
              "a finite time after t0", 0) == 0);
}

TEST_CASE("scene: a geometric sweep holds the decimals it meant, and one past a double's range is refused at its key") {
    const std::string head = "system = \"kepler\"\nmethods = [\"leapfrog_kdk\", \"odeint_dopri5\"]\nt_end = 1\n";
    // 1e-4 * (1e-3)^(1/2) is 1.0000000000000005e-07 in doubles: two ulps from
    // the 1e-7 the sweep means, which the scene now holds; 0.1 * 0.05^(1/2) =
    // 0.0223606797749979 is no short decimal and stays as computed.
    const scene s = parse_scene(head + "dt = {from = 0.1, to = 0.005, count = 3}\n"
                                       "tolerances = {from = 1e-4, to = 1e-10, count = 3}\n", "s.toml");
    REQUIRE(s.tolerances.size() == 3);
    CHECK(s.tolerances[0] == 1e-4);
    CHECK(s.tolerances[1] == 1e-7);
    CHECK(s.tolerances[2] == 1e-10);
    REQUIRE(s.dt.size() == 3);
    CHECK(s.dt[1] == 0.1 * std::pow(0.005 / 0.1, 0.5));
    CHECK(s.dt[2] == 0.005);
    // Steps per period that overflow the step, and a sweep whose ratio overflows.
    CHECK(error_of(head + "dt = {per_period = 1e-320}\n").rfind(
              "scene.toml:4:6: 'dt': the period 6.283185307179586 / 1e-320 gives inf; expected a finite value > 0", 0) == 0);
    CHECK(error_of(head + "dt = {from = 1e-300, to = 1e300, count = 3}\n").rfind(
              "scene.toml:4:6: 'dt': a point between 1e-300 and 1e+300 gives inf; expected a finite value > 0", 0) == 0);
}

}  // namespace test_program_test_scene

namespace test_program_test_scene_memory {

using namespace sympl::app;

TEST_CASE("scene: a run that would hold more than the memory budget is refused before it allocates") {
    // gauss_6 on 20000 masses: (4e4)^2 + (1.2e5)^2 doubles, 119 GiB of Newton matrices.
    const scene chain = parse_scene("system = \"fpu_beta\"\nparameters = {n = 20000}\nmethods = [\"gauss_6\"]\n"
                                    "dt = 0.1\nt_end = 1\n",
                                    "chain.toml");
    CHECK_THROWS_WITH_AS(check_run_size(plan_runs(chain, system_of(chain), sweep_use::first), 1e9),
                         "chain.toml: method 'gauss_6' would hold 119 GiB (Gauss-Legendre's Jacobian and Newton matrix "
                         "for 20000 degrees of freedom and 3 stages); the limit is 4 GiB a run (docs/reliability.md, "
                         "\"Memory\")",
                         scene_error);
    // An energy series of every step over 4e8 steps would be 12 GiB held:
    // `sympl run` writes it as the run goes instead, so it is no run's memory.
    const scene series = parse_scene("system = \"harmonic_oscillator\"\nmethods = [\"leapfrog_kdk\", \"gauss_6\"]\n"
                                     "dt = 0.01\nt_end = 4e6\n[output]\nenergy_every = 1\n",
                                     "series.toml");
    CHECK_NOTHROW(check_run_size(plan_runs(series, system_of(series), sweep_use::first), 1e9));
    const memory_estimate held = run_memory(series.methods[0], 1, 4e8, 1);  // as the Python module holds it
    CHECK(held.bytes > 12e9);
    CHECK(held.what == "an energy series of 4e+08 rows (energy_every = 1)");
    // An ensemble grid inside the 1e7-point limit that would hold more than the budget.
    const scene grid = parse_scene("system = \"henon_heiles\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 1\n"
                                   "[ensemble]\ngrid = {q2 = {from = -0.3, to = 0.3, count = 3000}, "
                                   "p2 = {from = -0.3, to = 0.3, count = 3000}}\n",
                                   "grid.toml");
    CHECK_THROWS_WITH_AS(set_up_ensemble(grid, 1e9), doctest::Contains("grid.toml: 9000000 trajectories of 2 degrees "
                                                                       "of freedom would hold"),
                         sympl::invalid_argument);
}

}  // namespace test_program_test_scene_memory

namespace test_program_test_scene_inputs {

using namespace sympl::app;

TEST_CASE("scene: the identity a checkpoint belongs to covers the states and elements files the scene reads") {
    const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("sympl_inputs_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    {
        std::ofstream(dir / "e.toml") << "system = \"henon_heiles\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 1\n"
                                         "[ensemble]\nstates = \"starts.csv\"\n";
        std::ofstream(dir / "starts.csv") << "q1,q2,p1,p2\n0,0.1,0.3,0\n";
    }
    const std::string before = load_scene((dir / "e.toml").string()).text_hash;
    CHECK(before == load_scene((dir / "e.toml").string()).text_hash);  // the same files, the same identity
    std::ofstream(dir / "starts.csv") << "q1,q2,p1,p2\n0,0.1,0.3,0.01\n";  // one number edited after a kill
    CHECK(load_scene((dir / "e.toml").string()).text_hash != before);
    // The same for a test-particle map's elements file.
    {
        std::ofstream(dir / "m.toml") << "system = \"outer_solar_system\"\nmethods = [\"wh(saba_2)\"]\ndt = 100\n"
                                         "t_end = 2000\n[test_particles]\nelements = \"orbits.csv\"\n"
                                         "indicator = \"megno\"\n";
        std::ofstream(dir / "orbits.csv") << "a,e\n6.5,0.1\n7,0\n";
    }
    const std::string map_before = load_scene((dir / "m.toml").string()).text_hash;
    CHECK(map_before == load_scene((dir / "m.toml").string()).text_hash);
    std::ofstream(dir / "orbits.csv") << "a,e\n6.5,0.1\n7,0.01\n";
    CHECK(load_scene((dir / "m.toml").string()).text_hash != map_before);
    // The scene's text alone, as before, where it reads no file.
    const std::string text = "system = \"pendulum\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 1\n";
    std::ofstream(dir / "p.toml") << text;
    CHECK(load_scene((dir / "p.toml").string()).text_hash == fnv1a_hex(text));
    std::filesystem::remove_all(dir);
}

}  // namespace test_program_test_scene_inputs
