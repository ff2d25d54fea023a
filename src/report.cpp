// The work-precision report: every scene's methods over their sweeps, the
// fastest method per accuracy level against Odeint, and the fixed studies.
#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <memory>
#include <ostream>
#include <set>
#include <sstream>

#include "format.hpp"
#include "loop_area.hpp"
#include "reference.hpp"
#include "studies/study.hpp"
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
};

std::string csv_number(double v) { return v < 0 ? "" : format_number(v, 6); }

// Fastest time to reach `level` for one method (infinity when never reached).
double time_to_reach(const std::vector<row>& rows, const scene& s, const std::string& method, double level) {
    double best = HUGE_VAL;
    for (const row& r : rows)
        if (r.s == &s && r.method->name == method && r.r.stable && r.final_error >= 0 && r.final_error <= level &&
            r.r.seconds >= 0)
            best = std::min(best, r.r.seconds);
    return best;
}

void write_work_precision_csv(const std::vector<row>& rows, const std::map<const scene*, reference_state>& references,
                              const fs::path& dir) {
    atomic_file csv(dir / "work_precision.csv");
    csv.stream() << csv_line({"scene", "method", "kind", "dt", "tolerance", "status", "blowup_step", "blowup_time", "steps",
                              "force_evaluations", "seconds", "max_energy_error", "final_error", "reference_error",
                              "loop_area_error"});
    for (const row& r : rows) {
        const bool ok = r.r.stable;
        csv.stream() << csv_line({r.s->name, r.method->name, entry_of(r.method->kind).label,
                                  r.dt > 0 ? format_number(r.dt, 6) : "", r.tolerance > 0 ? format_number(r.tolerance, 3) : "",
                                  ok ? "stable" : "unstable", ok ? "" : std::to_string(r.r.blowup_step),
                                  ok ? "" : format_number(r.r.blowup_time, 8), ok ? std::to_string(r.r.steps) : "",
                                  ok ? std::to_string(r.r.force_evaluations) : "", ok ? csv_number(r.r.seconds) : "",
                                  ok ? csv_number(r.r.max_energy_error) : "", ok ? csv_number(r.final_error) : "",
                                  format_number(references.at(r.s).error, 3), ok ? csv_number(r.loop_area_error) : ""});
    }
    csv.commit();
}

void plot_work_precision(const std::vector<row>& rows, const std::vector<scene>& scenes, const fs::path& dir) {
    const int cols = scenes.size() > 1 ? 2 : 1, rows_n = int((scenes.size() + 1) / 2);
    atomic_file gp(dir / "work_precision.gp");
    gp.stream() << "set terminal pngcairo size " << 700 * cols << "," << 450 * rows_n << "\nset output "
                << gnuplot_string((dir / "work_precision.png").string())
                << "\nset logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
                << "set xlabel 'wall time [s]'\nset ylabel 'final error (relative)'\nset key outside right font ',8'\n"
                << "set multiplot layout " << rows_n << "," << cols << "\n";
    std::vector<std::unique_ptr<atomic_file>> data_files;
    for (std::size_t k = 0; k < scenes.size(); ++k) {
        const scene& s = scenes[k];
        const fs::path data = dir / ("wp_" + std::to_string(k + 1) + "_" + file_name_part(s.name) + ".dat");
        auto d = std::make_unique<atomic_file>(data);
        for (const method_spec& m : s.methods) {
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
            gp.stream() << (i ? ", " : "") << gnuplot_string(data.string()) << " index " << i << " with linespoints title "
                        << gnuplot_string(s.methods[i].name) << " noenhanced";
        gp.stream() << "\n";
        data_files.push_back(std::move(d));
    }
    gp.stream() << "unset multiplot\n";
    for (auto& d : data_files) d->commit();
    gp.commit();
    run_gnuplot(dir / "work_precision.gp", dir / "work_precision.png");
}

// The section "fastest method per accuracy level", in markdown and as the table printed at the end.
void fastest_per_level(const std::vector<row>& rows, const std::vector<scene>& scenes, std::ostream& md,
                       std::ostream& table) {
    md << "## Fastest method per accuracy level\n\n"
       << "| scene | level | fastest | time [s] | vs odeint_rk4 | vs odeint_dopri5 |\n|---|---|---|---|---|---|\n";
    table << std::left << std::setw(22) << "scene" << std::setw(8) << "level" << std::setw(26) << "fastest" << std::right
          << std::setw(12) << "time [s]" << std::setw(14) << "x odeint_rk4" << std::setw(16) << "x odeint_dopri5" << "\n";
    for (const scene& s : scenes) {
        for (double level : {1e-4, 1e-8, 1e-12}) {
            std::string best;
            double best_t = HUGE_VAL;
            for (const method_spec& m : s.methods) {
                const double t = time_to_reach(rows, s, m.name, level);
                if (t < best_t) best_t = t, best = m.name;
            }
            const double rk = time_to_reach(rows, s, "odeint_rk4", level), dp = time_to_reach(rows, s, "odeint_dopri5", level);
            const auto ratio = [&](double base) {
                return std::isfinite(base) && std::isfinite(best_t) ? format_number(base / best_t, 3) + "x"
                                                                     : std::string("not reached");
            };
            const std::string fastest = std::isfinite(best_t) ? best : "none reached it";
            const std::string time = std::isfinite(best_t) ? format_number(best_t, 3) : "-";
            md << "| " << markdown_cell(s.name) << " | " << format_number(level) << " | " << markdown_cell(fastest) << " | "
               << time << " | " << ratio(rk) << " | " << ratio(dp) << " |\n";
            table << std::left << std::setw(22) << s.name << std::setw(8) << format_number(level) << std::setw(26)
                  << fastest << std::right << std::setw(12) << time << std::setw(14) << ratio(rk) << std::setw(16)
                  << ratio(dp) << "\n";
        }
    }
    md << "\n";
}

}  // namespace

