#pragma once
// What every method kind's run shares (run_kinds.hpp): the program's state
// types, what a system type offers (the library's concepts), the run context
// a kind's run receives, and the checkpointed driver.
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include <sympl/sympl.hpp>

#include "output/format.hpp"
#include "methods/method_kinds.hpp"
#include "running/runnable_system.hpp"

namespace sympl::app::detail {

// States of Dim degrees of freedom: fixed-size for small systems, as a
// library user would write them (the program's timings are theirs).
template <int Dim>
using state_of = phase_space<double, Dim>;

template <int Dim, class Container>
state_of<Dim> to_state(const Container& x) {
    return from_stacked<state_of<Dim>>(x);
}

// Any state as stacked doubles (the reference runs in long double).
template <class X>
std::vector<double> to_vector(const X& x) {
    const auto y = stacked(x);
    return {y.begin(), y.end()};
}

// What a system of type Sys offers, from the library's concepts. V < 0 and a
// kinetic energy quadratic in p are properties of the system's values, given
// by its registry entry (systems.cpp): `possible` takes them as met wherever
// the type allows, which is what a compile-time choice of the kinds compiled
// for Sys needs; otherwise V < 0 is left for the entry to say.
template <class Sys>
constexpr system_form form_of(bool possible = false) {
    using State = phase_space<double>;
    using V = State::vector;
    using E = decltype(equations_of<State>(std::declval<Sys>()));
    constexpr bool separable = separable_hamiltonian<Sys, V>;
    constexpr bool differentiable = [] {
        if constexpr (separable) return differentiable_force<Sys, V>;
        else return false;
    }();
    return {.separable_hamiltonian = separable,
            .newtonian = newtonian_form<E>,
            .damped_split = damped_newtonian_form<E, State>,
            .negative_potential = possible && separable,
            .differentiable_force = differentiable,
            .conformal = conformal_system<Sys, V>,
            .general_hamiltonian = general_hamiltonian<Sys, V> || separable,
            .quadratic_kinetic = separable,
            .planetary = requires(const Sys& sys) {
                std::size(sys.mass);
                double(sys.mass[0]);
                double(sys.G);
            },
            .charged = requires(const Sys& sys) {
                sys.particle();
                sys.electromagnetic_field();
            }};
}

// Whether a system of type Sys can meet a requirement: the requirement's row
// (requirements.hpp) asked at compile time of the type's form.
template <needs N, class Sys>
constexpr bool meets() {
    return *requirement_row(N).why_not(form_of<Sys>(true)) == '\0';
}

template <class Sys>
[[noreturn]] void refuse(const std::string& method, needs n) {
    throw invalid_argument("method '" + method + "' " + why_not(n, form_of<Sys>()));
}

using steps_and_forces = std::pair<std::size_t, std::uint64_t>;

// The stepper's carried memory as the checkpoint holds it, and back.
template <class V>
stepper_memory<std::vector<double>> to_record(const stepper_memory<V>& m) {
    const auto as_std = [](const V& v) { return std::vector<double>(v.data(), v.data() + v.size()); };
    return {as_std(m.force), as_std(m.velocity), as_std(m.q_error), as_std(m.p_error),
            m.force_fresh,   m.velocity_fresh,   m.force_evaluations, m.velocity_evaluations};
}
// A fixed-size vector takes exactly its size (a checkpoint's fields are
// checked against the state, not against LogH's one more or a stepper's
// residuals: 2 numbers into a 3-vector read past them, found by fuzz_checkpoint);
// a dynamic one is resized by the stepper's first step when it does not fit.
template <class V>
stepper_memory<V> from_record(const stepper_memory<std::vector<double>>& m) {
    const auto as_vector = [](const std::vector<double>& v) {
        if constexpr (V::SizeAtCompileTime != Eigen::Dynamic)
            if (v.size() != std::size_t(V::SizeAtCompileTime))
                throw invalid_argument("checkpoint: the stepper's memory holds a vector of " + std::to_string(v.size()) +
                                       " numbers; expected " + std::to_string(V::SizeAtCompileTime) +
                                       "; not resumed from (remove it to start over)");
        return V(Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size())));
    };
    return {as_vector(m.force), as_vector(m.velocity), as_vector(m.q_error), as_vector(m.p_error),
            m.force_fresh,      m.velocity_fresh,      m.force_evaluations, m.velocity_evaluations};
}

