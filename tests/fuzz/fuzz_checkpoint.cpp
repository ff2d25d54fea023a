// libFuzzer target: any bytes as a checkpoint a run resumes from. The first
// byte picks one of the scenes below (a method kind of `sympl run`, or the
// rank files of `sympl ensemble` and of a [test_particles] map); the rest is
// the file's body, which gets its format line and a checksum that matches, so
// that the fuzzer reaches what a hand-made file with a recomputed checksum
// reaches: every field read, checked against the scene and the method, and
// the run resumed from it. The run either finishes or throws sympl::error;
// any other exception, crash, hang or sanitizer report is a finding.
//
// SYMPL_FUZZ_SEEDS=DIR: writes a seed per scene into DIR (a real checkpoint
// of each, taken mid-run, checked to resume and finish) and exits;
// tests/fuzz/run.sh starts from them.
// SYMPL_FUZZ_VERBOSE: says on stderr whether each input was refused (and
// why) or resumed to the end.
#include <stdlib.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <sympl/core/error.hpp>

#include "commands/ensemble_run.hpp"
#include "commands/run_scene.hpp"
#include "commands/run_test_particles.hpp"
#include "methods/run_plan.hpp"
#include "output/checkpoint.hpp"
#include "output/row_checkpoint.hpp"
#include "output/writers.hpp"
#include "reading/scene.hpp"

