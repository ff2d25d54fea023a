#pragma once
// The report's fixed studies, one file each: the stability map, Kepler at
// e = 0.99, the long run with compensated summation, extreme scales and
// precisions, and the energy error along a run. Each writes its CSV in the
// report's directory and a section of summary.md.
#include <unistd.h>

#include <filesystem>
#include <iostream>
#include <ostream>
#include <string>
#include <vector>

#include "reading/scene.hpp"

namespace sympl::app {

struct report_row;  // report_rows.hpp

// One line of progress on a terminal (nothing when stderr is not one).
struct progress {
    bool tty = isatty(STDERR_FILENO);
    void show(const std::string& what) const {
        if (tty) std::cerr << "\r\033[K" << what << std::flush;
    }
    void done() const {
        if (tty) std::cerr << "\r\033[K" << std::flush;
    }
};

// The reference state at t_end: exact, or Sofroniou-Spaletta 10 in long double
// at two steps (the difference estimates the reference's own error).

struct study_context {
    bool quick = false;
    std::ostream& summary;  // summary.md, section by section
    std::filesystem::path dir;
    const progress& bar;
};

void stability_study(const study_context& c);
void kepler_099_study(const study_context& c);
void long_run_study(const study_context& c);
void extreme_study(const study_context& c);
void energy_long_span_study(const study_context& c);
// The energy error along the run on every Hamiltonian scene with a sweep: its
// fastest symplectic run at energy level 1e-8 (or the tightest above) against the
// fastest non-symplectic method there, at its run of the nearest time; one
// line per scene into `summary`.
void energy_series_study(const std::vector<scene>& scenes, const std::vector<report_row>& rows,
                         const std::filesystem::path& dir, bool plots, std::ostream& summary);

}  // namespace sympl::app
