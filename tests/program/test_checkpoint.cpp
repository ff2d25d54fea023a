// Checkpoint files: exact round trip, and every kind of bad file refused.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <tuple>
#include <utility>
#include <optional>

#include <sympl/core/error.hpp>

#include "methods/run_plan.hpp"
#include "output/checkpoint.hpp"
#include "reading/scene.hpp"
#include "scratch_directory.hpp"

namespace test_program_test_checkpoint {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;
namespace fs = std::filesystem;

namespace {
checkpoint_record sample() {
    checkpoint_record r;
    r.scene_hash = fnv1a_hex("name = \"x\"\n");
    r.method = "compensated(blanes_moan_s6)";
    r.dt = 0.1;  // not a binary fraction: must come back to the last bit
    r.step = 123456789;
    r.time = 12345678.9;
    r.state = {std::nextafter(1.0, 2.0), -0.0, 1e-310, -7.25};
    r.memory.force = {0.3, -0.7};
    r.memory.velocity = {1.0 / 3, 2.0 / 3};
    r.memory.q_error = {1e-17, -3e-18};
    r.memory.p_error = {0, 5e-324};
    r.memory.force_fresh = true;
    r.memory.force_evaluations = 987654321012ull;
    r.memory.velocity_evaluations = 42;
    r.carried = {1, 0, -1.0 / 7, 1e300};
    r.max_energy_error = 4.0123456789012345e-9;
    r.trajectory_bytes = 1113699;
    return r;
}
std::string read(const fs::path& f) {
    std::ifstream in(f, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
void write(const fs::path& f, const std::string& text) { std::ofstream(f, std::ios::binary) << text; }
std::string refusal(const fs::path& f, const checkpoint_record& r, const std::string& hash, double dt) {
    try {
        read_checkpoint(f, hash, r.method, dt);
    } catch (const sympl::error& e) {
        return e.what();
    }
    return "accepted";
}
// A Kepler run of `method` to t = 3 at dt = 0.01 whose request saves a
// checkpoint every 50 steps, and the first it saved.
struct kepler_run {
    scene s;
    runnable_system p;
    run_request rq;
    checkpoint_record first;
    explicit kepler_run(const std::string& method, std::size_t every = 50)
        : s(parse_scene("system = \"kepler\"\nmethods = [\"" + method + "\"]\nt_end = 3\ndt = 0.01\n", "k.toml")),
          p(system_of(s)), rq(plan_runs(s, p, sweep_use::first).runs.front().request()) {
        bool saved = false;
        rq.checkpoint.every_steps = every;
        rq.checkpoint.save = [&](checkpoint_record& r) {
            if (!std::exchange(saved, true)) first = r;
        };
        p.run(s.methods.front(), rq, s.t0, s.t_end, p.x0);
        REQUIRE(saved);
        rq.checkpoint.save = [](checkpoint_record&) {};
    }
    // Resumed from r: refused, or run to the end.
    run_result resumed_from(const checkpoint_record& r) {
        rq.checkpoint.resume = &r;
        return p.run(s.methods.front(), rq, s.t0, s.t_end, p.x0);
    }
};
}  // namespace

TEST_CASE("checkpoint: every number comes back to the last bit") {
    const fs::path dir = scratch_directory("sympl_test_checkpoint");
    fs::create_directories(dir);
    const checkpoint_record r = sample();
    write_checkpoint(dir / "c", r);
    const checkpoint_record back = read_checkpoint(dir / "c", r.scene_hash, r.method, r.dt);
    CHECK(back.step == r.step);
    CHECK(back.time == r.time);
    CHECK(back.carried == r.carried);
    CHECK(back.state == r.state);
    CHECK(std::signbit(back.state[1]));
    CHECK(back.memory.force == r.memory.force);
    CHECK(back.memory.velocity == r.memory.velocity);
    CHECK(back.memory.q_error == r.memory.q_error);
    CHECK(back.memory.p_error == r.memory.p_error);
    CHECK(back.memory.force_fresh);
    CHECK_FALSE(back.memory.velocity_fresh);
    CHECK(back.memory.force_evaluations == r.memory.force_evaluations);
    CHECK(back.memory.velocity_evaluations == r.memory.velocity_evaluations);
    CHECK(back.max_energy_error == r.max_energy_error);
    CHECK(back.trajectory_bytes == r.trajectory_bytes);
    CHECK_FALSE(fs::exists(dir / ("c.sympl-part-" + std::to_string(::getpid()))));  // no temporary left
    fs::remove_all(dir);
}

TEST_CASE("checkpoint: truncated, corrupted, foreign or mismatched files are refused with the reason") {
    const fs::path dir = scratch_directory("sympl_test_checkpoint_bad");
    fs::create_directories(dir);
    const checkpoint_record r = sample();
    write_checkpoint(dir / "c", r);
    const std::string good = read(dir / "c");
    const auto refused_for = [&](const std::string& text, const std::string& hash, double dt) {
        write(dir / "bad", text);
        return refusal(dir / "bad", r, hash, dt);
    };
    const auto says = [](const std::string& message, const std::string& part) {
        CAPTURE(message);
        CHECK(message.find(part) != std::string::npos);
        CHECK(message.find("not resumed from") != std::string::npos);
    };
    says(refused_for(good.substr(0, good.size() / 2), r.scene_hash, r.dt), "truncated");
    says(refused_for(good.substr(0, good.size() - 3), r.scene_hash, r.dt), "corrupted");
    std::string flipped = good;
    flipped[flipped.find("state") + 12] ^= 1;  // one bit of a state value
    says(refused_for(flipped, r.scene_hash, r.dt), "checksum mismatch");
    says(refused_for("", r.scene_hash, r.dt), "is not a sympl checkpoint");
    says(refused_for("sympl-checkpoint 99\n" + good.substr(good.find('\n') + 1), r.scene_hash, r.dt),
         "another format version");
    says(refused_for(good, fnv1a_hex("another scene"), r.dt), "belongs to another scene");
    says(refused_for(good, r.scene_hash, 0.2), "another dt");
    // A line after the last field, its checksum recomputed (fuzz_checkpoint found it accepted).
    const std::string body = good.substr(good.find('\n') + 1, good.rfind("checksum ") - good.find('\n') - 1) + "X\n";
    says(refused_for(good.substr(0, good.find('\n') + 1) + body + "checksum " + fnv1a_hex(body) + "\n", r.scene_hash,
                     r.dt),
         "holds 2 more bytes after 'trajectory_bytes'; expected its end");
    // Words after a line's values, the checksum recomputed: refused by line.
    const auto with_body = [&](const std::string& from, const std::string& to) {
        std::string changed = good.substr(good.find('\n') + 1, good.rfind("checksum ") - good.find('\n') - 1);
        changed.replace(changed.find(from), from.size(), to);
        return good.substr(0, good.find('\n') + 1) + changed + "checksum " + fnv1a_hex(changed) + "\n";
    };
    says(refused_for(with_body("step 123456789\n", "step 123456789 junk\n"), r.scene_hash, r.dt),
         "holds 'junk' after the values of 'step'; expected the line's end");
    says(refused_for(with_body("\nforce 2 ", "\nforce 1 "), r.scene_hash, r.dt), "after the values of 'force'");
    says(refused_for(with_body("evaluations 987654321012 42\n", "evaluations 987654321012 42 \x1b[31m\n"),
                     r.scene_hash, r.dt),
         "holds '\\x1b[31m' after the values of 'evaluations'");
    write(dir / "bad", good);
    checkpoint_record other = r;
    other.method = "rk4";
    try {
        read_checkpoint(dir / "bad", r.scene_hash, "rk4", r.dt);
        FAIL("a checkpoint of another method was accepted");
    } catch (const sympl::error& e) {
        CHECK(std::string(e.what()).find("is of method 'compensated(blanes_moan_s6)', not 'rk4'") != std::string::npos);
    }
    // The method's name as the file holds it, control characters and all:
    // quoted escaped.
    says(refused_for(with_body("\nmethod 27 compensated(blanes_moan_s6)\n", "\nmethod 9 a\x1b[31mb\tc\n"), r.scene_hash,
                     r.dt),
         "is of method 'a\\x1b[31mb\\tc', not 'compensated(blanes_moan_s6)'");
    says(refusal(dir / "missing", r, r.scene_hash, r.dt), "cannot be opened");
    // A directory and a device where the checkpoint should be: refused by
    // their kind, unread (an uncaught std::ios_base::failure before).
    fs::create_directories(dir / "a_directory");
    says(refusal(dir / "a_directory", r, r.scene_hash, r.dt), "is a directory; expected a regular file");
    says(refusal("/dev/zero", r, r.scene_hash, r.dt), "is a character device; expected a regular file");
    fs::remove_all(dir);
}

TEST_CASE("checkpoint: a stepper's memory of the wrong size is refused, not read past") {
    // Kepler's state is fixed-size: a table's memory holds 2 numbers a
    // vector, LogH's 3 (q and t). The record's fields pass
    // check_checkpoint_fields (half the state, or one more, or none) whatever
    // the kind; the stepper's own size is held at restoring (fuzz_checkpoint
    // found 2 numbers read as LogH's 3, and an empty q_error as a table's 2).
    struct cut_case {
        const char *method, *cut, *expected;
    };
    for (const cut_case& k : {cut_case{"logh(leapfrog_kdk)", "force", "expected 3"},
                              cut_case{"blanes_moan_s6", "q_error", "expected 2"}}) {
        const char* method = k.method;  // not a structured binding: clang 14 cannot capture one (CAPTURE)
        const char *cut = k.cut, *expected = k.expected;
        CAPTURE(method);
        kepler_run run(method);
        checkpoint_record r = run.first;
        std::vector<double>& v = std::string(cut) == "force" ? r.memory.force : r.memory.q_error;
        v.pop_back();
        CHECK_THROWS_WITH_AS(run.resumed_from(r), doctest::Contains(expected), sympl::error);
    }
}

TEST_CASE("checkpoint: LogH's carried time and state are held to the record's") {
    // The extended state LogH carries holds the time the run goes on from and
    // p_t, which sets every step's length; a record with the time set back
    // or p_t made huge (the checksum recomputed) ran to the step limit.
    kepler_run run("logh(leapfrog_kdk)");
    const checkpoint_record& first = run.first;
    REQUIRE(first.carried.size() == 6);  // (q, t) then (p, p_t), Kepler in the plane
    CHECK(first.carried[2] == first.time);
    for (const int changed : {2, 0, 4, 5}) {  // the time, a coordinate, a momentum, p_t
        CAPTURE(changed);
        checkpoint_record r = first;
        r.carried[std::size_t(changed)] = changed == 2 ? -1e300 : r.carried[std::size_t(changed)] * (1 + 1e-15);
        CHECK_THROWS_WITH_AS(run.resumed_from(r),
                             doctest::Contains("holds an extended state whose time, (q, p) or p_t is not the run's"),
                             sympl::error);
    }
    CHECK(run.resumed_from(first).stable);  // as written: resumes
}

TEST_CASE("checkpoint: a controlled run's carried time and step count are held to the record's") {
    // A controlled pair's controller and an Odeint run carry their time (and
    // the pair its count of accepted steps) beside the record's: one set
    // apart (the checksum recomputed) went on from another time or counted
    // on from another step.
    kepler_run pair("dprkn8_controlled", 5);
    const checkpoint_record& first = pair.first;
    REQUIRE(first.carried.size() > 4);  // t, dt, the last error, accepted, rejected, ...
    CHECK(first.carried[0] == first.time);
    CHECK(first.carried[3] == double(first.step));
    for (const int changed : {0, 3}) {
        CAPTURE(changed);
        checkpoint_record r = first;
        r.carried[std::size_t(changed)] = changed == 0 ? r.carried[0] * (1 + 1e-15) : r.carried[3] + 1;
        CHECK_THROWS_WITH_AS(
            pair.resumed_from(r),
            doctest::Contains("holds a controller time or count of accepted steps that is not the run's"),
            sympl::error);
    }
    CHECK(pair.resumed_from(first).stable);  // as written: resumes
    for (const char* method : {"odeint_dopri5", "odeint_rk4"}) {
        CAPTURE(method);
        kepler_run run(method, 5);
        REQUIRE(run.first.carried.size() > 2);  // t, dt, evaluations, ...
        CHECK(run.first.carried[0] == run.first.time);
        checkpoint_record r = run.first;
        r.carried[0] = r.carried[0] * (1 + 1e-15);
        CHECK_THROWS_WITH_AS(run.resumed_from(r), doctest::Contains("holds a time that is not the run's"),
                             sympl::error);
        CHECK(run.resumed_from(run.first).stable);
    }
}

TEST_CASE("checkpoint: a record's fields are held to the run it resumes, each refusal naming the field") {
    // sample(): 2 degrees of freedom, 123456789 steps of 0.1 to t = 12345678.9.
    const auto refusal_of = [](const checkpoint_record& r, double t_end = 2e7, bool fixed = true) -> std::string {
        try {
            check_checkpoint_fields(r, "run.ckpt", 4, 0, t_end, fixed);
        } catch (const sympl::error& e) {
            return e.what();
        }
        return "accepted";
    };
    CHECK(refusal_of(sample()) == "accepted");
    const auto with = [](auto change) {
        checkpoint_record r = sample();
        change(r);
        return r;
    };
    CHECK(refusal_of(with([](auto& r) { r.state.pop_back(); })).find("holds a state of 3 numbers; expected 4, q then p") !=
          std::string::npos);
    CHECK(refusal_of(with([](auto& r) { r.state[1] = NAN; })).find("state[1] = nan; expected a finite number") !=
          std::string::npos);
    // LogH at t = -1e300, or NaN: outside the span (the hang and the broken CSV of issue 59).
    CHECK(refusal_of(with([](auto& r) { r.time = -1e300; })).find("holds time = -1e+300; expected a time in the scene's "
                                                                 "span [0, 2e+07]") != std::string::npos);
    CHECK(refusal_of(with([](auto& r) { r.time = NAN; })).find("holds time = nan") != std::string::npos);
    CHECK(refusal_of(with([](auto& r) { r.step = 300000000; })).find("holds step = 300000000; expected at most "
                                                                    "200000001 steps of dt = 0.1") != std::string::npos);
    CHECK(refusal_of(with([](auto& r) { r.step = 300000000; }), 2e7, false) == "accepted");  // LogH counts its own steps
    // A fresh force of no numbers (the SIGSEGV of issue 59), a velocity of the wrong length.
    CHECK(refusal_of(with([](auto& r) { r.memory.force.clear(); })).find("holds a force of 0 numbers; expected 2 (it "
                                                                        "is marked fresh)") != std::string::npos);
    CHECK(refusal_of(with([](auto& r) { r.memory.velocity = {1, 2, 3}; })).find("a velocity of 3 numbers; expected 2 "
                                                                              "or none") != std::string::npos);
    CHECK(refusal_of(with([](auto& r) { r.carried[0] = INFINITY; })).find("carried[0] = inf") != std::string::npos);
    CHECK(refusal_of(with([](auto& r) { r.max_energy_error = -2; })).find("max_energy_error = -2; expected -1") !=
          std::string::npos);
}

}  // namespace test_program_test_checkpoint

#include "commands/run_scene.hpp"
#include "reading/scene.hpp"

namespace test_program_test_checkpoint_rows {

using namespace sympl::app;
namespace fs = std::filesystem;

TEST_CASE("checkpoint: a record whose trajectory offset is not a row's end is refused, the file kept") {
    const fs::path dir = scratch_directory("sympl_ckpt_rows");
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string text = "name = \"rows\"\nsystem = \"harmonic_oscillator\"\nmethods = [\"leapfrog_kdk\"]\ndt = 0.1\n"
                             "t_end = 10\ncheckpoint = {every_steps = 10, file = \"" + (dir / "run").string() + "\"}\n"
                             "[output]\ntrajectory_every = 1\ndirectory = \"" + (dir / "out").string() + "\"\n";
    const scene s = parse_scene(text, (dir / "rows.toml").string());
    const std::string header = "t,q1,p1\n", rows = "0,1,0\n0.1,0.995,-0.0998\n";
    checkpoint_record r;
    r.scene_hash = s.text_hash;
    r.method = "leapfrog_kdk";
    r.dt = 0.1;
    r.step = 1;
    r.time = 0.1;
    r.state = {0.995, -0.0998};
    r.trajectory_bytes = header.size() + 3;  // inside the first row
    write_checkpoint(dir / "run.leapfrog_kdk", r);
    std::ofstream(dir / "run.leapfrog_kdk.trajectory", std::ios::binary) << header << rows;
    std::ostringstream out;
    const std::string expected =
        "records 11 bytes of " + (dir / "run.leapfrog_kdk.trajectory").string() + ", which is not the end of a row";
    std::string refusal = "accepted";
    try {
        run_scene(s, false, out, 1e9, true);
    } catch (const sympl::error& e) {
        refusal = e.what();
    }
    CHECK_MESSAGE(refusal.find(expected) != std::string::npos, refusal);
    CHECK(fs::file_size(dir / "run.leapfrog_kdk.trajectory") == header.size() + rows.size());  // nothing cut
    fs::remove_all(dir);
}

}  // namespace test_program_test_checkpoint_rows
