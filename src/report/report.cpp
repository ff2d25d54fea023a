// The work-precision report: every scene's methods over their sweeps, the
// fastest method per accuracy level against Odeint, and the fixed studies.
// Compute (report_rows), gather (MPI), write (report_write, summary.md).
#include "report/report.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <ostream>
#include <set>
#include <sstream>

#include "output/format.hpp"
#include "output/output_set.hpp"
#include "report/report_rows.hpp"
#include "report/report_write.hpp"
#include "report/timing.hpp"
#include "output/writers.hpp"

#include <sympl/parallel/ensemble.hpp>
#ifdef _OPENMP
#include <omp.h>
#endif

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

// Everything is checked before anything runs: names, systems, methods, sizes.
void check_scenes(const std::vector<scene>& scenes, const report_options& options, std::vector<runnable_system>& systems,
                  std::vector<run_plan>& plans) {
    std::set<std::string> names;
    for (const scene& s : scenes)
        if (!names.insert(s.name).second)
            throw scene_error(printable(s.source) + ": a second scene named '" + s.name + "'; expected each scene name once");
    systems.reserve(scenes.size());  // plans point into systems and scenes: no reallocation after this
    for (const scene& s : scenes)
        if (s.test_particles)  // a map of one method, not a comparison of methods
            throw scene_error(printable(s.source) + ": a scene with [test_particles] is a MEGNO map, not a comparison of "
                              "methods; expected it run by `sympl run`");
    for (const scene& s : scenes) {
        systems.push_back(system_of(s));
        plans.push_back(plan_runs(s, systems.back(), sweep_use::whole));
        check_run_size(plans.back(), options.max_steps);
    }
}

// A reference whose two runs (dt and 2 dt) disagree this much has followed
// chaotic motion: nearby orbits separate, and a final error would measure the
// Lyapunov exponent, not the method.
constexpr double chaotic_reference = 1e-6;

// The threads `threads` asks for (0: OpenMP's default).
int threads_used(int threads) {
#ifdef _OPENMP
    return threads > 0 ? threads : omp_get_max_threads();
#else
    (void)threads;
    return 1;
#endif
}

// Wall time of the report's phases, each lap from the last.
class phase_clock {
public:
    void lap(const std::string& name) {
        const auto now = std::chrono::steady_clock::now();
        text_ += (text_.empty() ? "" : ", ") + name + " " +
                 format_number(std::chrono::duration<double>(now - last_).count(), 3) + " s";
        last_ = now;
    }
    const std::string& text() const { return text_; }

private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
    std::string text_;
};

void write_intro(std::ostream& md, const report_options& options, int rounds, const exchange& ranks) {
    md << "# sympl work-precision report\n\n"
       << (!options.studies ? std::string(options.quick ? "Quick run (`--quick`): each scene's [quick] span and sweeps "
                                                           "where it has them.\n\n"
                                                         : "Spans and sweeps as each scene sets them.\n\n")
           : options.quick ? "Quick run (`--quick`): spans of 1e3 characteristic periods (1e4 in the full report), "
                             "shorter sweeps.\n\n"
                           : "Spans of 1e4 characteristic periods (each scene's file says which period and how many).\n\n")
       << "Two measures, each with its own table and figure: the final error, max |x - x_ref| / max |x_ref| at t_end "
          "against the exact solution or a Sofroniou-Spaletta 10 reference in long double (its own error in "
          "work_precision.csv), for regular motion; and the largest relative energy error over the run, for every "
          "Hamiltonian scene. Wall time: median of "
       << rounds << " measurements with nothing observed, taken in rounds over all runs (interleaved between methods); "
          "each measurement repeats a run that lasts less than "
       << (options.quick ? "1 ms" : "5 ms") << " until it has (min and max in work_precision.csv). Timer: "
       << "std::chrono::steady_clock, smallest step between two readings " << format_number(clock_resolution() * 1e9, 2)
       << " ns here.";
    if (const int n = threads_used(options.threads); n > 1)
        md << " " << n << " runs were timed side by side, one per thread (`--threads 1` times one at a time); on "
           << "a machine with fewer free cores than threads they slow each other, evenly over the rounds.";
    if (ranks.size > 1)
        md << " The runs were dealt round-robin over " << ranks.size
           << " MPI ranks; each was timed on its rank while the other ranks timed theirs, so ranks sharing a node's "
              "cores or memory slow each other: compare times within this report, not with a report of another rank "
              "count. Everything else is identical to a one-process report.";
    md << "\n\n";
}

