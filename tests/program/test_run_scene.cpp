// `sympl run`: one scene, the outputs it asks for and nothing else, JSON that a parser reads.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "read_csv.hpp"
#include "scratch_directory.hpp"
#include "methods/run_plan.hpp"
#include "commands/run_scene.hpp"

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

TEST_CASE("run: the loop area of a checkpointed run: its loop's runs neither save nor resume the run's checkpoint") {
    const fs::path dir = scratch_directory("sympl_test_run_area_checkpoint");
    fs::remove_all(dir);
    const std::string text = "system = \"pendulum\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.5\nt_end = 200\n"
                             "checkpoint = {every_steps = 100, file = \"" + (dir / "state" / "area").string() +
                             "\"}\n[output]\nloop_area = true\n";
    const auto plain = run_json("system = \"pendulum\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.5\nt_end = 200\n"
                                "[output]\nloop_area = true\n",
                                "area.toml");
    const auto checkpointed = run_json(text, "area.toml");
    CHECK(checkpointed[0]["loop_area_error"] == plain[0]["loop_area_error"]);
    CHECK(checkpointed[0]["max_energy_error"] == plain[0]["max_energy_error"]);
    CHECK(fs::is_empty(dir / "state"));  // the complete run's checkpoint removed, no loop run's left
    fs::remove_all(dir);
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
                               "t_end = 10\n[output]\nfinal_error = true\n",
                               "stiff.toml");
    REQUIRE(json.size() == 2);
    CHECK(json[0]["reference_failure"].get<std::string>().find("the reference (sofroniou_spaletta_10, long double, "
                                                               "dt = 0.125") == 0);
    CHECK_FALSE(json[0].contains("final_error"));
    CHECK(json[1]["status"] == "stable");  // dopri5 adapts its step: its run and energy error are reported
    CHECK(json[1].contains("max_energy_error"));
    CHECK_FALSE(json[1].contains("final_error"));
}

namespace {
// The oscillator at omega dt = 3, unstable: it blows up within its first
// steps. `output` holds the [output] table's keys beside directory = dir.
scene unstable_oscillator(const std::string& name, const std::string& t_end, const std::string& output,
                          const fs::path& dir) {
    return parse_scene("name = \"" + name + "\"\nsystem = \"harmonic_oscillator\"\nparameters = {omega = 10}\n"
                       "methods = [\"leapfrog_kdk\"]\ndt = 0.3\nt_end = " + t_end + "\n[output]\n" + output +
                           "directory = \"" + dir.string() + "\"\n",
                       name + ".toml");
}
}  // namespace

TEST_CASE("run: files that would not fit on their file system are refused before anything runs") {
    // 1e12 steps, a trajectory row and an energy row each: about 1e14 bytes,
    // more than any disk of a machine that runs the tests has free. The
    // oscillator at omega dt = 3 is unstable: should the disk check not run,
    // the run blows up within its first steps and returns, and the test fails
    // at once instead of running 1e12 steps.
    const fs::path dir = scratch_directory("sympl_test_run_disk");
    fs::remove_all(dir);
    const scene s = unstable_oscillator("d", "3e11", "trajectory_every = 1\nenergy_every = 1\n", dir / "out");
    std::ostringstream out;
    try {
        run_scene(s, false, out, 1e13);
        FAIL("a run of 1e14 bytes of files was not refused");
    } catch (const scene_error& e) {
        const std::string message = e.what();
        CAPTURE(message);
        CHECK(message.find("d.toml: the run's files would take about 1e+05 GB (1e+12 trajectory rows of 3 numbers, "
                           "1e+12 energy rows") == 0);
        CHECK(message.find("output.directory's file system (") != std::string::npos);
        CHECK(message.find("GB free; expected fewer rows (a larger output.trajectory_every or output.energy_every)") !=
              std::string::npos);
    }
    CHECK_FALSE(fs::exists(dir));  // nothing made
    CHECK(out.str().empty());
}

