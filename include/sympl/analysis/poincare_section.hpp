#pragma once
// Poincare surface of section: the points where an orbit crosses q_k = 0
// upwards (dq_k/dt > 0), as Henon & Heiles (1964) plotted them. An event of
// events.hpp, g = q_k rising: a step whose ends have q_k < 0 and q_k >= 0
// holds a crossing, located by Brent's method on the step's cubic Hermite
// interpolant of q and p (dense_output.hpp: values and time derivatives
// dq/dt = dT/dp, dp/dt = -dV/dq at both ends) and the state interpolated
// there. The points are accurate to the interpolant's O(dt^4) about the step
// ends (|error| <= dt^4/384 max|x''''| in each component, plus |dx/dt| times
// the time's error, that of q_k over |dq_k/dt|; the root is found to
// rounding in the step's fraction, 4 eps dt) whatever the method's order,
// without stepping the flow backwards. q_k of a point is set to 0 exactly.
#include <cstddef>
#include <string>
#include <type_traits>
#include <vector>

#include "../core/error.hpp"
#include "../drivers/fixed_step.hpp"
#include "../drivers/events.hpp"

namespace sympl {

// Runs `steps` steps of dt from x at t = 0 with the stepper (any with
// step(x, dt) and hamiltonian(), run as integrate_steps runs it with an
// observer) and returns the states at the upward crossings of q_k = 0, in
// time order. A non-finite state throws blow_up naming the step.
template <class Stepper, class State>
std::vector<State> section_crossings(Stepper& stepper, State x, double dt, std::size_t steps, Eigen::Index k = 0) {
    static_assert(std::is_same_v<State, typename Stepper::state_type>,
                  "section_crossings: expected x of the stepper's state_type");
    using T = typename Stepper::scalar;
    const T step = T(dt);
    detail::check_dt(step, "section_crossings");
    if (k < 0 || k >= x.size())
        throw invalid_argument("section_crossings: k = " + std::to_string(k) + " for a state of dimension " +
                               std::to_string(x.size()) + "; expected 0 <= k < dimension");
    const std::vector<event<State>> upward{{[k](const State& s, T) { return s.q[k]; }, event_direction::rising}};
    const auto run = detail::run_events(stepper, stepper.hamiltonian(), x, upward, event_options{}, "section_crossings",
                                        [&](auto& observer) { return integrate_steps(stepper, x, T(0), step, steps, observer); });
    std::vector<State> crossings;
    crossings.reserve(run.hits.size());
    for (const auto& hit : run.hits) {
        crossings.push_back(hit.state);
        crossings.back().q[k] = 0;
    }
    return crossings;
}

}  // namespace sympl
