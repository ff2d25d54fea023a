// Checkpoints of `sympl ensemble` (ensemble_checkpoint.hpp), in the rank
// files of row_checkpoint.hpp.
#include "output/ensemble_checkpoint.hpp"

#include <cstdint>
#include <sstream>

#include "output/row_checkpoint.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {
constexpr const char* head = ensemble_checkpoint_head;
const std::string kind = "ensemble";

// A row: index, stable, blow-up step and time, energy error, MEGNO, the
// final state (count, numbers), the failure (length, then its bytes).
void put(std::ostringstream& o, std::size_t index, const ensemble_row& r) {
    o << "row " << index << ' ' << r.stable << ' ' << r.blowup_step << ' ' << hex_text(r.blowup_time) << ' '
      << hex_text(r.max_energy_error) << ' ' << hex_text(r.megno) << ' ' << r.final_state.size();
    for (double v : r.final_state) o << ' ' << hex_text(v);
    o << ' ' << r.failure.size() << ' ' << r.failure << '\n';
}

void read_rows(const fs::path& file, const std::string& text, ensemble_rows& rows) {
    std::istringstream in(text);
    std::string word;
    while (in >> word) {
        if (word != "row") refuse_row_checkpoint(kind, file, "expected 'row', found '" + word + "'");
        const std::size_t index = read_count(in, kind, file, std::size_t(1) << 48);
        ensemble_row r;
        r.stable = read_count(in, kind, file, 1) == 1;
        r.blowup_step = read_count(in, kind, file, SIZE_MAX / 2);
        r.blowup_time = read_number(in, kind, file);
        r.max_energy_error = read_number(in, kind, file);
        r.megno = read_number(in, kind, file);
        r.final_state.resize(read_count(in, kind, file, std::size_t(1) << 20));
        for (double& v : r.final_state) v = read_number(in, kind, file);
        r.failure = read_text(in, kind, file);
        rows[index] = std::move(r);
    }
}
}  // namespace

fs::path ensemble_checkpoint_file(const std::string& file, int rank) { return row_checkpoint_file(file, kind, rank); }

void write_ensemble_checkpoint(const fs::path& path, const std::string& scene_hash, const ensemble_rows& rows) {
    std::ostringstream body;
    for (const auto& [index, row] : rows) put(body, index, row);
    write_row_checkpoint(path, head, scene_hash, body.str());
}

ensemble_rows read_ensemble_checkpoints(const std::string& file, const std::string& scene_hash) {
    ensemble_rows rows;
    for (const auto& [path, text] : read_row_checkpoints(file, kind, head, scene_hash)) read_rows(path, text, rows);
    return rows;
}

void remove_ensemble_checkpoints(const std::string& file) { remove_row_checkpoints(file, kind); }

}  // namespace sympl::app
