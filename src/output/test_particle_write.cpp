// `sympl run` of a scene with [test_particles]: test_particles.csv, the MEGNO
// map (PNG) and summary.md, all committed together or none (output_set.hpp).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <ostream>
#include <sstream>

#include "commands/ensemble_run.hpp"
#include "output/format.hpp"
#include "output/output_set.hpp"
#include "commands/run_test_particles.hpp"
#include "report/timing.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

constexpr double degree = std::numbers::pi / 180;

std::string number_or_empty(double v) { return std::isfinite(v) ? shortest(v) : ""; }

// id, the elements as given (angles in degrees), what became of the particle.
void write_csv(const std::vector<test_particle_row>& rows, const fs::path& file) {
    atomic_file csv(file);
    csv.stream() << csv_line({"id", "a", "e", "inclination", "node", "pericentre", "mean_anomaly", "status", "megno",
                              "a_final", "e_final", "reason", "removed_time"});
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const test_particle_row& r = rows[i];
        const orbital_elements& o = r.start;
        csv.stream() << csv_line({std::to_string(i), shortest(o.a), shortest(o.e), shortest(o.inclination / degree),
                                  shortest(o.node / degree), shortest(o.pericentre / degree),
                                  shortest(std::fmod(o.mean_anomaly / degree, 360.0)), r.kept ? "kept" : "removed",
                                  number_or_empty(r.megno), number_or_empty(r.a), number_or_empty(r.e), r.reason,
                                  r.kept ? "" : shortest(r.removed_time)});
    }
    csv.commit();
}

// MEGNO over (a, e): one coloured square per particle, blue up to 2
// (quasi-periodic; below 2 not yet converged), orange from 4, red from 8
// (chaotic); removed particles as black crosses.
void draw_map(const scene& s, std::size_t particles, const fs::path& dir) {
    atomic_file gp(dir / "test_particles_megno.gp");
    const double size = particles > 2500 ? 0.5 : particles > 400 ? 0.9 : 1.5;
    gp.stream() << "set terminal pngcairo size 900,750\nset output " << gnuplot_string("test_particles_megno.png")
                << "\nset datafile separator ','\nset datafile missing ''\nset title "
                << gnuplot_string(s.name + ": MEGNO <Y> of test particles (x: removed)") << " noenhanced\n"
                << "set xlabel 'a [AU]'\nset ylabel 'e'\nset cblabel 'MEGNO <Y> (2: quasi-periodic, > 4: chaotic)'\n"
                << "set cbrange [0:8]\n"
                << "set palette defined (0 '#1f3fbf', 2 '#1f3fbf', 3 '#e8c000', 4 '#f08000', 8 '#c00000')\n"
                << "plot " << gnuplot_string("test_particles.csv") << " every ::1 using 2:3:9 with points pointtype 5 "
                << "pointsize " << size << " palette notitle, \\\n     " << gnuplot_string("test_particles.csv")
                << " every ::1 using 2:(strcol(8) eq 'removed' ? $3 : NaN) with points pointtype 2 pointsize "
                << size << " lc rgb 'black' notitle\n";
    gp.commit();
    run_gnuplot(dir / "test_particles_megno.gp", dir / "test_particles_megno.png");
}

struct counts {
    std::size_t kept = 0, removed = 0, chaotic = 0, measured = 0;
    double median_regular = NAN;  // of the kept with MEGNO <= the threshold
};

counts tally(const std::vector<test_particle_row>& rows) {
    counts c;
    std::vector<double> regular;
    for (const test_particle_row& r : rows) {
        (r.kept ? c.kept : c.removed)++;
        if (!r.kept || !std::isfinite(r.megno)) continue;
        ++c.measured;
        if (r.megno > chaotic_test_particle_megno) ++c.chaotic;
        else regular.push_back(r.megno);
    }
    if (!regular.empty()) {
        std::nth_element(regular.begin(), regular.begin() + std::ptrdiff_t(regular.size() / 2), regular.end());
        c.median_regular = regular[regular.size() / 2];
    }
    return c;
}

