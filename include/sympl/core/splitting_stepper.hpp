#pragma once
// splitting_stepper: any table (table.hpp) on any separable Hamiltonian and any
// phase_space state. Per sub-step a kick p += c dt F(q) or a drift
// q += c dt dT/dp(p) (Gould & Tobochnik, eq. 3.74); a force-gradient kick adds
// 2 g dt^3 J_F M^-1 F (table.hpp).
//
// A force is evaluated only when q has moved since the last one. Within a call
// the last force of a step serves the next (leapfrog KDK costs one force per
// step). Across calls the stepper keeps its last force with the q it belongs
// to, as Odeint's velocity_verlet keeps its acceleration, and reuses it when
// the next call is handed that q bit for bit: a loop of step() evaluates the
// forces steps(n) does. The check reads q and p once, evaluates nothing; a state
// changed in any bit gets a fresh force, and state_changed() drops the kept
// force when something else the force depends on has changed (a parameter the
// Hamiltonian refers to). The workspace is sized once; no step allocates.
// The loop's design and measured cost: docs/speed.md.
#include <algorithm>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "error.hpp"
#include "hamiltonian.hpp"
#include "phase_space.hpp"
#include "splitting_loop.hpp"
#include "stepper_memory.hpp"
#include "table.hpp"

namespace sympl {

template <class H, class State>
    requires phase_space_state<State> && separable_hamiltonian<H, typename State::vector>
class splitting_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    using vector = typename State::vector;

    splitting_stepper(H hamiltonian, table method, stepper_options options = {})
        : loop_(std::move(hamiltonian), std::move(method), options) {
        if constexpr (State::dimension != Eigen::Dynamic) size_workspace(State::dimension);
    }

    // One step of size dt (dt < 0 runs backwards). The force the last call
    // ended with is reused when x.q is the q that call returned, bit for bit.
    [[gnu::always_inline]] inline void step(State& x, scalar dt) { steps(x, dt, 1); }

    // n consecutive steps: forces and velocities carried over between steps,
    // and a step's last sub-step joined with the next step's first when they
    // are of one kind. n calls of step() give the same numbers where nothing
    // is joined, and on small fixed-size states of kick-first tables (which
    // join across calls); otherwise they differ by rounding.
    [[gnu::always_inline]] inline void steps(State& x, scalar dt, std::size_t n) {
        check_step(dt);
        const int kept = kept_force_matches(x);
        if constexpr (State::dimension != Eigen::Dynamic) {
            if (n == 1 && kept == 2 && dt == loop_.p_before_dt) {  // a loop of step() on a small state
                loop_.joined_step(x, dt);
                keep_force(x);
                return;
            }
        }
        if (kept == 0) check_state_once_sized(x);
        loop_.run(x, dt, n, kept > 0, false, kept == 2 && dt == loop_.p_before_dt);
        keep_force(x);
    }

    // n more steps of the state this stepper advanced last, unchanged since,
    // trusted without a check: the last force (and velocity) is carried over.
    // The driver uses this between chunks and after restore().
    void resume_steps(State& x, scalar dt, std::size_t n) {
        check_step(dt);
        check_state_once_sized(x);
        loop_.run(x, dt, n, loop_.force_fresh, loop_.velocity_fresh);
        keep_force(x);
    }

    // Drops the kept force: the next call evaluates it afresh whatever q it is
    // handed. Needed only when the force changed while q did not (a Hamiltonian
    // that refers to parameters the caller changed); any change of the state
    // itself is seen by the next call.
    void state_changed() { kept_ = false; }

    // The carried memory after the last run, and its restoration into a
    // stepper of the same Hamiltonian, table and options: the next
    // resume_steps() (or a driver with run_options::first_step) continues as
    // if never interrupted.
    stepper_memory<vector> memory() const {
        return {loop_.force,          loop_.velocity,       loop_.q_error,
                loop_.p_error,        loop_.force_fresh,    loop_.velocity_fresh,
                loop_.forces_counted, loop_.velocities_counted};
    }
    void restore(const stepper_memory<vector>& m) {
        const Eigen::Index n = m.force.size();
        const bool compensated = loop_.options.compensated;
        const bool sizes = m.velocity.size() == n && (!compensated || (m.q_error.size() == n && m.p_error.size() == n));
        if (!sizes)
            throw invalid_argument("splitting_stepper::restore: memory of sizes " + std::to_string(m.force.size()) + ", " +
                                   std::to_string(m.velocity.size()) + ", " + std::to_string(m.q_error.size()) + ", " +
                                   std::to_string(m.p_error.size()) + (compensated ? " (compensated)" : "") +
                                   "; expected force and velocity (and, compensated, both residuals) of one size");
        size_workspace(n);
        loop_.force = m.force;
        loop_.velocity = m.velocity;
        if (compensated) {
            loop_.q_error = m.q_error;
            loop_.p_error = m.p_error;
        }
        loop_.force_fresh = m.force_fresh;
        loop_.velocity_fresh = m.velocity_fresh;
        loop_.forces_counted = m.force_evaluations;
        loop_.velocities_counted = m.velocity_evaluations;
        kept_ = false;  // the q it belongs to is not in the memory: resume_steps trusts it
    }

