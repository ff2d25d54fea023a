// The report on one small scene: the CSV's columns, error falling with dt,
// unstable runs reported as such, and `run` writing only what is asked for.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "read_csv.hpp"
#include "scratch_directory.hpp"
#include "methods/run_plan.hpp"
#include "report/report.hpp"
#include "report/report_rows.hpp"
#include "report/report_write.hpp"
#include "reading/scene.hpp"
#include "output/writers.hpp"

namespace test_program_test_report {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;
namespace fs = std::filesystem;


TEST_CASE("report: one small scene gives the CSV columns and errors that fall with dt") {
    const fs::path dir = scratch_directory("sympl_test_report");
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
                                              "blowup_time", "steps", "force_evaluations", "seconds", "seconds_min",
                                              "seconds_max", "max_energy_error", "final_error", "reference_error",
                                              "loop_area_error", "path"});
    std::map<std::string, std::vector<double>> errors;
    for (std::size_t i = 1; i < rows.size(); ++i) {
        REQUIRE(rows[i].size() == rows[0].size());
        CHECK(rows[i][5] == "stable");
        errors[rows[i][1]].push_back(std::stod(rows[i][14]));
    }
    for (const auto& row : errors) {  // not a structured binding: CAPTURE takes none before clang 16
        const std::string& method = row.first;
        const std::vector<double>& e = row.second;
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

TEST_CASE("report: runs side by side on threads measure the same numbers as one at a time, and say where time went") {
    // Each run has a system of its own and a reference its two runs on two
    // threads: every measured number (steps, evaluations, errors) must be
    // the same bits whatever the thread count; only the times differ.
    const scene s = parse_scene(R"(name = "pendulum"
system = "pendulum"
methods = ["leapfrog_kdk", "blanes_moan_s6", "dprkn6_controlled", "odeint_dopri5"]
dt = {from = 0.2, to = 0.05, count = 3}
tolerances = [1e-5, 1e-9]
t_end = 30
)",
                                "threads.toml");
    std::map<int, std::vector<std::vector<std::string>>> measured;
    for (int threads : {1, 2}) {
        const fs::path dir = scratch_directory("sympl_test_report_threads_" + std::to_string(threads));
        fs::remove_all(dir);
        report_options o{dir.string(), true, false, false};
        o.threads = threads;
        std::ostringstream out;
        run_report({s}, o, out);
        for (auto row : read_csv(dir / "work_precision.csv")) {
            row.erase(row.begin() + 10, row.begin() + 13);  // seconds, seconds_min, seconds_max
            measured[threads].push_back(row);
        }
        const std::string summary = (std::stringstream() << std::ifstream(dir / "summary.md").rdbuf()).str();
        CHECK(summary.find("phases on " + std::to_string(threads) + " thread") != std::string::npos);
        CHECK(out.str().find("time: references and measured runs ") != std::string::npos);
        fs::remove_all(dir);
    }
    REQUIRE(measured[1].size() == 1 + 2 * 3 + 2 * 2);  // two methods over 3 steps, two over 2 tolerances
    CHECK(measured[1] == measured[2]);
}

TEST_CASE("report: a scene name that closes a quote reaches gnuplot as text, never as a command") {
    // The figures' titles carry the scene's name and the fastest methods'
    // names: inside gnuplot's quotes, so that a name cannot end the string
    // and run `system` (which would hand the rest to a shell).
    const fs::path dir = scratch_directory("sympl_test_report_hostile");
    fs::remove_all(dir);
    const fs::path sentinel = dir.parent_path() / "sympl_test_report_hostile_sentinel";
    fs::remove(sentinel);
    const std::string hostile = "x\" noenhanced; system \"touch " + sentinel.string() + "\"; set title \"y'z";
    const std::string quotes = "\x27\x27\x27";  // a TOML literal string takes the name as it is
    const scene s = parse_scene("name = " + quotes + hostile + quotes + R"(
system = "pendulum"
methods = ["leapfrog_kdk", "odeint_rk4"]
dt = {from = 0.2, to = 0.05, count = 3}
t_end = 10
)",
                                "hostile.toml");
    REQUIRE(s.name == hostile);
    std::ostringstream out;
    run_report({s}, {dir.string(), true, false, true}, out);
    if (have_gnuplot()) {
        const std::string gp = (std::stringstream() << std::ifstream(dir / "work_precision.gp").rdbuf()).str();
        const auto title = gp.find("set title ");
        REQUIRE(title != std::string::npos);
        CHECK(gp.compare(title, 12, "set title 'x") == 0);  // the name opens a single-quoted string
        CHECK(fs::exists(dir / "work_precision.png"));
    }
    CHECK(!fs::exists(sentinel));
    fs::remove(sentinel);
    fs::remove_all(dir);
}

