// The report's CSV, figure and fastest-method tables.
#include "report_write.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "format.hpp"
#include "work_precision.hpp"
#include "writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

std::string csv_number(double v) { return v < 0 ? "" : format_number(v, 6); }

// One method's measured runs on one scene, as a work-precision curve.
std::vector<work_point> curve_of(const std::vector<report_row>& rows, const scene_method& m) {
    std::vector<work_point> curve;
    for (const report_row& r : rows)
        if (&r.method() == &m && r.r.stable && r.final_error >= 0)
            curve.push_back({r.r.seconds, r.final_error, r.run->setting()});
    return curve;
}

// The fastest method of a group (sympl's or Odeint's) at one level.
struct verdict {
    const method_spec* method = nullptr;
    std::optional<time_to_accuracy> reach;
    double best_error = HUGE_VAL;  // the smallest error any of the group reached
};

verdict fastest(const std::vector<report_row>& rows, const scene& s, double level, bool odeint) {
    verdict v;
    for (const scene_method& m : s.methods) {
        if (entry_of(m.kind).odeint != odeint) continue;
        const auto curve = curve_of(rows, m);
        for (const work_point& p : curve) v.best_error = std::min(v.best_error, p.error);
        const auto reach = time_to_reach(curve, level);
        if (reach && (!v.reach || reach->seconds < v.reach->seconds)) v.method = &m, v.reach = reach;
    }
    return v;
}

// A colour per method of the figure: hues spread evenly, lightness alternating
// so that neighbours in hue still differ.
std::string colour(std::size_t i, std::size_t n) {
    const double h = 6.0 * double(i) / double(std::max<std::size_t>(n, 1)), v = i % 2 ? 0.65 : 0.9, s = 0.85;
    const double c = v * s, x = c * (1 - std::fabs(std::fmod(h, 2.0) - 1)), m = v - c;
    double rgb[3] = {0, 0, 0};
    const int sector = int(h) % 6;
    const int order[6][3] = {{0, 1, 2}, {1, 0, 2}, {2, 0, 1}, {2, 1, 0}, {1, 2, 0}, {0, 2, 1}};  // c, x, 0 slots
    rgb[order[sector][0]] = c;
    rgb[order[sector][1]] = x;
    char text[8];
    std::snprintf(text, sizeof text, "#%02x%02x%02x", int(255 * (rgb[0] + m)), int(255 * (rgb[1] + m)),
                  int(255 * (rgb[2] + m)));
    return text;
}

struct method_style {
    std::string colour;
    int marker;
    bool odeint;
};

// Every method name of the figure, in first-seen order, with its style.
std::map<std::string, method_style> styles_of(const std::vector<const run_plan*>& panels) {
    std::vector<const scene_method*> order;
    std::set<std::string> seen;
    for (const run_plan* plan : panels)
        for (const scene_method& m : plan->s->methods)
            if (seen.insert(m.name).second) order.push_back(&m);
    std::map<std::string, method_style> styles;
    for (std::size_t i = 0; i < order.size(); ++i)
        styles[order[i]->name] = {colour(i, order.size()), 1 + int(i % 13), entry_of(order[i]->kind).odeint};
    return styles;
}

std::string style_text(const method_style& st) {
    return "with linespoints lw 1.5 dt " + std::string(st.odeint ? "2" : "1") + " pt " + std::to_string(st.marker) +
           " ps 0.8 lc rgb " + gnuplot_string(st.colour);
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
                              "final_error", "reference_error", "loop_area_error"});
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
                                  csv_number(references.at(r.s).error), ok ? csv_number(r.loop_area_error) : ""});
    }
    csv.commit();
}

