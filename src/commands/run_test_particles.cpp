// A scene's [test_particles] run: the population read, cut into fixed
// pieces, each piece a Wisdom-Holman run of its own over the same planets,
// the pieces shared among threads and MPI ranks (run_test_particles.hpp).
#include "commands/run_test_particles.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <sstream>
#include <thread>
#include <tuple>

#include <sympl/parallel/ensemble.hpp>
#include <sympl/planetary/energy.hpp>
#include <sympl/planetary/test_particles/encounters.hpp>
#include <sympl/planetary/wisdom_holman_stepper.hpp>

#include "reading/csv_numbers.hpp"
#include "reading/file_text.hpp"
#include "commands/ensemble_run.hpp"
#include "output/format.hpp"
#include "output/row_checkpoint.hpp"
#include "methods/run_plan.hpp"
#include "running/systems.hpp"

namespace sympl::app {

namespace {

constexpr double degree = std::numbers::pi / 180;
const std::vector<std::string> element_columns{"a", "e", "inclination", "node", "pericentre", "mean_anomaly"};

// elements = "file.csv": a header naming the columns, a and e first, then
// any leading part of inclination, node, pericentre, mean_anomaly (degrees).
std::vector<orbital_elements> read_elements(const std::string& path) {
    const file_text read = read_file_text(path, max_elements_bytes);
    if (!read.failure.empty()) throw scene_error(printable(path) + ": the orbital elements file " + read.failure);
    std::istringstream in(read.text);
    std::string line, header;
    std::size_t number = 0, columns = 0;
    std::vector<orbital_elements> orbits;
    while (std::getline(in, line)) {
        ++number;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const std::string where = printable(path) + ":" + std::to_string(number) + ": ";
        if (number == 1) {
            for (std::size_t k = 0; k < element_columns.size(); ++k) {
                header += (k ? "," : "") + element_columns[k];
                if (k >= 1 && line == header) columns = k + 1;
            }
            if (!columns)
                throw scene_error(where + "header '" + line + "'; expected 'a,e' and optionally the next of "
                                  "',inclination,node,pericentre,mean_anomaly' in that order (angles in degrees)");
            continue;
        }
        if (line.empty()) continue;
        const std::vector<double> x = csv_numbers(line, where);
        if (x.size() != columns)
            throw scene_error(where + std::to_string(x.size()) + " fields; expected " + std::to_string(columns) +
                              " as the header names");
        if (!(x[0] > 0)) throw scene_error(where + "a = " + shortest(x[0]) + "; expected a semi-major axis > 0 (AU)");
        if (!(x[1] >= 0 && x[1] < 1))
            throw scene_error(where + "e = " + shortest(x[1]) + "; expected an eccentricity in [0, 1) (elliptic orbits)");
        if (const std::string why = orbit_outside(x[0], x[1]); !why.empty()) throw scene_error(where + why);
        if (double(orbits.size()) >= max_test_particles)
            throw scene_error(where + "more than " + std::to_string(std::size_t(max_test_particles)) +
                              " test particles; expected at most that");
        orbital_elements o{x[0], x[1]};
        double* angles[] = {&o.inclination, &o.node, &o.pericentre, &o.mean_anomaly};
        for (std::size_t k = 2; k < columns; ++k) *angles[k - 2] = x[k] * degree;
        orbits.push_back(o);
    }
    if (orbits.empty()) throw scene_error(printable(path) + ": no orbits; expected a header and at least one line of elements");
    return orbits;
}

// The osculating heliocentric a and e of a particle at (r, v) about G m_0,
// r and v relative to the star.
std::pair<double, double> elements_of(const std::array<double, 3>& r, const std::array<double, 3>& v, double gm) {
    const double rr = std::hypot(r[0], r[1], r[2]), v2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    const double rv = r[0] * v[0] + r[1] * v[1] + r[2] * v[2];
    std::array<double, 3> e{};
    for (int c = 0; c < 3; ++c) e[std::size_t(c)] = ((v2 - gm / rr) * r[std::size_t(c)] - rv * v[std::size_t(c)]) / gm;
    return {1 / (2 / rr - v2 / gm), std::hypot(e[0], e[1], e[2])};
}

struct planets {
    std::vector<double> mass;
    double G = 0;
    phase_space<double> x0;
    method_spec method;
    double t0 = 0, dt = 0;
    std::size_t steps = 0;
    std::vector<std::string> body_names;  // star first
    bool megno = false;
};

// A map over planets that fall into the star or leave it measures nothing:
// each planet's heliocentric two-body orbit at the start (about G (m_0 +
// m_k)) must be bound with its pericentre outside the star, as the test
// particles' are (orbit_outside). Planets started at rest have e = 1.
void check_planets_bound(const scene& s, const planets& p) {
    const auto at = [&](const Eigen::VectorXd& x, std::size_t k, int c) { return x[Eigen::Index(3 * k + std::size_t(c))]; };
    for (std::size_t k = 1; k < p.mass.size(); ++k) {
        std::array<double, 3> r{}, v{};
        for (int c = 0; c < 3; ++c) {
            r[std::size_t(c)] = at(p.x0.q, k, c) - at(p.x0.q, 0, c);
            v[std::size_t(c)] = at(p.x0.p, k, c) / p.mass[k] - at(p.x0.p, 0, c) / p.mass[0];
        }
        const double mu = p.G * (p.mass[0] + p.mass[k]);
        const double speed = std::hypot(v[0], v[1], v[2]), distance = std::hypot(r[0], r[1], r[2]);
        if (!(std::isfinite(speed) && speed * speed < 2 * mu / distance))  // v^2 / 2 - mu / r >= 0, or overflow
            throw scene_error(printable(s.source) + ": the planet " + p.body_names[k] + " starts at " +
                              format_number(distance, 6) + " AU from the star at " + format_number(speed, 6) +
                              " AU/day, at or past the escape speed " + format_number(std::sqrt(2 * mu / distance), 6) +
                              " AU/day" +
                              "; expected planets on bound orbits outside the star (" +
                              shortest(test_particle_star_radius) + " AU) for a test-particle map");
        const auto [a, e] = elements_of(r, v, mu);
        const std::string planet = printable(s.source) + ": the planet " + p.body_names[k] + " starts on a heliocentric orbit with ";
        const std::string expected = "; expected planets on bound orbits outside the star (" +
                                     shortest(test_particle_star_radius) + " AU) for a test-particle map";
        // The pericentre h^2 / (G M (1 + e)), for any conic: 0 for a fall (h = 0), where a (1 - e) rounds.
        const std::array<double, 3> h{r[1] * v[2] - r[2] * v[1], r[2] * v[0] - r[0] * v[2], r[0] * v[1] - r[1] * v[0]};
        const double h2 = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
        const double pericentre = h2 / (mu * (1 + e));
        const std::string orbit = "a = " + shortest(a) + " AU, e = " + shortest(e);
        if (pericentre <= test_particle_star_radius)
            throw scene_error(planet + orbit + ": pericentre " + shortest(pericentre) + " AU, inside the star" +
                              expected);
        if (!(std::isfinite(a) && std::isfinite(e) && a > 0 && e < 1))
            throw scene_error(planet + orbit + ", not bound" + expected);
    }
}

// One piece: orbits[first, last) with the planets, into rows[first, last).
void run_piece(const planets& p, const std::vector<orbital_elements>& orbits, std::size_t first, std::size_t last,
               std::vector<test_particle_row>& rows) {
    using State = phase_space<double>;
    const std::vector<orbital_elements> mine(orbits.begin() + std::ptrdiff_t(first), orbits.begin() + std::ptrdiff_t(last));
    wisdom_holman_stepper<State> wh(p.mass, p.G, *p.method.coefficients, wisdom_holman_options_of(p.method));
    State x = p.x0;
    wh.set_test_particles(particles_on(mine, x, p.mass, p.G));
    // Removed, never silently lost: inside a planet's Hill radius, where the
    // splitting about the star no longer holds, or past the escape distance.
    encounter_options lost;
    lost.radius.push_back(test_particle_star_radius);
    for (std::size_t k = 1; k < p.mass.size(); ++k) {
        const double d = std::hypot(x.q[Eigen::Index(3 * k)] - x.q[0], x.q[Eigen::Index(3 * k + 1)] - x.q[1],
                                    x.q[Eigen::Index(3 * k + 2)] - x.q[2]);
        lost.radius.push_back(d * std::cbrt(p.mass[k] / (3 * p.mass[0])));
    }
    lost.escape_distance = test_particle_escape_distance;
    wh.track_encounters(lost, p.t0);
    if (p.megno) wh.start_test_particle_megno();
    wh.steps(x, p.dt, p.steps);
    // The planets blown up (a scene's own initial state can do it): an error
    // with the figures, never rows of particles "kept" in a run that ended early.
    if (!x.q.allFinite() || !x.p.allFinite())
        throw scene_error("the planets' state became non-finite within " + std::to_string(p.steps) +
                          " steps of dt = " + shortest(p.dt) + " from t = " + shortest(p.t0) +
                          "; expected a bound planetary system (check the scene's initial state and dt)");
    // Nor a map over planets the run did not keep (two planets started close
    // fly apart at 1e21 AU/day, the particles "kept"): their energy error at
    // the end is held to what `sympl run` flags as an error of order one.
    // The scale: |E|, or the kinetic energy where that is larger (E near 0
    // in a frame where the system moves as a whole).
    const double e0 = nbody_energy(p.mass, p.G, p.x0), e1 = nbody_energy(p.mass, p.G, x);
    double kinetic = 0;
    for (std::size_t k = 0; k < p.mass.size(); ++k)
        kinetic += p.x0.p.segment<3>(Eigen::Index(3 * k)).squaredNorm() / (2 * p.mass[k]);
    if (const double error = std::fabs(e1 - e0) / std::max(std::fabs(e0), kinetic); !(error < order_one_error))
        throw scene_error("the planets' energy changed by " + format_number(error, 3) + " of its scale within " +
                          std::to_string(p.steps) + " steps of dt = " + shortest(p.dt) + " from t = " +
                          shortest(p.t0) + "; expected below " + shortest(order_one_error) +
                          ", a planetary system the method keeps (check the scene's initial state and dt)");
    const auto& kept = wh.test_particles();
    const std::vector<double> megno = p.megno ? wh.test_particle_megno() : std::vector<double>(kept.size(), NAN);
    const double gm = p.G * p.mass[0];
    const std::array<double, 3> sun_v{x.p[0] / p.mass[0], x.p[1] / p.mass[0], x.p[2] / p.mass[0]};
    for (std::size_t i = first; i < last; ++i) rows[i].start = orbits[i], rows[i].kept = false;
    for (std::size_t k = 0; k < kept.size(); ++k) {
        test_particle_row& row = rows[first + kept.id[k]];
        row.kept = true;
        row.megno = megno[k];
        std::tie(row.a, row.e) = elements_of({kept.x[k] - x.q[0], kept.y[k] - x.q[1], kept.z[k] - x.q[2]},
                                             {kept.vx[k] - sun_v[0], kept.vy[k] - sun_v[1], kept.vz[k] - sun_v[2]}, gm);
    }
    for (const auto& loss : wh.encounters().losses()) {
        test_particle_row& row = rows[first + loss.particle];
        row.kept = false;
        row.megno = row.a = row.e = NAN;
        row.reason = loss.reason != loss_reason::collision ? loss_reason_name(loss.reason)
                     : loss.body == 0                          ? "collision with the star"
                                                               : "inside the Hill radius of " + p.body_names[loss.body];
        row.removed_time = loss.time;
    }
}

// A row's results as bytes for another rank: its index, then the numbers
// bit for bit (memcpy), the reason with its length.
template <class T>
void put(std::string& out, const T& v) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &v, sizeof(T));
    out.append(bytes, sizeof(T));
}
void put_row(std::string& out, std::size_t index, const test_particle_row& r) {
    put(out, std::uint64_t(index));
    put(out, std::uint8_t(r.kept));
    for (double v : {r.megno, r.a, r.e, r.removed_time}) put(out, v);
    put(out, std::uint64_t(r.reason.size()));
    out += r.reason;
}

