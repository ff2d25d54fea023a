// `sympl run --resume` after SIGKILL, one test per method kind: a checkpointed
// run in a child process, killed by SIGKILL as soon as it has saved a
// checkpoint (mid-run, between or while writing the next ones), then resumed,
// prints and writes byte for byte what the uninterrupted run does: the
// summary (final state to 17 digits, step and force counts, energy and final
// errors) and the trajectory.
#include <doctest/doctest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>

#include <sympl/core/error.hpp>

#include "output/checkpoint.hpp"
#include "output/ensemble_checkpoint.hpp"
#include "commands/ensemble_run.hpp"
#include "commands/run_scene.hpp"
#include "reading/scene.hpp"
#include "scratch_directory.hpp"

namespace test_program_test_kill_and_resume {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;
namespace fs = std::filesystem;

namespace {
struct outputs {
    std::string summary;
    std::map<std::string, std::string> files;
};

// The files of `dir` by name, and the directory emptied.
std::map<std::string, std::string> take_files(const fs::path& dir) {
    std::map<std::string, std::string> files;
    for (const auto& entry : fs::directory_iterator(dir))
        if (entry.is_regular_file() && entry.path().filename() != ".sympl.lock") {
            std::ifstream in(entry.path(), std::ios::binary);
            std::stringstream text;
            text << in.rdbuf();
            files[entry.path().filename().string()] = text.str();
        }
    fs::remove_all(dir);
    return files;
}

// Whether a checkpoint (not a temporary, not a trajectory) is in `dir`.
bool has_checkpoint(const fs::path& dir) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (name.find(".sympl-part-") == std::string::npos && !name.ends_with(".trajectory")) return true;
    }
    return false;
}

// The scene run whole, then in a child killed by SIGKILL after its first
// checkpoint and resumed; both outputs, and whether the child was killed.
struct runs {
    outputs whole, resumed;
    bool killed = false;
};

runs kill_and_resume(const std::string& name, const std::string& system_lines, const std::string& method,
                     const std::string& span_lines, std::size_t every_steps, std::size_t trajectory_every) {
    const fs::path dir = scratch_directory("sympl_test_kill_" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string text = "name = \"resume\"\n" + system_lines + "methods = [\"" + method + "\"]\n" + span_lines +
                             "checkpoint = {every_steps = " + std::to_string(every_steps) + ", file = \"" +
                             (dir / "state" / "run").string() + "\"}\n[output]\ntrajectory_every = " +
                             std::to_string(trajectory_every) + "\nfinal_state = true\ndirectory = \"" +
                             (dir / "out").string() + "\"\n";
    const scene s = parse_scene(text, "resume.toml");
    runs r;
    std::ostringstream whole;
    run_scene(s, false, whole);
    r.whole = {whole.str(), take_files(dir / "out")};
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        std::ostringstream ignored;
        try {
            run_scene(s, false, ignored);
        } catch (...) {
            ::_exit(3);
        }
        ::_exit(0);
    }
    int status = 0;
    while (true) {
        if (has_checkpoint(dir / "state")) {
            ::kill(child, SIGKILL);
            ::waitpid(child, &status, 0);
            break;
        }
        if (::waitpid(child, &status, WNOHANG) == child) break;  // finished before it could be killed
        std::this_thread::sleep_for(std::chrono::microseconds(100));
    }
    r.killed = WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
    std::ostringstream resumed;
    run_scene(s, false, resumed, default_max_steps, true);
    r.resumed = {resumed.str(), take_files(dir / "out")};
    CHECK(fs::is_empty(dir / "state"));  // a finished run leaves no checkpoint
    fs::remove_all(dir);
    return r;
}

void check_byte_identical(const runs& r) {
    CHECK(r.killed);
    CHECK(r.resumed.summary == r.whole.summary);
    CHECK(r.resumed.files.size() == r.whole.files.size());
    CHECK(r.resumed.files == r.whole.files);
}

