// `sympl ensemble`: grid or CSV of states -> rows in input order, split over
// threads and ranks, written by rank 0 (see ensemble_run.hpp): set up,
// compute this rank's block, gather blocks and counts, write.
#include "commands/ensemble_run.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <ostream>
#include <sstream>

#include <sympl/core/error.hpp>
#include <sympl/parallel/ensemble.hpp>

#include "output/ensemble_checkpoint.hpp"
#include "reading/ensemble_points.hpp"
#include "output/ensemble_write.hpp"
#include "output/format.hpp"
#include "output/output_set.hpp"
#include "report/timing.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

// This rank's static block of the ensemble, computed.
struct ensemble_block {
    std::size_t first = 0;
    std::vector<ensemble_point> points;
    std::vector<ensemble_row> rows;
    std::vector<bool> has_row;  // false: an invalid point, not run
};

// The ensemble's checkpoints (ensemble_checkpoint.hpp): the rows any rank's
// file holds, and this rank's file, rewritten after each piece of `piece`
// trajectories (0: no checkpoints, one piece).
struct block_checkpoints {
    std::string scene_hash;
    std::string file;  // the scene's checkpoint file, which the ranks' files are named after
    fs::path mine;
    std::size_t piece = 0;
    ensemble_rows rows;
};

ensemble_block compute_block(const ensemble_setup& u, int threads, const exchange& ranks, block_checkpoints& saves) {
    const std::size_t n = u.trajectories;
    ensemble_block b;
    b.first = n * std::size_t(ranks.rank) / std::size_t(ranks.size);
    const std::size_t last = n * std::size_t(ranks.rank + 1) / std::size_t(ranks.size);
    for (std::size_t i = b.first; i < last; ++i) b.points.push_back(point_at(*u.s, *u.entry, u.defaults, i, u.states));
    b.rows.resize(b.points.size());
    b.has_row.assign(b.points.size(), false);
    // The valid points no checkpoint holds a row of, in pieces.
    std::vector<std::size_t> pending;
    for (std::size_t i = 0; i < b.points.size(); ++i) {
        if (!b.points[i].invalid.empty()) continue;
        if (const auto saved = saves.rows.find(b.first + i); saved != saves.rows.end()) {
            // A row of another state size would write a CSV line of other columns.
            if (saved->second.final_state.size() != b.points[i].x0.size())
                throw error("ensemble checkpoint " + printable(saves.file) + ".ensemble-rank-*: the row of point " +
                            std::to_string(b.first + i) + " holds a final state of " +
                            std::to_string(saved->second.final_state.size()) + " numbers; expected " +
                            std::to_string(b.points[i].x0.size()) +
                            " (q then p); not resumed from (remove them to start over)");
            b.rows[i] = saved->second;
            b.has_row[i] = true;
        } else {
            pending.push_back(i);
        }
    }
    const scene& s = *u.s;
    const auto run_group = [&](const std::vector<std::size_t>& g, int team) {
        const runnable_system p = make_system(s.system, b.points[g.front()].parameters, s.q0, s.p0, s.source);
        std::vector<std::vector<double>> starts;
        for (std::size_t m : g) starts.push_back(b.points[m].x0);
        ensemble_request r = u.request;
        r.threads = team;
        const auto result = p.ensemble(r, starts);
        for (std::size_t k = 0; k < g.size(); ++k) {
            b.rows[g[k]] = result[k];
            b.has_row[g[k]] = true;
        }
    };
    const std::size_t piece = saves.piece ? saves.piece : std::max<std::size_t>(1, pending.size());
    for (std::size_t from = 0; from < pending.size(); from += piece) {
        // Consecutive valid points of one Hamiltonian form a group: one call of
        // the library's ensemble (SIMD batches, threads).
        std::vector<std::vector<std::size_t>> groups;  // indices into points
        for (std::size_t k = from; k < std::min(pending.size(), from + piece); ++k) {
            const std::size_t i = pending[k];
            if (groups.empty() || b.points[groups.back().back()].hamiltonian_key != b.points[i].hamiltonian_key)
                groups.push_back({});
            groups.back().push_back(i);
        }
        if (groups.size() == 1)
            run_group(groups[0], threads);
        else if (!groups.empty())  // many Hamiltonians (a grid over a parameter of H): the groups over threads
            for_each_in_parallel(groups.size(), threads, [&](std::size_t g) { run_group(groups[g], 1); });
        if (!saves.piece) continue;
        for (const auto& g : groups)
            for (std::size_t i : g) saves.rows[b.first + i] = b.rows[i];
        ensemble_rows mine;
        for (std::size_t i = 0; i < b.points.size(); ++i)
            if (b.has_row[i]) mine[b.first + i] = b.rows[i];
        write_ensemble_checkpoint(saves.mine, saves.scene_hash, mine);
    }
    return b;
}

