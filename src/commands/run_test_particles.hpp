#pragma once
// A scene's [test_particles] (scene.hpp): massless bodies run with the
// planets by the scene's wh(...) method, MEGNO per particle. The particles
// are cut into pieces of a fixed size, each piece its own stepper over the
// same planets (whose run the particles do not change, bit for bit), and the
// pieces shared among threads and MPI ranks: every number written is the
// same for any thread or rank count. Written as test_particles.csv, a map of MEGNO over a and e
// (PNG, through gnuplot) and summary.md (test_particle_write.cpp).
#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

#include <sympl/planetary/kepler/orbital_elements.hpp>

#include "reading/scene.hpp"

namespace sympl::app {

// Particles per stepper run: what a thread takes at a time. Fixed, so that
// the pieces, and so every result, do not depend on the thread count.
inline constexpr std::size_t test_particle_piece = 256;

// A particle lost in a close encounter is logged with this distance from the
// planet: its Hill radius a (m / 3 m_0)^(1/3), where the Wisdom-Holman
// splitting (a Kepler orbit about the star perturbed) no longer holds.
// Farther than escape_distance from the star it has left the system.
inline constexpr double test_particle_escape_distance = 100;  // AU: three times Neptune's orbit
// Closer to the star than this a particle has hit it: the Sun's radius, 0.00465 AU.
inline constexpr double test_particle_star_radius = 0.005;  // AU

// Why an orbit of semi-major axis a (AU) and eccentricity e would be removed
// at its first step (its pericentre inside the star, its apocentre past the
// escape distance), or "" for an orbit between them.
std::string orbit_outside(double a, double e);

// The run's one step and its count: whole steps of dt, at least one, the
// first end at or past t_end (t0 + steps dt).
struct test_particle_span {
    double dt = 0, steps = 0;
};
test_particle_span test_particle_span_of(const scene& s);

struct test_particle_row {
    orbital_elements start;  // as given, angles in radians
    bool kept = true;        // false: removed (reason, at time)
    double megno = 0;        // NaN without MEGNO or when removed
    double a = 0, e = 0;     // osculating heliocentric elements at t_end (NaN when removed)
    std::string reason;
    double removed_time = 0;
};

// The orbits of the scene's population: its grid (a varying fastest, the
// mean anomaly spread by the golden angle) or its CSV file of elements;
// a file's error names it, the line and what was expected.
std::vector<orbital_elements> test_particle_orbits(const scene& s);

struct exchange;  // ensemble_run.hpp: the MPI ranks of one run

// Runs the particles (every one, in order) in pieces of `piece`, `threads`
// pieces at a time (0: OMP_NUM_THREADS, else every core); refuses, with the
// figures, more than max_steps steps or 1e4 times that in particle-steps.
std::vector<test_particle_row> run_test_particles(const scene& s, const std::vector<orbital_elements>& orbits,
                                                  int threads, double max_steps,
                                                  std::size_t piece = test_particle_piece);
// The same over MPI ranks: piece k runs on rank k mod size, and rank 0 gathers
// every row (the same numbers as one process); the other ranks get no rows.
// With the scene's checkpoint = {every_steps = N, file = "..."}, each rank
// saves the rows of its finished pieces to FILE.test-particles-rank-R
// (row_checkpoint.hpp) once N particle-steps have finished since its last
// save; `resume` runs only the pieces no rank's file holds whole, at any
// rank and thread count, to the same bits.
std::vector<test_particle_row> run_test_particles(const scene& s, const std::vector<orbital_elements>& orbits,
                                                  int threads, double max_steps, const exchange& ranks, bool resume,
                                                  std::size_t piece = test_particle_piece);

// MEGNO above this counts as chaotic (as for ensembles, ensemble_run.hpp).
inline constexpr double chaotic_test_particle_megno = 4;

// Every FILE.test-particles-rank-* of the scene's checkpoint.
void remove_test_particle_checkpoints(const scene& s);

// `sympl run SCENE --out DIR` for a scene with [test_particles]: the files
// in DIR (all of them or none), a few lines on `out`.
void test_particles_command(const scene& s, const std::filesystem::path& out_dir, int threads, double max_steps,
                            std::ostream& out, std::size_t piece = test_particle_piece);
// Under mpirun: the pieces shared among the ranks, rank 0 writing everything;
// `resume`: from the scene's checkpoints (run_test_particles), which rank 0
// removes once the files are written.
void test_particles_command(const scene& s, const std::filesystem::path& out_dir, int threads, double max_steps,
                            const exchange& ranks, bool resume, std::ostream& out,
                            std::size_t piece = test_particle_piece);

}  // namespace sympl::app