TEST_CASE("run: the disk a run's files take, counted per file system") {
    // 1e4 steps of the pendulum (3 numbers a row), a trajectory row each, at
    // 20 bytes a number: 600,060 bytes in the output directory, and once
    // more beside the checkpoint.
    const auto scene_with = [](const std::string& method, const std::string& more) {
        return parse_scene("name = \"d\"\nsystem = \"pendulum\"\nmethods = [\"" + method +
                               "\"]\ndt = 0.125\nt_end = 1250\n" + more + "[output]\ntrajectory_every = 1\n",
                           "d.toml");
    };
    const scene plain = scene_with("leapfrog_kdk", "");
    const runnable_system p = system_of(plain);
    const output_disk_use u = disk_use_of(plain, plan_runs(plain, p, sweep_use::first), p);
    CHECK(u.trajectory_rows == 10001);
    CHECK(u.columns == 3);
    REQUIRE(u.places.size() == 1);
    CHECK(u.places[0].bytes == 10001 * 3 * 20);
    // An extrapolated method writes a row per outer step, whatever its inner ones.
    const scene extrapolated = scene_with("extrapolated(leapfrog_kdk, 4)", "");
    CHECK(disk_use_of(extrapolated, plan_runs(extrapolated, p, sweep_use::first), p).trajectory_rows == 10001);
    // With a checkpoint: two places, on one device or two.
    const scene checkpointed = scene_with("leapfrog_kdk", "checkpoint = {every_steps = 100, file = \"state/run\"}\n");
    const output_disk_use both = disk_use_of(checkpointed, plan_runs(checkpointed, p, sweep_use::first), p);
    REQUIRE(both.places.size() == 2);
    CHECK(both.places[1].key == "checkpoint.file");
    const double one = 10001 * 3 * 20;
    const auto device = [](std::uint64_t d, double available) {
        return [=](const fs::path&) { return free_space{.known = true, .device = d, .available = available}; };
    };
    CHECK_NOTHROW(check_disk_use(checkpointed, both, device(7, 2 * one), 0));
    CHECK_THROWS_WITH_AS(check_disk_use(checkpointed, both, device(7, 2 * one - 1), 0),
                         doctest::Contains("the run's files would take about 0.0012 GB"), scene_error);
    CHECK_NOTHROW(check_disk_use(checkpointed, both, device(7, 2 * one - 1), 1));  // 1 byte written before
    CHECK_THROWS_AS(check_disk_use(checkpointed, both, device(7, 2 * one - 2), 1), scene_error);  // taken off once
    // On two devices each place counts alone; what the checkpoint's
    // trajectory holds already is taken off its own place only.
    int asked = 0;
    const auto two_devices = [&](double output_free) {
        asked = 0;
        return [&asked, output_free, one](const fs::path&) {
            const bool output = asked++ == 0;  // the places are asked in order: output, checkpoint
            return free_space{
                .known = true, .device = std::uint64_t(output ? 1 : 2), .available = output ? output_free : one};
        };
    };
    CHECK_NOTHROW(check_disk_use(checkpointed, both, two_devices(one), 0));
    CHECK_THROWS_WITH_AS(check_disk_use(checkpointed, both, two_devices(one - 1), 5),
                         doctest::Contains("where output.directory's file system"), scene_error);
    CHECK_NOTHROW(check_disk_use(checkpointed, both, [](const fs::path&) { return free_space{}; }, 0));
}

TEST_CASE("run: the trajectory of a run that blows up ends with a line that says so") {
    const fs::path dir = scratch_directory("sympl_test_run_truncated");
    fs::remove_all(dir);
    const scene s = unstable_oscillator("t", "100", "trajectory_every = 1\n", dir);
    std::ostringstream out;
    run_scene(s, false, out);
    CHECK(out.str().find("UNSTABLE") != std::string::npos);
    std::ifstream in(dir / "t_leapfrog_kdk_trajectory.csv");
    std::string line, last;
    while (std::getline(in, line)) last = line;
    CHECK(last.rfind("# truncated: the run diverged", 0) == 0);
    fs::remove_all(dir);
}

