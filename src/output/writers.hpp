#pragma once
// How the program writes files: complete or not at all (atomic_file), CSV
// with quoted fields, markdown cells, gnuplot scripts with quoted strings and
// gnuplot itself started without a shell. JSON is nlohmann-json's.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace sympl::app {

// A file written under a temporary name of its own (unique to this process)
// and renamed into place by commit(): a run that fails, or a full disk,
// leaves the previous file as it was. Every write is checked at commit.
class atomic_file {
public:
    explicit atomic_file(std::filesystem::path path);
    ~atomic_file();
    atomic_file(const atomic_file&) = delete;
    atomic_file& operator=(const atomic_file&) = delete;

    std::ofstream& stream() { return out_; }
    const std::filesystem::path& path() const { return path_; }
    // Flushes, checks every write and renames; an error names the file and the reason.
    void commit();

private:
    std::filesystem::path path_, temporary_;
    std::ofstream out_;
    bool committed_ = false;
};

// The name of this process's temporary for `path`: NAME.sympl-part-PID
// (hidden when `hidden`: .NAME.sympl-part-PID), and whether a file name is
// such a temporary. Only names of this form are ever removed as a dead
// process's leftovers (output_set.cpp): a user's `.notes.part-2024` is not.
std::filesystem::path temporary_for(const std::filesystem::path& path, bool hidden);
bool is_temporary_name(const std::string& name);
// Creates `path` as a new regular file for writing: never through a
// symlink, never over a file (O_EXCL | O_NOFOLLOW); a leftover regular file
// of the same name (a dead process with this PID) is replaced. The open
// descriptor, or -1 with errno set.
int create_new_file(const std::filesystem::path& path);

// One CSV field: quoted (with quotes doubled) when it holds a comma, a quote
// or a line break (RFC 4180).
std::string csv_field(const std::string& text);
// A CSV line of fields, each through csv_field.
std::string csv_line(const std::vector<std::string>& fields);

// A markdown table cell: '|' escaped, line breaks as spaces.
std::string markdown_cell(const std::string& text);

// A name that is safe as (part of) a file name in the output directory:
// letters, digits, '-', '_' and '.', never starting with '.'.
std::string file_name_part(const std::string& name);

// A gnuplot string literal: single quotes doubled, control characters as spaces.
std::string gnuplot_string(const std::string& text);

// Whether gnuplot can be started.
bool have_gnuplot();
// Runs `gnuplot script` in the script's directory (no shell: an argument
// list; scripts name their files relative to that directory). A failure, or a
// PNG that was not drawn, is said on stderr and leaves no empty PNG behind.
void run_gnuplot(const std::filesystem::path& script, const std::filesystem::path& png);

}  // namespace sympl::app
