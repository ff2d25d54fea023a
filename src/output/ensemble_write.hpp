#pragma once
// An ensemble's written outputs on rank 0 (ensemble_run.hpp): the CSV in
// input order, the summary's section, the map and the Poincare section.
#include <filesystem>
#include <string>
#include <vector>

#include "reading/ensemble_points.hpp"
#include "commands/ensemble_run.hpp"

namespace sympl::app {

// One rank's rows as CSV lines (its block of the ensemble, in input order).
struct ensemble_row_of {
    std::size_t index;
    const ensemble_point* point;
    const ensemble_row* row;  // nullptr: an invalid point, no run
};
std::string csv_rows(const ensemble_setup& u, const std::vector<ensemble_row_of>& rows);

// Writes `prefix`ensemble.csv (the header, then every rank's block), the
// markdown section, the map (2-D or 1-D grids, with plots) and the Poincare
// section of e.orbits orbits; fills outcome.summary and outcome.files.
void write_ensemble(const ensemble_setup& u, const std::vector<std::string>& blocks, const std::filesystem::path& dir,
                    const std::string& prefix, bool plots, ensemble_outcome& outcome);

}  // namespace sympl::app