TEST_CASE("run: a checkpoint's trajectory is never written through a symlink planted in its place") {
    const fs::path dir = scratch_directory("sympl_test_run_planted");
    fs::remove_all(dir);
    fs::create_directories(dir / "state");
    {
        std::ofstream(dir / "victim.txt") << "the user's file\n";
    }
    fs::create_symlink(dir / "victim.txt", dir / "state" / "run.leapfrog_kdk.trajectory");
    const scene s = parse_scene("name = \"run\"\nsystem = \"harmonic_oscillator\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.01\n"
                                "t_end = 10\ncheckpoint = {every_steps = 100, file = \"" +
                                    (dir / "state" / "run").string() + "\"}\n[output]\ntrajectory_every = 10\n"
                                    "directory = \"" + (dir / "out").string() + "\"\n",
                                "planted.toml");
    std::ostringstream out;
    const std::string refusal = "planted.toml: checkpoint trajectory " +
                                (dir / "state" / "run.leapfrog_kdk.trajectory").string() +
                                " is a symlink; expected a file this program made there (or none)";
    CHECK_THROWS_WITH_AS(run_scene(s, false, out), doctest::Contains(refusal.c_str()), std::exception);
    std::ifstream victim(dir / "victim.txt");
    std::string text((std::istreambuf_iterator<char>(victim)), std::istreambuf_iterator<char>());
    CHECK(text == "the user's file\n");
    CHECK_FALSE(fs::exists(dir / "out"));  // refused before anything ran
    // Without it the run writes its own file there, and removes it when complete.
    fs::remove(dir / "state" / "run.leapfrog_kdk.trajectory");
    run_scene(s, false, out);
    CHECK(fs::exists(dir / "out" / "run_leapfrog_kdk_trajectory.csv"));
    CHECK(fs::is_empty(dir / "state"));
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
    CHECK(text.str().find("(a sweep: leapfrog_kdk runs its first, largest, dt here; `sympl report` runs them all)") !=
          std::string::npos);
    std::ostringstream json;
    run_scene(s, true, json);
    CHECK(nlohmann::json::parse(json.str())[0]["steps"] == 10);
    const runnable_system p = system_of(s);
    CHECK_THROWS_WITH_AS(check_run_size(plan_runs(s, p, sweep_use::whole), default_max_steps),
                         doctest::Contains("method 'leapfrog_kdk' at dt = "), scene_error);
    // One value: nothing to say.
    std::ostringstream single;
    run_scene(parse_scene("system = \"harmonic_oscillator\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\nt_end = 1\n",
                          "one.toml"),
              false, single);
    CHECK(single.str().find("a sweep") == std::string::npos);
}

namespace {
// The rows (t, q, p) of `sympl run` of sofroniou_spaletta_10 (order 10: its
// own error is far below the interpolation's) on `system` at step dt to
// t = 10, with the [output] line `rows`.
std::vector<std::vector<double>> rows_of(const std::string& system, double dt, const std::string& rows) {
    const fs::path dir = scratch_directory("sympl_test_run_times");
    fs::remove_all(dir);
    const scene s = parse_scene("name = \"r\"\nsystem = \"" + system + "\"\nmethods = [\"sofroniou_spaletta_10\"]\n" +
                                    "dt = " + std::to_string(dt) + "\nt_end = 10\n[output]\n" + rows +
                                    "\ndirectory = \"" + dir.string() + "\"\n",
                                "r.toml");
    std::ostringstream out;
    run_scene(s, false, out);
    std::vector<std::vector<double>> numbers;
    const auto csv = read_csv(dir / "r_sofroniou_spaletta_10_trajectory.csv");
    for (std::size_t i = 1; i < csv.size(); ++i) {
        numbers.emplace_back();
        for (const std::string& field : csv[i]) numbers.back().push_back(std::stod(field));
    }
    fs::remove_all(dir);
    return numbers;
}

// Largest deviation of the rows at times 0.013 + 0.011 i (inside the steps of
// dt) from a run at dt = 0.001 whose step ends hold those times, in q and in p.
std::pair<double, double> interpolation_error(const std::string& system, double dt) {
    const auto rows = rows_of(system, dt, "times = {from = 0.013, to = 9.913, count = 901}");
    const auto reference = rows_of(system, 0.001, "trajectory_every = 1");
    REQUIRE(rows.size() == 901);
    REQUIRE(reference.size() == 10001);
    const std::size_t n = (rows[0].size() - 1) / 2;
    double q = 0, p = 0;
    for (const auto& row : rows) {
        const auto& exact = reference[std::size_t(std::lround(row[0] / 0.001))];
        REQUIRE(std::fabs(exact[0] - row[0]) < 1e-12);
        for (std::size_t k = 1; k <= n; ++k) q = std::max(q, std::fabs(row[k] - exact[k]));
        for (std::size_t k = n + 1; k <= 2 * n; ++k) p = std::max(p, std::fabs(row[k] - exact[k]));
    }
    return {q, p};
}
}  // namespace

