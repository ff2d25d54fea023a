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
    double seconds_min = 0, seconds_max = 0;  // its fastest and slowest timing round (0: only the median is known)
};

struct time_to_accuracy {
    double seconds = 0;
    double seconds_min = 0, seconds_max = 0;  // read the same way off the fastest and the slowest rounds
    work_point above, below;  // the runs bracketing the level (equal when the first run already reached it)
    bool bracketed = false;   // false: the largest dt or tolerance already reached the level, seconds is its time
};

// The first crossing of `level` along the curve ordered by its dt or
// tolerance, largest first (the cheapest run first); nullopt when no run
// reaches it. Points with non-positive time or error are ignored.
std::optional<time_to_accuracy> time_to_reach(std::vector<work_point> curve, double level);

}  // namespace sympl::app
