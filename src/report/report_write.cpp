// The report's CSV, figure and fastest-method tables.
#include "report/report_write.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>

#include "output/format.hpp"
#include "report/work_precision.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

std::string csv_number(double v) { return v < 0 ? "" : format_number(v, 6); }

// One method's measured runs on one scene, as a work-precision curve of the
// given measure. Runs whose error reached order one are no solution at any
// level: they are listed apart (order_one_runs), not drawn or interpolated.
std::vector<work_point> curve_of(const std::vector<report_row>& rows, const scene_method& m, error_measure by) {
    std::vector<work_point> curve;
    for (const report_row& r : rows)
        if (&r.method() == &m && r.r.stable && measured(r, by) >= 0 && measured(r, by) < order_one)
            curve.push_back({r.r.seconds, measured(r, by), r.run->setting(), r.r.seconds_min, r.r.seconds_max});
    return curve;
}

// Two times closer than this factor are a tie: on an idle machine two runs of
// one program put 95% of the report's timed rows within 3% of each other and
// 99% within 8% (docs/scenes.md, "Ties"), so which of two methods 5% apart
// comes first is not a property of the methods. On a busy machine the timing
// rounds themselves say how far apart they spread: b is tied with a faster a
// when b's fastest round is faster than a's slowest, too.
constexpr double tie_factor = 1.05;

bool tied(const time_to_accuracy& faster, const time_to_accuracy& slower) {
    return slower.seconds <= faster.seconds * tie_factor || slower.seconds_min <= faster.seconds_max;
}

// The fastest method of a group (sympl's or Odeint's) at one level, and the
// runner-up when it is within a tie of it.
struct verdict {
    const method_spec* method = nullptr;
    std::optional<time_to_accuracy> reach;
    const method_spec* tied = nullptr;  // the runner-up, when within tie_factor
    double best_error = HUGE_VAL;       // the smallest error any of the group reached
};

verdict fastest(const std::vector<report_row>& rows, const scene& s, double level, bool odeint, error_measure by) {
    verdict v;
    const method_spec* second = nullptr;
    std::optional<time_to_accuracy> second_reach;
    for (const scene_method& m : s.methods) {
        if (entry_of(m.kind).odeint != odeint) continue;
        const auto curve = curve_of(rows, m, by);
        for (const work_point& p : curve) v.best_error = std::min(v.best_error, p.error);
        const auto reach = time_to_reach(curve, level);
        if (!reach) continue;
        if (!v.reach || reach->seconds < v.reach->seconds) {
            if (v.reach) second = v.method, second_reach = v.reach;
            v.method = &m, v.reach = reach;
        } else if (!second_reach || reach->seconds < second_reach->seconds) {
            second = &m, second_reach = reach;
        }
    }
    if (second && tied(*v.reach, *second_reach)) v.tied = second;
    return v;
}

// Whether a scene has the measure at all: final errors need a reference, energy errors an energy.
bool scene_has(const std::vector<report_row>& rows, const scene& s, error_measure by) {
    for (const report_row& r : rows)
        if (r.s == &s && r.r.stable && measured(r, by) >= 0) return true;
    return false;
}

}  // namespace

bool has_sweep(const run_plan& plan) {
    for (const scene_method& m : plan.s->methods)
        if (plan.sweep_length(m) > 1) return true;
    return false;
}

void write_work_precision_csv(const std::vector<report_row>& rows,
                              const std::map<const scene*, reference_state>& references, const fs::path& dir) {
    atomic_file csv(dir / "work_precision.csv");
    csv.stream() << csv_line({"scene", "method", "kind", "dt", "tolerance", "status", "blowup_step", "blowup_time", "steps",
                              "force_evaluations", "seconds", "seconds_min", "seconds_max", "max_energy_error",
                              "final_error", "reference_error", "loop_area_error", "path"});
    for (const report_row& r : rows) {
        const bool ok = r.r.stable;
        const planned_run& p = *r.run;
        csv.stream() << csv_line({r.s->name, r.method().name, entry_of(r.method().kind).label,
                                  p.dt > 0 ? format_number(p.dt, 6) : "", p.tolerance > 0 ? format_number(p.tolerance, 3) : "",
                                  ok ? "stable" : "unstable", ok ? "" : std::to_string(r.r.blowup_step),
                                  ok ? "" : format_number(r.r.blowup_time, 8), ok ? std::to_string(r.r.steps) : "",
                                  ok ? std::to_string(r.r.force_evaluations) : "", ok ? csv_number(r.r.seconds) : "",
                                  ok ? csv_number(r.r.seconds_min) : "", ok ? csv_number(r.r.seconds_max) : "",
                                  ok ? csv_number(r.r.max_energy_error) : "", ok ? csv_number(r.final_error) : "",
                                  csv_number(references.at(r.s).error), ok ? csv_number(r.loop_area_error) : "",
                                  r.r.generic ? "generic" : "compiled"});
    }
    csv.commit();
}

