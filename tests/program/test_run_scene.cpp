// `sympl run`: one scene, the outputs it asks for and nothing else, JSON that a parser reads.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "read_csv.hpp"
#include "scratch_directory.hpp"
#include "run_plan.hpp"
#include "run_scene.hpp"

namespace test_program_test_run_scene {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;
namespace fs = std::filesystem;

namespace {
// `sympl run --json` of a scene given as text.
nlohmann::json run_json(const std::string& text, const std::string& source) {
    std::ostringstream out;
    run_scene(parse_scene(text, source), true, out);
    return nlohmann::json::parse(out.str());
}
}  // namespace

TEST_CASE("run: writes the trajectory it is asked for and nothing else") {
    const fs::path dir = scratch_directory("sympl_test_run");
    fs::remove_all(dir);
    const scene s = parse_scene("system = \"kepler\"\nmethods = [\"blanes_moan_s6\"]\ndt = 0.01\nt_end = 1\n"
                                "[output]\ntrajectory_every = 10\nfinal_state = true\ndirectory = \"" +
                                    dir.string() + "\"\n",
                                "run.toml");
    std::ostringstream out;
    run_scene(s, true, out);
    const auto json = nlohmann::json::parse(out.str());
    REQUIRE(json.size() == 1);
    CHECK(json[0]["method"] == "blanes_moan_s6");
    CHECK(json[0]["status"] == "stable");
    CHECK(json[0]["steps"] == 100);
    CHECK(json[0]["final_state"].size() == 4);
    CHECK_FALSE(json[0].contains("loop_area_error"));  // not asked for: not computed
    const auto rows = read_csv(dir / "run.toml_blanes_moan_s6_trajectory.csv");
    CHECK(rows.size() == 1 + 11);  // header, t = 0.0, 0.1, ..., 1.0
    CHECK(rows[0].size() == 5);
    // The trajectory, and the (hidden) lock that keeps a second run out; no staging left.
    std::size_t files = 0, entries = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        files += entry.is_regular_file() && entry.path().filename() != ".sympl.lock";
        ++entries;
    }
    CHECK(files == 1);
    CHECK(entries == 2);
    fs::remove_all(dir);
}

TEST_CASE("run: the loop area a scene asks for: kept by a symplectic table, lost by RK4 at a coarse step") {
    const auto json = run_json("system = \"pendulum\"\nmethods = [\"leapfrog_kdk\", \"rk4\"]\ndt = 0.5\nt_end = 200\n"
                               "[output]\nloop_area = true\nenergy_error = false\n",
                               "area.toml");
    REQUIRE(json.size() == 2);
    const double leapfrog = json[0]["loop_area_error"], rk4 = json[1]["loop_area_error"];
    CHECK(leapfrog < 2e-3);      // within the polygon's resolution (max_gap r/16)
    CHECK(rk4 > 10 * leapfrog);  // RK4 at dt = 0.5 loses area
    CHECK_FALSE(json[0].contains("max_energy_error"));
}

TEST_CASE("run: a method the system cannot run is refused before anything runs") {
    const scene two_step =
        parse_scene("system = \"pendulum\"\nmethods = [\"leapfrog_two_step\"]\ndt = 0.1\nt_end = 1\n", "two.toml");
    std::ostringstream out;
    CHECK_THROWS_WITH_AS(run_scene(two_step, false, out), doctest::Contains("needs Newton's form"), scene_error);
    CHECK(out.str().empty());
}

TEST_CASE("run: names with quotes, commas and line breaks stay inside their JSON strings") {
    const fs::path dir = scratch_directory("sympl_test_run_names");
    fs::remove_all(dir);
    const scene s = parse_scene("name = \"a \\\"quoted\\\", name\\nwith a break\"\nsystem = \"harmonic_oscillator\"\n"
                                "methods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 1\n[output]\ndirectory = \"" + dir.string() + "\"\n",
                                "names.toml");
    std::ostringstream out;
    run_scene(s, true, out);
    const auto json = nlohmann::json::parse(out.str());
    CHECK(json[0]["scene"] == "a \"quoted\", name\nwith a break");
    fs::remove_all(dir);
}

TEST_CASE("run: a reference that blows up is reported as the reference's failure, and the methods still run") {
    // Stiff FPU at dt = 0.5: the long-double reference at dt = 0.125 and 0.25 blows up.
    const auto json = run_json("system = \"stiff_fpu\"\nmethods = [\"leapfrog_kdk\", \"odeint_dopri5\"]\ndt = 0.5\n"
                               "t_end = 10\n",
                               "stiff.toml");
    REQUIRE(json.size() == 2);
    CHECK(json[0]["reference_failure"].get<std::string>().find("the reference (sofroniou_spaletta_10, long double, "
                                                               "dt = 0.125") == 0);
    CHECK_FALSE(json[0].contains("final_error"));
    CHECK(json[1]["status"] == "stable");  // dopri5 adapts its step: its run and energy error are reported
    CHECK(json[1].contains("max_energy_error"));
    CHECK_FALSE(json[1].contains("final_error"));
}

TEST_CASE("run: the trajectory of a run that blows up ends with a line that says so") {
    const fs::path dir = scratch_directory("sympl_test_run_truncated");
    fs::remove_all(dir);
    const scene s = parse_scene("name = \"t\"\nsystem = \"harmonic_oscillator\"\nparameters = {omega = 10}\n"
                                "methods = [\"leapfrog_kdk\"]\ndt = 0.3\nt_end = 100\n[output]\ntrajectory_every = 1\n"
                                "directory = \"" + dir.string() + "\"\n",
                                "t.toml");
    std::ostringstream out;
    run_scene(s, false, out);
    CHECK(out.str().find("UNSTABLE") != std::string::npos);
    std::ifstream in(dir / "t_leapfrog_kdk_trajectory.csv");
    std::string line, last;
    while (std::getline(in, line)) last = line;
    CHECK(last.rfind("# truncated: the run diverged", 0) == 0);
    fs::remove_all(dir);
}

TEST_CASE("run: a sweep runs its first (largest) value, says so, and the impossible tail is left to the report") {
    // dt from 0.1 down to 1e-320: `sympl run` takes 0.1 (10 steps) and says it
    // runs the first value; the report would refuse the tail with the figures.
    const scene s = parse_scene("system = \"harmonic_oscillator\"\nmethods = [\"leapfrog_kdk\"]\n"
                                "dt = {from = 0.1, to = 1e-320, count = 5}\nt_end = 1\n",
                                "sweep.toml");
    std::ostringstream text;
    run_scene(s, false, text);
    CHECK(text.str().find("(a sweep: each method runs its first, largest, value; `sympl report` runs them all)") !=
          std::string::npos);
    std::ostringstream json;
    run_scene(s, true, json);
    CHECK(nlohmann::json::parse(json.str())[0]["steps"] == 10);
    const problem p = problem_of(s);
    CHECK_THROWS_WITH_AS(check_run_size(plan_runs(s, p, sweep_use::whole), default_max_steps),
                         doctest::Contains("method 'leapfrog_kdk' at dt = "), scene_error);
    // One value: nothing to say.
    std::ostringstream single;
    run_scene(parse_scene("system = \"harmonic_oscillator\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 1\n",
                          "one.toml"),
              false, single);
    CHECK(single.str().find("a sweep") == std::string::npos);
}

}  // namespace test_program_test_run_scene
