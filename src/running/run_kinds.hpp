#pragma once
// How each method kind runs on a system: run_kind<K>::run, one per row of
// method_kind_entries (method_kinds.hpp), and run_method, the one dispatch
// that picks it. A kind whose requirement a system type cannot meet is not
// instantiated for it (the registry's requirement, checked by the library's
// concepts at compile time). Included by the systems' translation units
// (systems/*.cpp) through runnable.hpp only. The Odeint kinds are in
// run_odeint.hpp, those for any H(q, p) in run_general.hpp, the RKN pairs in
// run_rkn.hpp, what all kinds share in run_context.hpp.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

#include "running/run_charged.hpp"
#include "running/run_context.hpp"
#include "running/run_general.hpp"
#include "running/run_planetary.hpp"
#include "running/run_odeint.hpp"
#include "running/run_rkn.hpp"

namespace sympl::app::detail {

// A method the runner should have handed to the generic path (runnable.hpp).
[[noreturn]] inline void not_compiled(const method_spec& m) {
    throw std::logic_error("method '" + m.name + "': not compiled for the system, yet it reached its runner");
}

// A separable Hamiltonian's table, or a damped, driven system's (its drifts
// damped exactly, conformal_splitting.hpp); extrapolated and compensated
// tables need the separable stepper (requirement_of refuses them before).
template <>
struct run_kind<method_kind::table> {
    template <class C>
    static steps_and_forces run(const C& c) {
        using Sys = typename C::system;
        if constexpr (separable_hamiltonian<Sys, typename C::State::vector>) {
            splitting_stepper<Sys, typename C::State> stepper(c.sys, *c.m.coefficients, {c.m.compensated});
            constexpr bool extrapolated_resumable = !*entry_of(method_kind::table).extrapolated_not_resumable;
            if (c.m.extrapolation_columns > 0) {
                if constexpr (C::own.extrapolated)
                    return c.template drive<extrapolated_resumable>(
                        extrapolation_stepper(std::move(stepper), c.m.extrapolation_columns));
                else
                    not_compiled(c.m);
            }
            return c.drive(std::move(stepper));
        } else {
            return c.drive(conformal_stepper<Sys, typename C::State>(c.sys, *c.m.coefficients));
        }
    }
};

template <>
struct run_kind<method_kind::processed> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return c.drive(processed_stepper<typename C::system, typename C::State>(c.sys, *c.m.processing));
    }
};

// The table in LogH fictitious time (time_transformation.hpp), extrapolated
// when asked (extrapolation.hpp); the fictitious step ds is the request's dt.
template <>
struct run_kind<method_kind::logh> {
    template <class C>
    static steps_and_forces run(const C& c) {
        using Sys = typename C::system;
        using Extended = phase_space<double, extended_dimension(C::dimension)>;
        splitting_stepper<logh<Sys>, Extended> inner(logh<Sys>{c.sys}, *c.m.coefficients);
        if (c.m.extrapolation_columns > 0) {
            if constexpr (C::own.extrapolated)
                return in_fictitious_time(c, extrapolation_stepper(std::move(inner), c.m.extrapolation_columns));
            else
                not_compiled(c.m);
        }
        return in_fictitious_time(c, std::move(inner));
    }

    // What the run carries beyond the stepper's memory: the extended state X
    // (the time and its momentum with q and p). Read back, its time and (q, p)
    // must be the record's, which were observed from it: a time set far back
    // would otherwise run until the step limit.
    template <class Extended>
    struct extended_state {
        Extended& X;
        const checkpoint_record* from = nullptr;
        template <class Self, class List>
        static void carried_fields(Self& self, List& l) {
            // p_t is -H(x0), set by to_extended and never changed by a step
            // (its force is 0): a p_t read that differs would change every
            // step's length dt/ds = 1/(T + p_t) (a huge one: endless).
            const double p_t = self.X.p[self.X.size() - 1];
            l.values(self.X.q);
            l.values(self.X.p);
            l.check(!self.from || (physical_time(self.X) == self.from->time &&
                                   to_vector(physical_state(self.X)) == self.from->state &&
                                   self.X.p[self.X.size() - 1] == p_t),
                    "holds an extended state whose time, (q, p) or p_t is not the run's");
        }
    };