template <class Context, class Stepper>
steps_and_forces checkpointed(const Context& c, Stepper& stepper);

// The state at t + theta dt inside the last step, from a stepper that
// interpolates its own steps: the output times (runnable.hpp) read it instead
// of the Hermite interpolant, which is far off on a controlled pair's long
// steps (run_rkn.hpp sets it).
template <class State>
using own_interpolation = std::function<void(double theta, State& out)>;

// What a kind's run gets: the system, the method, the request, the span, the
// state (x0 in, the final state out) and the observer, called at t0 and after
// every step when the run is observed (empty when the run is timed), and,
// when the observer reads states between steps, where a kind whose stepper
// interpolates its own steps puts that interpolation. The observer is held
// by reference (observer_ref), so the timed and the observed run of a
// stepper are one driver, compiled once.
// Own: the methods compiled for Sys (its registry entry's, runnable.hpp);
// run_method reaches no other.
template <class Sys, int Dim, compiled_methods Own = compiled_methods{}>
struct run_context {
    using system = Sys;
    using State = state_of<Dim>;
    using observer = observer_ref<State, double>;
    static constexpr int dimension = Dim;
    static constexpr compiled_methods own = Own;

    const Sys& sys;
    const method_spec& m;
    const run_request& rq;
    double t0, t_end;
    State& x;
    observer observe;
    own_interpolation<State>* interpolation = nullptr;

    bool observed() const { return observe.observing(); }

    // Any sympl stepper over the span. A resumable method runs in the
    // checkpointed driver, observed or not, asked for checkpoints or not (it
    // saves none when not asked). Methods a checkpoint cannot resume were
    // refused before (run_method reads their row); Resumable false, the row's
    // answer for the kind (or a classic stepper's history), leaves that
    // driver uncompiled.
    template <bool Resumable = true, class Stepper>
    steps_and_forces drive(Stepper stepper) const {
        if constexpr (Resumable) {
            return checkpointed(*this, stepper);
        } else {
            if (observed() && rq.checkpoint.every_steps)
                throw std::logic_error("method '" + m.name +
                                       "': a checkpointed run its row refuses reached the driver");
            const run_summary s = integrate_until(stepper, x, t0, t_end, rq.dt, observe);
            return {s.steps, s.force_evaluations};
        }
    }
};

// A run context for kind K: its drive compiles the checkpointed driver only
// where the kind's row allows a resumable method.
template <method_kind K, class Context>
struct kind_context : Context {
    template <bool Resumable = true, class Stepper>
    steps_and_forces drive(Stepper stepper) const {
        return Context::template drive<Resumable && kind_may_resume(K)>(std::move(stepper));
    }
};

// What a run carries beyond its stepper's own list: nothing (fixed steps).
struct nothing_more {
    template <class Self, class List>
    static void carried_fields(Self&, List&) {}
};

// What a checkpoint holds of a run, for every kind: the stepper's memory()
// (splitting_stepper) in the record's memory, and one carried list: first
// the fields the run carries itself (`more`, a type with carried_fields:
// LogH's extended state, a controller's state, Odeint's time and step), then
// the stepper's own carried() list where it has one (wisdom_holman_stepper,
// tao_stepper, processed_stepper, the RKN pairs). Restored from the record
// resumed from; saved every rq.checkpoint.every_steps steps (but at t_end);
// the counters count on from the record's.
template <class Context, class Stepper, class More = nothing_more>
class checkpoint_keeper {
public:
    static constexpr bool has_memory = requires(const Stepper& s) { s.memory(); };
    static constexpr bool has_carried = requires(const Stepper& s) { s.carried(); };

    checkpoint_keeper(const Context& c, Stepper& stepper, More& more) : c_(c), stepper_(stepper), more_(more) {}