// Reads what put_row wrote into rows (their starts are rank 0's own).
class row_reader {
public:
    explicit row_reader(const std::string& text) : text_(text) {}
    bool done() const { return at_ == text_.size(); }
    void into(std::vector<test_particle_row>& rows) {
        const auto index = get<std::uint64_t>();
        if (index >= rows.size()) broken();
        test_particle_row& r = rows[std::size_t(index)];
        r.kept = get<std::uint8_t>() != 0;
        for (double* v : {&r.megno, &r.a, &r.e, &r.removed_time}) *v = get<double>();
        const auto length = get<std::uint64_t>();
        if (length > text_.size() - at_) broken();
        r.reason = text_.substr(at_, std::size_t(length));
        at_ += std::size_t(length);
    }

private:
    template <class T>
    T get() {
        if (text_.size() - at_ < sizeof(T)) broken();
        T v;
        std::memcpy(&v, text_.data() + at_, sizeof(T));
        at_ += sizeof(T);
        return v;
    }
    [[noreturn]] void broken() const {
        throw sympl::error("run_test_particles: a rank's rows end at byte " + std::to_string(at_) + " of " +
                           std::to_string(text_.size()) + "; expected whole rows of this run's particles");
    }
    const std::string& text_;
    std::size_t at_ = 0;
};

