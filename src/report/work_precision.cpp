// The time to an accuracy level, read off a work-precision curve.
#include "report/work_precision.hpp"

#include <algorithm>
#include <cmath>

namespace sympl::app {

std::optional<time_to_accuracy> time_to_reach(std::vector<work_point> curve, double level) {
    std::erase_if(curve, [](const work_point& p) { return !(p.seconds > 0) || !(p.error > 0); });
    // Along the sweep, from the largest dt or tolerance down: the same order in
    // every run of the report, where two runs of nearly equal time could swap
    // places from one report to the next if ordered by their measured times.
    std::stable_sort(curve.begin(), curve.end(),
                     [](const work_point& a, const work_point& b) { return a.parameter > b.parameter; });
    for (work_point& p : curve) {
        if (!(p.seconds_min > 0)) p.seconds_min = p.seconds;
        if (!(p.seconds_max > 0)) p.seconds_max = p.seconds;
    }
    for (std::size_t i = 0; i < curve.size(); ++i) {
        if (curve[i].error > level) continue;
        if (i == 0) return time_to_accuracy{curve[0].seconds, curve[0].seconds_min, curve[0].seconds_max, curve[0], curve[0], false};
        const work_point& a = curve[i - 1];  // error above the level
        const work_point& b = curve[i];      // error at or below it
        // log t is linear in log error between a and b.
        const double s = std::log(level / a.error) / std::log(b.error / a.error);
        const auto between = [s](double ta, double tb) { return ta * std::pow(tb / ta, s); };
        return time_to_accuracy{between(a.seconds, b.seconds), between(a.seconds_min, b.seconds_min),
                                between(a.seconds_max, b.seconds_max), a, b, true};
    }
    return std::nullopt;
}

}  // namespace sympl::app
