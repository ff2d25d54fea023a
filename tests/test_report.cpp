// The report on one small scene: the CSV's columns, error falling with dt,
// unstable runs reported as such, and `run` writing only what is asked for.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "report.hpp"
#include "scene.hpp"

using namespace sympl::app;
namespace fs = std::filesystem;

namespace {
std::vector<std::vector<std::string>> read_csv(const fs::path& file) {
    std::ifstream in(file);
    std::vector<std::vector<std::string>> rows;
    std::string line;
    while (std::getline(in, line)) {
        std::vector<std::string> cells;
        std::stringstream s(line);
        std::string cell;
        while (std::getline(s, cell, ',')) cells.push_back(cell);
        if (!line.empty() && line.back() == ',') cells.push_back("");
        rows.push_back(cells);
    }
    return rows;
}
}  // namespace

TEST_CASE("report: one small scene gives the CSV columns and errors that fall with dt") {
    const fs::path dir = fs::temp_directory_path() / "sympl_test_report";
    fs::remove_all(dir);
    const scene s = parse_scene(R"(name = "pendulum"
system = "pendulum"
methods = ["leapfrog_kdk", "blanes_moan_s6", "rk4", "odeint_rk4", "odeint_dopri5"]
dt = {from = 0.2, to = 0.025, count = 4}
tolerances = [1e-4, 1e-8]
t_end = 10
)",
                                "test.toml");
    std::ostringstream out;
    run_report({s}, {dir.string(), true, false, false}, out);
    const auto rows = read_csv(dir / "work_precision.csv");
    REQUIRE(rows.size() == 1 + 4 * 4 + 2);
    CHECK(rows[0] == std::vector<std::string>{"scene", "method", "kind", "dt", "tolerance", "status", "blowup_step",
                                              "blowup_time", "steps", "force_evaluations", "seconds", "max_energy_error",
                                              "final_error", "reference_error"});
    std::map<std::string, std::vector<double>> errors;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        REQUIRE(rows[i].size() == rows[0].size());
        CHECK(rows[i][5] == "stable");
        errors[rows[i][1]].push_back(std::stod(rows[i][12]));
    }
    for (const auto& [method, e] : errors) {
        CAPTURE(method);
        for (std::size_t k = 1; k < e.size(); ++k) CHECK(e[k] < e[k - 1]);  // dt (or the tolerance) falls: so does the error
    }
    // Second order: halving dt divides the leapfrog's error by about 4.
    CHECK(errors["leapfrog_kdk"][2] / errors["leapfrog_kdk"][3] == doctest::Approx(4).epsilon(0.1));
    const std::string summary = (std::stringstream() << std::ifstream(dir / "summary.md").rdbuf()).str();
    CHECK(summary.find("| pendulum | 0.0001 |") != std::string::npos);
    CHECK(out.str().find("pendulum") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("report: an unstable run is reported with its step and time, never as a number") {
    const fs::path dir = fs::temp_directory_path() / "sympl_test_unstable";
    fs::remove_all(dir);
    const scene s = parse_scene(R"(system = "harmonic_oscillator"
parameters = {omega = 10.0}
methods = ["leapfrog_kdk"]
dt = [0.5, 0.1]
t_end = 100
)",
                                "unstable.toml");
    std::ostringstream out;
    run_report({s}, {dir.string(), true, false, false}, out);
    const auto rows = read_csv(dir / "work_precision.csv");
    REQUIRE(rows.size() == 3);
    CHECK(rows[1][5] == "unstable");  // omega dt = 5 > 2
    CHECK(std::stoul(rows[1][6]) > 0);
    CHECK(rows[1][7] != "");
    for (int c : {10, 11, 12}) CHECK(rows[1][c] == "");
    CHECK(rows[2][5] == "stable");  // omega dt = 1
    fs::remove_all(dir);
}

TEST_CASE("run: writes the trajectory it is asked for and nothing else") {
    const fs::path dir = fs::temp_directory_path() / "sympl_test_run";
    fs::remove_all(dir);
    const scene s = parse_scene("system = \"kepler\"\nmethods = [\"blanes_moan_s6\"]\ndt = 0.01\nt_end = 1\n"
                                "[output]\ntrajectory_every = 10\nfinal_state = true\ndirectory = \"" +
                                    dir.string() + "\"\n",
                                "run.toml");
    std::ostringstream out;
    run_scene(s, true, out);
    CHECK(out.str().find("\"method\": \"blanes_moan_s6\", \"status\": \"stable\"") != std::string::npos);
    CHECK(out.str().find("\"steps\": 100") != std::string::npos);
    CHECK(out.str().find("\"final_state\": [") != std::string::npos);
    const auto rows = read_csv(dir / "run.toml_blanes_moan_s6_trajectory.csv");
    CHECK(rows.size() == 1 + 11);  // header, t = 0.0, 0.1, ..., 1.0
    CHECK(rows[0].size() == 5);
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) files += entry.is_regular_file();
    CHECK(files == 1);
    fs::remove_all(dir);
}