TEST_CASE("report: an unstable run is reported with its step and time, never as a number") {
    const fs::path dir = scratch_directory("sympl_test_unstable");
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
    for (int c : {10, 11, 12, 13, 14}) CHECK(rows[1][c] == "");
    CHECK(rows[2][5] == "stable");  // omega dt = 1
    fs::remove_all(dir);
}

TEST_CASE("report: a method the system cannot run stops everything before anything is written") {
    const fs::path dir = scratch_directory("sympl_test_unsupported");
    fs::remove_all(dir);
    const scene ok = parse_scene("system = \"pendulum\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 1\n", "ok.toml");
    const scene bad = parse_scene("system = \"damped_oscillator\"\nmethods = [\"blanes_2001_p6\"]\ndt = 0.1\nt_end = 1\n",
                                  "bad.toml");
    std::ostringstream out;
    CHECK_THROWS_WITH_AS(run_report({ok, bad}, {dir.string(), true, false, false}, out),
                         "bad.toml: method 'blanes_2001_p6' needs a separable Hamiltonian H = T(p) + V(q); this system "
                         "is not Hamiltonian (use a classic method)",
                         scene_error);
    CHECK_FALSE(fs::exists(dir / "work_precision.csv"));
    fs::remove_all(dir);
}

TEST_CASE("report: the stiff and extreme studies (stability map, Kepler e = 0.99, long run, scales)") {
    const fs::path dir = scratch_directory("sympl_test_studies");
    fs::remove_all(dir);
    const scene s = parse_scene("system = \"harmonic_oscillator\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 1\n",
                                "tiny.toml");
    std::ostringstream out;
    run_report({s}, {dir.string(), true, true, false}, out);
    // Stability: every table is stable up to its computed interval; leapfrog's limit is 2, RK4's 2 sqrt(2).
    const auto stability = read_csv(dir / "stability.csv");
    REQUIRE(stability.size() > 20);
    for (std::size_t i = 1; i < stability.size(); ++i) {
        CAPTURE(stability[i][0]);
        const double theory = std::stod(stability[i][1]), measured = std::stod(stability[i][2]);
        CHECK(measured >= 0.99 * theory);
        if (stability[i][0] == "leapfrog_kdk") CHECK(measured == doctest::Approx(2).epsilon(0.01));
        if (stability[i][0] == "rk4 (classic)") CHECK(measured == doctest::Approx(2 * std::sqrt(2.0)).epsilon(0.01));
        if (stability[i][0] == "leapfrog_kdk") CHECK(std::stod(stability[i][3]) == doctest::Approx(2).epsilon(0.03));
    }
    // Extreme scales: the same relative errors at L = 1e-20, 1 and 1e20.
    const auto scales = read_csv(dir / "extreme_scales.csv");
    REQUIRE(scales.size() >= 4);
    for (int row : {1, 3}) {
        CHECK(std::stod(scales[row][1]) == doctest::Approx(std::stod(scales[2][1])).epsilon(0.02));
        CHECK(std::stod(scales[row][2]) == doctest::Approx(std::stod(scales[2][2])).epsilon(0.02));
    }
    // Long run: compensated summation ends below the plain sum.
    const auto long_run = read_csv(dir / "long_run.csv");
    CHECK(std::stod(long_run.back()[2]) < std::stod(long_run.back()[1]));
    // Kepler e = 0.99: the adaptive Euler-Richardson row is there and finite.
    const auto kepler = read_csv(dir / "kepler_e0.99.csv");
    CHECK(kepler.back()[0] == "adaptive euler_richardson");
    CHECK(std::stod(kepler.back()[4]) < 1e-5);
    fs::remove_all(dir);
}

