#pragma once
// The registry of systems: per system one entry with its name, what it is,
// its parameters (defaults, valid ranges, meaning and units), whether it has
// an exact solution, and the factory that builds it with its default initial
// state. Scene parsing, the runner, the report, `sympl systems` and the error
// messages all read it. Adding a system is its header in hamiltonians/, one
// file systems/<name>.cpp with its entry (written with designated
// initializers), and its line in systems/list.cpp. Each entry is a
// translation unit of its own: it compiles for its system's type the methods
// its `compiled` names (runnable.hpp), and the files build in parallel; every
// other method runs on the generic path (generic_path.hpp).
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <utility>
#include <string>
#include <vector>

#include "running/runnable_system.hpp"

namespace sympl::app {

struct parameter {
    std::string name{};
    double value = 0;  // the default
    double low = -std::numeric_limits<double>::infinity();
    double high = std::numeric_limits<double>::infinity();
    bool low_open = false;   // low itself is not allowed
    bool high_open = false;  // high itself is not allowed
    bool integer = false;
    std::string meaning{};  // with its unit where it has one
    // Sets only the initial state, not the Hamiltonian (Henon-Heiles energy,
    // q2, p2): an ensemble over it runs in one Hamiltonian's batches.
    bool initial_state = false;

    bool accepts(double v) const;
    // "a number > 0", "an integer in [1, 1000000]": for error messages.
    std::string expected() const;
};

using parameter_values = std::map<std::string, double>;

inline constexpr double two_pi = 2 * std::numbers::pi;

// Parameter kinds, by their ranges.
inline constexpr double largest_chain = 1e6;  // degrees of freedom: 16 MB per state, a run needs a few
inline parameter positive(std::string name, double value, std::string meaning) {
    return {.name = std::move(name), .value = value, .low = 0, .low_open = true, .meaning = std::move(meaning)};
}
inline parameter nonnegative(std::string name, double value, std::string meaning) {
    return {.name = std::move(name), .value = value, .low = 0, .meaning = std::move(meaning)};
}
inline parameter any(std::string name, double value, std::string meaning) {
    return {.name = std::move(name), .value = value, .meaning = std::move(meaning)};
}
inline parameter count(std::string name, double value, double low, std::string meaning) {
    return {.name = std::move(name), .value = value, .low = low, .high = largest_chain, .integer = true,
            .meaning = std::move(meaning)};
}
inline parameter of_initial_state(parameter p) {
    p.initial_state = true;
    return p;
}

// The system's characteristic period (or time scale) in its time unit, for
// given parameters: what a scene's `t_end = {periods = N}` and
// `dt = {per_period = N}` count in (docs/scenes.md). No value: none.
struct time_scale {
    std::string meaning{};  // what it is, with its formula: "orbital period 2 pi / sqrt(mu)"
    std::function<double(const parameter_values&)> value{};
};

struct system_entry {
    std::string name;
    std::string description;  // the Hamiltonian or equations, with the source
    std::vector<parameter> parameters{};
    bool exact = false;  // an exact solution from the default state (and parameters, see description)
    std::function<runnable_system(const parameter_values&)> build;  // every parameter present and valid
    bool negative_potential = false;  // V(q) < 0 everywhere (gravitation): LogH applies
    bool kinetic_not_quadratic = false;  // a separable H whose T is not quadratic in p: no RKN pairs
    time_scale period{};
    // Names of q's components in output columns ("jupiter_x"); empty: q1..qn.
    std::vector<std::string> coordinate_names{};

    const parameter* find(const std::string& parameter_name) const;
};

// The program's systems in order, read once: defined per program, by the
// list sympl_add_program writes (cmake/sympl_add_program.cmake): sympl's own
// systems (builtin_systems(), systems/list.cpp), a user's, or both.
std::vector<system_entry> program_systems();
std::vector<system_entry> builtin_systems();

const std::vector<system_entry>& systems();
// A scene's own system (a [system] table of formulas, formulas/formula_entry.hpp),
// found by name from then on like the program's; `definition` is what
// defines it (the table's text): a second scene of the run may give the same
// name only with the same definition. A built-in system's name is refused.
const system_entry& add_scene_system(system_entry entry, const std::string& definition);
// What defines a system of a scene (or of Python) found by name: its
// definition as given to add_scene_system; empty for a built-in system.
std::string scene_system_definition(const std::string& name);
const system_entry* find_system(const std::string& name);
std::vector<std::string> system_names();

// The entry's defaults overridden by `given`; an unknown name or a value out
// of range is an invalid_argument naming the value and what was expected.
parameter_values with_defaults(const system_entry& entry, const parameter_values& given, const std::string& where);

// The characteristic period for these parameters (every one present), or 0
// when the system has none.
double period_of(const system_entry& entry, const parameter_values& values);

// Output columns of a state, q then p, counted from 1 as in physics texts and
// the parameters' names (q2 of henon_heiles): q1..qn, p1..pn, or by the
// registry's names ("jupiter_x", "jupiter_px").
std::vector<std::string> state_columns(const std::string& system, std::size_t degrees_of_freedom);

// A system by name, made runnable, with the given parameters and, when q0 is
// not empty, that initial state instead of the default (which drops the exact
// solution). `where` prefixes error messages (the scene's file).
runnable_system make_system(const std::string& system, const parameter_values& given, const std::vector<double>& q0,
                     const std::vector<double>& p0, const std::string& where);

}  // namespace sympl::app