// A map's checkpoints (row_checkpoint.hpp): a row per particle, its index,
// kept, MEGNO, final a and e, removal time and reason; the starts are the
// scene's.
constexpr const char* checkpoint_head = test_particles_checkpoint_head;
const std::string checkpoint_kind = "test-particles";
using saved_rows = std::map<std::size_t, test_particle_row>;

void put_saved(std::string& out, std::size_t index, const test_particle_row& r) {
    out += "row " + std::to_string(index) + (r.kept ? " 1 " : " 0 ") + hex_text(r.megno) + ' ' + hex_text(r.a) + ' ' +
           hex_text(r.e) + ' ' + hex_text(r.removed_time) + ' ' + std::to_string(r.reason.size()) + ' ' + r.reason +
           '\n';
}

saved_rows read_saved(const scene& s, std::size_t particles) {
    saved_rows rows;
    for (const auto& [file, text] :
         read_row_checkpoints(s.checkpoint.file, checkpoint_kind, checkpoint_head, s.text_hash)) {
        std::istringstream in(text);
        std::string word;
        while (in >> word) {
            if (word != "row") refuse_row_checkpoint(checkpoint_kind, file, "expected 'row', found '" + word + "'");
            const std::size_t index = read_count(in, checkpoint_kind, file, particles - 1);
            test_particle_row r;
            r.kept = read_count(in, checkpoint_kind, file, 1) == 1;
            for (double* v : {&r.megno, &r.a, &r.e, &r.removed_time}) *v = read_number(in, checkpoint_kind, file);
            r.reason = read_text(in, checkpoint_kind, file);
            rows[index] = std::move(r);
        }
    }
    return rows;
}