TEST_CASE("report: a scene with a single dt says so, writes no table, and summary.md lists only its files") {
    const fs::path dir = scratch_directory("sympl_test_single_dt");
    fs::remove_all(dir);
    const scene s = parse_scene("name = \"one\"\nsystem = \"pendulum\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 1\n",
                                "one.toml");
    std::ostringstream out;
    run_report({s}, {dir.string(), true, false, false}, out);
    CHECK(out.str().find("one: a single dt, so no work-precision curve") != std::string::npos);
    CHECK(out.str().find("fastest sympl") == std::string::npos);  // no empty table
    const std::string summary = (std::stringstream() << std::ifstream(dir / "summary.md").rdbuf()).str();
    CHECK(summary.find("a single dt") != std::string::npos);
    const std::string files = summary.substr(summary.find("## Files"));
    for (const char* absent : {"work_precision.png", "energy_long_span", "time_to_accuracy.csv", "stability.csv"}) {
        CAPTURE(absent);
        CHECK(files.find(absent) == std::string::npos);
        CHECK_FALSE(fs::exists(dir / absent));
    }
    CHECK(files.find("work_precision.csv") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("report: every scene its own energy-against-time panel, each panel names its fastest methods") {
    // Two scenes with different methods: each panel of energy_vs_time draws
    // that scene's own fastest symplectic and non-symplectic run, never
    // another scene's methods; the work-precision panels name the fastest
    // sympl and Odeint method in their titles, each curve its own colour.
    const fs::path dir = scratch_directory("sympl_test_energy_panels");
    fs::remove_all(dir);
    const scene pend = parse_scene(R"(name = "pend"
system = "pendulum"
methods = ["blanes_moan_s6", "odeint_rk4"]
dt = {from = 0.2, to = 0.0125, count = 5}
t_end = 20
)",
                                   "pend.toml");
    const scene osc = parse_scene(R"(name = "osc"
system = "harmonic_oscillator"
methods = ["forest_ruth_4", "kahan_li_8", "odeint_dopri5"]
dt = {from = 0.4, to = 0.025, count = 5}
tolerances = [1e-4, 1e-6, 1e-8, 1e-10]
t_end = 20
)",
                                  "osc.toml");
    // Not Hamiltonian: no energy, so no panel, and the summary says why.
    const scene damped = parse_scene(R"(name = "damped"
system = "damped_oscillator"
methods = ["leapfrog_kdk", "odeint_rk4"]
dt = {from = 0.2, to = 0.05, count = 3}
t_end = 20
)",
                                     "damped.toml");
    // A charged particle: the cylindrical splitting is symplectic, Boris's
    // pusher is not (it preserves volume); each on its side of the panel.
    const scene charged = parse_scene(R"toml(name = "charged"
system = "charged_particle"
parameters = {confinement = 0.2}
methods = ["cylindrical_split(blanes_moan_srkn6b)", "boris"]
dt = {from = 0.2, to = 0.0125, count = 5}
t_end = 10
)toml",
                                      "charged.toml");
    std::ostringstream out;
    run_report({pend, damped, osc, charged}, {dir.string(), true, false, true}, out);
    const auto rows = read_csv(dir / "energy_vs_time.csv");
    REQUIRE(rows.size() > 1);
    std::map<std::string, std::set<std::string>> drawn;  // scene -> methods
    for (std::size_t i = 1; i < rows.size(); ++i) drawn[rows[i][0]].insert(rows[i][1]);
    CHECK(drawn["pend"] == std::set<std::string>{"blanes_moan_s6", "odeint_rk4"});
    REQUIRE(drawn["osc"].size() == 2);
    CHECK(drawn["osc"].count("odeint_dopri5") == 1);
    CHECK(drawn["osc"].count("blanes_moan_s6") == 0);
    const std::string summary = (std::stringstream() << std::ifstream(dir / "summary.md").rdbuf()).str();
    const std::string section = summary.substr(summary.find("## Energy error against time"));
    CHECK(section.find("- pend: blanes_moan_s6") != std::string::npos);
    CHECK(section.find("- osc: ") != std::string::npos);
    CHECK(section.find("- No panel: damped (no energy: the system is not Hamiltonian).") != std::string::npos);
    CHECK(drawn.count("damped") == 0);
    CHECK(section.find("- charged: cylindrical_split(blanes_moan_srkn6b), ") != std::string::npos);
    CHECK(drawn["charged"] == std::set<std::string>{"cylindrical_split(blanes_moan_srkn6b)", "boris"});
    if (have_gnuplot()) {
        const std::string gp = (std::stringstream() << std::ifstream(dir / "energy_vs_time.gp").rdbuf()).str();
        CHECK(gp.find("set title 'pend'") != std::string::npos);
        CHECK(gp.find("set title 'osc'") != std::string::npos);
        // Each curve its own block of energy_vs_time.dat, in the CSV's order.
        for (int block = 0; block < 6; ++block)
            CHECK(gp.find("'energy_vs_time.dat' index " + std::to_string(block) + " ") != std::string::npos);
        const std::string dat = (std::stringstream() << std::ifstream(dir / "energy_vs_time.dat").rdbuf()).str();
        std::size_t data_lines = 0;
        for (std::size_t at = 0; (at = dat.find('\n', at)) != std::string::npos; ++at)
            data_lines += at > 0 && dat[at - 1] != '\n';
        CHECK(data_lines == rows.size() - 1);
        CHECK(fs::exists(dir / "energy_vs_time.png"));
        CHECK(section.find("energy_vs_time.png") != std::string::npos);
        const std::string wp = (std::stringstream() << std::ifstream(dir / "work_precision.gp").rdbuf()).str();
        CHECK(wp.find("'fastest at ") != std::string::npos);
        CHECK(wp.find(" (sympl), ") != std::string::npos);
        CHECK(wp.find(" (Odeint)'") != std::string::npos);
        // The oscillator's three curves in three colours.
        const std::string panel = wp.substr(wp.find("set title 'osc'"));
        std::set<std::string> colours;
        for (auto at = panel.find("lc rgb '"); at != std::string::npos; at = panel.find("lc rgb '", at + 1))
            colours.insert(panel.substr(at + 8, 7));
        CHECK(colours.size() == 3);
        CHECK(fs::exists(dir / "work_precision.png"));
        CHECK(fs::exists(dir / "energy_precision.png"));
    }
    fs::remove_all(dir);
}

