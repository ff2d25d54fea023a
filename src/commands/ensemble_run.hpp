#pragma once
// `sympl ensemble`: a scene's [ensemble] (scene.hpp) run over its grid or CSV
// of states, threads inside a process and MPI ranks across processes
// (exchange), written as ensemble.csv, a map (PNG), a Poincare section of a
// few orbits and summary.md. Every rank computes its static block of rows;
// rank 0 gathers them in input order and writes: the CSV is byte-identical
// for any thread and rank count.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "reading/scene.hpp"

namespace sympl::app {

// The processes an ensemble is split over: one by default, MPI ranks under mpirun.
struct exchange {
    int rank = 0;
    int size = 1;
    // On rank 0: every rank's text in rank order; on the others: empty.
    std::function<std::vector<std::string>(const std::string&)> gather = [](const std::string& mine) {
        return std::vector<std::string>{mine};
    };
    // Ends every rank's process with this exit code (MPI_Abort): a rank that
    // fails alone must not leave the others waiting in a gather.
    std::function<void(int)> abort_all = [](int) {};
};

struct ensemble_outcome {
    std::string scene_name;
    std::size_t trajectories = 0, stable = 0, unstable = 0, invalid = 0;
    std::size_t chaotic = 0;    // stable with MEGNO above chaotic_megno
    double seconds = 0;         // wall time of this process's share
    std::string summary;        // markdown (rank 0)
    std::vector<std::string> files;  // written, relative to the directory
};

// MEGNO above this after the run counts as chaotic (quasi-periodic orbits
// approach 2; Cincotta, Giordano & Simo 2003 use thresholds of this size).
inline constexpr double chaotic_megno = 4;

// Runs the ensemble; rank 0 writes into `dir` (a staging directory) files
// named `prefix` + "ensemble.csv" etc. Refuses up front, with the figures, an
// ensemble of more than max_steps trajectory-steps. With the scene's
// checkpoint, every rank saves its rows as it goes; `resume`: the rows any
// rank saved are not computed again (ensemble_checkpoint.hpp).
ensemble_outcome run_ensemble_scene(const scene& s, const std::filesystem::path& dir, const std::string& prefix,
                                    int threads, double max_steps, bool plots, const exchange& ranks,
                                    bool resume = false);

// `sympl ensemble SCENE --out DIR [--resume]`: output set, summary on `out`;
// the checkpoints removed once the outputs are in place.
void ensemble_command(const scene& s, const std::string& out_dir, int threads, double max_steps, const exchange& ranks,
                      std::ostream& out, bool resume = false);

}  // namespace sympl::app
