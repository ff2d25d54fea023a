#pragma once
// How each method kind runs on a system: run_kind<K>::run, one per row of
// method_kind_entries (method_kinds.hpp), and run_method, the one dispatch
// that picks it. A kind whose requirement a system type cannot meet is not
// instantiated for it (the registry's requirement, checked by the library's
// concepts at compile time). Included by the systems' translation units
// (systems/*.cpp) through model.hpp only.
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/interop/odeint.hpp>

#include "format.hpp"
#include "method_kinds.hpp"
#include "problem.hpp"

namespace sympl::app::detail {

namespace odeint = boost::numeric::odeint;

// States of Dim degrees of freedom: fixed-size for small systems, as a
// library user would write them (the program's timings are theirs).
template <int Dim>
using state_of = phase_space<double, Dim>;

// Odeint's state: std::array for a fixed size, std::vector otherwise.
template <int Dim>
struct odeint_state_of {
    using type = std::array<double, std::size_t(2 * Dim)>;
};
template <>
struct odeint_state_of<Eigen::Dynamic> {
    using type = std::vector<double>;
};
template <int Dim>
using odeint_state = typename odeint_state_of<Dim>::type;

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

template <int Dim>
odeint_state<Dim> to_odeint(const state_of<Dim>& x) {
    odeint_state<Dim> y{};
    if constexpr (Dim == Eigen::Dynamic) y.resize(std::size_t(2 * x.size()));
    const auto v = stacked(x);
    std::copy(v.begin(), v.end(), y.begin());
    return y;
}

// Whether a system of type Sys meets a requirement: decided by the library's
// concepts, at compile time; form_of<Sys>() is the registry's copy.
// (V < 0 is a property of the system's values, given by its registry entry.)
template <needs N, class Sys>
constexpr bool meets() {
    using State = phase_space<double>;
    using E = decltype(equations_of<State>(std::declval<Sys>()));
    if constexpr (N == needs::any) return true;
    else if constexpr (N == needs::separable_hamiltonian || N == needs::negative_potential)
        return separable_hamiltonian<Sys, State::vector>;
    else if constexpr (N == needs::differentiable_force) {
        if constexpr (separable_hamiltonian<Sys, State::vector>) return differentiable_force<Sys, State::vector>;
        else return false;
    } else if constexpr (N == needs::newtonian) return newtonian_form<E>;
    else return damped_newtonian_form<E, State>;
}

template <class Sys>
system_form form_of() {
    return {.separable_hamiltonian = meets<needs::separable_hamiltonian, Sys>(),
            .newtonian = meets<needs::newtonian, Sys>(),
            .damped_split = meets<needs::damped_split, Sys>(),
            .differentiable_force = meets<needs::differentiable_force, Sys>()};
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
template <class V>
stepper_memory<V> from_record(const stepper_memory<std::vector<double>>& m) {
    const auto as_vector = [](const std::vector<double>& v) {
        return V(Eigen::Map<const Eigen::VectorXd>(v.data(), Eigen::Index(v.size())));
    };
    return {as_vector(m.force), as_vector(m.velocity), as_vector(m.q_error), as_vector(m.p_error),
            m.force_fresh,      m.velocity_fresh,      m.force_evaluations, m.velocity_evaluations};
}

template <class Context, class Stepper>
steps_and_forces checkpointed(const Context& c, Stepper& stepper);

// What a kind's run gets: the system, the method, the request, the span, the
// state (x0 in, the final state out) and the observer, called at t0 and after
// every step when the run is observed (Observer is not no_observer).
template <class Sys, int Dim, class Observer>
struct run_context {
    using system = Sys;
    using State = state_of<Dim>;
    using OdeState = odeint_state<Dim>;
    static constexpr int dimension = Dim;
    static constexpr bool observed = !std::is_same_v<Observer, no_observer>;

    const Sys& sys;
    const method_spec& m;
    const run_request& rq;
    double t0, t_end;
    State& x;
    Observer& observe;

    // Any sympl stepper over the span; checkpointed when the request asks.
    // Steppers a checkpoint cannot resume (Resumable false: extrapolated,
    // processed, classic with history) are refused by the scene before they
    // get here, and their checkpointed driver is not compiled.
    template <bool Resumable = true, class Stepper>
    steps_and_forces drive(Stepper stepper) const {
        run_summary s;
        if constexpr (observed) {
            if (rq.checkpoint.every_steps) {
                if constexpr (Resumable)
                    return checkpointed(*this, stepper);
                else
                    throw invalid_argument(why_not_resumable(m));
            }
            s = integrate_until(stepper, x, t0, t_end, rq.dt, observe);
        } else {
            s = integrate_until(stepper, x, t0, t_end, rq.dt);
        }
        return {s.steps, s.force_evaluations};
    }
};

// The observed run with a checkpoint every rq.checkpoint.every_steps steps,
// or its continuation from rq.checkpoint.resume: the driver resumes at the
// checkpoint's step (times from the integer index), the stepper from its
// saved memory, so the rest of the run is bit for bit the uninterrupted one.
template <class Context, class Stepper>
steps_and_forces checkpointed(const Context& c, Stepper& stepper) {
    using State = typename Context::State;
    constexpr bool has_memory = requires { stepper.memory(); };
    const checkpoint_hooks& hooks = c.rq.checkpoint;
    run_options options;
    std::uint64_t forces_before = 0, velocities_before = 0;
    if (const checkpoint_record* from = hooks.resume) {
        c.x = to_state<Context::dimension>(from->state);
        if constexpr (has_memory) stepper.restore(from_record<typename State::vector>(from->memory));
        forces_before = from->memory.force_evaluations;
        velocities_before = from->memory.velocity_evaluations;
        options.first_step = from->step;
    }
    std::size_t done = options.first_step;
    bool at_start = options.first_step == 0;  // the observer's first call is t0, not a step
    const auto observe = [&](const State& y, double t) {
        c.observe(y, t);
        if (std::exchange(at_start, false)) return;
        if (++done % hooks.every_steps != 0 || t == c.t_end) return;
        checkpoint_record record;
        record.step = done;
        record.state = to_vector(y);
        if constexpr (has_memory) {
            record.memory = to_record(stepper.memory());
        } else {
            record.memory.force_evaluations = forces_before + stepper.force_evaluations();
            record.memory.velocity_evaluations = velocities_before + stepper.velocity_evaluations();
        }
        hooks.save(record);
    };
    const run_summary s = integrate_until(stepper, c.x, c.t0, c.t_end, c.rq.dt, observe, options);
    return {options.first_step + s.steps, forces_before + s.force_evaluations};
}

template <method_kind K>
struct run_kind;

template <>
struct run_kind<method_kind::table> {
    template <class C>
    static steps_and_forces run(const C& c) {
        splitting_stepper<typename C::system, typename C::State> stepper(c.sys, *c.m.coefficients, {c.m.compensated});
        if (c.m.extrapolation_columns > 0)
            return c.template drive<false>(extrapolation_stepper(std::move(stepper), c.m.extrapolation_columns));
        return c.drive(std::move(stepper));
    }
};

template <>
struct run_kind<method_kind::processed> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return c.template drive<false>(processed_stepper<typename C::system, typename C::State>(c.sys, *c.m.processing));
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
        if (c.m.extrapolation_columns > 0)
            return in_fictitious_time(c, extrapolation_stepper(std::move(inner), c.m.extrapolation_columns));
        return in_fictitious_time(c, std::move(inner));
    }

