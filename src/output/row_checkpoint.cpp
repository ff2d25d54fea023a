// Checkpoints of finished rows, one file per rank (row_checkpoint.hpp).
#include "output/row_checkpoint.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>

#include <sympl/core/error.hpp>

#include "output/checkpoint.hpp"
#include "output/format.hpp"
#include "output/writers.hpp"
#include "reading/file_text.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {
std::string prefix_of(const std::string& file, const std::string& kind) {
    return fs::path(file).filename().string() + "." + kind + "-rank-";
}
fs::path directory_of(const std::string& file) {
    const fs::path f(file);
    return f.has_parent_path() ? f.parent_path() : fs::path(".");
}
// Whether `name` is PREFIX<rank>, or with_temporaries and a writer's
// temporary of one (PREFIX<rank>.sympl-part-PID): digits only after the
// prefix, so that a user's `FILE.kind-rank-0.bak` is never one of ours.
bool rank_file_name(const std::string& name, const std::string& prefix, bool with_temporaries) {
    if (name.rfind(prefix, 0) != 0) return false;
    std::string rank = name.substr(prefix.size());
    if (is_temporary_name(name)) {
        if (!with_temporaries) return false;
        rank = rank.substr(0, rank.rfind(".sympl-part-"));
    }
    return !rank.empty() && rank.find_first_not_of("0123456789") == std::string::npos;
}

// The finished files of `kind` (not a writer's temporary FILE.sympl-part-PID)
// by name: a reader refuses one that is not a regular file, removal skips it.
std::vector<fs::path> files_of(const std::string& file, const std::string& kind, bool with_temporaries) {
    std::vector<fs::path> found;
    std::error_code ec;
    const std::string prefix = prefix_of(file, kind);
    for (const auto& entry : fs::directory_iterator(directory_of(file), ec)) {
        const std::string name = entry.path().filename().string();
        if (rank_file_name(name, prefix, with_temporaries)) found.push_back(entry.path());
    }
    return found;
}
}  // namespace

fs::path row_checkpoint_file(const std::string& file, const std::string& kind, int rank) {
    return directory_of(file) / (prefix_of(file, kind) + std::to_string(rank));
}

void write_row_checkpoint(const fs::path& path, const std::string& head, const std::string& scene_hash,
                          const std::string& rows) {
    const std::string body = "scene " + scene_hash + '\n' + rows;
    write_durably(path, head + body + "checksum " + fnv1a_hex(body) + "\n");
}

std::vector<std::pair<fs::path, std::string>> read_row_checkpoints(const std::string& file, const std::string& kind,
                                                                   const std::string& head,
                                                                   const std::string& scene_hash) {
    std::vector<std::pair<fs::path, std::string>> texts;
    for (const fs::path& path : files_of(file, kind, false)) {
        file_text read = read_file_text(path, max_checkpoint_file_bytes);
        if (!read.failure.empty()) refuse_row_checkpoint(kind, path, read.failure);
        const std::string text = std::move(read.text);
        if (text.rfind(head, 0) != 0) refuse_row_checkpoint(kind, path, "is not a sympl " + kind + " checkpoint of this format");
        const auto mark = text.rfind("checksum ");
        if (mark == std::string::npos || mark < head.size()) refuse_row_checkpoint(kind, path, "is truncated (no checksum)");
        const std::string body = text.substr(head.size(), mark - head.size());
        if (text.substr(mark) != "checksum " + fnv1a_hex(body) + "\n")
            refuse_row_checkpoint(kind, path, "is corrupted (checksum mismatch)");
        const std::string scene_line = "scene " + scene_hash + '\n';
        if (body.rfind("scene ", 0) != 0) refuse_row_checkpoint(kind, path, "has no scene line");
        if (body.rfind(scene_line, 0) != 0)
            refuse_row_checkpoint(kind, path, "belongs to another scene (or the scene file changed)");
        texts.emplace_back(path, body.substr(scene_line.size()));
    }
    return texts;
}

void remove_row_checkpoints(const std::string& file, const std::string& kind) {
    std::error_code ec;
    for (const fs::path& p : files_of(file, kind, true))
        if (fs::symlink_status(p, ec).type() == fs::file_type::regular) fs::remove(p, ec);
}

void refuse_row_checkpoint(const std::string& kind, const fs::path& file, const std::string& why) {
    throw error(kind + " checkpoint " + printable(file.string()) + ": " + why + "; not resumed from (remove it to start over)");
}

std::string hex_text(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%a", v);
    return b;
}

double read_number(std::istream& in, const std::string& kind, const fs::path& file) {
    std::string word;
    if (!(in >> word)) refuse_row_checkpoint(kind, file, "a row ends early");
    char* end = nullptr;
    const double v = std::strtod(word.c_str(), &end);
    if (end != word.c_str() + word.size()) refuse_row_checkpoint(kind, file, "'" + word + "' in a row is not a number");
    return v;
}

std::size_t read_count(std::istream& in, const std::string& kind, const fs::path& file, std::size_t largest) {
    std::size_t v = 0;
    if (!(in >> v) || v > largest) refuse_row_checkpoint(kind, file, "a row holds a bad count");
    return v;
}

std::string read_text(std::istream& in, const std::string& kind, const fs::path& file) {
    std::string text(read_count(in, kind, file, std::size_t(1) << 20), '\0');
    if (in.get() != ' ' || !in.read(text.data(), std::streamsize(text.size())) || in.get() != '\n')
        refuse_row_checkpoint(kind, file, "a row's text is cut");
    return text;
}

}  // namespace sympl::app
