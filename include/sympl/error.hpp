#pragma once
// Exceptions thrown by sympl. Every message names the bad value and what was
// expected, so that a caller can report it as it stands.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace sympl {

// Base of every error sympl throws.
struct error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// A coefficient table that cannot be a consistent splitting method.
struct invalid_table : error {
    using error::error;
};

// A bad argument: step size, tolerance, dimension, unknown name.
struct invalid_argument : error {
    using error::error;
};

// A run that produced a non-finite state. The state passed to the driver is
// left at the last finite state; step and time say where the run broke.
struct integration_error : error {
    integration_error(const std::string& what, std::size_t step_, double time_)
        : error(what), step(step_), time(time_) {}
    std::size_t step;  // index of the step that produced the non-finite state (1-based)
    double time;       // time at the start of that step
};

}  // namespace sympl
