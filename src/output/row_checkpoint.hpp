#pragma once
// Checkpoints that hold finished rows, one file per MPI rank
// (FILE.<kind>-rank-R): `sympl ensemble`'s trajectories
// (ensemble_checkpoint.hpp) and a [test_particles] map's particles
// (run_test_particles.hpp). A file is a head line naming its format, the
// scene's hash, the rows (each kind writes its own, numbers as hexadecimal
// floats so that they come back to the bit) and a checksum; it is written as
// checkpoint.hpp's are (temporary, fsync, rename). A truncated, corrupted or
// foreign file is refused with the reason, never read in part.
#include <cstddef>
#include <filesystem>
#include <istream>
#include <string>
#include <utility>
#include <vector>

namespace sympl::app {

// The head line of each kind's files, its format's version in it.
inline constexpr const char* ensemble_checkpoint_head = "sympl-ensemble-checkpoint 1\n";
inline constexpr const char* test_particles_checkpoint_head = "sympl-test-particles-checkpoint 1\n";

// FILE.<kind>-rank-R: rank R's file ("ensemble", "test-particles").
std::filesystem::path row_checkpoint_file(const std::string& file, const std::string& kind, int rank);

// head + "scene HASH\n" + rows + "checksum ...\n" into `path`, durably.
void write_row_checkpoint(const std::filesystem::path& path, const std::string& head, const std::string& scene_hash,
                          const std::string& rows);

// The rows text of every FILE.<kind>-rank-* (none: empty), each file checked
// for `head`, its checksum and the scene's hash.
std::vector<std::pair<std::filesystem::path, std::string>> read_row_checkpoints(const std::string& file,
                                                                                const std::string& kind,
                                                                                const std::string& head,
                                                                                const std::string& scene_hash);

// Every FILE.<kind>-rank-* (the run is complete: nothing to resume).
void remove_row_checkpoints(const std::string& file, const std::string& kind);

// "<kind> checkpoint FILE: WHY; not resumed from (remove it to start over)".
[[noreturn]] void refuse_row_checkpoint(const std::string& kind, const std::filesystem::path& file,
                                        const std::string& why);

// A row's parts read back: a number as written by hex_text, a count at most `largest`.
std::string hex_text(double v);
double read_number(std::istream& in, const std::string& kind, const std::filesystem::path& file);
std::size_t read_count(std::istream& in, const std::string& kind, const std::filesystem::path& file,
                       std::size_t largest);
// A text written as its length, a space and its bytes, then the row's end.
std::string read_text(std::istream& in, const std::string& kind, const std::filesystem::path& file);

}  // namespace sympl::app
