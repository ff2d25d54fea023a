#pragma once
// classic_stepper: one stepper that runs any classic rule (classic_steppers.hpp)
// over equations_of_motion, counting the evaluations of dq/dt and dp/dt, and
// the history a multistep rule keeps (used only when handed back, bitwise, the
// state it returned at the same dt). make_classic builds one for a system or a
// separable Hamiltonian. Gould & Tobochnik, ch. 3; docs/classic.md.
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "../core/carried_state.hpp"
#include "../core/checked_reads.hpp"
#include "../core/equations_of_motion.hpp"
#include "../core/error.hpp"
#include "../core/phase_space.hpp"

namespace sympl {

namespace detail {
// Counts the evaluations of the right-hand sides.
template <class System>
struct counted_equations {
    using system_type = System;
    System system;
    std::uint64_t forces = 0, velocities = 0;

    template <class Vec, class T>
    void dq_dt(const Vec& q, const Vec& p, T t, Vec& out) {
        system.dq_dt(q, p, t, out);
        ++velocities;
    }
    template <class Vec, class T>
    void dp_dt(const Vec& q, const Vec& p, T t, Vec& out) {
        system.dp_dt(q, p, t, out);
        ++forces;
    }
    // Both rates at one point, dq/dt first.
    template <class Vec, class T>
    void rates(const Vec& q, const Vec& p, T t, Vec& dq, Vec& dp) {
        dq_dt(q, p, t, dq);
        dp_dt(q, p, t, dp);
    }
};

template <class State>
void check_classic_step(const char* who, const State& x, typename State::scalar dt) {
    using std::isfinite;
    if (!isfinite(dt) || dt == typename State::scalar(0))
        throw invalid_argument(std::string(who) + ": dt = " + number(dt) + "; expected a finite non-zero step size");
    if (x.q.size() != x.p.size())
        throw invalid_argument(std::string(who) + ": q has " + std::to_string(x.q.size()) + " components but p has " +
                               std::to_string(x.p.size()) + "; expected equal dimensions");
}

// The state a multistep method returned last, to know whether its history applies.
template <class State>
struct step_history {
    State last;
    typename State::scalar dt{};
    bool valid = false;

    bool continues(const State& x, typename State::scalar dt_) const {
        return valid && dt_ == dt && x.size() == last.size() && x.q == last.q && x.p == last.p;
    }
    void remember(const State& x, typename State::scalar dt_) {
        last = x;
        dt = dt_;
        valid = true;
    }
};
// A multistep rule's carried part (classic_stepper::carried()): its history,
// a vector, or a number.
template <class S, class State>
void write_part(carried_writer<S>& w, const step_history<State>& h) {
    w.flag(h.valid);
    w.number(S(h.dt));
    w.numbers(h.last.q);
    w.numbers(h.last.p);
}
template <class S, class V>
void write_part(carried_writer<S>& w, const V& v) {
    if constexpr (std::is_arithmetic_v<V>) w.number(S(v));
    else w.numbers(v);
}
template <class S, class State>
void read_part(carried_reader<S>& r, step_history<State>& h) {
    h.valid = r.flag();
    h.dt = r.number();
    r.numbers(h.last.q);
    r.numbers(h.last.p);
    if (h.last.q.size() != h.last.p.size()) r.refuse("holds a last state whose q and p differ in size");
}
template <class S, class V>
void read_part(carried_reader<S>& r, V& v) {
    if constexpr (std::is_arithmetic_v<V>) v = V(r.number());
    else r.numbers(v);
}
}  // namespace detail

// One stepper for every classic algorithm: Rule<State> holds the algorithm
// (its advance() and its workspace and history), the stepper the counted
// system. Rule's accessors (error estimates, half-step momenta) are the stepper's.
template <class System, class State, template <class> class Rule>
    requires equations_of_motion<System, State>
class classic_stepper : public Rule<State> {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    using vector = typename State::vector;

    template <class... Options>
    explicit classic_stepper(System system, Options&&... options)
        : Rule<State>(std::forward<Options>(options)...), eq_{std::move(system)} {}

    void step(State& x, scalar t, scalar dt) {
        detail::check_classic_step(Rule<State>::name, x, dt);
        // Hamilton's equations of generic code: reads past the state refused
        // once per dimension (checked_reads.hpp); other systems are the user's.
        if constexpr (requires { eq_.system.hamiltonian; })
            check_reads_once(eq_.system.hamiltonian, x, Rule<State>::name);
        this->advance(eq_, x, t, dt);
    }

    std::uint64_t force_evaluations() const { return eq_.forces; }
    std::uint64_t velocity_evaluations() const { return eq_.velocities; }
    void reset_counters() { eq_.forces = eq_.velocities = 0; }
    const System& system() const { return eq_.system; }

    // What a multistep rule carries between steps (the state it returned
    // last, its half-step momenta or previous positions, the last force):
    // a stepper given restore_carried(carried()) and handed that state goes
    // on bit for bit (a checkpoint). Rules without a history carry nothing.
    std::vector<scalar> carried() const
        requires std::is_floating_point_v<scalar> && requires(Rule<State>& r) { r.carried_parts(); }
    {
        std::vector<scalar> out;
        detail::carried_writer<scalar> w{out};
        // carried_parts() ties the rule's members; they are only read here.
        std::apply([&](const auto&... part) { (detail::write_part(w, part), ...); },
                   const_cast<classic_stepper&>(*this).carried_parts());
        return out;
    }
    void restore_carried(std::span<const scalar> values)
        requires std::is_floating_point_v<scalar> && requires(Rule<State>& r) { r.carried_parts(); }
    {
        detail::carried_reader<scalar> r{values, Rule<State>::name};
        auto parts = this->carried_parts();
        auto kept = std::apply([](const auto&... part) { return std::make_tuple(part...); }, parts);  // if it does not fit
        try {
            std::apply([&](auto&... part) { (detail::read_part(r, part), ...); }, parts);
            r.done();
        } catch (...) {
            parts = kept;
            throw;
        }
    }

private:
    detail::counted_equations<System> eq_;
};

// A classic stepper for a system or a separable Hamiltonian:
//   auto s = make_classic<rk4, phase_space<double, 1>>(hamiltonians::pendulum{});
template <template <class, class> class Method, class State, class System, class... Options>
auto make_classic(System system, Options&&... options) {
    auto equations = equations_of<State>(std::move(system));
    return Method<decltype(equations), State>(std::move(equations), std::forward<Options>(options)...);
}

}  // namespace sympl
