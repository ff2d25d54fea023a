// Checkpoints of `sympl ensemble` (ensemble_checkpoint.hpp).
#include "ensemble_checkpoint.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

#include <sympl/core/error.hpp>

#include "checkpoint.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {
constexpr const char* head = "sympl-ensemble-checkpoint 1\n";

std::string hex(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%a", v);
    return b;
}

[[noreturn]] void refuse(const fs::path& file, const std::string& why) {
    throw error("ensemble checkpoint " + file.string() + ": " + why + "; not resumed from (remove it to start over)");
}

std::string prefix_of(const std::string& file) { return fs::path(file).filename().string() + ".ensemble-rank-"; }
fs::path directory_of(const std::string& file) {
    const fs::path f(file);
    return f.has_parent_path() ? f.parent_path() : fs::path(".");
}

// A row: index, stable, blow-up step and time, energy error, MEGNO, the
// final state (count, numbers), the failure (length, then its bytes).
void put(std::ostringstream& o, std::size_t index, const ensemble_row& r) {
    o << "row " << index << ' ' << r.stable << ' ' << r.blowup_step << ' ' << hex(r.blowup_time) << ' '
      << hex(r.max_energy_error) << ' ' << hex(r.megno) << ' ' << r.final_state.size();
    for (double v : r.final_state) o << ' ' << hex(v);
    o << ' ' << r.failure.size() << ' ' << r.failure << '\n';
}

double number(std::istream& in, const fs::path& file) {
    std::string word;
    if (!(in >> word)) refuse(file, "a row ends early");
    char* end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (end != word.c_str() + word.size()) refuse(file, "'" + word + "' in a row is not a number");
    return v;
}

template <class N>
N count(std::istream& in, const fs::path& file, N largest) {
    N v{};
    if (!(in >> v) || v > largest) refuse(file, "a row holds a bad count");
    return v;
}

void read_rows(const fs::path& file, const std::string& scene_hash, ensemble_rows& rows) {
    std::ifstream stream(file, std::ios::binary);
    if (!stream) refuse(file, "cannot be opened");
    const std::string text((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
    if (text.rfind(head, 0) != 0) refuse(file, "is not a sympl ensemble checkpoint of this format");
    const auto mark = text.rfind("checksum ");
    if (mark == std::string::npos || mark < std::string(head).size()) refuse(file, "is truncated (no checksum)");
    const std::string body = text.substr(std::string(head).size(), mark - std::string(head).size());
    if (text.substr(mark) != "checksum " + fnv1a_hex(body) + "\n") refuse(file, "is corrupted (checksum mismatch)");
    std::istringstream in(body);
    std::string word, hash;
    if (!(in >> word >> hash) || word != "scene") refuse(file, "has no scene line");
    if (hash != scene_hash) refuse(file, "belongs to another scene (or the scene file changed)");
    while (in >> word) {
        if (word != "row") refuse(file, "expected 'row', found '" + word + "'");
        const auto index = count<std::size_t>(in, file, std::size_t(1) << 48);
        ensemble_row r;
        r.stable = count<int>(in, file, 1) == 1;
        r.blowup_step = count<std::size_t>(in, file, SIZE_MAX / 2);
        r.blowup_time = number(in, file);
        r.max_energy_error = number(in, file);
        r.megno = number(in, file);
        r.final_state.resize(count<std::size_t>(in, file, 1u << 20));
        for (double& v : r.final_state) v = number(in, file);
        r.failure.resize(count<std::size_t>(in, file, 1u << 20));
        if (in.get() != ' ' || !in.read(r.failure.data(), std::streamsize(r.failure.size())) || in.get() != '\n')
            refuse(file, "a row's failure text is cut");
        rows[index] = std::move(r);
    }
}
}  // namespace

fs::path ensemble_checkpoint_file(const std::string& file, int rank) {
    return directory_of(file) / (prefix_of(file) + std::to_string(rank));
}

void write_ensemble_checkpoint(const fs::path& path, const std::string& scene_hash, const ensemble_rows& rows) {
    std::ostringstream body;
    body << "scene " << scene_hash << '\n';
    for (const auto& [index, row] : rows) put(body, index, row);
    write_durably(path, head + body.str() + "checksum " + fnv1a_hex(body.str()) + "\n");
}

ensemble_rows read_ensemble_checkpoints(const std::string& file, const std::string& scene_hash) {
    ensemble_rows rows;
    std::error_code ec;
    const std::string prefix = prefix_of(file);
    for (const auto& entry : fs::directory_iterator(directory_of(file), ec)) {
        const std::string name = entry.path().filename().string();
        if (name.rfind(prefix, 0) == 0 && name.find(".part-") == std::string::npos)
            read_rows(entry.path(), scene_hash, rows);
    }
    return rows;
}

void remove_ensemble_checkpoints(const std::string& file) {
    std::error_code ec;
    const std::string prefix = prefix_of(file);
    std::vector<fs::path> gone;
    for (const auto& entry : fs::directory_iterator(directory_of(file), ec))
        if (entry.path().filename().string().rfind(prefix, 0) == 0) gone.push_back(entry.path());
    for (const fs::path& p : gone) fs::remove(p, ec);
}

}  // namespace sympl::app
