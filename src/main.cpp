// The sympl command-line program.
//   sympl tables [--json]            every catalog entry and its properties
//   sympl systems [--json]           every system, its parameters and the method kinds
//   sympl check-table --kick ... --drift ... [--convention ...] [--json]
//   sympl run SCENE.toml [--json]    one scene: summary and the outputs it asks for
//   sympl run SCENE [--out DIR] [--threads N]   a scene's [test_particles] (a file or a built-in name)
//   sympl report [SCENE.toml ...] [--out DIR] [--quick] [--threads N]   the work-precision study
//   sympl ensemble SCENE.toml [--out DIR] [--threads N]   a scene's [ensemble]
// Invalid input: exit code 2 and one line on stderr.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <unistd.h>
#include <CLI/CLI.hpp>

#include <sympl/core/error.hpp>

#include "commands/check_table.hpp"
#include "commands/ensemble_run.hpp"
#include "output/format.hpp"
#include "output/interrupt.hpp"
#include "commands/listings.hpp"
#include "output/mpi_exchange.hpp"
#include "reading/near_names.hpp"
#include "report/report.hpp"
#include "commands/run_scene.hpp"
#include "reading/scene.hpp"
#include "commands/run_test_particles.hpp"

namespace {

using namespace sympl::app;

// Everything the command line can say, filled in by CLI11.
struct command_line {
    CLI::App* tables = nullptr;
    CLI::App* systems = nullptr;
    CLI::App* check = nullptr;
    CLI::App* run = nullptr;
    CLI::App* report = nullptr;
    CLI::App* ensemble = nullptr;
    bool json = false;
    std::string kick, drift, convention = "kick-first";
    std::string scene_file;
    double max_steps = default_max_steps;
    bool resume = false;
    std::vector<std::string> report_files;
    std::vector<std::string> system_scenes;
    report_options report_settings;
    std::string ensemble_out = "sympl-ensemble";
    std::string run_out = "sympl-test-particles";
    int threads = 0;
};

void add_max_steps(CLI::App* command, double& target) {
    command->add_option("--max-steps", target, "refuse runs of more steps than this (default 1e9)")
        ->check(CLI::Range(1.0, 1e18));
}

void add_listings(CLI::App& app, command_line& c) {
    c.tables = app.add_subcommand("tables", "List every method of the catalog");
    c.tables->add_flag("--json", c.json, "JSON output");
    c.systems = app.add_subcommand("systems", "List every system, its parameters and the method kinds");
    c.systems->add_flag("--json", c.json, "JSON output");
    c.systems->add_option("scenes", c.system_scenes, "scene files: list their systems (a [system] of formulas too)");
    c.check = app.add_subcommand("check-table", "Validate a table and measure its order and stability");
    c.check->add_option("--kick", c.kick, "kick coefficients, comma-separated")->required();
    c.check->add_option("--drift", c.drift, "drift coefficients, comma-separated")->required();
    c.check->add_option("--convention", c.convention, "kick-first (default), drift-first, or seed (eq. 3.74: sums = M)")
        ->check(CLI::IsMember({"kick-first", "drift-first", "seed"}));
    c.check->add_flag("--json", c.json, "JSON output");
}

void add_runs(CLI::App& app, command_line& c) {
    c.run = app.add_subcommand("run", "Run one scene file and print its summary");
    c.run->add_option("scene", c.scene_file, "scene file (TOML), or a built-in scene's name")->required();
    c.run->add_option("--out", c.run_out, "output directory of a [test_particles] scene (default sympl-test-particles)");
    c.run->add_option("--threads", c.threads,
                      "threads of a [test_particles] scene (default: OMP_NUM_THREADS, else every core)")
        ->check(CLI::Range(1, 1024));
    c.run->add_flag("--json", c.json, "JSON output");
    add_max_steps(c.run, c.max_steps);
    c.run->add_flag("--resume", c.resume,
                    "continue from the scene's checkpoints (checkpoint = {every_steps, file}); a [test_particles] map "
                    "at any rank and thread count");

    c.report = app.add_subcommand("report", "Work-precision study over scenes (default: the built-in set)");
    c.report->add_option("scenes", c.report_files, "scene files (TOML); none: the built-in set");
    c.report->add_option("--out", c.report_settings.out_dir, "output directory (default sympl-report)");
    c.report->add_flag("--quick", c.report_settings.quick, "short runs: under a minute on 2 cores");
    c.report->add_flag("--no-plots", [&c](std::int64_t) { c.report_settings.plots = false; }, "skip the gnuplot PNGs");
    add_max_steps(c.report, c.report_settings.max_steps);
    c.report->add_option("--threads", c.report_settings.threads,
                         "runs side by side, one per thread (default: OMP_NUM_THREADS, else every core)")
        ->check(CLI::Range(1, 1024));

    c.ensemble = app.add_subcommand("ensemble", "Run a scene's [ensemble] (grid or CSV of states): threads, MPI ranks");
    c.ensemble->add_option("scene", c.scene_file, "scene file (TOML) with an [ensemble] table")->required();
    c.ensemble->add_option("--out", c.ensemble_out, "output directory (default sympl-ensemble)");
    c.ensemble->add_option("--threads", c.threads, "threads per process (default: OMP_NUM_THREADS, else every core)")
        ->check(CLI::Range(1, 1024));
    add_max_steps(c.ensemble, c.max_steps);
    c.ensemble->add_flag("--resume", c.resume,
                         "continue from the rows the scene's checkpoints hold (checkpoint = {every_steps, file}), "
                         "at any rank and thread count");
}

// `sympl run`: a scene's methods, or its [test_particles] map (files in
// --out; under mpirun its pieces shared among the ranks).
void run_one(const command_line& c, const exchange& ranks) {
    const scene s = load_scene(c.scene_file);
    if (!s.test_particles) {
        if (ranks.size > 1)
            throw sympl::error("sympl run shares only a [test_particles] map among MPI ranks; " + s.source +
                               " has none: expected one process (sympl ensemble and sympl report run over ranks)");
        if (c.run->count("--out") || c.run->count("--threads"))
            throw sympl::error("--out and --threads are for a scene with [test_particles]; " + s.source +
                               " has none (its outputs go to output.directory)");
        return run_scene(s, c.json, std::cout, c.max_steps, c.resume);
    }
    if (c.json)
        throw sympl::error(printable(s.source) + " has [test_particles]: its run writes files in --out; expected no --json");
    test_particles_command(s, c.run_out, c.threads, c.max_steps, ranks, c.resume, std::cout);
}

// The chosen command; its exit code.
int dispatch(command_line& c, exchange& ranks) {
    if (*c.tables) print_tables(c.json);
    if (*c.systems) print_systems(c.json, c.system_scenes);
    if (*c.check) return check_table(c.kick, c.drift, c.convention, c.json);
    if (*c.ensemble || *c.report || *c.run) ranks = process_exchange();
    if (*c.ensemble)
        ensemble_command(load_scene(c.scene_file), c.ensemble_out, c.threads, c.max_steps, ranks, std::cout, c.resume);
    if (*c.run) run_one(c, ranks);
    if (*c.report) {
        std::vector<scene> scenes;
        for (const auto& f : c.report_files) scenes.push_back(load_scene(f, c.report_settings.quick));
        c.report_settings.studies = c.report_files.empty();
        if (scenes.empty()) scenes = default_scenes(c.report_settings.quick);
        run_report(scenes, c.report_settings, std::cout, ranks);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    handle_interrupts();  // first: before any other thread exists
    CLI::App app{"sympl: symplectic splitting methods for separable Hamiltonians H = T(p) + V(q)"};
    app.require_subcommand(1);
    command_line c;
    add_listings(app, c);
    add_runs(app, c);
    // A first word that is no subcommand: CLI11 would only say one is required.
    if (argc > 1 && argv[1][0] != '-') {
        std::vector<std::string> names;
        const CLI::App& all = app;
        for (const CLI::App* sub : all.get_subcommands([](const CLI::App*) { return true; })) names.push_back(sub->get_name());
        if (std::find(names.begin(), names.end(), argv[1]) == names.end()) {
            std::cerr << "sympl: unknown command '" << printable(argv[1]) << "'; " << printable(expected_one_of(argv[1], names))
                      << "\n";
            return 2;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << "sympl: " << printable_lines(e.what()) << "\n";
        return 2;
    }
    exchange ranks;  // the MPI ranks of `ensemble`, `report` and a [test_particles] `run` under mpirun
    // Under MPI an error on one rank ends them all (the others may wait for it in a gather).
    const auto fail = [&](const char* what) {
        const std::string who =
            ranks.size > 1 ? " (rank " + std::to_string(ranks.rank) + " of " + std::to_string(ranks.size) + ")" : "";
        // One write(2), so that Open MPI's abort banner from another rank cannot
        // land inside the line (it did in CI: "sympl (rank 0 of 3)<banner>: ...").
        const std::string line = "sympl" + who + ": " + printable_lines(what) + "\n";
        for (std::size_t done = 0; done < line.size();) {
            const ssize_t n = ::write(2, line.data() + done, line.size() - done);
            if (n <= 0) break;
            done += static_cast<std::size_t>(n);
        }
        if (ranks.size > 1) ranks.abort_all(2);
        return 2;
    };
    try {
        return dispatch(c, ranks);
    } catch (const sympl::error& e) {
        return fail(e.what());
    } catch (const std::filesystem::filesystem_error& e) {
        return fail(e.what());
    }
}
