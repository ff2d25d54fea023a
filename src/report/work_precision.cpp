// The time to an accuracy level, read off a work-precision curve.
#include "report/work_precision.hpp"

#include <algorithm>
#include <cmath>

namespace sympl::app {

std::optional<time_to_accuracy> time_to_reach(std::vector<work_point> curve, double level) {
    std::erase_if(curve, [](const work_point& p) { return !(p.seconds > 0) || !(p.error > 0); });
    std::sort(curve.begin(), curve.end(), [](const work_point& a, const work_point& b) { return a.seconds < b.seconds; });
    for (std::size_t i = 0; i < curve.size(); ++i) {
        if (curve[i].error > level) continue;
        if (i == 0) return time_to_accuracy{curve[0].seconds, curve[0], curve[0], false};
        const work_point& a = curve[i - 1];  // error above the level
        const work_point& b = curve[i];      // error at or below it
        // log t is linear in log error between a and b.
        const double s = std::log(level / a.error) / std::log(b.error / a.error);
        return time_to_accuracy{a.seconds * std::pow(b.seconds / a.seconds, s), a, b, true};
    }
    return std::nullopt;
}

}  // namespace sympl::app