    template <class C, class Stepper>
    static steps_and_forces in_fictitious_time(const C& c, Stepper stepper) {
        using Extended = typename Stepper::state_type;
        Extended X = to_extended(c.sys, c.x, c.t0);
        run_summary s;
        if constexpr (C::observed) {
            c.observe(std::as_const(c.x), c.t0);
            s = integrate_to_time(stepper, X, c.t_end, c.rq.dt,
                                  [&](const Extended& y, double time) { c.observe(physical_state(y), time); });
        } else {
            s = integrate_to_time(stepper, X, c.t_end, c.rq.dt);
        }
        c.x = physical_state(X);
        return {s.steps, s.force_evaluations};
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
            ((c.m.classic == I ? void(done = one<I>(c)) : void()), ...);
            return done;
        }(std::make_index_sequence<classic_method_count>{});
    }

    template <std::size_t I, class C>
    static steps_and_forces one(const C& c) {
        constexpr auto& method = std::get<I>(classic_methods);
        return with_stepper<!method.history>(method, c);
    }

    template <bool Resumable, template <class, class> class Stepper, needs N, class C>
    static steps_and_forces with_stepper(const classic_method<Stepper, N>&, const C& c) {
        if constexpr (meets<N, typename C::system>())
            return c.template drive<Resumable>(make_classic<Stepper, typename C::State>(c.sys));
        else
            refuse<typename C::system>(c.m.name, N);
    }
};

