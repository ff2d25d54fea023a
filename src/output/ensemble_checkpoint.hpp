#pragma once
// Checkpoints of `sympl ensemble` (checkpoint = {every_steps = N, file =
// "..."} in an ensemble scene): every rank saves the rows it has computed,
// by trajectory index, to FILE.ensemble-rank-R after each piece of about N
// trajectory-steps; `sympl ensemble SCENE --resume`, at any rank and thread
// count, reads every rank's file and computes only the rows none holds. A
// row is a pure function of its trajectory, and the rows are kept to the bit
// (hexadecimal floats), so ensemble.csv is byte-identical to an
// uninterrupted run's. Files are written as checkpoint.hpp's (temporary,
// fsync, rename) with the scene's hash and a checksum; a truncated,
// corrupted or foreign file is refused with the reason.
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>

#include "running/runnable_system.hpp"

namespace sympl::app {

using ensemble_rows = std::map<std::size_t, ensemble_row>;  // by trajectory index

// FILE.ensemble-rank-R: rank R's file.
std::filesystem::path ensemble_checkpoint_file(const std::string& file, int rank);

void write_ensemble_checkpoint(const std::filesystem::path& path, const std::string& scene_hash,
                               const ensemble_rows& rows);

// The rows of every FILE.ensemble-rank-* (none: empty), each file checked
// against the scene; a checkpoint_error-like error says what is wrong.
ensemble_rows read_ensemble_checkpoints(const std::string& file, const std::string& scene_hash);

// Every FILE.ensemble-rank-* (the ensemble is complete).
void remove_ensemble_checkpoints(const std::string& file);

}  // namespace sympl::app