namespace {

const char* measure_name(error_measure by) { return by == error_measure::final_error ? "final error" : "max energy error"; }

constexpr double levels[] = {1e-4, 1e-6, 1e-8, 1e-10, 1e-12};

// The tightest level both sympl and Odeint reach on a scene, for the figure's
// title: "fastest at 1e-10: ..."; nullopt when they share none.
std::optional<double> shared_level(const std::vector<report_row>& rows, const scene& s, error_measure by) {
    std::optional<double> found;
    for (double level : levels)
        if (fastest(rows, s, level, false, by).method && fastest(rows, s, level, true, by).method) found = level;
    return found;
}

// A palette of ten colours told apart by most eyes (Okabe & Ito's eight and
// two darker ones); with 5 dash types and markers a panel of 20 methods still
// draws each curve its own way.
const char* const palette[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7", "#e69f00",
                               "#56b4e9", "#000000", "#8b4513", "#7f7f7f", "#6a3d9a"};

}  // namespace

void plot_work_precision(const std::vector<report_row>& rows, const std::vector<run_plan>& plans, const fs::path& dir,
                         error_measure by) {
    std::vector<const run_plan*> panels;
    for (const run_plan& p : plans)
        if (has_sweep(p) && scene_has(rows, *p.s, by)) panels.push_back(&p);
    if (panels.empty()) return;
    const std::string stem = by == error_measure::final_error ? "work_precision" : "energy_precision";
    const int cols = panels.size() > 1 ? 2 : 1, rows_n = int((panels.size() + 1) / 2);
    atomic_file gp(dir / (stem + ".gp"));
    gp.stream() << "set terminal pngcairo size " << 1000 * cols << "," << 520 * rows_n << " font ',10'\nset output "
                << gnuplot_string(stem + ".png") << "\nset logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
                << "set xlabel 'wall time [s]'\nset ylabel " << gnuplot_string(std::string(measure_name(by)) + " (relative)")
                << "\nset grid\nset key outside right top font ',8' noenhanced spacing 0.9\n"
                << "set multiplot layout " << rows_n << "," << cols << "\n";
    std::vector<std::unique_ptr<atomic_file>> data_files;
    for (std::size_t k = 0; k < panels.size(); ++k) {
        const scene& s = *panels[k]->s;
        const std::string data = stem + "_" + std::to_string(k + 1) + "_" + file_name_part(s.name) + ".dat";
        auto d = std::make_unique<atomic_file>(dir / data);
        for (const scene_method& m : s.methods) {
            int points = 0;
            for (const work_point& p : curve_of(rows, m, by))
                if (p.error > 0 && p.seconds > 0) {
                    d->stream() << p.seconds << " " << p.error << "\n";
                    ++points;
                }
            if (points == 0) d->stream() << "NaN NaN\n";
            d->stream() << "\n\n";
        }
        // The title as gnuplot string expressions: every name inside single
        // quotes (gnuplot_string), the line break the only text between them,
        // so no scene or table name can end the string and add a command.
        std::string title = gnuplot_string(s.name);
        if (const auto level = shared_level(rows, s, by))
            title += ".\"\\n\"." + gnuplot_string("fastest at " + format_number(*level) + ": " +
                                                  fastest(rows, s, *level, false, by).method->name + " (sympl), " +
                                                  fastest(rows, s, *level, true, by).method->name + " (Odeint)");
        gp.stream() << "set title " << title << " noenhanced\nplot ";
        for (std::size_t i = 0; i < s.methods.size(); ++i) {
            const bool odeint = entry_of(s.methods[i].kind).odeint;
            gp.stream() << (i ? ", " : "") << gnuplot_string(data) << " index " << i << " with linespoints lw 1.6 dt "
                        << (odeint ? 2 : 1 + int(i / 10) % 4 * 2) << " pt " << 1 + int(i % 13) << " ps 0.9 lc rgb "
                        << gnuplot_string(palette[i % 10]) << " title " << gnuplot_string(s.methods[i].name);
        }
        gp.stream() << "\n";
        data_files.push_back(std::move(d));
    }
    gp.stream() << "unset multiplot\n";
    for (auto& d : data_files) d->commit();
    gp.commit();
    run_gnuplot(dir / (stem + ".gp"), dir / (stem + ".png"));
}