TEST_CASE("report: two measures side by side, a pick per level, order-one runs flagged and left out") {
    const fs::path dir = scratch_directory("sympl_test_measures");
    fs::remove_all(dir);
    // Kepler e = 0.5 over 2 orbits: dt = 5 throws the leapfrog off the orbit (error of order one).
    const scene s = parse_scene(R"(name = "kep"
system = "kepler"
methods = ["leapfrog_kdk", "blanes_moan_s6", "odeint_dopri5"]
dt = [5.0, 0.05, 0.02, 0.01]
tolerances = [1e-6, 1e-9]
t_end = 12.566370614359172
)",
                                "kep.toml");
    std::ostringstream out;
    run_report({s}, {dir.string(), true, false, false}, out);
    const std::string summary = (std::stringstream() << std::ifstream(dir / "summary.md").rdbuf()).str();
    CHECK(summary.find("## Fastest method per final error") != std::string::npos);
    CHECK(summary.find("## Fastest method per max energy error") != std::string::npos);
    CHECK(summary.find("| pick |") != std::string::npos);
    CHECK(summary.find("reached an error of order one") != std::string::npos);
    CHECK(summary.find("(order_one_runs.csv lists them)") != std::string::npos);
    const auto flagged = read_csv(dir / "order_one_runs.csv");
    REQUIRE(flagged.size() >= 2);
    CHECK(flagged[0] == std::vector<std::string>{"scene", "method", "dt", "tolerance", "final_error", "max_energy_error"});
    CHECK(flagged[1][0] == "kep");
    CHECK(flagged[1][1] == "leapfrog_kdk");
    CHECK(flagged[1][2] == "5");
    CHECK(std::stod(flagged[1][4]) >= 0.1);
    CHECK(out.str().find("max energy error:") != std::string::npos);
    const auto rows = read_csv(dir / "time_to_accuracy.csv");
    REQUIRE(rows.size() > 1);
    CHECK(rows[0][1] == "measure");
    for (std::size_t i = 1; i < rows.size(); ++i) CHECK(rows[i][4] != "");
    fs::remove_all(dir);
}

}  // namespace test_program_test_report