TEST_CASE("run: output times are read off each step's interpolant at its order, the run stepping as without them") {
    // T = p^2/2: the quintic Hermite in q, O(dt^6), and its derivative in p, O(dt^5).
    const auto [q1, p1] = interpolation_error("pendulum", 0.2);
    const auto [q2, p2] = interpolation_error("pendulum", 0.1);
    MESSAGE("pendulum, dt 0.2 -> 0.1: q error " << q1 << " -> " << q2 << ", p error " << p1 << " -> " << p2);
    CHECK(std::fabs(std::log2(q1 / q2) - 6) < 0.15);
    CHECK(std::fabs(std::log2(p1 / p2) - 5) < 0.15);
    // T not quadratic: the cubic Hermite in both, O(dt^4).
    const auto [rq1, rp1] = interpolation_error("relativistic_pendulum", 0.2);
    const auto [rq2, rp2] = interpolation_error("relativistic_pendulum", 0.1);
    MESSAGE("relativistic pendulum: q error " << rq1 << " -> " << rq2 << ", p error " << rp1 << " -> " << rp2);
    CHECK(std::fabs(std::log2(rq1 / rq2) - 4) < 0.15);
    CHECK(std::fabs(std::log2(rp1 / rp2) - 4) < 0.15);

    // The run itself: the same final state and energy error, to the last bit,
    // as without output; a time on a step end is that step's state itself.
    const auto json_of = [](const std::string& output) {
        const scene s = parse_scene("system = \"kepler\"\nmethods = [\"blanes_moan_s6\"]\ndt = 0.01\nt_end = 3\n"
                                    "[output]\nfinal_state = true\ndirectory = \"" +
                                        scratch_directory("sympl_test_run_times_kepler").string() + "\"\n" + output,
                                    "k.toml");
        std::ostringstream out;
        run_scene(s, true, out);
        return nlohmann::json::parse(out.str())[0];
    };
    const auto plain = json_of("");
    const auto timed = json_of("times = {from = 0.0003, to = 2.9997, count = 577}");
    CHECK(timed["final_state"] == plain["final_state"]);
    CHECK(timed["max_energy_error"] == plain["max_energy_error"]);
    CHECK(timed["steps"] == plain["steps"]);
    CHECK(timed["force_evaluations"] == plain["force_evaluations"]);
    fs::remove_all(scratch_directory("sympl_test_run_times_kepler"));
    const auto on_ends = rows_of("pendulum", 0.25, "times = [0, 0.25, 5, 10]");
    const auto every = rows_of("pendulum", 0.25, "trajectory_every = 20");
    REQUIRE(on_ends.size() == 4);
    REQUIRE(every.size() == 3);
    CHECK(on_ends[0] == every[0]);
    CHECK(on_ends[2] == every[1]);
    CHECK(on_ends[3] == every[2]);
}

namespace {
// An observed, untimed run at step dt writing the rows of the scene's output
// times (quintic: the systems here have T = p^2/2) to `rows`.
run_request timed_rows_request(const scene& s, double dt, std::ostringstream& rows) {
    run_request rq;
    rq.dt = dt;
    rq.energy = true;
    rq.timing_repeats = 0;
    rq.output_times = s.output.times;
    rq.output_order = 5;
    rows << std::setprecision(17);
    rq.trajectory = &rows;
    return rq;
}
}  // namespace

