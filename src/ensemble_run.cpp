// `sympl ensemble`: grid or CSV of states -> rows in input order, split over
// threads and ranks, written by rank 0 (see ensemble_run.hpp).
#include "ensemble_run.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <ostream>
#include <optional>
#include <sstream>

#include <sympl/ensemble.hpp>
#include <sympl/error.hpp>

#include "format.hpp"
#include "output_set.hpp"
#include "systems.hpp"
#include "writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

// One trajectory of the ensemble: where it comes from and its start (or why it has none).
struct point {
    std::vector<double> grid_values;  // the grid's values (grid) or the state's numbers (CSV)
    parameter_values parameters;      // every parameter given to the system
    std::vector<double> x0;
    std::string invalid;              // not empty: no start, and why
    std::string hamiltonian_key;      // points with equal keys share one Hamiltonian
};

constexpr std::size_t max_states_bytes = std::size_t(256) << 20;

// The states of a CSV file: a header q1..qn,p1..pn, then one state per line.
std::vector<std::vector<double>> read_states(const std::string& path, std::size_t dof) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw scene_error(path + ": cannot open the states file");
    in.seekg(0, std::ios::end);
    if (std::size_t(in.tellg()) > max_states_bytes)
        throw scene_error(path + ": larger than " + std::to_string(max_states_bytes) + " bytes; expected at most that");
    in.seekg(0);
    std::string line;
    std::size_t number = 0;
    std::vector<std::vector<double>> states;
    std::string expected_header;
    for (std::size_t i = 1; i <= dof; ++i) expected_header += (i > 1 ? ",q" : "q") + std::to_string(i);
    for (std::size_t i = 1; i <= dof; ++i) expected_header += ",p" + std::to_string(i);
    while (std::getline(in, line)) {
        ++number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::string where = path + ":" + std::to_string(number) + ": ";
        if (number == 1) {
            if (line != expected_header)
                throw scene_error(where + "header '" + line + "'; expected '" + expected_header + "'");
            continue;
        }
        if (line.empty()) continue;
        std::vector<double> x;
        std::size_t start = 0;
        while (true) {
            const std::size_t comma = line.find(',', start);
            const std::string field = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
            double v = 0;
            const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
            if (ec != std::errc() || end != field.data() + field.size() || field.empty() || !std::isfinite(v))
                throw scene_error(where + "field " + std::to_string(x.size() + 1) + " '" + field +
                                  "'; expected a finite number");
            x.push_back(v);
            if (comma == std::string::npos) break;
            start = comma + 1;
        }
        if (x.size() != 2 * dof)
            throw scene_error(where + std::to_string(x.size()) + " numbers; expected " + std::to_string(2 * dof) +
                              " (q1..q" + std::to_string(dof) + ", p1..p" + std::to_string(dof) + ")");
        if (double(states.size()) >= max_ensemble_size)
            throw scene_error(where + "more than " + shortest(max_ensemble_size) + " states; expected at most that");
        states.push_back(std::move(x));
    }
    if (number == 0) throw scene_error(path + ": empty; expected the header '" + expected_header + "' and states");
    return states;
}

std::string key_of(const system_entry& entry, const parameter_values& v) {
    std::string key;
    for (const auto& q : entry.parameters)
        if (!q.initial_state) key += q.name + "=" + shortest(v.at(q.name)) + ";";
    return key;
}

