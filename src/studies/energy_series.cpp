// The energy error along the run, every Hamiltonian scene with a sweep: its
// fastest symplectic method against its fastest non-symplectic one at equal
// cost, on a log time axis (energy_vs_time.csv and .png).
#include "study.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "output/format.hpp"
#include "report/report_write.hpp"
#include "report/work_precision.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

struct contender {
    const report_row* row = nullptr;  // the run drawn
    double level = 0;                 // the energy level its method reaches fastest
};

std::vector<work_point> energy_curve(const std::vector<report_row>& rows, const scene_method& m) {
    std::vector<work_point> curve;
    for (const report_row& r : rows)
        if (&r.method() == &m && r.r.stable && r.r.max_energy_error >= 0 && r.r.max_energy_error < order_one)
            curve.push_back({r.r.seconds, r.r.max_energy_error, r.run->setting()});
    return curve;
}

// The fastest method of the group at `level` and its run that reaches it.
std::optional<std::pair<const scene_method*, double>> fastest_at(const std::vector<report_row>& rows, const scene& s,
                                                                 double level, bool want_symplectic) {
    std::optional<std::pair<const scene_method*, double>> best;
    for (const scene_method& m : s.methods) {
        if (symplectic(m) != want_symplectic) continue;
        if (const auto r = time_to_reach(energy_curve(rows, m), level); r && (!best || r->seconds < best->second))
            best = std::pair{&m, r->seconds};
    }
    return best;
}

// The run of method m whose time is nearest `seconds` (log scale).
const report_row* nearest_run(const std::vector<report_row>& rows, const scene_method& m, double seconds) {
    const report_row* found = nullptr;
    for (const report_row& r : rows)
        if (&r.method() == &m && r.r.stable && r.r.seconds > 0 && r.r.max_energy_error >= 0 &&
            (!found || std::fabs(std::log(r.r.seconds / seconds)) < std::fabs(std::log(found->r.seconds / seconds))))
            found = &r;
    return found;
}

}  // namespace

