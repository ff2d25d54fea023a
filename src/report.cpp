// The work-precision report: every scene's methods over their sweeps, the
// fastest method per accuracy level against Odeint, and the fixed studies.
#include "report.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <map>
#include <optional>
#include <memory>
#include <ostream>
#include <set>
#include <sstream>

#include "format.hpp"
#include "loop_area.hpp"
#include "ensemble_run.hpp"
#include "output_set.hpp"
#include "reference.hpp"
#include "studies/study.hpp"
#include "work_precision.hpp"
#include "writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

struct row {
    const scene* s;
    const method_spec* method;
    double dt = 0, tolerance = 0;
    run_result r;
    double final_error = -1;
    double loop_area_error = -1;  // only where the scene asks for it
    std::vector<double> times;    // one per timing round
    double setting() const { return dt > 0 ? dt : tolerance; }  // the sweep's value: dt or tolerance
};

std::string csv_number(double v) { return v < 0 ? "" : format_number(v, 6); }

// A row's measurements as text, for the gather to rank 0 under MPI: numbers
// as the shortest text that reads back as the same double (to_chars), the
// failure message with its length. Rank 0 then has exactly what it would
// have measured itself, timings aside.
std::string row_record(std::size_t index, const row& r) {
    std::string t = std::to_string(index);
    const auto number = [&](double v) { t += ' ' + shortest(v); };
    const run_result& m = r.r;
    t += ' ' + std::to_string(int(m.stable)) + ' ' + std::to_string(m.blowup_step);
    number(m.blowup_time);
    t += ' ' + std::to_string(m.steps) + ' ' + std::to_string(m.force_evaluations);
    number(m.max_energy_error);
    number(r.loop_area_error);
    t += ' ' + std::to_string(m.final_state.size());
    for (double v : m.final_state) number(v);
    t += ' ' + std::to_string(r.times.size());
    for (double v : r.times) number(v);
    t += ' ' + std::to_string(m.failure.size()) + ' ' + m.failure + '\n';
    return t;
}

// Reads the records of one rank's block into `rows`.
void read_row_records(const std::string& block, std::vector<row>& rows) {
    const char* at = block.data();
    const char* const end = block.data() + block.size();
    const auto fail = [] {
        throw error("sympl report: a rank sent a malformed result record; expected the same sympl on every rank");
    };
    const auto word = [&](auto& v) {
        while (at < end && (*at == ' ' || *at == '\n')) ++at;
        const auto [next, ec] = std::from_chars(at, end, v);
        if (ec != std::errc()) fail();
        at = next;
    };
    const auto count = [&](std::size_t largest) {
        std::size_t n = 0;
        word(n);
        if (n > largest) fail();
        return n;
    };
    while (true) {
        while (at < end && *at == '\n') ++at;
        if (at == end) return;
        row& r = rows.at(count(rows.size() - 1));
        run_result& m = r.r;
        m.stable = count(1) == 1;
        word(m.blowup_step);
        word(m.blowup_time);
        word(m.steps);
        word(m.force_evaluations);
        word(m.max_energy_error);
        word(r.loop_area_error);
        m.final_state.resize(count(std::size_t(1) << 30));
        for (double& v : m.final_state) word(v);
        r.times.resize(count(1000));
        for (double& v : r.times) word(v);
        const std::size_t n = count(std::size_t(1) << 20);
        if (at == end || *at != ' ' || std::size_t(end - at - 1) < n) fail();
        m.failure.assign(at + 1, n);
        at += 1 + n;
    }
}

// One method's measured runs on one scene, as a work-precision curve.
std::vector<work_point> curve_of(const std::vector<row>& rows, const scene& s, const method_spec& m) {
    std::vector<work_point> curve;
    for (const row& r : rows)
        if (r.s == &s && r.method == &m && r.r.stable && r.final_error >= 0)
            curve.push_back({r.r.seconds, r.final_error, r.setting()});
    return curve;
}

// The fastest method of a group (sympl's or Odeint's) at one level.
struct verdict {
    const method_spec* method = nullptr;
    std::optional<time_to_accuracy> reach;
    double best_error = HUGE_VAL;  // the smallest error any of the group reached
};

verdict fastest(const std::vector<row>& rows, const scene& s, double level, bool odeint) {
    verdict v;
    for (const method_spec& m : s.methods) {
        if (entry_of(m.kind).odeint != odeint) continue;
        const auto curve = curve_of(rows, s, m);
        for (const work_point& p : curve) v.best_error = std::min(v.best_error, p.error);
        const auto reach = time_to_reach(curve, level);
        if (reach && (!v.reach || reach->seconds < v.reach->seconds)) v.method = &m, v.reach = reach;
    }
    return v;
}

