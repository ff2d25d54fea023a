// An ensemble's CSV, summary section, map and Poincare section (rank 0).
#include "output/ensemble_write.hpp"

#include <cmath>
#include <ostream>
#include <sstream>

#include "output/format.hpp"
#include "running/systems.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

std::vector<std::string> header(const scene& s, const runnable_system& p) {
    const ensemble_spec& e = *s.ensemble;
    std::vector<std::string> h{"index"};
    // The run's own column names (q1.., or the bodies' "jupiter_x" where the system names them).
    const std::vector<std::string> columns = state_columns(p.system, p.degrees_of_freedom);
    if (!e.grid.empty())
        for (const auto& a : e.grid) h.push_back(a.name);
    else
        for (const auto& c : columns) h.push_back(c + "_0");
    for (const char* c : {"status", "blowup_step", "blowup_time"}) h.push_back(c);
    if (e.megno) h.push_back("megno");
    h.push_back("max_energy_error");
    for (const auto& c : columns) h.push_back(c + "_final");
    h.push_back("reason");
    return h;
}

std::string row_text(const scene& s, std::size_t index, const ensemble_point& pt, const ensemble_row* r, std::size_t dof) {
    std::vector<std::string> f{std::to_string(index)};
    for (double v : pt.grid_values) f.push_back(shortest(v));
    const bool megno = s.ensemble->megno;
    if (!r) {
        f.insert(f.end(), {"invalid", "", ""});
        if (megno) f.push_back("");
        f.push_back("");
        for (std::size_t i = 0; i < 2 * dof; ++i) f.push_back("");
        f.push_back(pt.invalid);
        return csv_line(f);
    }
    f.push_back(r->stable ? "stable" : "unstable");
    f.push_back(r->stable ? "" : std::to_string(r->blowup_step));
    f.push_back(r->stable ? "" : shortest(r->blowup_time));
    if (megno) f.push_back(std::isfinite(r->megno) ? shortest(r->megno) : "");
    f.push_back(shortest(r->max_energy_error));
    for (double v : r->final_state) f.push_back(shortest(v));
    f.push_back(r->failure);
    return csv_line(f);
}

// The map: one colored square per grid point (2-D grids), or a curve (1-D).
void draw_map(const scene& s, std::size_t status_column, const fs::path& dir, const std::string& prefix,
              ensemble_outcome& outcome) {
    const ensemble_spec& e = *s.ensemble;
    const std::string value_column = std::to_string(status_column + 4);  // MEGNO, else the energy error
    atomic_file gp(dir / (prefix + "ensemble_map.gp"));
    gp.stream() << "set terminal pngcairo size 900,750\nset output " << gnuplot_string(prefix + "ensemble_map.png")
                << "\nset datafile separator ','\nset datafile missing ''\nset title "
                << gnuplot_string(s.name + (e.megno ? ": MEGNO <Y>" : ": log10 max relative energy error"))
                << " noenhanced\n";
    if (e.grid.size() == 2) {
        gp.stream() << "set xlabel " << gnuplot_string(e.grid[0].name) << " noenhanced\nset ylabel "
                    << gnuplot_string(e.grid[1].name) << " noenhanced\n"
                    << (e.megno ? "set cbrange [0:8]\nset palette defined (0 'white', 2 'blue', 4 'orange', 8 'red')\n"
                                : "set palette rgbformulae 33,13,10\n")
                    << "plot " << gnuplot_string(prefix + "ensemble.csv") << " every ::1 using 2:3:("
                    << (e.megno ? "$" + value_column : "log10($" + value_column + ")")
                    << ") with points pointtype 5 pointsize " << (e.grid[0].count * e.grid[1].count > 2500 ? 0.5 : 1.2)
                    << " palette notitle\n";
    } else {
        gp.stream() << "set xlabel " << gnuplot_string(e.grid[0].name) << " noenhanced\n"
                    << (e.megno ? "" : "set logscale y\n") << "plot " << gnuplot_string(prefix + "ensemble.csv")
                    << " every ::1 using 2:" << value_column << " with linespoints notitle\n";
    }
    gp.commit();
    run_gnuplot(dir / (prefix + "ensemble_map.gp"), dir / (prefix + "ensemble_map.png"));
    if (fs::exists(dir / (prefix + "ensemble_map.png"))) outcome.files.push_back(prefix + "ensemble_map.png");
}