namespace {

// One measure's table: per scene with a sweep and the measure, per level, the
// fastest sympl and Odeint method and which of them to pick.
void fastest_table(const std::vector<report_row>& rows, const std::vector<run_plan>& plans, error_measure by,
                   std::ostream& md, std::ostream& table, std::ostream& csv) {
    const std::string name_of_measure = measure_name(by);
    md << "## Fastest method per " << name_of_measure << "\n\n"
       << (by == error_measure::final_error
               ? "Time to a final error (max |x - x_ref| / max |x_ref| at t_end) of "
               : "Time to a largest relative energy error |H - H_0| / |H_0| over the whole run of ")
       << "1e-4, 1e-6, 1e-8, 1e-10 and 1e-12, read off each method's curve by log-log interpolation between the two "
          "runs that bracket the level (time_to_accuracy.csv lists them). Odeint: the fastest of the Odeint steppers "
          "of the scene over all their tolerances. Pick: the faster of the two.\n\n";
    std::vector<std::string> without;
    for (const run_plan& plan : plans)
        if (has_sweep(plan) && !scene_has(rows, *plan.s, by)) without.push_back(plan.s->name);
    if (!without.empty()) {
        md << "Not in this table: ";
        for (std::size_t i = 0; i < without.size(); ++i) md << (i ? ", " : "") << markdown_cell(without[i]);
        md << (by == error_measure::final_error ? " (no final errors: see above).\n\n"
                                          : " (no energy: the system is not Hamiltonian).\n\n");
    }
    md << "| scene | level | fastest sympl method | time [s] | fastest Odeint method | time [s] | Odeint / sympl | pick |\n"
       << "|---|---|---|---|---|---|---|---|\n";
    table << "\n" << name_of_measure << ":\n"
          << std::left << std::setw(22) << "scene" << std::setw(8) << "level" << std::setw(38) << "fastest sympl"
          << std::right << std::setw(10) << "time [s]" << "  " << std::left << std::setw(24) << "fastest Odeint" << std::right
          << std::setw(10) << "time [s]" << std::setw(10) << "ratio" << "\n";
    bool below = false;  // some winner's run at its largest dt or tolerance is below its level
    bool ties = false;   // some cell names a tie
    for (const run_plan& plan : plans) {
        const scene& s = *plan.s;
        if (!has_sweep(plan) || !scene_has(rows, s, by)) continue;
        for (double level : levels) {
            std::vector<std::pair<time_to_accuracy, std::string>> reached;  // each method reaching the level
            for (const scene_method& m : s.methods)
                if (const auto r = time_to_reach(curve_of(rows, m, by), level)) {
                    reached.emplace_back(*r, m.name);
                    csv << csv_line({s.name, name_of_measure, format_number(level), m.name, format_number(r->seconds, 6),
                                     r->bracketed ? "yes" : "no", format_number(r->above.parameter, 6),
                                     format_number(r->above.error, 6), format_number(r->above.seconds, 6),
                                     format_number(r->below.parameter, 6), format_number(r->below.error, 6),
                                     format_number(r->below.seconds, 6)});
                }
            const verdict ours = fastest(rows, s, level, false, by), theirs = fastest(rows, s, level, true, by);
            const auto name = [&below, &ties](const verdict& v) {
                // "*": the method's largest dt or tolerance is already below the level; "~": a tie (footnotes).
                if (v.method && !v.reach->bracketed) below = true;
                if (v.tied) ties = true;
                if (v.method)
                    return v.method->name + (v.reach->bracketed ? "" : " *") + (v.tied ? " ~ " + v.tied->name : "");
                return std::isfinite(v.best_error) ? "not reached (best " + format_number(v.best_error, 2) + ")"
                                                   : std::string("none");
            };
            const auto time = [](const verdict& v) { return v.reach ? format_number(v.reach->seconds, 3) : "-"; };
            const std::string ratio =
                ours.reach && theirs.reach ? format_number(theirs.reach->seconds / ours.reach->seconds, 3) + "x" : "-";
            // The pick: the fastest of all, and every method of either group within a tie of it, fastest first.
            std::stable_sort(reached.begin(), reached.end(),
                             [](const auto& a, const auto& b) { return a.first.seconds < b.first.seconds; });
            std::string picked = reached.empty() ? "-" : reached[0].second;
            for (std::size_t k = 1; k < reached.size(); ++k)
                if (tied(reached[0].first, reached[k].first)) picked += " ~ " + reached[k].second, ties = true;
            md << "| " << markdown_cell(s.name) << " | " << format_number(level) << " | " << markdown_cell(name(ours))
               << " | " << time(ours) << " | " << markdown_cell(name(theirs)) << " | " << time(theirs) << " | " << ratio
               << " | " << markdown_cell(picked) << " |\n";
            table << std::left << std::setw(22) << s.name << std::setw(8) << format_number(level) << std::setw(38)
                  << name(ours) << std::right << std::setw(10) << time(ours) << "  " << std::left << std::setw(24)
                  << name(theirs) << std::right << std::setw(10) << time(theirs) << std::setw(10) << ratio << "\n";
        }
    }
    md << "\n";
    if (ties) {
        const std::string note = "A ~ B: a tie, either may come first in another run: B's time is within 5% of "
                                 "A's (on an idle machine two runs of this program put 95% of timed runs within 3% "
                                 "of each other, 99% within 8%), or B's fastest timing round beat A's slowest.";
        md << note << "\n\n";
        table << note << "\n";
    }
    if (!below) return;
    // Such a cell measures no accuracy: Boris's pusher, for one, keeps |v| and so H
    // exactly in a pure magnetic field, at any dt (docs/charged-particles.md).
    const std::string note = "* the method's run at its largest dt or tolerance is already below the level: the time "
                             "is that run's, not "
                             "read off a curve, and the cell says little about accuracy (a method that keeps this "
                             "measure exactly, such as Boris's pusher for the energy in a pure magnetic field, wins it "
                             "at any dt).";
    md << note << "\n\n";
    table << note << "\n";
}

}  // namespace