namespace test_program_test_report {

// Rows with set times and errors: each method's error falls as dt^2 and its
// time grows as 1/dt, scaled by the method's `cost`; the timing rounds spread
// by the factor 1 -+ `spread` about it.
std::string summary_of_costs(const std::map<std::string, double>& cost, const fs::path& dir, double spread = 0) {
    const scene s = parse_scene(R"(name = "osc"
system = "harmonic_oscillator"
methods = ["leapfrog_kdk", "leapfrog_dkd", "odeint_rk4"]
dt = [0.1, 0.01, 0.001]
t_end = 1
)",
                                "osc.toml");
    std::vector<runnable_system> systems{system_of(s)};
    std::vector<run_plan> plans{plan_runs(s, systems[0], sweep_use::whole)};
    std::vector<report_row> rows = rows_of(plans, systems);
    for (report_row& r : rows) {
        r.r.stable = true;
        r.final_error = r.run->dt * r.run->dt;
        r.r.max_energy_error = r.final_error;
        r.r.seconds = cost.at(r.method().name) / r.run->dt;
        r.r.seconds_min = r.r.seconds * (1 - spread);
        r.r.seconds_max = r.r.seconds * (1 + spread);
    }
    std::ostringstream md, table;
    fs::create_directories(dir);
    fastest_per_level(rows, plans, md, table, dir);
    return md.str();
}

TEST_CASE("report: times within 5% or with overlapping rounds are named as a tie, others as a pick") {
    const fs::path dir = scratch_directory("sympl_test_ties");
    fs::remove_all(dir);
    // 1e-4 is reached at dt = 1e-2 by all three: times 100 cost.
    const std::string tie = summary_of_costs({{"leapfrog_kdk", 1.0}, {"leapfrog_dkd", 1.04}, {"odeint_rk4", 1.5}}, dir);
    CHECK(tie.find("| osc | 0.0001 | leapfrog_kdk ~ leapfrog_dkd |") != std::string::npos);
    // The pick names every method within 5% of the fastest, of either group: Odeint's, 1.5x, is not one.
    CHECK(tie.find("| leapfrog_kdk ~ leapfrog_dkd |\n") != std::string::npos);
    CHECK(tie.find("A ~ B: a tie, either may come first in another run") != std::string::npos);
    const std::string apart = summary_of_costs({{"leapfrog_kdk", 1.0}, {"leapfrog_dkd", 1.1}, {"odeint_rk4", 1.04}}, dir);
    CHECK(apart.find("| osc | 0.0001 | leapfrog_kdk |") != std::string::npos);
    CHECK(apart.find("| leapfrog_kdk ~ odeint_rk4 |\n") != std::string::npos);  // sympl against Odeint, 4% apart
    const std::string none = summary_of_costs({{"leapfrog_kdk", 1.0}, {"leapfrog_dkd", 1.1}, {"odeint_rk4", 1.5}}, dir);
    CHECK(none.find(" ~ ") == std::string::npos);
    CHECK(none.find("A ~ B") == std::string::npos);
    // 10% apart, but the timing rounds spread by 6% each way: they overlap, a tie.
    const std::string noisy = summary_of_costs({{"leapfrog_kdk", 1.0}, {"leapfrog_dkd", 1.1}, {"odeint_rk4", 1.5}}, dir, 0.06);
    CHECK(noisy.find("| osc | 0.0001 | leapfrog_kdk ~ leapfrog_dkd |") != std::string::npos);
    CHECK(noisy.find("| leapfrog_kdk ~ leapfrog_dkd |\n") != std::string::npos);
    const std::string quiet = summary_of_costs({{"leapfrog_kdk", 1.0}, {"leapfrog_dkd", 1.1}, {"odeint_rk4", 1.5}}, dir, 0.04);
    CHECK(quiet.find(" ~ ") == std::string::npos);
    fs::remove_all(dir);
}

}  // namespace test_program_test_report
