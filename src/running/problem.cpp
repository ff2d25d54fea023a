// What every problem shares.
#include "running/problem.hpp"

#include <algorithm>
#include <cmath>

namespace sympl::app {

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
    double diff = 0, scale = 0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        diff = std::max(diff, std::fabs(a[i] - b[i]));
        scale = std::max(scale, std::fabs(b[i]));
    }
    return scale > 0 ? diff / scale : diff;
}

}  // namespace sympl::app
