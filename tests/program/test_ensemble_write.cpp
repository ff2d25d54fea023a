// An ensemble's CSV names its columns as the run's trajectory does: q1..qn,
// p1..pn, or the bodies' names where the system has them (issue: one
// numbering everywhere, bodies named in planetary outputs); its states file
// is read with the same header.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sympl/core/error.hpp>

#include "commands/ensemble_run.hpp"
#include "output/format.hpp"
#include "running/runnable_system.hpp"
#include "methods/run_plan.hpp"
#include "reading/scene.hpp"
#include "scratch_directory.hpp"
#include "running/systems.hpp"

namespace test_program_test_ensemble_write {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;
namespace fs = std::filesystem;

namespace {
std::string first_line(const fs::path& file) {
    std::ifstream in(file);
    std::string line;
    std::getline(in, line);
    return line;
}

std::string joined(const std::vector<std::string>& names, const std::string& suffix) {
    std::string text;
    for (const auto& n : names) text += "," + n + suffix;
    return text;
}
}  // namespace

TEST_CASE("ensemble.csv: the planets' columns carry the bodies' names, read back from a states file") {
    const fs::path dir = scratch_directory("sympl_test_ensemble_write");
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string head = "name = \"belt\"\nsystem = \"outer_solar_system\"\nmethods = [\"leapfrog_kdk\"]\n"
                             "dt = 50\nt_end = 500\n";
    const runnable_system planets = system_of(parse_scene(head, "planets.toml"));
    const std::vector<std::string> columns = state_columns("outer_solar_system", planets.degrees_of_freedom);
    REQUIRE(columns.size() == 36);
    CHECK(columns[3] == "jupiter_x");
    CHECK(columns[18 + 5] == "jupiter_pz");
    // Two starts: the default state and one with Jupiter's momentum 1e-3 larger.
    {
        std::ofstream states(dir / "starts.csv");
        std::string header;
        for (const auto& c : columns) header += (header.empty() ? "" : ",") + c;
        states << header << '\n';
        for (double scale : {1.0, 1.001}) {
            for (std::size_t i = 0; i < planets.x0.size(); ++i) {
                const double v = (i >= 21 && i < 24) ? planets.x0[i] * scale : planets.x0[i];
                states << (i ? "," : "") << shortest(v);
            }
            states << '\n';
        }
    }
    const scene s = parse_scene(head + "[ensemble]\nstates = \"" + (dir / "starts.csv").string() + "\"\n",
                                (dir / "belt.toml").string());
    std::ostringstream ignored;
    ensemble_command(s, (dir / "out").string(), 1, default_max_steps, exchange{}, ignored);
    const std::string header = first_line(dir / "out" / "ensemble.csv");
    CHECK(header.find(joined(columns, "_0")) != std::string::npos);
    CHECK(header.find(joined(columns, "_final")) != std::string::npos);
    CHECK(header.find("q1") == std::string::npos);

    // The numbered header is not this system's: refused, naming the one expected.
    {
        std::ofstream states(dir / "numbered.csv");
        states << "q1,q2\n0,0\n";
    }
    const scene numbered = parse_scene(head + "[ensemble]\nstates = \"" + (dir / "numbered.csv").string() + "\"\n",
                                       (dir / "belt.toml").string());
    CHECK_THROWS_WITH_AS(ensemble_command(numbered, (dir / "out2").string(), 1, default_max_steps, exchange{}, ignored),
                         doctest::Contains("header 'q1,q2'; expected 'sun_x,sun_y,sun_z,jupiter_x"), sympl::error);
    fs::remove_all(dir);
}

TEST_CASE("ensemble.csv: a system without names numbers its columns from 1") {
    const fs::path dir = scratch_directory("sympl_test_ensemble_numbered");
    fs::remove_all(dir);
    const scene s = parse_scene("name = \"grid\"\nsystem = \"kepler\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.05\n"
                                "t_end = 5\n[ensemble]\ngrid = {eccentricity = {from = 0.1, to = 0.5, count = 3}}\n",
                                "grid.toml");
    std::ostringstream ignored;
    ensemble_command(s, dir.string(), 1, default_max_steps, exchange{}, ignored);
    const std::string header = first_line(dir / "ensemble.csv");
    CHECK(header.find(",q1_final,q2_final,p1_final,p2_final,") != std::string::npos);
    fs::remove_all(dir);
}

}  // namespace test_program_test_ensemble_write
