#pragma once
// `sympl run`: one scene, every method at its first step size (or tolerance).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "methods/run_plan.hpp"
#include "reading/scene.hpp"

namespace sympl::app {

// Prints the summary (text, or JSON with every string escaped) and writes the
// outputs the scene asks for, all together at the end.
// A run longer than max_steps steps is refused up front (check_run_size).
// `resume`: continue each method from its checkpoint (the scene's
// `checkpoint`), byte for byte as the run that was interrupted would have gone.
void run_scene(const scene& s, bool json, std::ostream& out, double max_steps = default_max_steps, bool resume = false);

// What a run's streamed files (trajectories, energy series) take on disk, at
// about 20 bytes a number as written (measured: 18.9 on the pendulum's
// trajectory, 19.8 on Henon-Heiles' and on energy series), and where: the
// output directory, and beside the checkpoint a second copy of the
// trajectory (docs/reliability.md, "Disk").
struct output_disk_use {
    struct place {
        std::filesystem::path folder;  // the nearest existing folder
        std::string key;               // the scene key that put the files there
        double bytes = 0;
    };
    double trajectory_rows = 0, energy_rows = 0;
    std::size_t columns = 0;
    double bytes_a_number = 20;
    std::vector<place> places;
};
output_disk_use disk_use_of(const scene& s, const run_plan& plan, const runnable_system& p);

// A folder's file system: its device and free bytes (known false: could not be asked).
struct free_space {
    bool known = false;
    std::uint64_t device = 0;
    double available = 0;
};
free_space free_space_of(const std::filesystem::path& folder);

// Refuses, with the figures, files that would not fit: each file system's
// places together against its free space, less what a resumed checkpoint's
// trajectory already holds (already_written bytes).
void check_disk_use(const scene& s, const output_disk_use& u,
                    const std::function<free_space(const std::filesystem::path&)>& space_of, double already_written);

}  // namespace sympl::app