// Point `index` of the scene's grid (the last axis varies fastest) or state
// `index` of its CSV, with its start or the reason it has none.
point point_at(const scene& s, const system_entry& entry, const parameter_values& defaults, std::size_t index,
               const std::vector<std::vector<double>>& states) {
    point pt;
    pt.parameters = s.parameters;
    std::vector<double> q0 = s.q0, p0 = s.p0;
    const ensemble_spec& e = *s.ensemble;
    if (!e.grid.empty()) {
        std::size_t rest = index;
        pt.grid_values.resize(e.grid.size());
        for (std::size_t a = e.grid.size(); a-- > 0;) {
            pt.grid_values[a] = e.grid[a].value(rest % e.grid[a].count);
            rest /= e.grid[a].count;
        }
        for (std::size_t a = 0; a < e.grid.size(); ++a) {
            const parameter& q = *entry.find(e.grid[a].name);
            if (!q.accepts(pt.grid_values[a]) && pt.invalid.empty())
                pt.invalid = q.name + " = " + shortest(pt.grid_values[a]) + "; expected " + q.expected();
            pt.parameters[q.name] = pt.grid_values[a];
        }
    } else {
        pt.grid_values = states[index];
        const std::size_t n = states[index].size() / 2;
        q0.assign(states[index].begin(), states[index].begin() + std::ptrdiff_t(n));
        p0.assign(states[index].begin() + std::ptrdiff_t(n), states[index].end());
    }
    parameter_values merged = defaults;
    for (const auto& [k, v] : pt.parameters) merged[k] = v;
    pt.hamiltonian_key = key_of(entry, merged);
    if (!pt.invalid.empty()) return pt;
    try {
        const problem p = make_problem(s.system, pt.parameters, q0, p0, "");
        if (p.energy && !std::isfinite(p.energy(p.x0)))
            pt.invalid = "the start has energy " + shortest(p.energy(p.x0)) + "; expected a finite energy";
        else
            pt.x0 = p.x0;
    } catch (const error& err) {
        std::string why = err.what();
        if (why.rfind(": ", 0) == 0) why.erase(0, 2);
        pt.invalid = why;
    }
    return pt;
}

// "q3", "p1_0": built with a stream (GCC 12 warns falsely on "q" + to_string(i)).
std::string numbered(const char* name, std::size_t i, const char* suffix = "") {
    std::ostringstream text;
    text << name << i << suffix;
    return text.str();
}

std::vector<std::string> header(const scene& s, const problem& p) {
    const ensemble_spec& e = *s.ensemble;
    std::vector<std::string> h{"index"};
    const std::size_t n = p.degrees_of_freedom;
    if (!e.grid.empty())
        for (const auto& a : e.grid) h.push_back(a.name);
    else {
        for (std::size_t i = 1; i <= n; ++i) h.push_back(numbered("q", i, "_0"));
        for (std::size_t i = 1; i <= n; ++i) h.push_back(numbered("p", i, "_0"));
    }
    for (const char* c : {"status", "blowup_step", "blowup_time"}) h.push_back(c);
    if (e.megno) h.push_back("megno");
    h.push_back("max_energy_error");
    for (std::size_t i = 1; i <= n; ++i) h.push_back(numbered("q", i, "_final"));
    for (std::size_t i = 1; i <= n; ++i) h.push_back(numbered("p", i, "_final"));
    h.push_back("reason");
    return h;
}

