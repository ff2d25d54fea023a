#pragma once
// Measured order of convergence of any method on any problem, with no
// reference solution: log2(d(dt) / d(dt/2)) of the differences between runs
// at dt, dt/2, dt/4, ... reads the order p, where three consecutive slopes
// agree (failing that, two within 0.15). A final run of low slopes set by the
// rounding of a table's own coefficients is cut off first, and the result
// says between which differences the order was read. table_order.hpp runs
// this on the library's own problems in 113-bit precision; the rounding tail
// and the figures behind it: docs/reliability.md.
#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

#include "../core/phase_space.hpp"

namespace sympl {

struct order_measurement {
    double order = 0;              // slope read in the asymptotic range (0: none found)
    bool converged = false;        // consecutive slopes agreed (see order_options::agreement)
    int agreeing = 0;              // how many consecutive slopes the reading rests on (3, 2, or 1)
    // Where the order was read: the differences |x(dt) - x(dt/2)| and step sizes of the agreeing slopes.
    double largest_difference = 0, smallest_difference = 0;
    double largest_dt = 0, smallest_dt = 0;
    // The level below which the coefficients' rounding set the slope (0: not seen).
    double rounding_level = 0;
    // Every slope read, finest error level last: (difference, dt, slope).
    struct slope_reading {
        double difference, dt, slope;
    };
    std::vector<slope_reading> slopes;
};

struct order_options {
    std::size_t min_steps = 1;
    std::size_t max_steps = std::size_t(1) << 14;
    // Differences below this are not used: runs in 113-bit precision reach
    // 1e-30; runs in double need about 1e-10.
    double floor = 1e-22;
    // Three consecutive slopes within this of each other mark the asymptotic range.
    double agreement = 0.08;
};

// Reads the order from m.slopes (coarsest first). First the rounding tail is
// cut: a final run of slopes of at most 2.5, all below differences of 1e-14
// (where no double-precision run looks, and where no method's own plateau
// starts), after a slope higher by 1.5 or more; with it goes one slope in
// transition. Then the order is the coarsest three agreeing slopes, or the
// coarsest two within 0.15 (the house threshold), or the finest single slope
// read (converged = false).
inline order_measurement read_order(order_measurement m, const order_options& options) {
    const auto& s = m.slopes;
    std::size_t usable = s.size();
    std::size_t tail = s.size();
    while (tail > 0 && s[tail - 1].slope <= 2.5 && s[tail - 1].difference < 1e-14) --tail;
    double above = 0, tail_max = 0;
    for (std::size_t k = 0; k < tail; ++k) above = std::max(above, s[k].slope);
    for (std::size_t k = tail; k < s.size(); ++k) tail_max = std::max(tail_max, s[k].slope);
    if (tail < s.size() && s.size() - tail >= 2 && tail > 0 && above >= tail_max + 1.5) {
        usable = tail;
        if (usable >= 2 && s[usable - 1].slope < s[usable - 2].slope - 0.5) --usable;  // in transition
        m.rounding_level = s[tail].difference;
    }
    const auto spread = [&](std::size_t i, std::size_t count) {
        double lo = s[i].slope, hi = s[i].slope;
        for (std::size_t k = i; k < i + count; ++k) lo = std::min(lo, s[k].slope), hi = std::max(hi, s[k].slope);
        return hi - lo;
    };
    const auto read = [&](std::size_t i, std::size_t count) {
        m.order = s[i + count / 2].slope;
        m.converged = count > 1;
        m.agreeing = static_cast<int>(count);
        m.largest_difference = s[i].difference;
        m.smallest_difference = s[i + count - 1].difference;
        m.largest_dt = s[i].dt;
        m.smallest_dt = s[i + count - 1].dt;
        return m;
    };
    for (std::size_t i = 0; i + 3 <= usable; ++i)
        if (spread(i, 3) <= options.agreement) return read(i, 3);
    for (std::size_t i = 0; i + 2 <= usable; ++i)
        if (spread(i, 2) <= 0.15) return read(i, 2);
    if (usable > 0) return read(usable - 1, 1);
    return m;
}

// Measured order of any method: run(n) returns the state reached at t_end by
// n steps of t_end/n, for n = min_steps, 2 min_steps, 4 min_steps, ... Works for any state type with max_difference.
template <class Run>
    requires std::invocable<Run&, std::size_t>
order_measurement measure_order(Run&& run, double t_end, const order_options& options = {}) {
    using State = std::decay_t<std::invoke_result_t<Run&, std::size_t>>;
    order_measurement m;
    State previous;
    double last_difference = 0;
    for (std::size_t n = std::max<std::size_t>(options.min_steps, 1), first = n; n <= options.max_steps; n *= 2) {
        State x = run(n);
        if (n > first) {
            const double d = static_cast<double>(max_difference(previous, x));
            if (!std::isfinite(d)) {
                last_difference = 0;
            } else {
                if (d < options.floor) break;
                if (last_difference > 0)
                    m.slopes.push_back({d, t_end / static_cast<double>(n / 2), std::log2(last_difference / d)});
                last_difference = d;
                // Three agreeing slopes end the reading, unless they could be a rounding tail.
                const order_measurement r = read_order(m, options);
                if (r.agreeing == 3 && (r.order > 2.5 || r.smallest_difference >= 1e-14)) return r;
            }
        }
        previous = std::move(x);
    }
    return read_order(m, options);
}

}  // namespace sympl
