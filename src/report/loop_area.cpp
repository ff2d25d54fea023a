// The loop-area measure: a loop of initial conditions carried by any method.
#include "report/loop_area.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <sympl/analysis/phase_space_measures.hpp>

namespace sympl::app {

double loop_area_error(const runnable_system& p, const method_spec& m, run_request rq, double t0, double t_end) {
    // Energy watched so that a loop point that runs away (finite but huge)
    // counts as unstable instead of giving a meaningless area.
    rq.energy = p.hamiltonian;
    rq.timing_repeats = 0;
    rq.trajectory = nullptr;
    rq.trajectory_every = rq.energy_series_every = 0;
    rq.output_times.clear();
    // The loop's runs are not the method's run: none of its checkpoints
    // (saved or resumed), progress line or per-step hook.
    rq.checkpoint = {};
    rq.progress = nullptr;
    rq.each_step = nullptr;
    const std::size_t n = p.degrees_of_freedom;
    const double r = 0.05 * std::max(1.0, std::hypot(p.x0[0], p.x0[n])), pi = std::numbers::pi;
    using State = phase_space<double>;
    const auto circle = [&](double s) {
        std::vector<double> v = p.x0;
        v[0] += r * std::cos(2 * pi * s);
        v[n] += r * std::sin(2 * pi * s);
        return from_stacked<State>(v);
    };
    bool stable = true;
    const auto flow = [&](State& x) {
        const run_result res = p.run(m, rq, t0, t_end, stacked(x));
        if (!res.stable) stable = false;
        else x = from_stacked<State>(res.final_state);
    };
    const auto loop = carry_loop(circle, flow, {64, 4096, r / 16});  // polygon error ~ (1/16)^2/6 ~ 7e-4
    return stable ? std::fabs(loop_area(loop, 0) - pi * r * r) / (pi * r * r) : -1;
}

}  // namespace sympl::app