void plot_work_precision(const std::vector<report_row>& rows, const std::vector<run_plan>& plans, const fs::path& dir) {
    std::vector<const run_plan*> panels;
    for (const run_plan& p : plans)
        if (has_sweep(p)) panels.push_back(&p);
    if (panels.empty()) return;
    const auto styles = styles_of(panels);
    const std::size_t slots = panels.size() + 1;  // the last slot holds the one legend
    const int cols = slots > 1 ? 2 : 1, rows_n = int((slots + 1) / 2);
    atomic_file gp(dir / "work_precision.gp");
    gp.stream() << "set terminal pngcairo size " << 700 * cols << "," << 430 * rows_n << "\nset output "
                << gnuplot_string("work_precision.png") << "\nset logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
                << "set xlabel 'wall time [s]'\nset ylabel 'final error (relative)'\nunset key\n"
                << "set multiplot layout " << rows_n << "," << cols << "\n";
    std::vector<std::unique_ptr<atomic_file>> data_files;
    for (std::size_t k = 0; k < panels.size(); ++k) {
        const scene& s = *panels[k]->s;
        const std::string data = "wp_" + std::to_string(k + 1) + "_" + file_name_part(s.name) + ".dat";
        auto d = std::make_unique<atomic_file>(dir / data);
        for (const scene_method& m : s.methods) {
            int points = 0;
            for (const report_row& r : rows)
                if (&r.method() == &m && r.r.stable && r.final_error > 0 && r.r.seconds > 0) {
                    d->stream() << r.r.seconds << " " << r.final_error << "\n";
                    ++points;
                }
            if (points == 0) d->stream() << "NaN NaN\n";
            d->stream() << "\n\n";
        }
        gp.stream() << "set title " << gnuplot_string(s.name) << " noenhanced\nplot ";
        for (std::size_t i = 0; i < s.methods.size(); ++i)
            gp.stream() << (i ? ", " : "") << gnuplot_string(data) << " index " << i << " "
                        << style_text(styles.at(s.methods[i].name)) << " notitle";
        gp.stream() << "\n";
        data_files.push_back(std::move(d));
    }
    // The legend: every method once, solid for sympl's, dashed for Odeint's.
    gp.stream() << "unset title\nunset border\nunset tics\nunset xlabel\nunset ylabel\nunset logscale\nset xrange [0:1]\n"
                << "set yrange [0:1]\nset key inside center center maxrows " << (styles.size() + 1) / 2
                << " font ',8' noenhanced\nplot ";
    std::size_t i = 0;
    for (const auto& [name, st] : styles)
        gp.stream() << (i++ ? ", " : "") << "NaN " << style_text(st) << " title " << gnuplot_string(name);
    gp.stream() << "\nunset multiplot\n";
    for (auto& d : data_files) d->commit();
    gp.commit();
    run_gnuplot(dir / "work_precision.gp", dir / "work_precision.png");
}

void fastest_per_level(const std::vector<report_row>& rows, const std::vector<run_plan>& plans, std::ostream& md,
                       std::ostream& table, const fs::path& dir) {
    md << "## Fastest method per accuracy level\n\n"
       << "Time to a final error of 1e-4, 1e-6, 1e-8, 1e-10 and 1e-12, read off each method's work-precision curve by log-log "
          "interpolation between the two runs that bracket the level (time_to_accuracy.csv lists them). Odeint: the "
          "fastest of the Odeint steppers of the scene over all their tolerances. Scenes without a sweep (the chaos "
          "map) are left out.\n\n"
       << "| scene | level | fastest sympl method | time [s] | fastest Odeint method | time [s] | Odeint / sympl |\n"
       << "|---|---|---|---|---|---|---|\n";
    table << std::left << std::setw(22) << "scene" << std::setw(8) << "level" << std::setw(38) << "fastest sympl"
          << std::right << std::setw(10) << "time [s]" << "  " << std::left << std::setw(24) << "fastest Odeint" << std::right
          << std::setw(10) << "time [s]" << std::setw(10) << "ratio" << "\n";
    atomic_file csv(dir / "time_to_accuracy.csv");
    csv.stream() << csv_line({"scene", "level", "method", "seconds", "bracketed", "above_dt_or_tolerance", "above_error",
                              "above_seconds", "below_dt_or_tolerance", "below_error", "below_seconds"});
    for (const run_plan& plan : plans) {
        if (!has_sweep(plan)) continue;
        const scene& s = *plan.s;
        for (double level : {1e-4, 1e-6, 1e-8, 1e-10, 1e-12}) {
            for (const scene_method& m : s.methods)
                if (const auto r = time_to_reach(curve_of(rows, m), level))
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

}  // namespace sympl::app
