// What every runnable system shares.
#include "running/runnable_system.hpp"

#include <algorithm>
#include <cmath>

#include <sympl/core/error.hpp>

namespace sympl::app {

run_result runnable_system::run(const method_spec& m, const run_request& rq, double t0, double t_end,
                         const std::vector<double>& x0) const {
    if (const std::string why = why_not(m, form); !why.empty()) throw invalid_argument(why);
    return runner(m, rq, t0, t_end, x0);
}

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
    double diff = 0, scale = 0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        diff = std::max(diff, std::fabs(a[i] - b[i]));
        scale = std::max(scale, std::fabs(b[i]));
    }
    return scale > 0 ? diff / scale : diff;
}

}  // namespace sympl::app