// This rank's file, rewritten once `every` particle-steps have finished
// since the last time: the rows of its finished pieces and of every piece
// the checkpoints resumed from held.
struct piece_saves {
    bool on = false;
    std::filesystem::path mine;
    std::string scene_hash;
    double every = 0, since = 0;
    saved_rows rows;
    std::mutex lock;

    void finished(const std::vector<test_particle_row>& all, std::size_t first, std::size_t last, double steps) {
        if (!on) return;
        const std::lock_guard<std::mutex> hold(lock);
        for (std::size_t i = first; i < last; ++i) rows[i] = all[i];
        since += double(last - first) * steps;
        if (since < every) return;
        since = 0;
        std::string text;
        for (const auto& [index, row] : rows) put_saved(text, index, row);
        write_row_checkpoint(mine, checkpoint_head, scene_hash, text);
    }
};

}  // namespace

void remove_test_particle_checkpoints(const scene& s) { remove_row_checkpoints(s.checkpoint.file, checkpoint_kind); }

test_particle_span test_particle_span_of(const scene& s) {
    const double dt = sweep_of(s, s.methods[0])[0];
    return {dt, std::max(1.0, std::ceil((s.t_end - s.t0) / dt - 1e-9))};
}

std::string orbit_outside(double a, double e) {
    const std::string orbit = "a = " + shortest(a) + " AU, e = " + shortest(e) + ": ";
    const std::string expected = "; expected orbits between the star's radius (" +
                                 shortest(test_particle_star_radius) + " AU) and the escape distance (" +
                                 shortest(test_particle_escape_distance) + " AU)";
    if (a * (1 - e) <= test_particle_star_radius)
        return orbit + "pericentre " + shortest(a * (1 - e)) + " AU, inside the star" + expected;
    if (a * (1 + e) >= test_particle_escape_distance)
        return orbit + "apocentre " + shortest(a * (1 + e)) + " AU, past the escape distance" + expected;
    return "";
}

std::vector<orbital_elements> test_particle_orbits(const scene& s) {
    const test_particle_spec& tp = *s.test_particles;
    if (!tp.elements_file.empty()) return read_elements(tp.elements_file);
    orbital_elements rest;
    rest.inclination = tp.inclination * degree, rest.node = tp.node * degree, rest.pericentre = tp.pericentre * degree;
    rest.mean_anomaly = tp.mean_anomaly * degree;
    return element_grid(tp.a.from, tp.a.to, tp.a.count, tp.e.from, tp.e.to, tp.e.count, rest);
}

std::vector<test_particle_row> run_test_particles(const scene& s, const std::vector<orbital_elements>& orbits,
                                                  int threads, double max_steps, std::size_t piece) {
    return run_test_particles(s, orbits, threads, max_steps, exchange{}, false, piece);
}