TEST_CASE("run: an output time at t_end gets its row though the last step's time is a rounding below it") {
    // 3 * 0.3 = 0.8999999999999999: the steps end a hair before t_end = 0.9,
    // and the run ends there (no step of 1e-16 is taken).
    REQUIRE(0.0 + 3 * 0.3 < 0.9);
    const scene s = parse_scene("system = \"pendulum\"\nmethods = [\"leapfrog_kdk\", \"odeint_rk4\"]\ndt = 0.3\n"
                                "t_end = 0.9\n[output]\ntimes = [0, 0.45, 0.9]\n",
                                "end.toml");
    const runnable_system p = system_of(s);
    for (const scene_method& m : s.methods) {
        CAPTURE(m.name);
        std::ostringstream rows;
        const run_request rq = timed_rows_request(s, 0.3, rows);
        const run_result r = p.run(m, rq, s.t0, s.t_end, p.x0);
        REQUIRE(r.stable);
        CHECK(r.steps == 3);
        std::istringstream lines(rows.str());
        std::vector<std::string> all;
        for (std::string line; std::getline(lines, line);) all.push_back(line);
        REQUIRE(all.size() == 3);
        std::ostringstream last;
        last << std::setprecision(17) << 0.9 << ',' << r.final_state[0] << ',' << r.final_state[1];
        CHECK(all[2] == last.str());
    }
}

TEST_CASE("run: output times of a controlled RKN pair are its own interpolation's, within 10x the tolerance") {
    // The Hermite interpolant on dprkn12's long steps was 1e5x the tolerance
    // off; the pair's own (a continuous extension, or a partial step) is as
    // good as its steps. Rows at 0.013 + 0.011 i against a run of
    // sofroniou_spaletta_10 at dt = 0.001 whose step ends hold those times.
    const scene s = parse_scene("system = \"pendulum\"\nmethods = [\"dprkn6_controlled\", \"dprkn8_controlled\", "
                                "\"dprkn12_controlled\"]\ndt = 0.1\nt_end = 10\n[output]\n"
                                "times = {from = 0.013, to = 9.913, count = 901}\n",
                                "dense.toml");
    const runnable_system p = system_of(s);
    const auto reference = rows_of("pendulum", 0.001, "trajectory_every = 1");
    REQUIRE(reference.size() == 10001);
    for (const double tolerance : {1e-8, 1e-10}) {
        for (const scene_method& m : s.methods) {
            CAPTURE(m.name);
            CAPTURE(tolerance);
            std::ostringstream rows;
            run_request rq = timed_rows_request(s, 0, rows);
            rq.tolerance = tolerance;
            const run_result r = p.run(m, rq, s.t0, s.t_end, p.x0);
            REQUIRE(r.stable);
            // The run steps as without output times.
            run_request plain = rq;
            plain.output_times.clear();
            plain.trajectory = nullptr;
            const run_result q = p.run(m, plain, s.t0, s.t_end, p.x0);
            CHECK(q.final_state == r.final_state);
            CHECK(q.steps == r.steps);
            std::istringstream lines(rows.str());
            double worst = 0;
            std::size_t count = 0;
            for (std::string line; std::getline(lines, line); ++count) {
                std::vector<double> row;
                std::istringstream fields(line);
                for (std::string f; std::getline(fields, f, ',');) row.push_back(std::stod(f));
                REQUIRE(row.size() == 3);
                const auto& exact = reference[std::size_t(std::lround(row[0] / 0.001))];
                REQUIRE(std::fabs(exact[0] - row[0]) < 1e-12);
                worst = std::max({worst, std::fabs(row[1] - exact[1]), std::fabs(row[2] - exact[2])});
            }
            CHECK(count == 901);
            MESSAGE(m.name << " at tolerance " << tolerance << ": " << r.steps << " steps, largest error at the "
                           << "output times " << worst << " = " << worst / tolerance << " tolerance");
            CHECK(worst < 10 * tolerance);
        }
    }
}

