// The run plan of a scene: its runs, steps and reference, once.
#include "methods/run_plan.hpp"

#include <algorithm>
#include <cmath>

#include "output/format.hpp"
#include "running/systems.hpp"

namespace sympl::app {

run_request planned_run::request() const {
    run_request rq;
    rq.dt = dt;
    rq.tolerance = tolerance;
    return rq;
}

std::size_t run_plan::sweep_length(const scene_method& m) const {
    return std::size_t(std::count_if(runs.begin(), runs.end(), [&](const planned_run& r) { return r.method == &m; }));
}

const std::vector<double>& sweep_of(const scene& s, const scene_method& m) {
    if (adaptive(m)) return m.tolerances.empty() ? s.tolerances : m.tolerances;
    return m.dt.empty() ? s.dt : m.dt;
}

run_plan plan_runs(const scene& s, const runnable_system& p, sweep_use use) {
    run_plan plan{.s = &s, .use = use};
    plan.degrees_of_freedom = p.degrees_of_freedom;
    const double span = s.t_end - s.t0;
    double finest = HUGE_VAL;
    for (const scene_method& m : s.methods) {
        const auto& sweep = sweep_of(s, m);
        const std::size_t count = use == sweep_use::whole ? sweep.size() : 1;
        const bool controlled = adaptive(m), physical = steps_in_physical_time(m);
        // extrapolated(<table>, k) runs 1 + 2 + ... + k steps per step.
        const double inner = m.extrapolation_columns > 0
                                 ? double(m.extrapolation_columns) * double(m.extrapolation_columns + 1) / 2
                                 : 1.0;
        for (std::size_t i = 0; i < count; ++i) {
            planned_run r{.method = &m, .dt = controlled ? 0.0 : sweep[i], .tolerance = controlled ? sweep[i] : 0.0};
            if (physical) {
                r.steps = std::ceil(span / sweep[i]) * inner;
                finest = std::min(finest, sweep[i]);
            }
            plan.runs.push_back(r);
        }
    }
    plan.finest_dt = std::isfinite(finest) ? finest : use == sweep_use::whole ? s.dt.back() : s.dt.front();
    if (!p.exact) {
        // The reference (reference.hpp) runs at a quarter and at half of the finest step.
        plan.reference_dt = plan.finest_dt / 4;
        plan.reference_steps = std::ceil(span / plan.reference_dt) * 1.5;
    }
    return plan;
}

void check_run_size(const run_plan& plan, double max_steps) {
    const scene& s = *plan.s;
    const auto refuse = [&](const std::string& what, double dt, double steps) {
        throw scene_error(printable(s.source) + ": " + what + " at dt = " + shortest(dt) + " over t = " + shortest(s.t0) + " .. " +
                          shortest(s.t_end) + " takes " + format_number(steps, 3) + " steps; the limit is " +
                          format_number(max_steps, 3) + " (raise it with --max-steps)");
    };
    for (const planned_run& r : plan.runs) {
        if (!(r.steps <= max_steps)) refuse("method '" + r.method->name + "'", r.dt, r.steps);
        // `sympl run` writes its energy series as the run goes (run_scene.cpp): none held.
        const memory_estimate m = run_memory(*r.method, plan.degrees_of_freedom, r.steps, 0);
        if (!(m.bytes <= memory_budget_bytes))
            throw scene_error(printable(s.source) + ": method '" + r.method->name + "' would hold " +
                              format_number(m.bytes / double(1 << 30), 3) + " GiB (" + m.what + "); the limit is " +
                              format_number(memory_budget_bytes / double(1 << 30), 3) +
                              " GiB a run (docs/reliability.md, \"Memory\")");
    }
    if (plan.reference_dt > 0 && !(plan.reference_steps <= max_steps))
        refuse("the reference (its dt is a quarter of the finest step, " + shortest(plan.finest_dt) + ")",
               plan.reference_dt, plan.reference_steps);
}

memory_estimate run_memory(const method_spec& m, std::size_t degrees_of_freedom, double steps,
                           std::size_t energy_every, double real_bytes) {
    memory_estimate e;
    if (m.kind == method_kind::gauss) {
        const double n2 = 2.0 * double(degrees_of_freedom), s = m.parameters.stages;
        e.bytes += (n2 * n2 + n2 * s * n2 * s) * real_bytes;
        e.what = "Gauss-Legendre's Jacobian and Newton matrix for " + std::to_string(degrees_of_freedom) +
                 " degrees of freedom and " + std::to_string(m.parameters.stages) + " stages";
    }
    if (energy_every > 0 && steps > 0) {
        e.bytes += (steps / double(energy_every) + 1) * 2 * 16;  // a (t, error) pair, the vector's growth
        e.what += std::string(e.what.empty() ? "" : ", and ") + "an energy series of " +
                  format_number(steps / double(energy_every) + 1, 3) + " rows (energy_every = " +
                  std::to_string(energy_every) + ")";
    }
    return e;
}

runnable_system system_of(const scene& s) {
    runnable_system p = make_system(s.system, s.parameters, s.q0, s.p0, s.source);
    // An energy that is already infinite (q at a singularity, 1e308 squared)
    // would make every energy error read 0 or NaN.
    if (p.energy)
        if (const double e0 = p.energy(p.x0); !std::isfinite(e0))
            throw scene_error(printable(s.source) + ": the initial state of " + s.system + " has energy H = " + shortest(e0) +
                              "; expected a state of finite energy");
    for (const method_spec& m : s.methods)
        if (const std::string why = why_not(m, p.form); !why.empty()) throw scene_error(printable(s.source) + ": " + why);
    return p;
}

}  // namespace sympl::app