std::string summary(const scene& s, const std::vector<test_particle_row>& rows, const counts& c, double seconds,
                    std::size_t piece, const std::vector<std::string>& files) {
    const test_particle_spec& tp = *s.test_particles;
    const auto [dt, steps] = test_particle_span_of(s);
    std::ostringstream md;
    md << "# sympl test particles\n\n## " << markdown_cell(s.name) << "\n\n"
       << s.system << " with " << rows.size() << " test particles ("
       << (tp.elements_file.empty() ? "a grid of " + std::to_string(tp.a.count) + " a in [" + shortest(tp.a.from) +
                                          ", " + shortest(tp.a.to) + "] AU by " + std::to_string(tp.e.count) +
                                          " e in [" + shortest(tp.e.from) + ", " + shortest(tp.e.to) + "]"
                                    : "the orbital elements of " + tp.elements_file)
       << "), " << s.methods[0].name << ", dt = " << shortest(dt) << ", t = " << shortest(s.t0) << " .. "
       << shortest(s.t0 + steps * dt) << " (" << format_number(steps, 6) << " whole steps).\n\n| kept | removed |" << (tp.megno ? " chaotic (MEGNO > 4) |" : "")
       << "\n|---|---|" << (tp.megno ? "---|" : "") << "\n| " << c.kept << " | " << c.removed << " |";
    if (tp.megno)
        md << " " << c.chaotic << " (" << fixed(c.measured ? 100.0 * double(c.chaotic) / double(c.measured) : 0, 1)
           << "% of the kept) |";
    md << "\n\n";
    if (tp.megno)
        md << "MEGNO <Y> per particle (Cincotta & Simo 2000) from its tangent vector along the numerical flow, the "
              "planets' run given: it tends to 2 on quasi-periodic orbits and grows like lambda t / 2 on chaotic ones "
              "(lambda the Lyapunov exponent); the regular particles' median here is "
           << (std::isfinite(c.median_regular) ? format_number(c.median_regular, 3) : "(none)") << ". ";
    md << "A particle is removed (status `removed`, the reason and time in the CSV) inside a planet's Hill radius "
          "a (m / 3 m_0)^(1/3), where a Kepler orbit about the star is no longer the main motion, or farther than "
       << shortest(test_particle_escape_distance) << " AU from the star.\n\nParticles run in pieces of "
       << piece << ", each with the same planets: test_particles.csv and the map are the same for any thread and "
          "MPI rank count. "
       << "Wall time " << fixed(seconds, 2) << " s.\n\nFiles: ";
    for (std::size_t k = 0; k < files.size(); ++k) md << (k ? ", " : "") << files[k];
    md << ", summary.md.\n";
    return md.str();
}

}  // namespace

void test_particles_command(const scene& s, const fs::path& out_dir, int threads, double max_steps, std::ostream& out,
                            std::size_t piece) {
    test_particles_command(s, out_dir, threads, max_steps, exchange{}, false, out, piece);
}

void test_particles_command(const scene& s, const fs::path& out_dir, int threads, double max_steps,
                            const exchange& ranks, bool resume, std::ostream& out, std::size_t piece) {
    const std::vector<orbital_elements> orbits = test_particle_orbits(s);
    if (ranks.rank != 0) {  // runs its pieces and hands them to rank 0, which writes
        run_test_particles(s, orbits, threads, max_steps, ranks, resume, piece);
        return;
    }
    output_set outputs(out_dir);
    const fs::path dir = outputs.staging();
    const double start = clock_seconds();
    const std::vector<test_particle_row> rows =
        run_test_particles(s, orbits, threads, max_steps, ranks, resume, piece);
    const double seconds = clock_seconds() - start;
    write_csv(rows, dir / "test_particles.csv");
    std::vector<std::string> files{"test_particles.csv"};
    if (have_gnuplot() && s.test_particles->megno) {
        draw_map(s, rows.size(), dir);
        files.push_back("test_particles_megno.gp");
        if (fs::exists(dir / "test_particles_megno.png")) files.push_back("test_particles_megno.png");
    }
    const counts c = tally(rows);
    atomic_file md(dir / "summary.md");
    md.stream() << summary(s, rows, c, seconds, piece, files);
    md.commit();
    outputs.commit();
    if (s.checkpoint.every_steps) remove_test_particle_checkpoints(s);  // complete: nothing to resume
    out << s.name << ": " << rows.size() << " test particles: " << c.kept << " kept, " << c.removed << " removed";
    if (s.test_particles->megno) out << ", " << c.chaotic << " chaotic (MEGNO > 4)";
    out << " (" << fixed(seconds, 2) << " s)\nwrote " << (outputs.directory() / "test_particles.csv").string();
    for (std::size_t k = 1; k < files.size(); ++k) out << ", " << files[k];
    out << " and summary.md\n";
}

}  // namespace sympl::app