const std::string kepler = "system = \"kepler\"\nparameters = {eccentricity = 0.6}\n";
const std::string planets = "system = \"outer_solar_system\"\n";
}  // namespace

TEST_CASE("kill and resume: tables, plain, compensated, force-gradient and extrapolated") {
    for (const std::string method : {"blanes_moan_s6", "compensated(leapfrog_kdk)", "chin_4a", "extrapolated(leapfrog_kdk, 3)"}) {
        CAPTURE(method);
        check_byte_identical(kill_and_resume("table", kepler, method, "t_end = 300\ndt = 0.01\n", 1000, 50));
    }
}

TEST_CASE("kill and resume: logh(<table>) and extrapolated(logh(<table>), k), in fictitious time") {
    for (const std::string method : {"logh(blanes_moan_s6)", "extrapolated(logh(leapfrog_kdk), 3)"}) {
        CAPTURE(method);
        check_byte_identical(kill_and_resume("logh", kepler, method, "t_end = 300\ndt = 0.01\n", 1000, 50));
    }
}

TEST_CASE("kill and resume: a processed method, its kernel's state carried") {
    check_byte_identical(
        kill_and_resume("processed", kepler, "bcm_2006_p8", "t_end = 300\ndt = 0.01\n", 1000, 50));
}

TEST_CASE("kill and resume: classic steppers with and without a history, Gauss-Legendre, dprkn at a fixed step") {
    for (const std::string method : {"rk4", "velocity_verlet", "half_step", "predictor_corrector", "gauss_4", "dprkn8"}) {
        CAPTURE(method);
        check_byte_identical(kill_and_resume("fixed", kepler, method, "t_end = 200\ndt = 0.01\n", 1000, 50));
    }
}

TEST_CASE("kill and resume: the controlled RKN pairs, with the controller's step and error") {
    for (const std::string method : {"dprkn6_controlled", "dprkn8_controlled", "dprkn12_controlled"}) {
        CAPTURE(method);
        check_byte_identical(kill_and_resume("rkn", kepler, method, "t_end = 600\ndt = 0.01\ntolerances = [1e-10]\n", 200, 10));
    }
}

TEST_CASE("kill and resume: Boost.Odeint's rk4 and its controlled steppers, with their step size") {
    // bulirsch_stoer also with Boost's private order and step history.
    for (const std::string method : {"odeint_rk4", "odeint_dopri5", "odeint_fehlberg78", "odeint_bulirsch_stoer"}) {
        CAPTURE(method);
        check_byte_identical(
            kill_and_resume("odeint", kepler, method, "t_end = 300\ndt = 0.01\ntolerances = [1e-9]\n",
                            method == "odeint_bulirsch_stoer" ? 100 : 300, 10));  // its ~600 steps: killed after 100
    }
}

TEST_CASE("kill and resume: tao(<table>) with its second copy, semiexplicit(<table>), Gauss with its stages") {
    const std::string charged = "system = \"charged_particle\"\n";
    for (const std::string method : {"tao(yoshida_4)", "semiexplicit(yoshida_4)", "gauss_6"}) {
        CAPTURE(method);
        check_byte_identical(kill_and_resume("general", charged, method, "t_end = 40\ndt = 0.005\n", 400, 20));
    }
}

TEST_CASE("kill and resume: a charged particle's pushers and splittings (nothing carried beyond q, p)") {
    const std::string uniform = "system = \"charged_uniform\"\n";
    for (const std::string method : {"boris", "boris(relativistic = true)", "cartesian_split(yoshida_6)"}) {
        CAPTURE(method);
        check_byte_identical(kill_and_resume("charged", uniform, method, "t_end = 100\ndt = 0.005\n", 1000, 50));
    }
}