std::vector<test_particle_row> run_test_particles(const scene& s, const std::vector<orbital_elements>& orbits,
                                                  int threads, double max_steps, const exchange& ranks, bool resume,
                                                  std::size_t piece) {
    if (resume && !s.checkpoint.every_steps)
        throw scene_error(printable(s.source) + ": --resume, but the scene has no checkpoint = {every_steps = N, file = \"...\"}");
    if (piece == 0) throw invalid_argument("run_test_particles: pieces of 0 particles; expected at least 1");
    const runnable_system base = make_system(s.system, s.parameters, s.q0, s.p0, s.source);
    planets p{base.masses, base.G, phase_space<double>(base.x0.size() / 2), s.methods[0], s.t0,
              test_particle_span_of(s).dt, 0, {}, s.test_particles->megno};
    // Bodies by the registry's coordinate names ("jupiter_x": jupiter), else "body k".
    const std::vector<std::string> columns = state_columns(s.system, base.x0.size() / 2);
    for (std::size_t k = 0; k < p.mass.size(); ++k) {
        const std::string& c = columns[3 * k];
        p.body_names.push_back(c.ends_with("_x") ? c.substr(0, c.size() - 2) : "body " + std::to_string(k));
    }
    const std::size_t n = base.x0.size() / 2;
    for (std::size_t i = 0; i < n; ++i) p.x0.q[Eigen::Index(i)] = base.x0[i], p.x0.p[Eigen::Index(i)] = base.x0[n + i];
    check_planets_bound(s, p);
    const double span_steps = test_particle_span_of(s).steps;
    const double total = span_steps * double(orbits.size());
    if (!(span_steps <= max_steps) || !(total <= 1e4 * max_steps))
        throw scene_error(printable(s.source) + ": " + shortest(double(orbits.size())) + " test particles over " +
                          format_number(span_steps, 6) + " steps of dt = " + shortest(p.dt) + " take " +
                          format_number(total, 6) + " particle-steps; the limit is " + format_number(max_steps, 6) +
                          " steps and 1e4 times that in particle-steps (raise it with --max-steps)");
    p.steps = std::size_t(span_steps);
    std::vector<test_particle_row> rows(orbits.size());
    const std::size_t pieces = (orbits.size() + piece - 1) / piece;
    // Piece k on rank k mod size; each piece writes its own rows: the same
    // numbers for any thread and rank count. A piece a checkpoint holds whole
    // is taken from it (its rows are those numbers, to the bit).
    piece_saves saves;
    if (s.checkpoint.every_steps) {
        saves.on = true;
        saves.mine = row_checkpoint_file(s.checkpoint.file, checkpoint_kind, ranks.rank);
        // Made before any piece runs, as run and ensemble make theirs: a
        // folder that does not exist would otherwise fail the first save.
        if (saves.mine.has_parent_path()) std::filesystem::create_directories(saves.mine.parent_path());
        saves.scene_hash = s.text_hash;
        saves.every = double(s.checkpoint.every_steps);
    }
    const saved_rows saved = resume ? read_saved(s, orbits.size()) : saved_rows{};
    saves.rows = saved;  // kept in this rank's file too: a second kill at another rank count loses none of them
    std::vector<std::size_t> mine, pending;
    for (std::size_t k = std::size_t(ranks.rank); k < pieces; k += std::size_t(ranks.size)) mine.push_back(k);
    for (std::size_t k : mine) {
        const std::size_t first = k * piece, last = std::min(orbits.size(), (k + 1) * piece);
        bool whole = true;
        for (std::size_t i = first; i < last && whole; ++i) whole = saved.count(i) == 1;
        if (!whole) {
            pending.push_back(k);
            continue;
        }
        for (std::size_t i = first; i < last; ++i) rows[i] = saved.at(i), rows[i].start = orbits[i];
    }
    for_each_in_parallel(pending.size(), threads, [&](std::size_t j) {
        const std::size_t k = pending[j], first = k * piece, last = std::min(orbits.size(), (k + 1) * piece);
        run_piece(p, orbits, first, last, rows);
        saves.finished(rows, first, last, double(p.steps));
    });
    if (ranks.size == 1) return rows;
    std::string text;
    for (std::size_t k : mine)
        for (std::size_t i = k * piece; i < std::min(orbits.size(), (k + 1) * piece); ++i) put_row(text, i, rows[i]);
    const std::vector<std::string> all = ranks.gather(text);
    if (ranks.rank != 0) return {};
    for (std::size_t i = 0; i < orbits.size(); ++i) rows[i].start = orbits[i];
    for (std::size_t r = 1; r < all.size(); ++r)
        for (row_reader in(all[r]); !in.done();) in.into(rows);
    return rows;
}

}  // namespace sympl::app
