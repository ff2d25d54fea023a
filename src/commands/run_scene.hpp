#pragma once
// `sympl run`: one scene, every method at its first step size (or tolerance).
#include <iosfwd>

#include "reading/scene.hpp"

namespace sympl::app {

// Prints the summary (text, or JSON with every string escaped) and writes the
// outputs the scene asks for, all together at the end.
// A run longer than max_steps steps is refused up front (check_run_size).
// `resume`: continue each method from its checkpoint (the scene's
// `checkpoint`), byte for byte as the run that was interrupted would have gone.
void run_scene(const scene& s, bool json, std::ostream& out, double max_steps = default_max_steps, bool resume = false);

}  // namespace sympl::app
