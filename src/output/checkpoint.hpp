#pragma once
// Checkpoints of a run (`checkpoint = {every_steps = N, file = "..."}` in a
// scene; `sympl run SCENE --resume`): after every N steps, everything the run
// needs to continue bit for bit: the step index (time is t0 + i dt from it at
// a fixed step) and the time, the state, the stepper's carried memory
// (stepper_memory) and what else its kind carries, the counters, the
// observed maximum energy error and how many bytes of the trajectory are
// written. Numbers are stored as hexadecimal floats, exactly.
//
// A file is written under a temporary name, flushed to disk (fsync) and
// renamed over the previous one: a crash leaves the old checkpoint or the new,
// never half of one. It carries a format version, the scene it belongs to (a
// hash of the scene file's text), the method, dt and a checksum; a truncated,
// corrupted or mismatched file is refused with the reason, never resumed from.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <sympl/core/stepper_memory.hpp>

namespace sympl::app {

struct checkpoint_record {
    // What the checkpoint belongs to: checked on reading.
    std::string scene_hash, method;
    double dt = 0;
    // Where the run is.
    std::size_t step = 0;  // steps done
    double time = 0;       // the time after them (t0 + step dt at a fixed step)
    std::vector<double> state;  // q then p
    // The stepper's carried memory (splitting_stepper; for classic steppers
    // only the counters).
    stepper_memory<std::vector<double>> memory;
    // What else the method carries between steps, as its kind's run lays it
    // out: a stepper's carried() (Wisdom-Holman's coordinates, Tao's second
    // copy, a processed kernel's state), LogH's extended state.
    std::vector<double> carried;
    // The observer's part.
    double max_energy_error = -1;
    std::uint64_t trajectory_bytes = 0;
};

// 3: a wh(...) run's carried list holds its test particles and their MEGNO
// state, and odeint_bulirsch_stoer's Boost's order and step history.
// 4: a controlled RKN pair's own list follows the controller's state without
// its length before it (every run's list: its own fields, then the
// stepper's, run_context.hpp).
inline constexpr int checkpoint_format = 4;

// A record read back, held to what the run it resumes can take before
// anything runs from it: a state of `state_size` finite numbers, a time in
// [t0, t_end], at a fixed step no more steps than the span holds, each of the
// stepper's vectors empty or of the half state's size (one more for LogH's
// extended state; present where it is marked fresh), every number finite,
// the energy error -1 or >= 0. A field
// out of place is a refusal naming the file, the field, its value and what
// was expected.
void check_checkpoint_fields(const checkpoint_record& r, const std::filesystem::path& file, std::size_t state_size,
                             double t0, double t_end, bool fixed_step);

// FNV-1a, 64 bits, as 16 hex digits: the scene's identity and the file's checksum.
std::string fnv1a_hex(const std::string& bytes);

void write_checkpoint(const std::filesystem::path& file, const checkpoint_record& r);

// `text` into `file` as a checkpoint is written: under a temporary name
// (FILE.sympl-part-PID, created new, never through a symlink), fsync'ed, renamed over the previous file.
void write_durably(const std::filesystem::path& file, const std::string& text);

// The record in `file`, checked against the scene, method and dt expected;
// a checkpoint_error says what is wrong.
checkpoint_record read_checkpoint(const std::filesystem::path& file, const std::string& scene_hash,
                                  const std::string& method, double dt);

}  // namespace sympl::app