TEST_CASE("run: output times after a resume from a checkpoint: the rows of the uninterrupted run, byte for byte") {
    const scene s = parse_scene("system = \"kepler\"\nparameters = {eccentricity = 0.7}\nmethods = [\"blanes_moan_s6\"]\n"
                                "dt = 0.01\nt_end = 5\n[output]\ntimes = {from = 0, to = 5, count = 201}\n",
                                "resume.toml");
    const runnable_system p = system_of(s);
    std::ostringstream whole;
    run_request rq = timed_rows_request(s, 0.01, whole);
    std::vector<checkpoint_record> saved;
    rq.checkpoint.every_steps = 37;  // between output times (every 0.025) and, at t = 1.85, on one
    rq.checkpoint.save = [&](checkpoint_record& r) {
        r.trajectory_bytes = whole.str().size();
        saved.push_back(r);
    };
    const run_result a = p.run(s.methods[0], rq, s.t0, s.t_end, p.x0);
    REQUIRE(a.stable);
    REQUIRE(saved.size() == 13);
    for (const checkpoint_record& from : {saved[2], saved[4], saved[12]}) {
        std::ostringstream resumed;
        resumed << std::setprecision(17) << whole.str().substr(0, from.trajectory_bytes);
        run_request again = rq;
        again.trajectory = &resumed;
        again.checkpoint.resume = &from;
        again.checkpoint.save = [](checkpoint_record&) {};
        const run_result b = p.run(s.methods[0], again, s.t0, s.t_end, p.x0);
        CHECK(b.final_state == a.final_state);
        CHECK(resumed.str() == whole.str());
    }
    const std::string rows = whole.str();
    CHECK(std::count(rows.begin(), rows.end(), '\n') == 201);
}

TEST_CASE("run: trajectory columns count from 1 and name the planets' bodies") {
    const fs::path dir = scratch_directory("sympl_test_run_columns");
    fs::remove_all(dir);
    const auto header_of = [&](const std::string& system) {
        const scene s = parse_scene("name = \"c\"\nsystem = \"" + system + "\"\nmethods = [\"leapfrog_kdk\"]\ndt = 1\n"
                                    "t_end = 2\n[output]\ntrajectory_every = 1\ndirectory = \"" + dir.string() + "\"\n",
                                    "c.toml");
        std::ostringstream out;
        run_scene(s, true, out);
        return read_csv(dir / "c_leapfrog_kdk_trajectory.csv").at(0);
    };
    CHECK(header_of("henon_heiles") == std::vector<std::string>{"t", "q1", "q2", "p1", "p2"});
    const auto planets = header_of("outer_solar_system");
    REQUIRE(planets.size() == 37);
    CHECK(planets[1] == "sun_x");
    CHECK(planets[4] == "jupiter_x");
    CHECK(planets[19] == "sun_px");
    CHECK(planets[36] == "pluto_pz");
    fs::remove_all(dir);
}

