// `sympl run`: one scene, the outputs it asks for and nothing else, JSON that a parser reads.
#include <doctest/doctest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "read_csv.hpp"
#include "scratch_directory.hpp"
#include "run_scene.hpp"

using namespace sympl::app;
namespace fs = std::filesystem;

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
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
    CHECK(files == 1);
    fs::remove_all(dir);
}

TEST_CASE("run: the loop area a scene asks for: kept by a symplectic table, lost by RK4 at a coarse step") {
    const scene s = parse_scene("system = \"pendulum\"\nmethods = [\"leapfrog_kdk\", \"rk4\"]\ndt = 0.5\nt_end = 200\n"
                                "[output]\nloop_area = true\nenergy_error = false\n",
                                "area.toml");
    std::ostringstream out;
    run_scene(s, true, out);
    const auto json = nlohmann::json::parse(out.str());
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