void write_work_precision_csv(const std::vector<row>& rows, const std::map<const scene*, reference_state>& references,
                              const fs::path& dir) {
    atomic_file csv(dir / "work_precision.csv");
    csv.stream() << csv_line({"scene", "method", "kind", "dt", "tolerance", "status", "blowup_step", "blowup_time", "steps",
                              "force_evaluations", "seconds", "seconds_min", "seconds_max", "max_energy_error",
                              "final_error", "reference_error", "loop_area_error"});
    for (const row& r : rows) {
        const bool ok = r.r.stable;
        csv.stream() << csv_line({r.s->name, r.method->name, entry_of(r.method->kind).label,
                                  r.dt > 0 ? format_number(r.dt, 6) : "", r.tolerance > 0 ? format_number(r.tolerance, 3) : "",
                                  ok ? "stable" : "unstable", ok ? "" : std::to_string(r.r.blowup_step),
                                  ok ? "" : format_number(r.r.blowup_time, 8), ok ? std::to_string(r.r.steps) : "",
                                  ok ? std::to_string(r.r.force_evaluations) : "", ok ? csv_number(r.r.seconds) : "",
                                  ok ? csv_number(r.r.seconds_min) : "", ok ? csv_number(r.r.seconds_max) : "",
                                  ok ? csv_number(r.r.max_energy_error) : "", ok ? csv_number(r.final_error) : "",
                                  csv_number(references.at(r.s).error), ok ? csv_number(r.loop_area_error) : ""});
    }
    csv.commit();
}

void plot_work_precision(const std::vector<row>& rows, const std::vector<scene>& scenes, const fs::path& dir) {
    const int cols = scenes.size() > 1 ? 2 : 1, rows_n = int((scenes.size() + 1) / 2);
    atomic_file gp(dir / "work_precision.gp");
    gp.stream() << "set terminal pngcairo size " << 700 * cols << "," << 450 * rows_n << "\nset output "
                << gnuplot_string("work_precision.png")
                << "\nset logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
                << "set xlabel 'wall time [s]'\nset ylabel 'final error (relative)'\nset key outside right font ',8'\n"
                << "set multiplot layout " << rows_n << "," << cols << "\n";
    std::vector<std::unique_ptr<atomic_file>> data_files;
    for (std::size_t k = 0; k < scenes.size(); ++k) {
        const scene& s = scenes[k];
        const std::string data = "wp_" + std::to_string(k + 1) + "_" + file_name_part(s.name) + ".dat";
        auto d = std::make_unique<atomic_file>(dir / data);
        for (const scene_method& m : s.methods) {
            int points = 0;
            for (const row& r : rows)
                if (r.s == &s && r.method == &m && r.r.stable && r.final_error > 0 && r.r.seconds > 0) {
                    d->stream() << r.r.seconds << " " << r.final_error << "\n";
                    ++points;
                }
            if (points == 0) d->stream() << "NaN NaN\n";
            d->stream() << "\n\n";
        }
        gp.stream() << "set title " << gnuplot_string(s.name) << " noenhanced\nplot ";
        for (std::size_t i = 0; i < s.methods.size(); ++i)
            gp.stream() << (i ? ", " : "") << gnuplot_string(data) << " index " << i << " with linespoints title "
                        << gnuplot_string(s.methods[i].name) << " noenhanced";
        gp.stream() << "\n";
        data_files.push_back(std::move(d));
    }
    gp.stream() << "unset multiplot\n";
    for (auto& d : data_files) d->commit();
    gp.commit();
    run_gnuplot(dir / "work_precision.gp", dir / "work_precision.png");
}