void energy_series_study(const std::vector<scene>& scenes, const std::vector<report_row>& rows, const fs::path& dir,
                         bool plots, std::ostream& md) {
    struct panel {
        const scene* s;
        std::vector<std::string> labels;
        std::vector<int> blocks;  // each label's block of energy_vs_time.dat
    };
    std::vector<panel> panels;
    atomic_file csv(dir / "energy_vs_time.csv");
    csv.stream() << "scene,method,setting,t,energy_error\n";
    csv.stream().precision(8);
    // gnuplot reads each series as one block of a plain file: selecting rows
    // of the CSV by name made it parse the whole CSV once per series (11 s of
    // a 56 s quick report), a block is skipped unparsed.
    std::optional<atomic_file> dat;
    if (plots) {
        dat.emplace(dir / "energy_vs_time.dat");
        dat->stream().precision(8);
    }
    int blocks = 0;
    std::vector<std::string> left_out;  // scenes without a panel, each with why
    const auto open_section = [&] {
        if (panels.empty() && left_out.empty())
            md << "## Energy error against time\n\nPer scene, the symplectic run that reaches a max energy error of "
                  "1e-8 fastest (or the tightest level above it one reaches), against the non-symplectic method fastest at that level (or the nearest "
                  "level it reaches), at its run of about the same time: equal cost (energy_vs_time.csv"
               << (plots ? ", energy_vs_time.png" : "") << "; log time axis).\n\n";
    };
    for (const scene& s : scenes) {
        if (s.ensemble) continue;  // the chaos map: one dt, its own section
        // Level 1e-8, or the tightest above it a symplectic method reaches (below it rounding, not the
        // method, sets the drift); the symplectic run reaching it fastest; the non-symplectic method
        // fastest at that level, at its run of the nearest time (equal cost).
        std::optional<std::pair<const scene_method*, double>> ours;
        double level = 0;
        for (double l : {1e-4, 1e-6, 1e-8})
            if (const auto f = fastest_at(rows, s, l, true)) ours = f, level = l;
        if (!ours) {
            const bool has_energy = std::any_of(rows.begin(), rows.end(), [&](const report_row& r) {
                return r.s == &s && r.r.max_energy_error >= 0;
            });
            open_section();
            left_out.push_back(markdown_cell(s.name) + (has_energy ? " (no symplectic run reaches a max energy error of 1e-4)"
                                                                   : " (no energy: the system is not Hamiltonian)"));
            continue;
        }
        const report_row* a = nearest_run(rows, *ours->first, ours->second);
        std::optional<std::pair<const scene_method*, double>> theirs;
        for (double l = level; l <= 1e-4 * 1.0001 && !theirs; l *= 100) theirs = fastest_at(rows, s, l, false);
        const report_row* b = theirs ? nearest_run(rows, *theirs->first, a->r.seconds) : nullptr;
        open_section();
        panel p{&s, {}, {}};
        for (const report_row* r : {a, b}) {
            if (!r) continue;
            run_request rq = r->run->request();
            rq.energy = true;
            rq.energy_series_every = std::max<std::size_t>(1, r->r.steps / 2000);
            rq.timing_repeats = 0;
            const run_result out = r->p->run(r->method(), rq, s.t0, s.t_end, r->p->x0);
            const std::string setting = (r->run->dt > 0 ? "dt " : "tolerance ") + format_number(r->run->setting(), 3);
            std::string head = csv_line({s.name, r->method().name, setting});
            head.pop_back();  // csv_line ends the line
            for (const auto& [t, e] : out.energy_series)
                if (t > s.t0) {
                    csv.stream() << head << "," << t << "," << e << "\n";
                    if (dat) dat->stream() << t << " " << e << "\n";
                }
            if (dat) dat->stream() << "\n\n";  // ends gnuplot's block (data set `index`)
            p.blocks.push_back(blocks++);
            p.labels.push_back(r->method().name + ", " + setting + ", " + format_number(r->r.seconds, 2) + " s");
        }
        md << "- " << markdown_cell(s.name) << ": " << markdown_cell(p.labels[0])
           << (p.labels.size() > 1 ? " against " + markdown_cell(p.labels[1]) : std::string(" (no non-symplectic method reaches 1e-4)"))
           << "\n";
        panels.push_back(std::move(p));
    }
    csv.commit();
    if (!left_out.empty()) {
        md << "- No panel: ";
        for (std::size_t i = 0; i < left_out.size(); ++i) md << (i ? ", " : "") << left_out[i];
        md << ".\n";
    }
    if (!panels.empty() || !left_out.empty()) md << "\n";
    if (!plots) return;
    dat->commit();
    atomic_file gp(dir / "energy_vs_time.gp");
    const int cols = panels.size() > 1 ? 2 : 1, rows_n = int((panels.size() + 1) / 2);
    gp.stream() << "set terminal pngcairo size " << 900 * cols << "," << 420 * rows_n << " font ',10'\nset output "
                << gnuplot_string("energy_vs_time.png") << "\nset logscale xy\n"
                << "set format x '10^{%L}'\nset format y '10^{%L}'\nset xlabel 't'\n"
                << "set ylabel 'relative energy error'\nset key below font ',8' noenhanced\nset grid\n"
                << "set multiplot layout " << rows_n << "," << cols << "\n";
    for (const panel& p : panels) {
        gp.stream() << "set title " << gnuplot_string(p.s->name) << " noenhanced\nplot ";
        const char* colours[] = {"#0072b2", "#d55e00"};
        for (std::size_t i = 0; i < p.labels.size(); ++i) {
            gp.stream() << (i ? ", " : "") << gnuplot_string("energy_vs_time.dat") << " index " << p.blocks[i]
                        << " using 1:($2 > 0 ? $2 : NaN) with lines lw 1.5 lc rgb " << gnuplot_string(colours[i])
                        << " title " << gnuplot_string(p.labels[i] + (i ? " (not symplectic)" : " (symplectic)"));
        }
        gp.stream() << "\n";
    }
    gp.stream() << "unset multiplot\n";
    gp.commit();
    run_gnuplot(dir / "energy_vs_time.gp", dir / "energy_vs_time.png");
}

}  // namespace sympl::app