std::string row_text(const scene& s, std::size_t index, const point& pt, const ensemble_row* r, std::size_t dof) {
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

double seconds_now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

ensemble_outcome run_ensemble_scene(const scene& s, const fs::path& dir, const std::string& prefix, int threads,
                                    double max_steps, bool plots, const exchange& ranks) {
    if (!s.ensemble) throw invalid_argument(s.source + ": the scene has no [ensemble] table");
    const ensemble_spec& e = *s.ensemble;
    const system_entry& entry = *find_system(s.system);
    const problem base = problem_of(s);
    if (!base.ensemble)
        throw invalid_argument(s.source + ": " + s.system +
                               " is not a separable Hamiltonian H = T(p) + V(q); an ensemble runs splitting tables on one");
    const double span_steps = std::ceil((s.t_end - s.t0) / s.dt[0] - 1e-9);
    if (!(span_steps <= max_steps))
        throw invalid_argument(s.source + ": each trajectory at dt = " + shortest(s.dt[0]) + " over t = " + shortest(s.t0) +
                               " .. " + shortest(s.t_end) + " takes " + format_number(span_steps, 6) +
                               " steps; the limit is " + format_number(max_steps, 6) + " (raise it with --max-steps)");
    std::vector<std::vector<double>> states;
    if (e.grid.empty()) states = read_states(e.states_file, base.degrees_of_freedom);
    const std::size_t n = e.grid.empty() ? states.size() : e.size();
    if (double(n) * span_steps > 1e4 * max_steps)
        throw invalid_argument(s.source + ": " + std::to_string(n) + " trajectories of " + format_number(span_steps, 6) +
                               " steps are " + format_number(double(n) * span_steps, 6) +
                               " trajectory-steps; the limit is 1e4 times --max-steps = " + format_number(1e4 * max_steps, 6));

    // This rank's static block of rows, in input order.
    const std::size_t first = n * std::size_t(ranks.rank) / std::size_t(ranks.size);
    const std::size_t last = n * std::size_t(ranks.rank + 1) / std::size_t(ranks.size);
    const double started = seconds_now();
    std::vector<point> points;
    const parameter_values defaults = with_defaults(entry, s.parameters, s.source);
    for (std::size_t i = first; i < last; ++i) points.push_back(point_at(s, entry, defaults, i, states));

    // Consecutive valid points of one Hamiltonian form a group: one call of
    // the library's ensemble (SIMD batches, threads).
    struct group {
        std::vector<std::size_t> members;  // indices into points
    };
    std::vector<group> groups;
    for (std::size_t i = 0; i < points.size(); ++i) {
        if (!points[i].invalid.empty()) continue;
        if (groups.empty() || points[groups.back().members.back()].hamiltonian_key != points[i].hamiltonian_key)
            groups.push_back({});
        groups.back().members.push_back(i);
    }
    ensemble_request rq;
    rq.method = s.methods[0].coefficients;
    rq.t0 = s.t0;
    rq.dt = s.dt[0];
    rq.steps = std::size_t(span_steps);
    rq.sample_every = std::min<std::size_t>(e.sample_every, rq.steps);
    rq.megno = e.megno;
    std::vector<ensemble_row> rows(points.size());
    std::vector<bool> has_row(points.size(), false);
    const auto run_group = [&](const group& g, int team) {
        const point& leader = points[g.members.front()];
        const problem p = make_problem(s.system, leader.parameters, s.q0, s.p0, s.source);
        std::vector<std::vector<double>> starts;
        for (std::size_t m : g.members) starts.push_back(points[m].x0);
        ensemble_request r = rq;
        r.threads = team;
        const auto result = p.ensemble(r, starts);
        for (std::size_t k = 0; k < g.members.size(); ++k) {
            rows[g.members[k]] = result[k];
            has_row[g.members[k]] = true;
        }
    };
    if (groups.size() == 1) {
        run_group(groups[0], threads);
    } else if (!groups.empty()) {
        // Many Hamiltonians (a grid over a parameter of H): the groups over threads.
        for_each_in_parallel(groups.size(), threads, [&](std::size_t g) { run_group(groups[g], 1); });
    }
    std::string mine;
    for (std::size_t i = 0; i < points.size(); ++i)
        mine += row_text(s, first + i, points[i], has_row[i] ? &rows[i] : nullptr, base.degrees_of_freedom);
    ensemble_outcome outcome;
    outcome.seconds = seconds_now() - started;
    const std::vector<std::string> all = ranks.gather(mine);
    if (ranks.rank != 0) return outcome;

    // Rank 0: the CSV, counts, map, Poincare section, summary.
    const std::vector<std::string> columns = header(s, base);
    const std::size_t status_column = 1 + (e.grid.empty() ? 2 * base.degrees_of_freedom : e.grid.size());
    atomic_file csv(dir / (prefix + "ensemble.csv"));
    csv.stream() << csv_line(columns);
    std::vector<std::pair<std::size_t, std::vector<double>>> stable_starts;  // for the section
    for (const std::string& block : all) {
        csv.stream() << block;
        std::istringstream lines(block);
        std::string line;
        while (std::getline(lines, line)) {
            ++outcome.trajectories;
            std::vector<std::string> f;
            std::size_t start = 0;
            for (std::size_t c = 0; c <= status_column + 3; ++c) {
                const std::size_t comma = line.find(',', start);
                f.push_back(line.substr(start, comma - start));
                start = comma + 1;
            }
            const std::string& status = f[status_column];
            if (status == "invalid") ++outcome.invalid;
            else if (status == "unstable") ++outcome.unstable;
            else {
                ++outcome.stable;
                if (e.megno && !f[status_column + 3].empty() && std::stod(f[status_column + 3]) > chaotic_megno)
                    ++outcome.chaotic;
            }
        }
    }
    csv.commit();
    outcome.files.push_back(prefix + "ensemble.csv");

    std::ostringstream md;
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
           << rq.sample_every << " steps: it tends to 2 on quasi-periodic orbits and grows like lambda t / 2 on "
              "chaotic ones. Unstable rows escaped (relative energy error > 1e3 or a non-finite state) at the step "
              "given; invalid rows have no start (reason in the last column).\n\n";

    // The map: one colored square per grid point (2-D grids), or a curve (1-D).
    const bool drawn_map = plots && !e.grid.empty() && e.grid.size() <= 2;
    if (drawn_map) {
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
    if (e.orbits > 0 && base.section) {
        std::vector<std::pair<std::size_t, point>> chosen;
        for (std::size_t k = 0; k < e.orbits; ++k) {
            const std::size_t i = n * (2 * k + 1) / (2 * e.orbits);
            point pt = point_at(s, entry, defaults, i, states);
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
            const problem p = make_problem(s.system, pt.parameters, s.q0, s.p0, s.source);
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
                        << " noenhanced\nset xlabel 'q2'\nset ylabel 'p2'\nplot "
                        << gnuplot_string(prefix + "poincare.csv") << " every ::1 using 3:" << (d + 3)
                        << ":1 with dots lc variable notitle\n";
            gp.commit();
            run_gnuplot(dir / (prefix + "poincare.gp"), dir / (prefix + "poincare.png"));
            if (fs::exists(dir / (prefix + "poincare.png"))) outcome.files.push_back(prefix + "poincare.png");
        }
    }
    outcome.summary = md.str();
    return outcome;
}

void ensemble_command(const scene& s, const std::string& out_dir, int threads, double max_steps, const exchange& ranks,
                      std::ostream& out) {
    // Only rank 0 writes; the others compute their rows and send them.
    std::optional<output_set> outputs;
    if (ranks.rank == 0) outputs.emplace(out_dir);
    const fs::path dir = outputs ? outputs->staging() : fs::path();
    const ensemble_outcome o = run_ensemble_scene(s, dir, "", threads, max_steps, have_gnuplot(), ranks);
    if (ranks.rank != 0) return;
    std::ostringstream md;
    md << "# sympl ensemble\n\n" << o.summary << "Processes: " << ranks.size << " (rank 0 took " << fixed(o.seconds, 2)
       << " s for its share).\n\nFiles: ";
    for (std::size_t k = 0; k < o.files.size(); ++k) md << (k ? ", " : "") << o.files[k];
    md << ", summary.md.\n";
    atomic_file summary(dir / "summary.md");
    summary.stream() << md.str();
    summary.commit();
    outputs->commit();
    out << s.name << ": " << o.trajectories << " trajectories: " << o.stable << " stable, " << o.unstable
        << " unstable, " << o.invalid << " invalid";
    if (s.ensemble->megno) out << ", " << o.chaotic << " chaotic (MEGNO > " << shortest(chaotic_megno) << ")";
    out << "\nwrote " << (outputs->directory() / "ensemble.csv").string() << " and summary.md";
    for (const auto& f : o.files)
        if (f != "ensemble.csv") out << ", " << f;
    out << "\n";
}

}  // namespace sympl::app
