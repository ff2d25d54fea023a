#pragma once
// `sympl run`: one scene, every method at its first step size (or tolerance).
#include <iosfwd>

#include "scene.hpp"

namespace sympl::app {

// Prints the summary (text, or JSON with every string escaped) and writes the
// outputs the scene asks for, all together at the end.
void run_scene(const scene& s, bool json, std::ostream& out);

}  // namespace sympl::app