    // integrate_to_time observes the steps only: t0 is observed here.
    template <class C, class Stepper>
    static steps_and_forces in_fictitious_time(const C& c, Stepper stepper) {
        using Extended = typename Stepper::state_type;
        using observer = observer_ref<Extended, double>;
        Extended X = to_extended(c.sys, c.x, c.t0);
        steps_and_forces done;
        if (c.observed()) {
            extended_state<Extended> more{X, c.rq.checkpoint.resume};
            done = checkpointed_run(c, stepper, more, [&](auto observe, const checkpoint_record* from, const auto& keeper) {
                time_transformed_options options;
                if (from) options.first_step = from->step;
                else observe(std::as_const(c.x), c.t0);
                const auto physical = [&](const Extended& y, double time) { observe(physical_state(y), time); };
                const run_summary s = integrate_to_time(stepper, X, c.t_end, c.rq.dt, observer(physical), {}, options);
                return steps_and_forces{options.first_step + s.steps, keeper.forces_before() + s.force_evaluations};
            });
        } else {  // the same driver, nothing observed
            const run_summary s = integrate_to_time(stepper, X, c.t_end, c.rq.dt, observer{}, {}, {});
            done = {s.steps, s.force_evaluations};
        }
        c.x = physical_state(X);
        return done;
    }
};

// The classic stepper at the method's index in classic_methods, where the
// system meets that stepper's own requirement.
template <>
struct run_kind<method_kind::classic> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return [&]<std::size_t... I>(std::index_sequence<I...>) {
            steps_and_forces done{};
            ((c.m.classic == I ? void(done = one_compiled<I>(c)) : void()), ...);
            return done;
        }(std::make_index_sequence<classic_method_count>{});
    }

    template <std::size_t I, class C>
    static steps_and_forces one_compiled(const C& c) {
        if constexpr (C::own.classic.has(I))
            return one<I>(c);
        else
            not_compiled(c.m);
    }

    template <std::size_t I, class C>
    static steps_and_forces one(const C& c) {
        constexpr auto& method = std::get<I>(classic_methods);
        return with_stepper<!method.history || !*entry_of(method_kind::classic).history_not_resumable>(method, c);
    }

    template <bool Resumable, template <class, class> class Stepper, needs N, class C>
    static steps_and_forces with_stepper(const classic_method<Stepper, N>&, const C& c) {
        if constexpr (meets<N, typename C::system>())
            return c.template drive<Resumable>(make_classic<Stepper, typename C::State>(c.sys));
        else
            refuse<typename C::system>(c.m.name, N);
    }
};

// The kind's run where the system type meets the kind's requirement; the
// method's own requirement (a classic stepper's, force-gradient kicks) was
// checked before.
template <method_kind K, class C>
steps_and_forces run_where_met(const C& c) {
    if constexpr (!C::own.kinds.has(K))
        not_compiled(c.m);
    else if constexpr (meets<entry_of(K).requirement, typename C::system>())
        return run_kind<K>::run(kind_context<K, C>{c});
    else
        refuse<typename C::system>(c.m.name, entry_of(K).requirement);
}

// The one dispatch: a method's kind to its run. Its requirement was asked
// once, by runnable_system::run; a checkpointed run of a method its row says cannot
// resume is refused here, with the row's reason.
template <class C>
steps_and_forces run_method(const C& c) {
    if (c.observed() && c.rq.checkpoint.every_steps)
        if (const std::string why = why_not_resumable(c.m); !why.empty()) throw invalid_argument(why);
    return [&]<std::size_t... K>(std::index_sequence<K...>) {
        steps_and_forces done{};
        ((std::size_t(c.m.kind) == K ? void(done = run_where_met<method_kind(K)>(c)) : void()), ...);
        return done;
    }(std::make_index_sequence<method_kind_entries.size()>{});
}

}  // namespace sympl::app::detail