namespace {

namespace fs = std::filesystem;
using namespace sympl::app;

enum class kind { run, ensemble, test_particles };

struct fuzz_scene {
    kind k;
    const char* text;  // `checkpoint.file` is set to the scratch directory after parsing
};

// Short runs, each with a checkpoint taken before its end: every kind of
// carried state (table memory, compensated residuals, LogH's extended state,
// a processed kernel, Gauss's stages, a controller's step, Odeint's history,
// Tao's second copy, Wisdom-Holman's coordinates) and both rank files.
const fuzz_scene scenes[] = {
    {kind::run, "name = \"f\"\nsystem = \"kepler\"\nparameters = {eccentricity = 0.6}\nmethods = [\"blanes_moan_s6\"]\n"
                "t_end = 3\ndt = 0.01\ncheckpoint = {every_steps = 100, file = \"cp\"}\n"},
    {kind::run, "name = \"f\"\nsystem = \"kepler\"\nmethods = [\"compensated(leapfrog_kdk)\"]\n"
                "t_end = 3\ndt = 0.01\ncheckpoint = {every_steps = 100, file = \"cp\"}\n"},
    {kind::run, "name = \"f\"\nsystem = \"kepler\"\nparameters = {eccentricity = 0.9}\nmethods = [\"logh(leapfrog_kdk)\"]\n"
                "t_end = 3\ndt = 0.01\ncheckpoint = {every_steps = 100, file = \"cp\"}\n"},
    {kind::run, "name = \"f\"\nsystem = \"kepler\"\nmethods = [\"extrapolated(leapfrog_kdk, 3)\"]\n"
                "t_end = 3\ndt = 0.01\ncheckpoint = {every_steps = 100, file = \"cp\"}\n"},
    {kind::run, "name = \"f\"\nsystem = \"kepler\"\nmethods = [\"bcm_2006_p8\"]\n"
                "t_end = 3\ndt = 0.01\ncheckpoint = {every_steps = 100, file = \"cp\"}\n"},
    {kind::run, "name = \"f\"\nsystem = \"kepler\"\nmethods = [\"gauss_4\"]\n"
                "t_end = 2\ndt = 0.01\ncheckpoint = {every_steps = 100, file = \"cp\"}\n"},
    {kind::run, "name = \"f\"\nsystem = \"kepler\"\nmethods = [\"predictor_corrector\"]\n"
                "t_end = 3\ndt = 0.01\ncheckpoint = {every_steps = 100, file = \"cp\"}\n"},
    {kind::run, "name = \"f\"\nsystem = \"kepler\"\nmethods = [\"dprkn8_controlled\"]\ntolerances = [1e-8]\n"
                "t_end = 6\ndt = 0.01\ncheckpoint = {every_steps = 5, file = \"cp\"}\n"},
    {kind::run, "name = \"f\"\nsystem = \"kepler\"\nmethods = [\"odeint_dopri5\"]\ntolerances = [1e-8]\n"
                "t_end = 6\ndt = 0.01\ncheckpoint = {every_steps = 20, file = \"cp\"}\n"},
    {kind::run, "name = \"f\"\nsystem = \"kepler\"\nmethods = [\"odeint_bulirsch_stoer\"]\ntolerances = [1e-8]\n"
                "t_end = 6\ndt = 0.01\ncheckpoint = {every_steps = 5, file = \"cp\"}\n"},
    {kind::run, "name = \"f\"\nsystem = \"charged_particle\"\nmethods = [\"tao(yoshida_4)\"]\n"
                "t_end = 1\ndt = 0.005\ncheckpoint = {every_steps = 100, file = \"cp\"}\n"},
    {kind::run, "name = \"f\"\nsystem = \"outer_solar_system\"\n"
                "methods = [\"wh(leapfrog_dkd, corrector = 17, kernel = lazy, coordinates = jacobi)\"]\n"
                "t_end = 3000\ndt = 50\ncheckpoint = {every_steps = 30, file = \"cp\"}\n"},
    {kind::ensemble, "name = \"f\"\nsystem = \"henon_heiles\"\nmethods = [\"leapfrog_kdk\"]\nt_end = 2\ndt = 0.05\n"
                     "checkpoint = {every_steps = 40, file = \"cp\"}\n[ensemble]\n"
                     "grid = {q2 = {from = -0.2, to = 0.2, count = 3}, p2 = {from = -0.1, to = 0.1, count = 2}}\n"
                     "indicator = \"megno\"\nsample_every = 4\n"},
    {kind::test_particles, "name = \"f\"\nsystem = \"outer_solar_system\"\nmethods = [\"wh(saba_2)\"]\ndt = 100\n"
                           "t_end = 2000\ncheckpoint = {every_steps = 40, file = \"cp\"}\n[test_particles]\n"
                           "grid = {a = {from = 6.0, to = 9.0, count = 3}, e = {from = 0.0, to = 0.2, count = 2}}\n"},
};
constexpr std::size_t scene_count = std::size(scenes);
constexpr std::size_t particle_piece = 2;  // several pieces, so several rows in a rank file

// The format lines the program's readers expect (checkpoint.hpp, row_checkpoint.hpp).
const std::string run_head = "sympl-checkpoint " + std::to_string(checkpoint_format) + "\n";
const char* const ensemble_head = ensemble_checkpoint_head;
const char* const test_particles_head = test_particles_checkpoint_head;

fs::path scratch;  // this process's own directory
bool verbose = false;  // SYMPL_FUZZ_VERBOSE: say what became of each input (run on one file to see)

scene scene_of(std::size_t i) {
    scene s = parse_scene(scenes[i].text, "fuzz.toml");
    s.checkpoint.file = (scratch / "cp").string();
    s.output.directory = (scratch / "out").string();
    return s;
}

std::string read_whole(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// The body of a checkpoint file: between its format line and its checksum.
std::string body_of(const std::string& text, const std::string& head) {
    const std::size_t from = head.size(), to = text.rfind("checksum ");
    return to == std::string::npos || to < from ? std::string() : text.substr(from, to - from);
}

void clear_scratch() {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(scratch, ec)) fs::remove_all(entry.path(), ec);
}

fs::path run_checkpoint_file(const scene& s) {
    return s.checkpoint.file + "." + file_name_part(s.methods.front().name);
}

// A checkpoint of scene i taken mid-run, as its body.
std::string seed_of(std::size_t i) {
    clear_scratch();
    fs::create_directories(scratch / "out");
    const scene s = scene_of(i);
    switch (scenes[i].k) {
        case kind::run: {
            // The run's first save, written as the program writes it.
            const runnable_system p = system_of(s);
            const run_plan plan = plan_runs(s, p, sweep_use::first);
            run_request rq = plan.runs.front().request();
            bool saved = false;
            rq.checkpoint.every_steps = s.checkpoint.every_steps;
            rq.checkpoint.save = [&](checkpoint_record& r) {
                if (saved) return;
                r.scene_hash = s.text_hash;
                r.method = s.methods.front().name;
                r.dt = rq.dt;
                write_checkpoint(run_checkpoint_file(s), r);
                saved = true;
            };
            p.run(s.methods.front(), rq, s.t0, s.t_end, p.x0);
            return body_of(read_whole(run_checkpoint_file(s)), run_head);
        }
        case kind::ensemble:
            run_ensemble_scene(s, scratch / "out", "", 1, default_max_steps, false, exchange{});
            return body_of(read_whole(row_checkpoint_file(s.checkpoint.file, "ensemble", 0)), ensemble_head);
        case kind::test_particles:
            run_test_particles(s, test_particle_orbits(s), 1, default_max_steps, exchange{}, false, particle_piece);
            return body_of(read_whole(row_checkpoint_file(s.checkpoint.file, "test-particles", 0)),
                           test_particles_head);
    }
    return {};
}

void write_file(const fs::path& file, const std::string& text) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << text;
}