TEST_CASE("kill and resume: wh(...) in both coordinates, with kernels and correctors") {
    for (const std::string method : {"wh(leapfrog_kdk)", "wh(saba_2, corrector = 5)",
                               "wh(leapfrog_dkd, corrector = 17, kernel = composition)",
                               "wh(leapfrog_dkd, corrector = 17, kernel = lazy, coordinates = jacobi)",
                               "wh(sbab_3, coordinates = jacobi)"}) {
        CAPTURE(method);
        check_byte_identical(kill_and_resume("wh", planets, method, "t_end = 100000\ndt = 50\n", 100, 10));
    }
}

// The ensemble's rows saved by one rank of three, then the ensemble resumed
// in one process: only the other rows are computed, and ensemble.csv is the
// uninterrupted run's byte for byte (tests/ensemble_kill_and_resume.sh kills
// real processes and MPI ranks).
TEST_CASE("kill and resume: an ensemble resumed at another rank count from one rank's saved rows") {
    const fs::path dir = scratch_directory("sympl_test_kill_ensemble");
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string text = "name = \"grid\"\n" + kepler + "methods = [\"blanes_moan_s6\"]\ndt = 0.05\nt_end = 30\n"
                             "checkpoint = {every_steps = 1200, file = \"" + (dir / "state" / "grid").string() +
                             "\"}\n[ensemble]\ngrid = {eccentricity = {from = 0.05, to = 0.75, count = 7}, mu = {from = 0.8, to = 1.2, count = 5}}\n"
                             "indicator = \"megno\"\n";
    const scene s = parse_scene(text, "grid.toml");
    std::ostringstream ignored;
    ensemble_command(s, (dir / "whole").string(), 1, default_max_steps, exchange{}, ignored);
    CHECK(fs::is_empty(dir / "state"));  // complete: its checkpoints removed
    // Rank 1 of 3 alone, as if ranks 0 and 2 were lost: its rows saved (and nothing written).
    exchange one_of_three;
    one_of_three.rank = 1;
    one_of_three.size = 3;
    run_ensemble_scene(s, dir / "unused", "", 1, default_max_steps, false, one_of_three);
    REQUIRE(fs::exists(ensemble_checkpoint_file(s.checkpoint.file, 1)));
    const ensemble_rows saved = read_ensemble_checkpoints(s.checkpoint.file, s.text_hash);
    CHECK(saved.size() == 12);  // rows 11..22 of 35
    CHECK(saved.begin()->first == 11);
    ensemble_command(s, (dir / "resumed").string(), 2, default_max_steps, exchange{}, ignored, true);
    const auto whole = take_files(dir / "whole"), resumed = take_files(dir / "resumed");
    REQUIRE(whole.count("ensemble.csv") == 1);
    CHECK(resumed.at("ensemble.csv") == whole.at("ensemble.csv"));
    CHECK(fs::is_empty(dir / "state"));
    // A checkpoint of another scene is refused with the reason.
    write_ensemble_checkpoint(ensemble_checkpoint_file(s.checkpoint.file, 0), fnv1a_hex("another"), saved);
    CHECK_THROWS_WITH_AS(read_ensemble_checkpoints(s.checkpoint.file, s.text_hash),
                         doctest::Contains("belongs to another scene"), sympl::error);
    // A row whose final state is not the scene's size (its checksum right):
    // refused, where its CSV line would have had other columns.
    ensemble_rows short_row = saved;
    short_row.begin()->second.final_state.pop_back();
    write_ensemble_checkpoint(ensemble_checkpoint_file(s.checkpoint.file, 0), s.text_hash, short_row);
    CHECK_THROWS_WITH_AS(ensemble_command(s, (dir / "short").string(), 1, default_max_steps, exchange{}, ignored, true),
                         doctest::Contains(".ensemble-rank-*: the row of point 11 holds a final state of 3 numbers; expected 4 (q then p)"),
                         sympl::error);
    CHECK(!fs::exists(dir / "short" / "ensemble.csv"));
    fs::remove_all(dir);
}

}  // namespace test_program_test_kill_and_resume