    // The record the run resumes from, the stepper and `more` restored from
    // it (nullptr: the run starts at t0).
    const checkpoint_record* restore() {
        const checkpoint_record* from = c_.rq.checkpoint.resume;
        if (!from) return nullptr;
        // A list that does not fit is refused naming the file, as the record's other fields are.
        const std::string& file = c_.rq.checkpoint.resume_file;
        const std::string who = "checkpoint " + (file.empty() ? "" : printable(file) + " ") + "of '" + c_.m.name + "'";
        try {
            if constexpr (has_memory) stepper_.restore(from_record<typename Stepper::state_type::vector>(from->memory));
            sympl::detail::carried_reader<double> r{from->carried, who.c_str()};
            r.part(more_);
            if constexpr (has_carried) stepper_.restore_carried(r.rest());
            r.done();
        } catch (const invalid_argument& e) {
            throw invalid_argument(std::string(e.what()) + "; not resumed from (remove it to start over)");
        }
        forces_before_ = from->memory.force_evaluations;
        velocities_before_ = from->memory.velocity_evaluations;
        done_ = from->step;
        return from;
    }

    // After each step to time t with the (physical) state y: a checkpoint when one is due.
    template <class State>
    void after_step(const State& y, double t) {
        const std::size_t every = c_.rq.checkpoint.every_steps;
        if (every == 0 || ++done_ % every != 0 || t == c_.t_end) return;
        checkpoint_record record;
        record.step = done_;
        record.time = t;
        record.state = to_vector(y);
        if constexpr (has_memory) {
            record.memory = to_record(stepper_.memory());
        } else {
            record.memory.force_evaluations = forces_before_ + sympl::detail::forces(stepper_);
            record.memory.velocity_evaluations = velocities_before_ + sympl::detail::velocities(stepper_);
        }
        sympl::detail::carried_writer<double> w{record.carried};
        w.part(std::as_const(more_));
        if constexpr (has_carried) w.values(stepper_.carried());
        c_.rq.checkpoint.save(record);
    }

    std::uint64_t forces_before() const { return forces_before_; }

private:
    const Context& c_;
    Stepper& stepper_;
    More& more_;
    std::uint64_t forces_before_ = 0, velocities_before_ = 0;
    std::size_t done_ = 0;
};

// The observed run of every kind, with a checkpoint every
// rq.checkpoint.every_steps steps (none when 0), or its continuation from
// rq.checkpoint.resume: the state, the stepper and `more` restored from the
// record, then drive(observer, from, keeper), the kind's own driver from the
// record's step (nullptr: from t0), returning the whole run's steps and
// forces. Its observer is the context's, called at t0 unless resumed (the
// record's step was observed before), then after every step, each step
// saving a checkpoint when one is due; so the rest of a resumed run is bit
// for bit the uninterrupted one.
template <class Context, class Stepper, class More, class Drive>
steps_and_forces checkpointed_run(const Context& c, Stepper& stepper, More& more, Drive&& drive) {
    using State = typename Context::State;
    checkpoint_keeper<Context, Stepper, More> keeper(c, stepper, more);
    const checkpoint_record* from = keeper.restore();
    if (from) c.x = to_state<Context::dimension>(from->state);
    bool at_start = !from;
    const auto observe = [&](const State& y, double t) {
        c.observe(y, t);
        if (!std::exchange(at_start, false)) keeper.after_step(y, t);
    };
    return drive(typename Context::observer(observe), from, std::as_const(keeper));
}

// A sympl stepper at fixed steps, timed (nothing saved or restored) or
// observed through checkpointed_run.
template <class Context, class Stepper>
steps_and_forces checkpointed(const Context& c, Stepper& stepper) {
    using observer = typename Context::observer;
    if (!c.observed()) {
        const run_summary s = integrate_until(stepper, c.x, c.t0, c.t_end, c.rq.dt, observer{});
        return {s.steps, s.force_evaluations};
    }
    nothing_more nothing;
    return checkpointed_run(c, stepper, nothing, [&](observer observe, const checkpoint_record* from, const auto& keeper) {
        run_options options;
        if (from) options.first_step = from->step;
        const run_summary s = integrate_until(stepper, c.x, c.t0, c.t_end, c.rq.dt, observe, options);
        return steps_and_forces{options.first_step + s.steps, keeper.forces_before() + s.force_evaluations};
    });
}

// How a kind runs: run_kind<K>::run(context), one per row of method_kind_entries.
template <method_kind K>
struct run_kind;

}  // namespace sympl::app::detail
