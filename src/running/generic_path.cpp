// The generic path of separable systems (generic_path.hpp): every kind it
// runs, the reference, ensembles and sections, compiled once for
// erased_separable. Any H(q, p): generic_path_general.cpp.
#include "running/generic_path.hpp"

#include <sympl/drivers/events.hpp>

#include "running/runnable.hpp"

namespace sympl::app::detail {

namespace {

using events_state = state_of<Eigen::Dynamic>;

// The events of any kind but a plain table and the RKN pairs: the method
// run by `run` as run() runs it (compensated and extrapolated tables,
// processed, LogH with dt its fictitious step, classic steppers, Gauss, Tao,
// semiexplicit, Odeint at `tolerance`), observed at each of its own steps in
// physical time (run_request::each_step), its events located on the cubic
// Hermite interpolant between those steps; x ends where the run ended.
event_run<events_state> events_by_run(const erased_separable& sys, const run_function& run, const method_spec& m,
                                      double dt, double tolerance, double t0, double t_end,
                                      const std::vector<double>& x0, events_state& x,
                                      const std::vector<event<events_state>>& events) {
    using S = events_state;
    if (!generic_kinds().has(m.kind))
        throw invalid_argument("events method '" + printable(m.name) + "' (" + entry_of(m.kind).label +
                               "): its runs are not offered with events; expected a method of another kind (a "
                               "table, a processed method, an RKN pair, LogH, Gauss, Tao, semiexplicit, a "
                               "classic or an Odeint stepper)");
    step_interpolant<erased_separable, S> dense(sys, hermite_order::cubic);
    run_summary summary;  // steps observed so far
    const auto drive = [&](auto& observer) {
        run_request rq;
        rq.dt = dt;
        rq.tolerance = tolerance;
        rq.timing_repeats = 0;
        rq.energy = true;  // blow-up told as run() tells it (relative energy error > divergence_limit)
        bool first = true;
        S y = x;
        rq.each_step = [&](double t, const std::vector<double>& state) {
            y = from_stacked<S>(state);
            if (!std::exchange(first, false)) ++summary.steps;
            observer(std::as_const(y), t);
        };
        const run_result r = run(m, rq, t0, t_end, x0);
        if (!r.stable) throw integration_error(r.failure, r.blowup_step, r.blowup_time);
        x = from_stacked<S>(r.final_state);
        summary.t = t_end;
        summary.force_evaluations = r.force_evaluations;
        return summary;
    };
    const auto stopped = [&](std::size_t) { return summary; };
    return sympl::detail::locate_events<dense_summary>(dense, x, events, event_options{}, "events", drive, stopped);
}

// A method's events on the generic path (drivers/events.hpp). A plain
// splitting table's or an RKN pair's at fixed steps of dt are located on the
// cubic Hermite interpolant, a pair's controlled to `tolerance` (absolute =
// relative; dt its first trial step) on the pair's own interpolation; any
// other kind through events_by_run. Each g is called on the stacked state,
// which costs a copy a call; g is the user's (a Python callable, say),
// which costs more.
events_function events_of(erased_separable sys, run_function run) {
    return [sys = std::move(sys), run = std::move(run)](const method_spec& m, double dt, double tolerance, double t0,
                                                        double t_end, const std::vector<double>& x0,
                                                        const std::vector<event_spec>& specs) {
        using S = events_state;
        std::vector<event<S>> events;
        for (const event_spec& e : specs)
            // g by reference: `specs` outlives the run, and a copy of a
            // caller's g may own a Python object (src/python/system_events.cpp).
            events.push_back({[&g = e.g](const S& x, double t) { return g(t, to_vector(x)); },
                              e.direction > 0   ? event_direction::rising
                              : e.direction < 0 ? event_direction::falling
                                                : event_direction::both,
                              e.stop ? event_action::stop : event_action::record});
        S x = from_stacked<S>(x0);
        const auto outcome_of = [&](const auto& run) {
            event_outcome out;
            for (const auto& h : run.hits) out.hits.push_back({h.event, h.t, to_vector(h.state)});
            out.stopped = run.stopped;
            out.t = run.t;
            out.x = to_vector(x);
            return out;
        };
        const auto with_pair = [&]<class Pair>(Pair) {
            auto stepper = make_rkn_stepper<Pair, S>(sys);
            if (!adaptive(m)) return outcome_of(integrate_events(stepper, sys, x, t0, t_end, dt, events));
            control_options control;
            control.absolute_tolerance = control.relative_tolerance = tolerance;
            control.dt_initial = dt;
            return outcome_of(integrate_events(stepper, sys, x, t0, t_end, control, events));
        };
        if (m.kind == method_kind::table && m.coefficients && !m.extrapolation_columns && !m.compensated) {
            splitting_stepper<erased_separable, S> stepper(sys, *m.coefficients);
            return outcome_of(integrate_events(stepper, sys, x, t0, t_end, dt, events));
        }
        if (m.kind == method_kind::dprkn) {
            switch (m.parameters.pair) {
                case rkn_pair::dprkn6: return with_pair(dprkn6{});
                case rkn_pair::dprkn8: return with_pair(dprkn8{});
                case rkn_pair::dprkn12: return with_pair(dprkn12{});
            }
        }
        return outcome_of(events_by_run(sys, run, m, dt, tolerance, t0, t_end, x0, x, events));
    };
}

}  // namespace

// The RKN pairs on a state of one degree of freedom (a pendulum) run on
// fixed-size states; every other method on the dynamic-size ones. On a
// dynamic state of one number the pairs' stage sums cost about twice the
// compiled pairs' (docs/speed.md, "The generic path").
run_function generic_run(erased_separable sys, energy_function energy) {
    using one_dof_pairs = runner<erased_fixed_size<1>, 1, compiled_methods{.kinds = kind_set{method_kind::dprkn}}>;
    return [every = generic_runner(sys, energy), one = one_dof_pairs(erased_fixed_size<1>(sys), energy)](
               const method_spec& m, const run_request& rq, double t0, double t_end, const std::vector<double>& x0) {
        if (m.kind != method_kind::dprkn || x0.size() != 2) return every(m, rq, t0, t_end, x0);
        run_result out = one(m, rq, t0, t_end, x0);
        out.generic = true;
        return out;
    };
}

generic_parts generic_separable(erased_separable sys, energy_function energy) {
    generic_parts parts{.run = generic_run(sys, std::move(energy)),
                        .reference_method = splitting_reference_method,
                        .reference = reference_by_splitting(sys),
                        .ensemble = ensemble_of<Eigen::Dynamic, 1>(sys),
                        .section = section_of<Eigen::Dynamic>(sys),
                        .events = {}};
    parts.events = events_of(std::move(sys), parts.run);
    return parts;
}

}  // namespace sympl::app::detail