// Boost.Odeint's steppers on the library's bridge (odeint.hpp), whose
// workspace keeps the evaluations free of allocation and counts them. The
// observer reaches them type-erased (nullptr: not observed), so each Odeint
// stepper is compiled once per system, not once per observer; a call per
// step costs nothing next to an Odeint step.
template <class Sys, int Dim>
struct odeint_run {
    using State = state_of<Dim>;
    using OdeState = odeint_state<Dim>;
    const Sys& sys;
    const method_spec& m;
    const run_request& rq;
    double t0, t_end;
    State& x;
    const std::function<void(const State&, double)>* observe;

    static void check_finite(const OdeState& y, std::size_t step, double t, double h) {
        for (double v : y)
            if (!std::isfinite(v)) throw blow_up(step, t, h);
    }

    steps_and_forces fixed_step() const {
        odeint_workspace<double, Dim> w;
        const auto f = make_odeint_system<Dim>(sys, &w);
        OdeState y = to_odeint<Dim>(x);
        odeint::runge_kutta4<OdeState> rk4;
        const double dt = rq.dt, span = t_end - t0;
        const auto n = static_cast<std::size_t>(std::floor(span / dt));
        double rest = span - double(n) * dt;
        if (rest <= 8 * std::numeric_limits<double>::epsilon() * span) rest = 0;
        if (observe) (*observe)(std::as_const(x), t0);  // as sympl's driver: t0 first
        const std::size_t total = n + (rest > 0 ? 1 : 0);
        for (std::size_t i = 0; i < total; ++i) {
            const double t = t0 + double(i) * dt, h = i < n ? dt : rest;
            rk4.do_step(f, y, t, h);
            if (observe) {
                check_finite(y, i + 1, t, h);
                (*observe)(to_state<Dim>(y), t + h);
            }
        }
        if (!observe) check_finite(y, total, t_end, dt);
        x = to_state<Dim>(y);
        return {total, w.evaluations};
    }

    // Any Odeint controlled stepper (try_step), from t0 to exactly t_end.
    template <class Controlled>
    steps_and_forces controlled(Controlled stepper) const {
        odeint_workspace<double, Dim> w;
        const auto f = make_odeint_system<Dim>(sys, &w);
        OdeState y = to_odeint<Dim>(x);
        double t = t0, h = (t_end - t0) / 1000;
        std::size_t steps = 0, failed = 0;
        if (observe) (*observe)(std::as_const(x), t0);
        while (t < t_end) {
            if (t + h > t_end) h = t_end - t;
            if (!(h > 1e-14 * (t_end - t0)) || t + h == t || ++failed > 500)
                throw integration_error(m.name + ": step size underflow at t = " + format_number(t, 17) + " (dt = " +
                                            format_number(h, 3) + ")",
                                        steps + 1, t);
            if (stepper.try_step(f, y, t, h) == odeint::success) {
                ++steps;
                failed = 0;
                check_finite(y, steps, t, h);
                if (observe) (*observe)(to_state<Dim>(y), t);
            }
        }
        x = to_state<Dim>(y);
        return {steps, w.evaluations};
    }
};

