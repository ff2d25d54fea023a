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
#include <type_traits>
#include <utility>
#include <vector>

#include "../core/carried_in_place.hpp"
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
    // Its part of a multistep rule's carried list (classic_stepper::carried()).
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.flag(self.valid);
        l.number(self.dt);
        l.numbers(self.last.q);
        l.numbers(self.last.p);
        l.check(self.last.q.size() == self.last.p.size(), "holds a last state whose q and p differ in size");
    }
};
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

    // Whether the rule carries a history from step to step (it has carried_fields).
    static constexpr bool carries_history =
        requires(const Rule<State>& r, detail::carried_writer<scalar>& w) { Rule<State>::carried_fields(r, w); };

    // What a multistep rule carries between steps (the state it returned
    // last, its half-step momenta or previous positions, the last force; the
    // rule's carried_fields): a stepper given restore_carried(carried()) and
    // handed that state goes on bit for bit (a checkpoint). Rules without a
    // history carry nothing. Restored in place (carried_in_place.hpp): the
    // stepper holds the caller's system.
    std::vector<scalar> carried() const
        requires std::is_floating_point_v<scalar> && carries_history
    {
        return detail::carried_list<scalar>(*this);
    }
    void restore_carried(std::span<const scalar> values)
        requires std::is_floating_point_v<scalar> && carries_history
    {
        detail::restore_carried_in_place<scalar>(*this, values, Rule<State>::name);
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
