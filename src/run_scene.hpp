#pragma once
// `sympl run`: one scene, every method at its first step size (or tolerance).
#include <iosfwd>

#include "scene.hpp"

namespace sympl::app {

// Prints the summary (text, or JSON with every string escaped) and writes the
// outputs the scene asks for, all together at the end.
// A run longer than max_steps steps is refused up front (check_run_size).
void run_scene(const scene& s, bool json, std::ostream& out, double max_steps = default_max_steps);

}  // namespace sympl::app
