#pragma once
// A scene: one system, its initial state, the methods to compare, the step
// sizes, the time span and what to output. Read from a small TOML file (toml++);
// every error names the file, line and column and what was expected.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <sympl/core/error.hpp>
#include <sympl/core/table.hpp>

#include "output/checkpoint.hpp"
#include "methods/method_kinds.hpp"
#include "running/runnable_system.hpp"

namespace sympl::app {

// What a run writes; what is not asked for is neither computed nor stored.
struct output_spec {
    bool energy_error = true;          // max relative energy error
    // `energy_every = k`: `run` writes <scene>_<method>_energy.csv, the
    // relative energy error against time every k steps (0: no file).
    std::size_t energy_every = 0;
    // The final error against the exact solution or a reference run. Unset:
    // where it is free (an exact solution); a reference is run only when asked.
    std::optional<bool> final_error;
    std::size_t trajectory_every = 0;  // 0: no trajectory file
    // `times = [...]` or `{from, to, count}`: trajectory rows at these times,
    // read off each step's Hermite interpolant (drivers/hermite_interpolant.hpp); the
    // steps are the run's own. Sorted, inside [t0, t_end]; --quick drops those
    // past its shorter t_end (times_dropped counts them; the trajectory file is
    // still written, with the rows that remain, so that it is never missing).
    std::vector<double> times;
    std::size_t times_dropped = 0;
    bool final_state = false;
    bool loop_area = false;            // area of a loop of initial conditions around x0, plane 0
    std::string directory = ".";       // where `sympl run` writes its files
    bool writes_trajectory() const { return trajectory_every != 0 || !times.empty() || times_dropped != 0; }
    bool writes_files() const { return writes_trajectory() || energy_every != 0; }
};
inline constexpr std::size_t max_output_times = 10'000'000;

// A relative error at or above this (final or energy) leaves no correct digit:
// such a run is flagged as not a result (a smaller dt), not printed as a row.
inline constexpr double order_one_error = 0.1;

// A method as a scene lists it: a name, or {name = ..., dt = ..., tolerances = ...}
// with a sweep of its own (a LogH method's fictitious step differs from dt).
struct scene_method : method_spec {
    std::vector<double> dt, tolerances;  // empty: the scene's
};

// `checkpoint = {every_steps = N, file = "..."}`: a run saves where it is every
// N steps (checkpoint.hpp), one file per method: FILE.<method>, with the
// trajectory written so far beside it (FILE.<method>.trajectory).
struct checkpoint_spec {
    std::size_t every_steps = 0;  // 0: no checkpoints
    std::string file;
};

// `[ensemble]`: the scene's set-up run over a grid of its system's parameters
// (each {from, to, count}; the first in the file varies slowest) or over the
// initial states of a CSV file, with what to compute (ensemble_run.hpp).
struct ensemble_axis {
    std::string name;
    double from = 0, to = 0;
    std::size_t count = 1;
    double value(std::size_t i) const { return count == 1 ? from : from + (to - from) * double(i) / double(count - 1); }
};
struct ensemble_spec {
    std::vector<ensemble_axis> grid;  // empty: states_file
    std::string states_file;          // columns as state_columns names them; relative to the scene file
    bool megno = false;               // indicator = "megno" (or "none")
    std::size_t sample_every = 10;    // energy error and MEGNO sampled every k steps
    std::size_t orbits = 0;           // a Poincare section (q1 = 0, p1 > 0) of this many orbits of the grid
    std::size_t size() const;         // trajectories
};
inline constexpr double max_ensemble_size = 1e7;

// `[test_particles]`: massless bodies run with the planets by the scene's one
// wh(...) method, MEGNO per particle (run_test_particles.hpp): a grid over the
// semi-major axis a [AU] and eccentricity e, the angles fixed, or a CSV of
// orbital elements (a, e, then optionally inclination, node, pericentre,
// mean_anomaly; angles in degrees) about the star.
struct test_particle_spec {
    ensemble_axis a{"a"}, e{"e"};  // a grid (a varying fastest); unused with elements_file
    double inclination = 0, node = 0, pericentre = 0, mean_anomaly = 0;  // degrees
    std::string elements_file;  // relative to the scene file; empty: the grid
    bool megno = true;          // indicator = "megno" (or "none")
    std::size_t grid_size() const { return a.count * e.count; }
};
// A population larger than this is refused before anything runs (each
// particle is 6 numbers and, with MEGNO, 12 more: 1e6 of them is ~150 MB).
inline constexpr double max_test_particles = 1e6;

struct scene {
    std::string source;  // file path, or "built-in"
    // Of the scene file's text and of the files it reads (load_scene): what a
    // checkpoint belongs to, so that a resume notices an edited states or
    // elements file.
    std::string text_hash;
    std::string name;
    std::string system;
    std::map<std::string, double> parameters;
    std::vector<double> q0, p0;  // empty: the system's default
    std::vector<scene_method> methods;
    double period = 0;               // the system's characteristic period here (0: none), systems.hpp
    std::vector<double> dt;          // one step size or a sweep, largest first
    std::vector<double> tolerances;  // for odeint_dopri5 (default 1e-3 .. 1e-12)
    double t0 = 0;
    double t_end = 0;
    output_spec output;
    checkpoint_spec checkpoint;
    std::optional<ensemble_spec> ensemble;
    std::optional<test_particle_spec> test_particles;
};

// A scene file that cannot be read: "file:line:column: what; expected ...".
struct scene_error : error {
    using error::error;
};

// A scene file is small text: larger ones are refused before they are read;
// so are the files a scene names, each kind at its own limit.
inline constexpr std::size_t max_scene_bytes = 1 << 20;
inline constexpr std::size_t max_states_bytes = std::size_t(256) << 20;   // [ensemble] states
inline constexpr std::size_t max_elements_bytes = std::size_t(64) << 20;  // [test_particles] elements

// `quick`: apply the scene's [quick] table (shorter t_end, fewer steps), if it has one.
scene parse_scene(const std::string& text, const std::string& source, bool quick = false);
scene load_scene(const std::string& path, bool quick = false);

// Runs longer than this many steps are refused before anything runs
// (`--max-steps` raises it): about a minute of leapfrog on a small system.
inline constexpr double default_max_steps = 1e9;

// The built-in scenes: the TOML files of src/scenes/, compiled in; those
// with [test_particles] (a stability map, not a method comparison) are left
// out of this set, which the report runs, and run by name (builtin_scene).
std::vector<scene> default_scenes(bool quick);
// A built-in scene by its file name, with or without ".toml" and the
// leading "NN_" ("outer_belt_megno"); nullopt when there is none.
std::optional<scene> builtin_scene(const std::string& name, bool quick = false);

// Their texts, by file name (generated from src/scenes/ at build time).
const std::vector<std::pair<std::string, std::string>>& builtin_scene_texts();

}  // namespace sympl::app
