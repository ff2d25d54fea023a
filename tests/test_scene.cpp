// Scene files: what they may say, and errors that name file, line and column.
#include <doctest/doctest.h>

#include <string>

#include "scene.hpp"

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
    CHECK(s.methods[3].kind == method_kind::odeint_dopri5);
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
          "scene.toml:7:8: unknown key 'step' in the scene; expected one of: dt, initial, methods, name, output, "
          "parameters, quick, system, t0, t_end, table, tolerances");
    CHECK(error_of(replace(good, "\"kepler\"\nparameters", "\"kepplr\"\nparameters")).rfind("scene.toml:2:10: unknown system 'kepplr'", 0) == 0);
    CHECK(error_of(replace(good, "\"rk4\"", "\"rk5\"")).rfind("scene.toml:4:36: unknown method 'rk5'", 0) == 0);
    CHECK(error_of(replace(good, "trajectory_every = 10", "trajectory_every = \"often\"")) ==
          "scene.toml:8:20: 'output.trajectory_every' must be an integer >= 0");
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
    CHECK_THROWS_WITH_AS(load_scene("/nonexistent/scene.toml"), doctest::Contains("cannot open"), scene_error);
}

TEST_CASE("scene: the built-in set parses, quick and full") {
    CHECK(default_scenes(true).size() == 11);
    CHECK(default_scenes(false).size() == 11);
    for (const scene& s : default_scenes(true)) {
        CAPTURE(s.name);
        CHECK(s.dt.size() >= 3);
        CHECK(s.t_end > s.t0);
    }
}
