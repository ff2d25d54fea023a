#pragma once
// Reading a method's work-precision curve: the time it needs to reach an
// accuracy level, interpolated log-log between the two measured runs that
// bracket the level (not the nearest run).
#include <optional>
#include <vector>

namespace sympl::app {

struct work_point {
    double seconds = 0;  // median wall time of the run
    double error = 0;    // its final error
    double parameter = 0;  // its dt or tolerance
};

struct time_to_accuracy {
    double seconds = 0;
    work_point above, below;  // the runs bracketing the level (equal when the first run already reached it)
    bool bracketed = false;   // false: the cheapest run already reached the level, seconds is its time
};

// The first crossing of `level` along the curve ordered by time; nullopt when
// no run reaches it. Points with non-positive time or error are ignored.
std::optional<time_to_accuracy> time_to_reach(std::vector<work_point> curve, double level);

}  // namespace sympl::app