// The counts of a block, from its rows.
void count(const ensemble_block& b, bool megno, ensemble_outcome& o) {
    for (std::size_t i = 0; i < b.points.size(); ++i) {
        ++o.trajectories;
        if (!b.has_row[i]) ++o.invalid;
        else if (!b.rows[i].stable) ++o.unstable;
        else {
            ++o.stable;
            if (megno && std::isfinite(b.rows[i].megno) && b.rows[i].megno > chaotic_megno) ++o.chaotic;
        }
    }
}

// A block as sent to rank 0: a line of its counts, then its CSV rows.
std::string block_text(const ensemble_setup& u, const ensemble_block& b, const ensemble_outcome& counts) {
    std::vector<ensemble_row_of> rows;
    for (std::size_t i = 0; i < b.points.size(); ++i)
        rows.push_back({b.first + i, &b.points[i], b.has_row[i] ? &b.rows[i] : nullptr});
    return std::to_string(counts.trajectories) + ' ' + std::to_string(counts.stable) + ' ' +
           std::to_string(counts.unstable) + ' ' + std::to_string(counts.invalid) + ' ' +
           std::to_string(counts.chaotic) + '\n' + csv_rows(u, rows);
}

// Rank 0: every rank's counts added up; the blocks' CSV rows returned.
std::vector<std::string> add_up(const std::vector<std::string>& blocks, ensemble_outcome& o) {
    std::vector<std::string> rows;
    for (const std::string& block : blocks) {
        const std::size_t eol = block.find('\n');
        std::istringstream line(block.substr(0, eol));
        std::size_t n[5];
        for (std::size_t& v : n)
            if (!(line >> v)) throw error("sympl ensemble: a rank sent a malformed block; expected the same sympl on every rank");
        o.trajectories += n[0], o.stable += n[1], o.unstable += n[2], o.invalid += n[3], o.chaotic += n[4];
        rows.push_back(eol == std::string::npos ? std::string() : block.substr(eol + 1));
    }
    return rows;
}

}  // namespace

ensemble_outcome run_ensemble_scene(const scene& s, const fs::path& dir, const std::string& prefix, int threads,
                                    double max_steps, bool plots, const exchange& ranks, bool resume) {
    const ensemble_setup u = set_up_ensemble(s, max_steps);
    const double started = clock_seconds();
    block_checkpoints saves;
    if (s.checkpoint.every_steps) {
        saves.scene_hash = s.text_hash;
        saves.mine = ensemble_checkpoint_file(s.checkpoint.file, ranks.rank);
        saves.piece = std::max<std::size_t>(1, s.checkpoint.every_steps / std::max<std::size_t>(1, u.request.steps));
        if (saves.mine.has_parent_path()) fs::create_directories(saves.mine.parent_path());
        saves.file = s.checkpoint.file;
        if (resume) saves.rows = read_ensemble_checkpoints(s.checkpoint.file, s.text_hash);
    } else if (resume) {
        throw scene_error(printable(s.source) + ": --resume, but the scene has no checkpoint = {every_steps = N, file = \"...\"}");
    }
    const ensemble_block block = compute_block(u, threads, ranks, saves);
    ensemble_outcome mine;
    count(block, s.ensemble->megno, mine);
    ensemble_outcome outcome;
    outcome.scene_name = s.name;
    outcome.seconds = clock_seconds() - started;  // this process's share
    const std::vector<std::string> all = ranks.gather(block_text(u, block, mine));
    if (ranks.rank != 0) return outcome;
    write_ensemble(u, add_up(all, outcome), dir, prefix, plots, outcome);
    return outcome;
}

void ensemble_command(const scene& s, const std::string& out_dir, int threads, double max_steps, const exchange& ranks,
                      std::ostream& out, bool resume) {
    // Only rank 0 writes; the others compute their rows and send them.
    std::optional<output_set> outputs;
    if (ranks.rank == 0) outputs.emplace(out_dir);
    const fs::path dir = outputs ? outputs->staging() : fs::path();
    const ensemble_outcome o = run_ensemble_scene(s, dir, "", threads, max_steps, have_gnuplot(), ranks, resume);
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
    if (s.checkpoint.every_steps) remove_ensemble_checkpoints(s.checkpoint.file);  // complete: nothing to resume
    out << s.name << ": " << o.trajectories << " trajectories: " << o.stable << " stable, " << o.unstable
        << " unstable, " << o.invalid << " invalid";
    if (s.ensemble->megno) out << ", " << o.chaotic << " chaotic (MEGNO > " << shortest(chaotic_megno) << ")";
    out << "\nwrote " << (outputs->directory() / "ensemble.csv").string() << " and summary.md";
    for (const auto& f : o.files)
        if (f != "ensemble.csv") out << ", " << f;
    out << "\n";
}

}  // namespace sympl::app
