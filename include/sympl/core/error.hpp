#pragma once
// Exceptions thrown by sympl. Every message names the bad value and what was
// expected, so that a caller can report it as it stands.
#include <cstddef>
#include <sstream>
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

namespace detail {
// A number in an error message: every digit a double (or long double) needs.
inline std::string number_text(long double v) {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
}
}  // namespace detail

// The one message for a step that produced a non-finite state, wherever it is
// detected (sympl's drivers, the program's Odeint runs).
inline integration_error blow_up(std::size_t step, long double t, long double dt, const std::string& note = "") {
    return integration_error("integration blew up: step " + std::to_string(step) + " (from t = " +
                                 detail::number_text(t) + " with dt = " + detail::number_text(dt) +
                                 ") produced a non-finite state" + note,
                             step, static_cast<double>(t));
}

}  // namespace sympl