// The section "fastest method per accuracy level" in markdown, the table
// printed at the end, and time_to_accuracy.csv with the bracketing runs.
void fastest_per_level(const std::vector<row>& rows, const std::vector<scene>& scenes, std::ostream& md,
                       std::ostream& table, const fs::path& dir) {
    md << "## Fastest method per accuracy level\n\n"
       << "Time to a final error of 1e-4, 1e-6, 1e-8, 1e-10 and 1e-12, read off each method's work-precision curve by log-log "
          "interpolation between the two runs that bracket the level (time_to_accuracy.csv lists them). Odeint: the "
          "fastest of the Odeint steppers of the scene over all their tolerances.\n\n"
       << "| scene | level | fastest sympl method | time [s] | fastest Odeint method | time [s] | Odeint / sympl |\n"
       << "|---|---|---|---|---|---|---|\n";
    table << std::left << std::setw(22) << "scene" << std::setw(8) << "level" << std::setw(38) << "fastest sympl"
          << std::right << std::setw(10) << "time [s]" << "  " << std::left << std::setw(24) << "fastest Odeint" << std::right
          << std::setw(10) << "time [s]" << std::setw(10) << "ratio" << "\n";
    atomic_file csv(dir / "time_to_accuracy.csv");
    csv.stream() << csv_line({"scene", "level", "method", "seconds", "bracketed", "above_dt_or_tolerance", "above_error",
                              "above_seconds", "below_dt_or_tolerance", "below_error", "below_seconds"});
    for (const scene& s : scenes) {
        for (double level : {1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
            for (const method_spec& m : s.methods)
                if (const auto r = time_to_reach(curve_of(rows, s, m), level))
                    csv.stream() << csv_line({s.name, format_number(level), m.name, format_number(r->seconds, 6),
                                              r->bracketed ? "yes" : "no", format_number(r->above.parameter, 6),
                                              format_number(r->above.error, 6), format_number(r->above.seconds, 6),
                                              format_number(r->below.parameter, 6), format_number(r->below.error, 6),
                                              format_number(r->below.seconds, 6)});
            const verdict ours = fastest(rows, s, level, false), theirs = fastest(rows, s, level, true);
            const auto name = [](const verdict& v) {
                if (v.method) return v.method->name;
                return std::isfinite(v.best_error) ? "not reached (best " + format_number(v.best_error, 2) + ")"
                                                   : std::string("none");
            };
            const auto time = [](const verdict& v) { return v.reach ? format_number(v.reach->seconds, 3) : "-"; };
            const std::string ratio =
                ours.reach && theirs.reach ? format_number(theirs.reach->seconds / ours.reach->seconds, 3) + "x" : "-";
            md << "| " << markdown_cell(s.name) << " | " << format_number(level) << " | " << markdown_cell(name(ours))
               << " | " << time(ours) << " | " << markdown_cell(name(theirs)) << " | " << time(theirs) << " | " << ratio
               << " |\n";
            table << std::left << std::setw(22) << s.name << std::setw(8) << format_number(level) << std::setw(38)
                  << name(ours) << std::right << std::setw(10) << time(ours) << "  " << std::left << std::setw(24)
                  << name(theirs) << std::right << std::setw(10) << time(theirs) << std::setw(10) << ratio << "\n";
        }
    }
    csv.commit();
    md << "\n";
}

}  // namespace