void run_report(const std::vector<scene>& scenes, const report_options& options, std::ostream& out) {
    // Everything is checked before anything runs: names, systems, methods.
    std::set<std::string> names;
    for (const scene& s : scenes)
        if (!names.insert(s.name).second)
            throw scene_error(s.source + ": a second scene named '" + s.name + "'; expected each scene name once");
    std::vector<problem> problems;
    for (const scene& s : scenes) problems.push_back(problem_of(s));

    const fs::path dir = options.out_dir;
    fs::create_directories(dir);
    const progress bar;
    std::vector<row> rows;
    std::map<const scene*, reference_state> references;
    const int repeats = options.quick ? 2 : 5;
    for (std::size_t k = 0; k < scenes.size(); ++k) {
        const scene& s = scenes[k];
        const problem& p = problems[k];
        const std::string head = "[" + std::to_string(k + 1) + "/" + std::to_string(scenes.size()) + "] " + s.name;
        bar.show(head + ": reference");
        const reference_state& ref = references[&s] =
            make_reference(s, p, *std::min_element(s.dt.begin(), s.dt.end()), dir / "cache");
        for (const method_spec& m : s.methods) {
            const bool adaptive = entry_of(m.kind).adaptive;
            for (double v : adaptive ? s.tolerances : s.dt) {
                bar.show(head + ": " + m.name + " " + format_number(v));
                row r{&s, &m, adaptive ? 0.0 : v, adaptive ? v : 0.0, {}, -1};
                run_request rq;
                rq.dt = v;
                rq.tolerance = v;
                rq.energy = p.hamiltonian;
                rq.timing_repeats = repeats;
                r.r = p.run(m, rq, s.t0, s.t_end, p.x0);
                if (r.r.stable) r.final_error = relative_difference(r.r.final_state, ref.x);
                if (r.r.stable && s.output.loop_area) r.loop_area_error = loop_area_error(p, m, rq, s.t0, s.t_end);
                rows.push_back(std::move(r));
            }
        }
    }
    write_work_precision_csv(rows, references, dir);

    std::ostringstream md, table;
    md << "# sympl work-precision report\n\n" << (options.quick ? "Quick run (`--quick`): short spans, few steps.\n\n" : "")
       << "Final error: max |x - x_ref| / max |x_ref| at t_end against the exact solution or a Sofroniou-Spaletta 10 "
          "reference in long double (its own error in work_precision.csv). Wall time: best of "
       << repeats << " runs with nothing observed. Speed-up: time Odeint needs for the same accuracy divided by the "
          "fastest method's time (log-linear interpolation is not used: each is the fastest measured run that reaches "
          "the level).\n\n";
    fastest_per_level(rows, scenes, md, table);
    const bool plots = options.plots && have_gnuplot();
    if (plots) plot_work_precision(rows, scenes, dir);
    energy_series_study(scenes, dir, plots);
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
       << (options.studies ? ", stability.csv, kepler_e0.99.csv, long_run.csv, extreme_scales.csv" : "") << ".\n";
    atomic_file summary(dir / "summary.md");
    summary.stream() << md.str();
    summary.commit();
    bar.done();
    out << table.str() << "\nwrote " << (dir / "summary.md").string() << ", " << (dir / "work_precision.csv").string()
        << (plots && fs::exists(dir / "work_precision.png") ? ", " + (dir / "work_precision.png").string() : std::string())
        << "\n";
}

}  // namespace sympl::app
