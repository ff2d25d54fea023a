#pragma once
// An ensemble's inputs (scene.hpp's [ensemble]): the trajectories of a grid
// over the system's parameters or of a CSV file of states, each with its
// start or the reason it has none.
#include <cstddef>
#include <string>
#include <vector>

#include "reading/scene.hpp"
#include "running/systems.hpp"

namespace sympl::app {

// One trajectory of the ensemble: where it comes from and its start (or why it has none).
struct ensemble_point {
    std::vector<double> grid_values;  // the grid's values (grid) or the state's numbers (CSV)
    parameter_values parameters;      // every parameter given to the system
    std::vector<double> x0;
    std::string invalid;              // not empty: no start, and why
    std::string hamiltonian_key;      // points with equal keys share one Hamiltonian
};

// The states of a CSV file: a header of the run's columns (state_columns: q1..qn,p1..pn,
// or the bodies' names), then one state per line.
std::vector<std::vector<double>> read_states(const std::string& path, const std::vector<std::string>& columns);

// Point `index` of the scene's grid (the last axis varies fastest) or state
// `index` of its CSV, with its start or the reason it has none.
ensemble_point point_at(const scene& s, const system_entry& entry, const parameter_values& defaults, std::size_t index,
                        const std::vector<std::vector<double>>& states);

// An ensemble run's set-up, checked: the scene's base system, the states of
// its CSV (empty for a grid), its size, and the request every group shares.
struct ensemble_setup {
    const scene* s = nullptr;
    const system_entry* entry = nullptr;
    runnable_system base{};
    parameter_values defaults{};  // the scene's parameters over the system's defaults
    std::vector<std::vector<double>> states{};
    std::size_t trajectories = 0;
    ensemble_request request{};
};

// Refuses, with the figures, an ensemble of more than max_steps steps per
// trajectory or 1e4 max_steps trajectory-steps.
ensemble_setup set_up_ensemble(const scene& s, double max_steps);

}  // namespace sympl::app