void run_report(const std::vector<scene>& scenes, const report_options& options, std::ostream& out,
                const exchange& ranks) {
    // Everything is checked before anything runs: names, systems, methods.
    std::set<std::string> names;
    for (const scene& s : scenes)
        if (!names.insert(s.name).second)
            throw scene_error(s.source + ": a second scene named '" + s.name + "'; expected each scene name once");
    std::vector<problem> problems;
    for (const scene& s : scenes) {
        problems.push_back(problem_of(s));
        check_run_size(s, problems.back(), options.max_steps, true);
    }

    // Under mpirun the (scene, method, dt) runs are dealt round-robin over the
    // ranks; rank 0 makes the references, gathers every rank's results and
    // writes everything. One process is rank 0 of 1.
    const bool writer = ranks.rank == 0;
    const auto mine = [&](std::size_t i) { return int(i % std::size_t(ranks.size)) == ranks.rank; };
    // Written into a staging directory and moved into place together at the end.
    std::optional<output_set> outputs;
    if (writer) outputs.emplace(options.out_dir);
    const fs::path dir = writer ? outputs->staging() : fs::path();
    const progress bar{writer && isatty(STDERR_FILENO)};
    const int rounds = options.quick ? 3 : 5;
    std::map<const scene*, reference_state> references;
    if (writer)
        for (std::size_t k = 0; k < scenes.size(); ++k) {
            bar.show("[" + std::to_string(k + 1) + "/" + std::to_string(scenes.size()) + "] " + scenes[k].name + ": reference");
            references[&scenes[k]] = make_reference(scenes[k], problems[k], finest_step(scenes[k]), outputs->directory() / "cache");
        }
    std::vector<row> rows;
    for (const scene& s : scenes)
        for (const scene_method& m : s.methods) {
            const bool adaptive = entry_of(m.kind).adaptive;
            for (double v : sweep_of(s, m)) rows.push_back(row{&s, &m, adaptive ? 0.0 : v, adaptive ? v : 0.0, {}, -1, -1, {}});
        }
    const auto problem_of_row = [&](const row& r) -> const problem& { return problems[std::size_t(r.s - scenes.data())]; };
    for (std::size_t i = 0; i < rows.size(); ++i) {
        if (!mine(i)) continue;
        row& r = rows[i];
        const scene& s = *r.s;
        const problem& p = problem_of_row(r);
        const std::string head = "[" + std::to_string(i + 1) + "/" + std::to_string(rows.size()) + "] " + s.name + ": " +
                                 r.method->name + " " + format_number(r.setting());
        bar.show(head);
        run_request rq;
        rq.dt = r.setting();
        rq.tolerance = rq.dt;
        rq.energy = p.hamiltonian;
        rq.timing_repeats = 0;
        if (bar.tty)
            rq.progress = [&](double t) {
                bar.show(head + ", t = " + format_number(t, 6) + " of " + format_number(s.t_end, 6));
            };
        r.r = p.run(*r.method, rq, s.t0, s.t_end, p.x0);
        if (r.r.stable && s.output.loop_area) r.loop_area_error = loop_area_error(p, *r.method, rq, s.t0, s.t_end);
    }
    // Timing: rounds over every stable run, interleaved between methods, so a
    // slow spell of a shared machine falls on all of them; median, min, max.
    // Under MPI each rank times its own runs while the others time theirs.
    for (int round = 0; round < rounds; ++round) {
        bar.show("timing, round " + std::to_string(round + 1) + " of " + std::to_string(rounds));
        for (std::size_t i = 0; i < rows.size(); ++i) {
            row& r = rows[i];
            if (!mine(i) || !r.r.stable) continue;
            run_request rq;
            rq.dt = r.setting();
            rq.tolerance = rq.dt;
            rq.observed = false;
            rq.timing_repeats = 1;
            rq.min_measurement = options.quick ? 1e-3 : 5e-3;
            r.times.push_back(problem_of_row(r).run(*r.method, rq, r.s->t0, r.s->t_end, problem_of_row(r).x0).seconds);
        }
    }
    if (ranks.size > 1) {
        std::string records;
        for (std::size_t i = 0; i < rows.size(); ++i)
            if (mine(i)) records += row_record(i, rows[i]);
        for (const std::string& block : ranks.gather(records)) read_row_records(block, rows);
    }
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
    for (row& r : rows) {
        const reference_state& ref = references.at(r.s);
        if (r.r.stable && ref.failure.empty()) r.final_error = relative_difference(r.r.final_state, ref.x);
        if (r.times.empty()) continue;
        std::sort(r.times.begin(), r.times.end());
        r.r.seconds = r.times[r.times.size() / 2];
        r.r.seconds_min = r.times.front();
        r.r.seconds_max = r.times.back();
    }
    write_work_precision_csv(rows, references, dir);

    std::ostringstream md, table;
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
    for (const scene& s : scenes)
        if (const std::string& why = references.at(&s).failure; !why.empty()) {
            md << "**" << markdown_cell(s.name) << ": no final errors.** " << markdown_cell(why)
               << " The methods' runs, energy errors and blow-ups are in work_precision.csv.\n\n";
            table << s.name << ": no final errors: " << why << "\n";
        }
    fastest_per_level(rows, scenes, md, table, dir);
    const bool plots = options.plots && have_gnuplot();
    if (plots) plot_work_precision(rows, scenes, dir);
    energy_series_study(scenes, dir, plots);
    std::vector<std::string> ensemble_files;
    for (const ensemble_outcome& e : ensembles) {
        md << e.summary;
        ensemble_files.insert(ensemble_files.end(), e.files.begin(), e.files.end());
    }
    for (std::size_t k = 0, j = 0; k < scenes.size(); ++k)
        if (scenes[k].ensemble) {
            const ensemble_outcome& e = ensembles[j++];
            table << scenes[k].name << ": " << e.trajectories << " trajectories, " << e.chaotic << " chaotic, " << e.invalid
                  << " invalid\n";
        }
    if (options.studies) {
        const study_context c{options.quick, md, dir, bar};
        stability_study(c);
        kepler_099_study(c);
        long_run_study(c);
        extreme_study(c);
    }
    md << "## Files\n\nwork_precision.csv (every run; unstable runs give the step and time of blow-up and no error "
          "numbers), energy_vs_time.csv"
       << (plots ? ", work_precision.png, energy_vs_time.png" : " (install gnuplot for the PNGs)")
       << (options.studies ? ", stability.csv, kepler_e0.99.csv, long_run.csv, extreme_scales.csv" : "");
    for (const auto& f : ensemble_files) md << ", " << f;
    md << ".\n";
    atomic_file summary(dir / "summary.md");
    summary.stream() << md.str();
    summary.commit();
    const bool drawn = plots && fs::exists(dir / "work_precision.png");
    outputs->commit();
    bar.done();
    const fs::path final_dir = outputs->directory();
    out << table.str() << "\nwrote " << (final_dir / "summary.md").string() << ", "
        << (final_dir / "work_precision.csv").string()
        << (drawn ? ", " + (final_dir / "work_precision.png").string() : std::string()) << "\n";
}

}  // namespace sympl::app
