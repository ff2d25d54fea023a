#pragma once
// A scene: one system, its initial state, the methods to compare, the step
// sizes, the time span and what to output. Read from a small TOML file (toml++);
// every error names the file, line and column and what was expected.
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <sympl/error.hpp>
#include <sympl/table.hpp>

namespace sympl::app {

enum class method_kind { table, classic, odeint_rk4, odeint_dopri5 };

struct method_spec {
    std::string name;
    method_kind kind = method_kind::table;
    std::optional<table> coefficients;  // for kind == table
};

// What a run writes; what is not asked for is neither computed nor stored.
struct output_spec {
    bool energy_error = true;          // max relative energy error (and its series in `run`)
    std::size_t trajectory_every = 0;  // 0: no trajectory file
    bool final_state = false;
    bool loop_area = false;            // area of a loop of initial conditions around x0, plane 0
    std::string directory = ".";       // where `sympl run` writes its files
};

struct scene {
    std::string source;  // file path, or "built-in"
    std::string name;
    std::string system;
    std::map<std::string, double> parameters;
    std::vector<double> q0, p0;  // empty: the system's default
    std::vector<method_spec> methods;
    std::vector<double> dt;          // one step size or a sweep, largest first
    std::vector<double> tolerances;  // for odeint_dopri5 (default 1e-3 .. 1e-12)
    double t0 = 0;
    double t_end = 0;
    output_spec output;
};

// A scene file that cannot be read: "file:line:column: what; expected ...".
struct scene_error : error {
    using error::error;
};

scene parse_scene(const std::string& text, const std::string& source);
scene load_scene(const std::string& path);

// The built-in scenes (compiled in); quick ones are shorter and sweep fewer steps.
std::vector<scene> default_scenes(bool quick);

// The system names a scene may use, and the method names beside the catalog.
const std::vector<std::string>& system_names();
const std::vector<std::string>& system_parameters(const std::string& system);
const std::vector<std::string>& classic_method_names();

}  // namespace sympl::app