// Scene i resumed from a checkpoint of `body` (the format line and a
// matching checksum added): empty when it resumed and finished, else the
// refusal.
std::string resume_from(std::size_t i, const std::string& body) {
    clear_scratch();
    try {
        const scene s = scene_of(i);
        fs::create_directories(scratch / "out");
        std::ostringstream summary;
        switch (scenes[i].k) {
            case kind::run:
                write_file(run_checkpoint_file(s), run_head + body + "checksum " + fnv1a_hex(body) + "\n");
                run_scene(s, false, summary, default_max_steps, true);
                break;
            case kind::ensemble:
                write_file(row_checkpoint_file(s.checkpoint.file, "ensemble", 0),
                           ensemble_head + body + "checksum " + fnv1a_hex(body) + "\n");
                run_ensemble_scene(s, scratch / "out", "", 1, default_max_steps, false, exchange{}, true);
                break;
            case kind::test_particles:
                write_file(row_checkpoint_file(s.checkpoint.file, "test-particles", 0),
                           test_particles_head + body + "checksum " + fnv1a_hex(body) + "\n");
                run_test_particles(s, test_particle_orbits(s), 1, default_max_steps, exchange{}, true,
                                   particle_piece);
                break;
        }
    } catch (const sympl::error& e) {
        return e.what();
    }
    return {};
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    char pattern[] = "/tmp/sympl-fuzz-checkpoint-XXXXXX";
    if (!::mkdtemp(pattern)) {
        std::perror("fuzz_checkpoint: mkdtemp");
        std::exit(2);
    }
    scratch = pattern;
    // Removed when the fuzzer ends normally (a crash leaves it, with what the input wrote).
    std::atexit([] {
        std::error_code ec;
        fs::remove_all(scratch, ec);
    });
    verbose = std::getenv("SYMPL_FUZZ_VERBOSE") != nullptr;
    if (const char* dir = std::getenv("SYMPL_FUZZ_SEEDS")) {
        fs::create_directories(dir);
        for (std::size_t i = 0; i < scene_count; ++i) {
            const std::string body = seed_of(i);
            if (body.empty()) {
                std::fprintf(stderr, "fuzz_checkpoint: scene %zu saved no checkpoint\n", i);
                std::exit(2);
            }
            // A seed the program refuses would only teach the fuzzer refusals.
            if (const std::string refusal = resume_from(i, body); !refusal.empty()) {
                std::fprintf(stderr, "fuzz_checkpoint: the seed of scene %zu is refused: %s\n", i, refusal.c_str());
                std::exit(2);
            }
            write_file(fs::path(dir) / ("seed-" + std::to_string(i)), std::string(1, char(i)) + body);
        }
        fs::remove_all(scratch);
        std::exit(0);
    }
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    const std::size_t i = data[0] % scene_count;
    const std::string refusal = resume_from(i, std::string(reinterpret_cast<const char*>(data) + 1, size - 1));
    if (verbose) {
        if (refusal.empty()) std::fprintf(stderr, "resumed and finished: scene %zu\n", i);
        else std::fprintf(stderr, "refused: %s\n", refusal.c_str());
    }
    return 0;
}