// summary.md's list of files: what is in the directory, nothing else.
void write_files(std::ostream& md, const fs::path& dir, bool plots_asked) {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir)) {
        const std::string ext = entry.path().extension().string();
        if (entry.is_regular_file() && (ext == ".csv" || ext == ".png")) names.push_back(entry.path().filename().string());
    }
    std::sort(names.begin(), names.end());
    md << "## Files\n\n";
    for (std::size_t i = 0; i < names.size(); ++i) md << (i ? ", " : "") << names[i];
    md << ". work_precision.csv has every run (unstable runs give the step and time of blow-up and no error numbers)"
       << (plots_asked && !have_gnuplot() ? "; install gnuplot for the PNGs" : "") << ".\n";
}

// Rank 0's written outputs, once every row is in.
void write_report(const std::vector<scene>& scenes, const std::vector<run_plan>& plans,
                  const std::vector<report_row>& rows, const std::map<const scene*, reference_state>& references,
                  const std::vector<ensemble_outcome>& ensembles, const report_options& options, int rounds,
                  const exchange& ranks, const fs::path& dir, const progress& bar, std::ostream& table,
                  phase_clock& phases) {
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
    if (plots) {
        plot_work_precision(rows, plans, dir, error_measure::final_error);
        plot_work_precision(rows, plans, dir, error_measure::energy_error);
    }
    // The energy series and the fixed studies side by side on the threads,
    // each into its own part of summary.md, appended in this order.
    using study = void (*)(const study_context&);
    const std::vector<study> studies = options.studies ? std::vector<study>{stability_study, kepler_099_study,
                                                                            long_run_study, extreme_study,
                                                                            energy_long_span_study}
                                                       : std::vector<study>{};
    std::vector<std::ostringstream> parts(1 + studies.size());
    for_each_in_parallel(parts.size(), options.threads, [&](std::size_t k) {
        if (k == 0) energy_series_study(scenes, rows, dir, plots, parts[0]);
        else studies[k - 1](study_context{options.quick, parts[k], dir, bar});
    });
    md << parts[0].str();
    for (const ensemble_outcome& e : ensembles) {
        md << e.summary;
        table << e.scene_name << ": " << e.trajectories << " trajectories, " << e.chaotic << " chaotic, " << e.invalid
              << " invalid\n";
    }
    for (std::size_t k = 1; k < parts.size(); ++k) md << parts[k].str();
    phases.lap("tables, figures and studies");
    const int threads = threads_used(options.threads);
    md << "## Where the time went\n\nWall time of this report's phases on " << threads << " thread"
       << (threads == 1 ? "" : "s") << ": " << phases.text() << ".\n\n";
    table << "time: " << phases.text() << "\n";
    write_files(md, dir, options.plots);
    atomic_file summary(dir / "summary.md");
    summary.stream() << md.str();
    summary.commit();
}

}  // namespace

void run_report(const std::vector<scene>& scenes, const report_options& options, std::ostream& out,
                const exchange& ranks) {
    std::vector<runnable_system> systems;
    std::vector<run_plan> plans;
    check_scenes(scenes, options, systems, plans);
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
    phase_clock phases;
    // The references and the measured runs side by side on the threads (the
    // measured runs do not need the references; the timing rounds do).
    std::map<const scene*, reference_state> references;  // rank 0's
    std::vector<std::function<void()>> reference_runs;
    if (writer) {
        for (const scene& s : scenes) references[&s];  // every key in place before the threads fill the values
        const fs::path cache = outputs->directory() / "cache";
        fs::create_directories(cache);
        for (std::size_t k = 0; k < scenes.size(); ++k)
            reference_runs.push_back([&, k, cache] {
                reference_state& ref = references.at(&scenes[k]);
                ref = make_reference(scenes[k], systems[k], plans[k], cache, threads_used(options.threads) > 1);
                if (ref.failure.empty() && ref.error > chaotic_reference)
                    ref.failure = "its two references (" + ref.kind + " and twice that step) differ by " +
                                  format_number(ref.error, 2) + ": over this span nearby orbits separate (chaotic "
                                  "motion), so a final error would measure the Lyapunov exponent, not the method. The "
                                  "energy error still measures the method.";
            });
    }
    std::vector<report_row> rows = rows_of(plans, systems);
    measure_rows(rows, mine, bar, options.threads, reference_runs);
    phases.lap("references and measured runs");
    time_rows(rows, mine, rounds, options.quick ? 1e-3 : 5e-3, bar, references, options.threads);  // each rank its own
    phases.lap("timing rounds");
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
    phases.lap("ensembles");
    if (!writer) return;
    finish_rows(rows, references);
    std::ostringstream table;
    write_report(scenes, plans, rows, references, ensembles, options, rounds, ranks, dir, bar, table, phases);
    const bool drawn = options.plots && fs::exists(dir / "work_precision.png");
    outputs->commit();
    bar.done();
    const fs::path final_dir = outputs->directory();
    out << table.str() << "\nwrote " << (final_dir / "summary.md").string() << ", "
        << (final_dir / "work_precision.csv").string()
        << (drawn ? ", " + (final_dir / "work_precision.png").string() : std::string()) << "\n";
}

}  // namespace sympl::app