TEST_CASE("run: energy_every writes the energy error against time, whose largest value is the summary's") {
    const fs::path dir = scratch_directory("sympl_test_run_energy");
    fs::remove_all(dir);
    const scene s = parse_scene("name = \"e\"\nsystem = \"pendulum\"\nmethods = [\"leapfrog_kdk\", \"rk4\"]\ndt = 0.1\n"
                                "t_end = 100\n[output]\nenergy_every = 10\ndirectory = \"" + dir.string() + "\"\n",
                                "e.toml");
    std::ostringstream out;
    run_scene(s, true, out);
    const auto json = nlohmann::json::parse(out.str());
    for (int k = 0; k < 2; ++k) {
        const std::string method = json[k]["method"];
        CAPTURE(method);
        const auto rows = read_csv(dir / ("e_" + method + "_energy.csv"));
        REQUIRE(rows.size() == 1 + 101);  // header, t = 0, 1, ..., 100
        CHECK(rows[0] == std::vector<std::string>{"t", "energy_error"});
        CHECK(std::stod(rows[1][0]) == 0);
        CHECK(std::stod(rows.back()[0]) == doctest::Approx(100));
        double largest = 0;
        for (std::size_t i = 1; i < rows.size(); ++i) largest = std::max(largest, std::stod(rows[i][1]));
        // Sampled every 10th step: at most the max over all steps, and near it.
        CHECK(largest <= json[k]["max_energy_error"].get<double>());
        CHECK(largest > 0.5 * json[k]["max_energy_error"].get<double>());
    }
    // RK4's energy error drifts, leapfrog's stays bounded: the series shows which is which.
    const auto series = [&](const std::string& method) {
        std::vector<double> e;
        for (const auto& row : read_csv(dir / ("e_" + method + "_energy.csv"))) e.push_back(row[0] == "t" ? 0 : std::stod(row[1]));
        return e;  // e[i]: t = i - 1
    };
    const auto rk4 = series("rk4"), leapfrog = series("leapfrog_kdk");
    CHECK(rk4[101] > 5 * rk4[11]);  // t = 100 against t = 10
    const double first_half = *std::max_element(leapfrog.begin() + 1, leapfrog.begin() + 51);
    const double second_half = *std::max_element(leapfrog.begin() + 51, leapfrog.end());
    CHECK(second_half < 2 * first_half);
    fs::remove_all(dir);
    CHECK_THROWS_WITH_AS(run_scene(parse_scene("system = \"damped_oscillator\"\nmethods = [\"rk4\"]\ndt = 0.1\nt_end = 1\n"
                                               "[output]\nenergy_every = 1\n", "d.toml"), true, out),
                         doctest::Contains("d.toml: output.energy_every: damped_oscillator has no energy"), scene_error);
}

TEST_CASE("run: the energy series is written as the run goes, none of it held") {
    const scene s = parse_scene("system = \"pendulum\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.01\nt_end = 1000\n"
                                "[output]\nenergy_every = 1\n",
                                "e.toml");
    const runnable_system p = system_of(s);
    run_request rq = plan_runs(s, p, sweep_use::first).runs.front().request();
    rq.energy = true;
    rq.energy_series_every = 1;
    std::ostringstream rows;
    rows.precision(17);
    rq.energy_series_file = &rows;
    const run_result r = p.run(s.methods.front(), rq, s.t0, s.t_end, p.x0);
    CHECK(r.energy_series.empty());
    std::istringstream in(rows.str());
    std::string line;
    std::size_t count = 0;
    double largest = 0;
    while (std::getline(in, line)) ++count, largest = std::max(largest, std::stod(line.substr(line.find(',') + 1)));
    CHECK(count == r.steps + 1);  // t0, then every step
    CHECK(largest == r.max_energy_error);
}

TEST_CASE("run: the final error, and so a reference, only where it is free or asked for") {
    const std::string pendulum = "system = \"pendulum\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.01\nt_end = 10\n";
    const auto plain = run_json(pendulum, "p.toml");
    CHECK_FALSE(plain[0].contains("final_error"));
    CHECK(plain[0]["reference"].get<std::string>().rfind("none (output.final_error = true measures", 0) == 0);
    const auto asked = run_json(pendulum + "[output]\nfinal_error = true\n", "p.toml");
    CHECK(asked[0]["reference"].get<std::string>().rfind("sofroniou_spaletta_10, long double", 0) == 0);
    CHECK(asked[0]["final_error"].get<double>() < 1e-3);
    const auto exact = run_json("system = \"kepler\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.01\nt_end = 10\n", "k.toml");
    CHECK(exact[0]["reference"] == "exact");
    CHECK(exact[0].contains("final_error"));
    // A reference far dearer than the limit (scaled with --max-steps) is refused before anything runs:
    // FPU with 1000 masses, 6e4 long-double steps of Sofroniou-Spaletta 10 against a limit of 0.216 s.
    const scene fpu = parse_scene("system = \"fpu_beta\"\nparameters = {n = 1000}\nmethods = [\"leapfrog_kdk\"]\n"
                                  "dt = 0.1\nt_end = 1000\n[output]\nfinal_error = true\n",
                                  "fpu.toml");
    std::ostringstream out;
    CHECK_THROWS_WITH_AS(run_scene(fpu, true, out, 6e4),
                         doctest::Contains("fpu.toml: the reference for the final errors (sofroniou_spaletta_10, long "
                                           "double, dt = 0.025, 6e+04 steps of 1000 degrees of freedom) takes about "),
                         scene_error);
    CHECK(out.str().empty());
}

