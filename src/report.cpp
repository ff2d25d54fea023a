// The work-precision report: every scene's methods over their sweeps, the
// fastest method per accuracy level against Odeint, and the fixed studies.
// Compute (report_rows), gather (MPI), write (report_write, summary.md).
#include "report.hpp"

#include <ostream>
#include <set>
#include <sstream>

#include "format.hpp"
#include "output_set.hpp"
#include "report_rows.hpp"
#include "report_write.hpp"
#include "writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

// Everything is checked before anything runs: names, systems, methods, sizes.
void check_scenes(const std::vector<scene>& scenes, const report_options& options, std::vector<problem>& problems,
                  std::vector<run_plan>& plans) {
    std::set<std::string> names;
    for (const scene& s : scenes)
        if (!names.insert(s.name).second)
            throw scene_error(s.source + ": a second scene named '" + s.name + "'; expected each scene name once");
    problems.reserve(scenes.size());  // plans point into problems and scenes: no reallocation after this
    for (const scene& s : scenes) {
        problems.push_back(problem_of(s));
        plans.push_back(plan_runs(s, problems.back(), sweep_use::whole));
        check_run_size(plans.back(), options.max_steps);
    }
}

void write_intro(std::ostream& md, const report_options& options, int rounds, const exchange& ranks) {
    md << "# sympl work-precision report\n\n" << (options.quick ? "Quick run (`--quick`): short spans, few steps.\n\n" : "")
       << "Final error: max |x - x_ref| / max |x_ref| at t_end against the exact solution or a Sofroniou-Spaletta 10 "
          "reference in long double (its own error in work_precision.csv). Wall time: median of "
       << rounds << " measurements with nothing observed, taken in rounds over all runs (interleaved between methods); "
          "each measurement repeats the run until it lasts "
       << (options.quick ? "1 ms" : "5 ms") << " (min and max in work_precision.csv).";
    if (ranks.size > 1)
        md << " The runs were dealt round-robin over " << ranks.size
           << " MPI ranks; each was timed on its rank while the other ranks timed theirs, so ranks sharing a node's "
              "cores or memory slow each other: compare times within this report, not with a report of another rank "
              "count. Everything else is identical to a one-process report.";
    md << "\n\n";
}

// Rank 0's written outputs, once every row is in.
void write_report(const std::vector<scene>& scenes, const std::vector<run_plan>& plans,
                  const std::vector<report_row>& rows, const std::map<const scene*, reference_state>& references,
                  const std::vector<ensemble_outcome>& ensembles, const report_options& options, int rounds,
                  const exchange& ranks, const fs::path& dir, const progress& bar, std::ostream& table) {
    write_work_precision_csv(rows, references, dir);
    std::ostringstream md;
    write_intro(md, options, rounds, ranks);
    for (const scene& s : scenes)
        if (const std::string& why = references.at(&s).failure; !why.empty()) {
            md << "**" << markdown_cell(s.name) << ": no final errors.** " << markdown_cell(why)
               << " The methods' runs, energy errors and blow-ups are in work_precision.csv.\n\n";
            table << s.name << ": no final errors: " << why << "\n";
        }
    fastest_per_level(rows, plans, md, table, dir);
    const bool plots = options.plots && have_gnuplot();
    if (plots) plot_work_precision(rows, plans, dir);
    energy_series_study(scenes, dir, plots);
    std::vector<std::string> files;
    for (const ensemble_outcome& e : ensembles) {
        md << e.summary;
        files.insert(files.end(), e.files.begin(), e.files.end());
        table << e.scene_name << ": " << e.trajectories << " trajectories, " << e.chaotic << " chaotic, " << e.invalid
              << " invalid\n";
    }
    if (options.studies) {
        const study_context c{options.quick, md, dir, bar};
        stability_study(c);
        kepler_099_study(c);
        long_run_study(c);
        extreme_study(c);
        energy_long_span_study(c);
    }
    md << "## Files\n\nwork_precision.csv (every run; unstable runs give the step and time of blow-up and no error "
          "numbers), energy_vs_time.csv"
       << (plots ? ", work_precision.png, energy_vs_time.png" : " (install gnuplot for the PNGs)")
       << (options.studies ? ", stability.csv, kepler_e0.99.csv, long_run.csv, extreme_scales.csv, energy_long_span.csv" : "");
    for (const auto& f : files) md << ", " << f;
    md << ".\n";
    atomic_file summary(dir / "summary.md");
    summary.stream() << md.str();
    summary.commit();
}

}  // namespace

void run_report(const std::vector<scene>& scenes, const report_options& options, std::ostream& out,
                const exchange& ranks) {
    std::vector<problem> problems;
    std::vector<run_plan> plans;
    check_scenes(scenes, options, problems, plans);
    // Under mpirun the (scene, method, dt) runs are dealt round-robin over the
    // ranks; rank 0 makes the references, gathers every rank's results and
    // writes everything. One process is rank 0 of 1.
    const bool writer = ranks.rank == 0;
    const row_filter mine = [&](std::size_t i) { return int(i % std::size_t(ranks.size)) == ranks.rank; };
    std::optional<output_set> outputs;  // written into a staging directory, moved into place together at the end
    if (writer) outputs.emplace(options.out_dir);
    const fs::path dir = writer ? outputs->staging() : fs::path();
    const progress bar{writer && isatty(STDERR_FILENO)};
    const int rounds = options.quick ? 3 : 5;
    std::map<const scene*, reference_state> references;
    if (writer)
        for (std::size_t k = 0; k < scenes.size(); ++k) {
            bar.show(counter(k + 1, scenes.size()) + scenes[k].name + ": reference");
            references[&scenes[k]] = make_reference(scenes[k], problems[k], plans[k], outputs->directory() / "cache");
        }
    std::vector<report_row> rows = rows_of(plans, problems);
    measure_rows(rows, mine, bar);
    time_rows(rows, mine, rounds, options.quick ? 1e-3 : 5e-3, bar);  // each rank times its own rows
    gather_rows(rows, mine, ranks);
    // Scenes with an [ensemble] (the Henon-Heiles chaos map) run it too, over
    // this process's threads and the ranks.
    std::vector<ensemble_outcome> ensembles;
    for (const scene& s : scenes)
        if (s.ensemble) {
            bar.show(s.name + ": ensemble of " + std::to_string(s.ensemble->size()) + " trajectories");
            ensembles.push_back(run_ensemble_scene(s, dir, file_name_part(s.name) + "_", 0, options.max_steps,
                                                   options.plots && have_gnuplot(), ranks));
        }
    if (!writer) return;
    finish_rows(rows, references);
    std::ostringstream table;
    write_report(scenes, plans, rows, references, ensembles, options, rounds, ranks, dir, bar, table);
    const bool drawn = options.plots && fs::exists(dir / "work_precision.png");
    outputs->commit();
    bar.done();
    const fs::path final_dir = outputs->directory();
    out << table.str() << "\nwrote " << (final_dir / "summary.md").string() << ", "
        << (final_dir / "work_precision.csv").string()
        << (drawn ? ", " + (final_dir / "work_precision.png").string() : std::string()) << "\n";
}

}  // namespace sympl::app