// A Poincare section (q1 = 0, upwards) of a few orbits spread over the grid.
void write_section(const ensemble_setup& u, const fs::path& dir, const std::string& prefix, bool plots, std::ostream& md,
                   ensemble_outcome& outcome) {
    const scene& s = *u.s;
    const ensemble_spec& e = *s.ensemble;
    const runnable_system& base = u.base;
    const ensemble_request& rq = u.request;
    const std::size_t n = u.trajectories;
    std::vector<std::pair<std::size_t, ensemble_point>> chosen;
    for (std::size_t k = 0; k < e.orbits; ++k) {
        const std::size_t i = n * (2 * k + 1) / (2 * e.orbits);
        ensemble_point pt = point_at(s, *u.entry, u.defaults, i, u.states);
        if (pt.invalid.empty()) chosen.emplace_back(i, std::move(pt));
    }
    atomic_file section(dir / (prefix + "poincare.csv"));
    std::ostringstream head;
    head << "orbit";
    for (std::size_t i = 1; i <= base.degrees_of_freedom; ++i) head << ",q" << i;
    for (std::size_t i = 1; i <= base.degrees_of_freedom; ++i) head << ",p" << i;
    section.stream() << head.str() << "\n";
    std::size_t crossings = 0;
    for (const auto& [i, pt] : chosen) {
        const runnable_system p = make_system(s.system, pt.parameters, s.q0, s.p0, s.source);
        try {
            for (const auto& c : p.section(*rq.method, rq.dt, rq.steps, pt.x0)) {
                section.stream() << i;
                for (double v : c) section.stream() << ',' << shortest(v);
                section.stream() << '\n';
                ++crossings;
            }
        } catch (const integration_error&) {
            // an escaping orbit: its crossings up to the escape are kept
        }
    }
    section.commit();
    outcome.files.push_back(prefix + "poincare.csv");
    md << "Poincare section q1 = 0 (p1 > 0) of " << chosen.size() << " orbits (rows "
       << [&] {
              std::string list;
              for (const auto& c : chosen) list += (list.empty() ? "" : ", ") + std::to_string(c.first);
              return list;
          }()
       << " of the CSV): " << crossings << " crossings, each located on the cubic Hermite interpolant of its step.\n\n";
    if (plots && base.degrees_of_freedom >= 2) {
        const std::size_t d = base.degrees_of_freedom;
        atomic_file gp(dir / (prefix + "poincare.gp"));
        gp.stream() << "set terminal pngcairo size 800,700\nset output " << gnuplot_string(prefix + "poincare.png")
                    << "\nset datafile separator ','\nset title " << gnuplot_string(s.name + ": section q1 = 0")
                    << " noenhanced\nset xlabel 'q2'\nset ylabel 'p2'\n";
        // Filled points of eight dark, distinct colours (no pale yellow on white), one per orbit in turn.
        const char* const colours[] = {"#0072b2", "#d55e00", "#009e73", "#cc79a7", "#000000", "#56b4e9", "#8b4513", "#6a3d9a"};
        for (int k = 0; k < 8; ++k) gp.stream() << "set linetype " << 101 + k << " lc rgb " << gnuplot_string(colours[k]) << "\n";
        gp.stream() << "plot " << gnuplot_string(prefix + "poincare.csv") << " every ::1 using 3:" << (d + 3)
                    << ":(101 + int($1) % 8) with points pt 7 ps 0.3 lc variable notitle\n";
        gp.commit();
        run_gnuplot(dir / (prefix + "poincare.gp"), dir / (prefix + "poincare.png"));
        if (fs::exists(dir / (prefix + "poincare.png"))) outcome.files.push_back(prefix + "poincare.png");
    }
}

void write_counts(const ensemble_setup& u, const ensemble_outcome& outcome, std::ostream& md) {
    const scene& s = *u.s;
    const ensemble_spec& e = *s.ensemble;
    md << "## Ensemble: " << markdown_cell(s.name) << "\n\n"
       << s.system << ", " << s.methods[0].name << ", dt = " << shortest(s.dt[0]) << ", t = " << shortest(s.t0) << " .. "
       << shortest(s.t_end) << ", " << outcome.trajectories << " trajectories ("
       << (e.grid.empty() ? "states of " + e.states_file : std::to_string(e.grid.size()) + "-D grid") << ").\n\n"
       << "| stable | unstable | invalid |" << (e.megno ? " chaotic (MEGNO > " + shortest(chaotic_megno) + ") |" : "")
       << "\n|---|---|---|" << (e.megno ? "---|" : "") << "\n| " << outcome.stable << " | " << outcome.unstable << " | "
       << outcome.invalid << " |";
    if (e.megno) {
        const double fraction = outcome.stable ? double(outcome.chaotic) / double(outcome.stable) : 0;
        md << " " << outcome.chaotic << " (" << fixed(100 * fraction, 1) << "% of the stable) |";
    }
    md << "\n\n";
    if (e.megno)
        md << "MEGNO <Y> (Cincotta & Simo 2000) from the tangent map of the numerical flow, sampled every "
           << u.request.sample_every << " steps: it tends to 2 on quasi-periodic orbits and grows like lambda t / 2 on "
              "chaotic ones. Unstable rows escaped (relative energy error > " << shortest(divergence_limit)
           << " or a non-finite state) at the step given; invalid rows have no start (reason in the last column).\n\n";
}

}  // namespace

std::string csv_rows(const ensemble_setup& u, const std::vector<ensemble_row_of>& rows) {
    std::string text;
    for (const ensemble_row_of& r : rows) text += row_text(*u.s, r.index, *r.point, r.row, u.base.degrees_of_freedom);
    return text;
}

void write_ensemble(const ensemble_setup& u, const std::vector<std::string>& blocks, const fs::path& dir,
                    const std::string& prefix, bool plots, ensemble_outcome& outcome) {
    const ensemble_spec& e = *u.s->ensemble;
    atomic_file csv(dir / (prefix + "ensemble.csv"));
    csv.stream() << csv_line(header(*u.s, u.base));
    for (const std::string& block : blocks) csv.stream() << block;
    csv.commit();
    outcome.files.push_back(prefix + "ensemble.csv");
    std::ostringstream md;
    write_counts(u, outcome, md);
    const std::size_t status_column = 1 + (e.grid.empty() ? 2 * u.base.degrees_of_freedom : e.grid.size());
    if (plots && !e.grid.empty() && e.grid.size() <= 2) draw_map(*u.s, status_column, dir, prefix, outcome);
    if (e.orbits > 0 && u.base.section) write_section(u, dir, prefix, plots, md, outcome);
    outcome.summary = md.str();
}

}  // namespace sympl::app