TEST_CASE("run: an error of order one is flagged, not printed as an ordinary row, and the heading says what was given") {
    // Kepler e = 0.5 at dt = 5 (the issue's): energy error in the hundreds, below the divergence limit.
    const std::string kepler = "system = \"kepler\"\nmethods = [\"leapfrog_kdk\"]\nt_end = 100\n";
    const auto coarse = run_json(kepler + "dt = 5\n", "k.toml");
    CHECK(coarse[0]["status"] == "stable");
    CHECK(coarse[0]["error_order_one"] == true);
    const auto fine = run_json(kepler + "dt = 0.001\n", "k.toml");
    CHECK(fine[0]["error_order_one"] == false);
    std::ostringstream text;
    run_scene(parse_scene("system = \"kepler\"\nmethods = [\"leapfrog_kdk\"]\nt_end = 1\ndt = 0.05\n", "k.toml"), false,
              text);
    CHECK(text.str().find("t = 0 .. 1 (0.159155 periods), dt = 0.05, reference: exact") !=
          std::string::npos);  // not 0.050000000000000003
    CHECK(text.str().find("tolerance") == std::string::npos);  // no adaptive method, no tolerance
    CHECK(text.str().find("ORDER ONE") == std::string::npos);
    std::ostringstream flagged;
    run_scene(parse_scene(kepler + "dt = 5\n", "k.toml"), false, flagged);
    CHECK(flagged.str().find("^ ERROR OF ORDER ONE (>= 0.1): no correct digit, not a result; a smaller dt") !=
          std::string::npos);
}

TEST_CASE("run: the heading shows what the scene has, dt as its shortest text, a sweep only for a sweep") {
    const scene s = parse_scene("system = \"kepler\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.05\nt_end = 1\n", "one.toml");
    std::ostringstream text;
    run_scene(s, false, text);
    const std::string heading = text.str().substr(0, text.str().find('\n'));
    CHECK(heading.find("dt = 0.05,") != std::string::npos);  // not 0.050000000000000003
    CHECK(heading.find("tolerance") == std::string::npos);   // no adaptive method
    CHECK(text.str().find("(a sweep") == std::string::npos);
    const scene d = parse_scene("system = \"kepler\"\nmethods = [\"odeint_dopri5\"]\ndt = 0.05\ntolerances = [1e-6]\n"
                                "t_end = 1\n",
                                "adaptive.toml");
    std::ostringstream adaptive;
    run_scene(d, false, adaptive);
    CHECK(adaptive.str().find("tolerance 1e-06,") != std::string::npos);
    CHECK(adaptive.str().find("dt = ") == std::string::npos);
}

TEST_CASE("run: a run whose error reaches order one is flagged, not an ordinary row") {
    // Kepler e = 0.5 at dt = 5: the leapfrog jumps across the orbit (the energy error 778).
    const scene s = parse_scene("system = \"kepler\"\nmethods = [\"leapfrog_kdk\", \"blanes_moan_s6\"]\n"
                                "dt = [5.0]\nt_end = 50\n[output]\nenergy_error = true\n",
                                "coarse.toml");
    std::ostringstream text;
    run_scene(s, false, text);
    CHECK(text.str().find("ERROR OF ORDER ONE") != std::string::npos);
    const scene fine = parse_scene("system = \"kepler\"\nmethods = [\"blanes_moan_s6\"]\ndt = [0.01]\nt_end = 6\n",
                                   "fine.toml");
    std::ostringstream good;
    run_scene(fine, false, good);
    CHECK(good.str().find("ORDER ONE") == std::string::npos);
}

}  // namespace test_program_test_run_scene
