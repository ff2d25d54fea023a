// The generic path of separable systems (generic_path.hpp): every kind it
// runs, the reference, ensembles and sections, compiled once for
// erased_separable. Any H(q, p): generic_path_general.cpp.
#include "running/generic_path.hpp"

#include <sympl/drivers/events.hpp>

#include "running/runnable.hpp"

namespace sympl::app::detail {

namespace {

// A method's events on the generic path (drivers/events.hpp): a plain
// splitting table's or an RKN pair's, at fixed steps of dt (located on the
// cubic Hermite interpolant), or a pair controlled to `tolerance` (absolute
// = relative; dt its first trial step), located on the pair's own
// interpolation. Each g is called on the stacked state, which costs a copy
// a call; g is the user's (a Python callable, say), which costs more.
events_function events_of(erased_separable sys) {
    return [sys = std::move(sys)](const method_spec& m, double dt, double tolerance, double t0, double t_end,
                                  const std::vector<double>& x0, const std::vector<event_spec>& specs) {
        using S = state_of<Eigen::Dynamic>;
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
        throw invalid_argument("events method '" + printable(m.name) +
                               "'; expected a plain splitting table or an RKN pair (dprkn6, dprkn8, dprkn12, at fixed "
                               "steps or _controlled)");
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
    return {.run = generic_run(sys, std::move(energy)),
            .reference_method = splitting_reference_method,
            .reference = reference_by_splitting(sys),
            .ensemble = ensemble_of<Eigen::Dynamic, 1>(sys),
            .section = section_of<Eigen::Dynamic>(sys),
            .events = events_of(sys)};
}

}  // namespace sympl::app::detail