// The kind's Odeint run with the context's observer type-erased.
template <class C, class Run>
steps_and_forces with_odeint(const C& c, Run run) {
    using R = odeint_run<typename C::system, C::dimension>;
    std::function<void(const typename C::State&, double)> observe;
    if constexpr (C::observed) observe = [&](const typename C::State& y, double t) { c.observe(y, t); };
    return run(R{c.sys, c.m, c.rq, c.t0, c.t_end, c.x, C::observed ? &observe : nullptr});
}

// One instantiation per system for each Odeint kind, whatever the observer.
template <class Sys, int Dim>
steps_and_forces odeint_rk4_run(const odeint_run<Sys, Dim>& r) {
    return r.fixed_step();
}
template <class Sys, int Dim>
steps_and_forces odeint_dopri5_run(const odeint_run<Sys, Dim>& r) {
    using OdeState = odeint_state<Dim>;
    return r.controlled(odeint::make_controlled(r.rq.tolerance, r.rq.tolerance, odeint::runge_kutta_dopri5<OdeState>()));
}
template <class Sys, int Dim>
steps_and_forces odeint_fehlberg78_run(const odeint_run<Sys, Dim>& r) {
    using OdeState = odeint_state<Dim>;
    return r.controlled(
        odeint::make_controlled(r.rq.tolerance, r.rq.tolerance, odeint::runge_kutta_fehlberg78<OdeState>()));
}
template <class Sys, int Dim>
steps_and_forces odeint_bulirsch_stoer_run(const odeint_run<Sys, Dim>& r) {
    return r.controlled(odeint::bulirsch_stoer<odeint_state<Dim>>(r.rq.tolerance, r.rq.tolerance));
}

template <>
struct run_kind<method_kind::odeint_rk4> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return with_odeint(c, odeint_rk4_run<typename C::system, C::dimension>);
    }
};

template <>
struct run_kind<method_kind::odeint_dopri5> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return with_odeint(c, odeint_dopri5_run<typename C::system, C::dimension>);
    }
};

template <>
struct run_kind<method_kind::odeint_fehlberg78> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return with_odeint(c, odeint_fehlberg78_run<typename C::system, C::dimension>);
    }
};

template <>
struct run_kind<method_kind::odeint_bulirsch_stoer> {
    template <class C>
    static steps_and_forces run(const C& c) {
        return with_odeint(c, odeint_bulirsch_stoer_run<typename C::system, C::dimension>);
    }
};

// Whether Sys meets `n`, asked at run time of the compile-time answers.
template <class Sys>
bool meets_at_run_time(needs n) {
    constexpr std::array answers{meets<needs::any, Sys>(),          meets<needs::separable_hamiltonian, Sys>(),
                                 meets<needs::newtonian, Sys>(),    meets<needs::damped_split, Sys>(),
                                 meets<needs::negative_potential, Sys>(), meets<needs::differentiable_force, Sys>()};
    return answers[std::size_t(n)];
}

// The kind's run where the system type meets the kind's requirement; the
// method's own requirement (a classic stepper's, force-gradient kicks) was
// checked before.
template <method_kind K, class C>
steps_and_forces run_where_met(const C& c) {
    if constexpr (meets<entry_of(K).requirement, typename C::system>())
        return run_kind<K>::run(c);
    else
        refuse<typename C::system>(c.m.name, entry_of(K).requirement);
}

// The one dispatch: a method's kind to its run.
template <class C>
steps_and_forces run_method(const C& c) {
    if (const needs n = requirement_of(c.m); !meets_at_run_time<typename C::system>(n))
        refuse<typename C::system>(c.m.name, n);
    return [&]<std::size_t... K>(std::index_sequence<K...>) {
        steps_and_forces done{};
        ((std::size_t(c.m.kind) == K ? void(done = run_where_met<method_kind(K)>(c)) : void()), ...);
        return done;
    }(std::make_index_sequence<method_kind_entries.size()>{});
}

}  // namespace sympl::app::detail
