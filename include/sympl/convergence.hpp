#pragma once
// Measured order of convergence of a method (a table, or any stepper) on a
// nonlinear problem.
//
// The global error of an order-p method at a fixed time is C dt^p + ..., so the
// difference between runs at dt and dt/2 also shrinks as dt^p: the slope
// log2(d(dt) / d(dt/2)) of successive differences measures p with no reference
// solution. Runs are in quadruple precision (113-bit Boost.Multiprecision
// float), so that even a 10th-order method has many halvings between its
// pre-asymptotic range and roundoff; the order is read where two consecutive
// slopes agree.
// The harmonic oscillator is never used alone: it cannot tell a
// kick from a drift, so a table copied with its roles swapped would pass there.
#include <cmath>
#include <algorithm>
#include <concepts>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <boost/math/constants/constants.hpp>
#include <boost/multiprecision/cpp_bin_float.hpp>
#include <boost/multiprecision/eigen.hpp>

#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/relativistic_pendulum.hpp>

#include "error.hpp"
#include "phase_space.hpp"
#include "splitting_stepper.hpp"
#include "table.hpp"

namespace sympl {

// IEEE-754 binary128 layout in software: 113-bit significand, eps ~ 1e-34.
using quad = boost::multiprecision::number<
    boost::multiprecision::cpp_bin_float<113, boost::multiprecision::digit_base_2, void, std::int16_t, -16382, 16383>,
    boost::multiprecision::et_off>;

struct order_measurement {
    double order = 0;                 // slope read in the asymptotic range (0: none found)
    bool converged = false;           // consecutive slopes agreed (see order_options::agreement)
    std::vector<double> dt;           // step sizes tried
    std::vector<double> difference;   // max |x(dt) - x(dt/2)| for each dt but the last
};

struct order_options {
    std::size_t min_steps = 1;
    std::size_t max_steps = std::size_t(1) << 14;
    // Differences below this are not used: table coefficients are stored in
    // long double (~1e-19 relative), which leaves an error term of that size.
    // Runs in double need about 1e-10.
    double floor = 1e-22;
    // Three consecutive slopes, each within this of the next, mark the asymptotic range.
    double agreement = 0.08;
};

// Measured order of any method: run(n) returns the state reached at t_end by
// n steps of t_end/n, for n = 1, 2, 4, ... (up to options.max_steps, from
// options.min_steps). Works for any state type with max_difference.
template <class Run>
    requires std::invocable<Run&, std::size_t>
order_measurement measure_order(Run&& run, double t_end, const order_options& options = {}) {
    using State = std::decay_t<std::invoke_result_t<Run&, std::size_t>>;
    order_measurement m;
    State previous;
    double last_slope = HUGE_VAL, last_change = HUGE_VAL;
    double pair_slope = 0;  // finest slope that agreed with the one before it
    for (std::size_t n = std::max<std::size_t>(options.min_steps, 1); n <= options.max_steps; n *= 2) {
        State x = run(n);
        m.dt.push_back(t_end / static_cast<double>(n));
        if (m.dt.size() > 1) {
            const double d = static_cast<double>(max_difference(previous, x));
            m.difference.push_back(std::isfinite(d) ? d : HUGE_VAL);
            if (!(d >= options.floor)) break;
            const std::size_t k = m.difference.size() - 1;
            if (k >= 1 && std::isfinite(m.difference[k - 1])) {
                const double slope = std::log2(m.difference[k - 1] / d);
                const double change = std::fabs(slope - last_slope);
                m.order = slope;
                if (change <= options.agreement && last_change <= options.agreement) {
                    m.converged = true;
                    return m;
                }
                if (change <= options.agreement) pair_slope = slope;
                last_slope = slope;
                last_change = change;
            }
        }
        previous = std::move(x);
    }
    // No three agreeing slopes before the floor: the finest agreeing pair, or
    // failing that the finest slope read (converged = false).
    if (pair_slope != 0) {
        m.order = pair_slope;
        m.converged = true;
    }
    return m;
}

// Measured order of `method` on H from x0 over [0, t_end], halving dt from t_end.
template <class H, int D>
order_measurement measure_order(const table& method, const H& h, const phase_space<quad, D>& x0, const quad& t_end,
                                const order_options& options = {}) {
    using State = phase_space<quad, D>;
    splitting_stepper<H, State> stepper(h, method);
    return measure_order(
        [&](std::size_t n) {
            State x = x0;
            stepper.steps(x, t_end / quad(n), n);
            return x;
        },
        static_cast<double>(t_end), options);
}

// The built-in nonlinear test problems.
enum class order_problem {
    pendulum,               // quadratic T, V = 1 - cos q: q0 = 1.2, p0 = 0.3, t in [0, 3]
    kepler,                 // e = 0.5 from pericentre over half a period
    nonquadratic_kinetic,   // relativistic pendulum, T = sqrt(1 + p^2): q0 = 1.2, p0 = 0.9, t in [0, 3]
};

inline const char* to_string(order_problem p) {
    switch (p) {
        case order_problem::pendulum: return "pendulum";
        case order_problem::kepler: return "kepler";
        case order_problem::nonquadratic_kinetic: return "nonquadratic_kinetic";
    }
    return "?";
}

inline order_measurement measure_order(const table& method, order_problem problem = order_problem::pendulum,
                                       const order_options& options = {}) {
    using V1 = Eigen::Matrix<quad, 1, 1>;
    const quad q0 = quad(12) / 10;
    switch (problem) {
        case order_problem::pendulum:
            return measure_order(method, hamiltonians::pendulum{}, phase_space<quad, 1>(V1(q0), V1(quad(3) / 10)),
                                 quad(3), options);
        case order_problem::kepler:
            return measure_order(method, hamiltonians::kepler{}, hamiltonians::kepler::initial_state<quad>(0.5),
                                 boost::math::constants::pi<quad>(), options);
        case order_problem::nonquadratic_kinetic:
            return measure_order(method, hamiltonians::relativistic_pendulum{},
                                 phase_space<quad, 1>(V1(q0), V1(quad(9) / 10)), quad(3), options);
    }
    throw invalid_argument("measure_order: unknown problem");
}

}  // namespace sympl