void fastest_per_level(const std::vector<report_row>& rows, const std::vector<run_plan>& plans, std::ostream& md,
                       std::ostream& table, const fs::path& dir) {
    // A scene with one dt (and one tolerance) has no curve to read: say so rather than print an empty table.
    bool any = false;
    for (const run_plan& plan : plans) {
        if (has_sweep(plan)) {
            any = true;
            continue;
        }
        if (plan.s->ensemble) continue;  // the chaos map: its own section below
        const std::string why = plan.s->name + ": a single dt" + (plan.s->tolerances.size() == 1 ? " and tolerance" : "") +
                                ", so no work-precision curve and no fastest method; give dt = {from, to, count} "
                                "(or tolerances) for a sweep.";
        md << "**" << markdown_cell(why) << "**\n\n";
        table << why << "\n";
    }
    // Runs whose error reached order one: no solution, whatever their time.
    // One line in summary.md, before the tables it stays out of; the runs
    // themselves in order_one_runs.csv.
    atomic_file flagged(dir / "order_one_runs.csv");
    flagged.stream() << csv_line({"scene", "method", "dt", "tolerance", "final_error", "max_energy_error"});
    std::size_t count = 0;
    for (const report_row& r : rows) {
        if (!r.r.stable || (r.final_error < order_one && r.r.max_energy_error < order_one)) continue;
        const planned_run& p = *r.run;
        flagged.stream() << csv_line({r.s->name, r.method().name, p.dt > 0 ? shortest(p.dt) : "",
                                      p.tolerance > 0 ? shortest(p.tolerance) : "", csv_number(r.final_error),
                                      csv_number(r.r.max_energy_error)});
        ++count;
    }
    flagged.commit();  // a header alone when none did: no older report's list left behind
    if (count) {
        md << count << " runs reached an error of order one (final or energy error >= " << format_number(order_one)
           << "): no solution at any level, left out of the tables and figures (order_one_runs.csv lists them).\n\n";
        table << count << " runs reached an error of order one (>= " << format_number(order_one)
              << ") and are left out of the tables (order_one_runs.csv lists them)\n";
    }
    if (!any) return;
    atomic_file csv(dir / "time_to_accuracy.csv");
    csv.stream() << csv_line({"scene", "measure", "level", "method", "seconds", "bracketed", "above_dt_or_tolerance",
                              "above_error", "above_seconds", "below_dt_or_tolerance", "below_error", "below_seconds"});
    fastest_table(rows, plans, error_measure::final_error, md, table, csv.stream());
    fastest_table(rows, plans, error_measure::energy_error, md, table, csv.stream());
    csv.commit();
}

}  // namespace sympl::app