    std::uint64_t force_evaluations() const { return loop_.forces_counted; }
    std::uint64_t velocity_evaluations() const { return loop_.velocities_counted; }
    // Evaluations of J_F u by force-gradient kicks (0 for other tables).
    std::uint64_t force_derivative_evaluations() const { return loop_.derivatives_counted; }
    void reset_counters() { loop_.forces_counted = loop_.velocities_counted = loop_.derivatives_counted = 0; }

    const H& hamiltonian() const { return loop_.h; }
    // What the last call found T to be (quadratic_kinetic.hpp): a generic T
    // recognised as quadratic drifts by a product with the inverse mass.
    typename quadratic_kinetic<vector>::form kinetic_energy_form() const { return loop_.kinetic.recognised(); }
    const table& method() const { return loop_.method; }
    const stepper_options& options() const { return loop_.options; }

private:
    void check_step(scalar dt) const {
        using std::isfinite;
        if (!isfinite(dt) || dt == scalar(0))
            throw invalid_argument("splitting_stepper: dt = " + std::to_string(static_cast<double>(primal(dt))) +
                                   "; expected a finite non-zero step size");
    }

    // The full check (hamiltonian.hpp): sizes, finiteness, reads in range.
    [[gnu::noinline, gnu::cold]] void check_state_once_sized(const State& x) {
        check_state(loop_.h, x, "splitting_stepper");
        if (loop_.kinetic.dimension() != x.q.size()) loop_.kinetic.recognise(loop_.h, x.q.size());
        if (loop_.force.size() != x.q.size()) {  // once per dimension
            size_workspace(x.q.size());
            if constexpr (State::dimension == Eigen::Dynamic)
                detail::check_output_sizes(loop_.h, x, loop_.force, loop_.velocity);
        }
    }

    void size_workspace(Eigen::Index n) {
        loop_.size_workspace(n);
        if constexpr (caches) kept_q_.resize(n);
        kept_ = false;
    }

    // Only built-in floating types are compared bit for bit; other scalars
    // (dual numbers, multiprecision) get a fresh force on every call.
    static constexpr bool caches = std::same_as<scalar, double> || std::same_as<scalar, float>;
    using bits = std::conditional_t<sizeof(scalar) == 8, std::uint64_t, std::uint32_t>;
    static constexpr bits exponent = sizeof(scalar) == 8 ? bits(0x7ff0000000000000ull) : bits(0x7f800000u);

    // 1 if x.q is, bit for bit, the q the kept force belongs to (known
    // finite), and p is finite: one pass of integer operations the compiler
    // vectorises, in place of check_state's; 2 if moreover the loop kept the
    // p before its last kick and x.p is the p it returned (small states). 0:
    // the full check and a fresh force.
    [[gnu::always_inline]] inline int kept_force_matches(const State& x) const {
        if constexpr (caches) {
            if (!kept_ || x.q.size() != kept_q_.size() || x.p.size() != kept_q_.size()) return 0;
            const scalar* const q = x.q.data();
            const scalar* const p = x.p.data();
            const scalar* const k = kept_q_.data();
            bits differ = 0, not_finite = 0;
            for (Eigen::Index i = 0, n = kept_q_.size(); i < n; ++i) {
                differ |= std::bit_cast<bits>(q[i]) ^ std::bit_cast<bits>(k[i]);
                not_finite |= (std::bit_cast<bits>(p[i]) & exponent) == exponent;
            }
            if (differ != 0 || not_finite != 0) return 0;
            if constexpr (State::dimension != Eigen::Dynamic) {
                if (!loop_.p_before_valid) return 1;
                bits p_differ = 0;
                for (Eigen::Index i = 0; i < State::dimension; ++i)
                    p_differ |= std::bit_cast<bits>(p[i]) ^ std::bit_cast<bits>(kept_p_[i]);
                return p_differ == 0 ? 2 : 1;
            }
            return 1;
        } else {
            return 0;
        }
    }

    // After a run that ends with a fresh force, the q it belongs to, copied if
    // finite (a non-finite q is refused by the next call's full check).
    [[gnu::always_inline]] inline void keep_force(const State& x) {
        if constexpr (caches) {
            kept_ = false;
            if (!loop_.first_is_kick || !loop_.force_fresh) return;
            const scalar* const q = x.q.data();
            scalar* const k = kept_q_.data();
            bits not_finite = 0;
            for (Eigen::Index i = 0, n = kept_q_.size(); i < n; ++i) {
                k[i] = q[i];
                not_finite |= (std::bit_cast<bits>(q[i]) & exponent) == exponent;
            }
            kept_ = not_finite == 0;
            if constexpr (State::dimension != Eigen::Dynamic) kept_p_ = x.p;
        }
    }

    detail::splitting_loop<H, State> loop_;
    vector kept_q_;      // the q at which loop_.force was evaluated, when kept_
    vector kept_p_;      // the p the last call returned (fixed-size states)
    bool kept_ = false;  // loop_.force belongs to kept_q_ and the first sub-step is a kick
};

// Deduction helper: make_stepper<State>(h, method("leapfrog_kdk")).
template <class State, class H>
splitting_stepper<H, State> make_stepper(H h, table method, stepper_options options = {}) {
    return splitting_stepper<H, State>(std::move(h), std::move(method), options);
}

}  // namespace sympl
