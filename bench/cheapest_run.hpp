#pragma once
// What the time-to-accuracy benchmarks share: finding the cheapest setting
// that meets an accuracy target, and timing a run.
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "report/timing.hpp"

namespace sympl::bench {

// Median over `repeats` of the time per call of f, each repeat calling f
// until at least `least` seconds have passed: the program's one timing
// procedure (src/report/timing.hpp).
inline double seconds_of(const std::function<void()>& f, int repeats, double least = 0.02) {
    return app::time_per_call(f, repeats, least).median;
}

// The loosest setting (a step or a tolerance) in [tight, loose] whose error
// meets target: a scan from loose to tight on a `grid`-point log grid finds the
// first that meets it (too small a step can miss it again through rounding),
// then bisection on the logarithm between it and the one before, to 1%.
// Nothing when no point of the grid meets it.
inline std::optional<double> loosest_meeting(const std::function<double(double)>& error, double loose, double tight,
                                             double target, int grid) {
    const double a = std::log(loose), b = std::log(tight);
    for (int i = 0; i <= grid; ++i) {
        double lo = a + (b - a) * i / grid;
        if (!(error(std::exp(lo)) <= target)) continue;
        double hi = i == 0 ? lo : a + (b - a) * (i - 1) / grid;
        for (int k = 0; k < 40 && std::fabs(hi - lo) > 0.01; ++k) {
            const double mid = (lo + hi) / 2;
            (error(std::exp(mid)) <= target ? lo : hi) = mid;
        }
        return std::exp(lo);
    }
    return std::nullopt;
}

}  // namespace sympl::bench
