#pragma once
// One generic loop that runs any table (table.hpp) on any separable
// Hamiltonian and any phase_space state.
//
// Per sub-step: a kick p += c*dt*force(q) or a drift q += c*dt*velocity(p)
// (Gould & Tobochnik, eq. 3.74). A force is evaluated only when q has moved since the
// last one, so the last force of a step is reused by the next (leapfrog KDK
// costs one force per step), and likewise for velocities. The workspace is
// sized once; no step allocates.
#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "error.hpp"
#include "hamiltonian.hpp"
#include "phase_space.hpp"
#include "stepper_memory.hpp"
#include "table.hpp"

namespace sympl {

struct stepper_options {
    // Compensated (Kahan) summation of the q and p increments: the rounding
    // error of each update is carried into the next, so roundoff no longer
    // grows with the number of steps (Kahan 1965; Hairer, Lubich & Wanner,
    // GNI ch. VIII.5).
    bool compensated = false;
};

template <class H, class State>
    requires phase_space_state<State> && separable_hamiltonian<H, typename State::vector>
class splitting_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    using vector = typename State::vector;

    splitting_stepper(H hamiltonian, table method, stepper_options options = {})
        : h_(std::move(hamiltonian)), table_(std::move(method)), options_(options) {
        const auto ops = table_.substeps();  // canonical: kinds alternate, no zero weights
        // Valid tables hold at least one kick and one drift (both sum to 1).
        first_is_kick_ = ops.front().kind == substep::kick;
        last_is_kick_ = ops.back().kind == substep::kick;
        joined_ = ops.size() > 1 && ops.front().kind == ops.back().kind;
        for (const substep& o : ops) weights_.push_back(static_cast<scalar>(o.weight));
        for (std::size_t k = 1; k < ops.size(); ++k) (ops[k].kind == substep::kick ? tail_kicks_ : tail_drifts_) += 1;
        body_.resize(joined_ ? ops.size() - 1 : ops.size());
        tail_.resize(ops.size() - 1);
        rotated_.resize(body_.size());
        if constexpr (State::dimension != Eigen::Dynamic) size_workspace(State::dimension);
        if (table_.has_force_gradient()) {
            if constexpr (!differentiable_force<H, vector>)
                throw invalid_argument("splitting_stepper: table '" + table_.name() +
                                       "' has force-gradient kicks, which need the force's derivative J_F u; "
                                       "expected a Hamiltonian with force_derivative(q, u, df) or a potential "
                                       "templated on its scalar (differentiated twice by dual numbers)");
            gradient_ops_ = ops;
        }
    }

    // One step of size dt (dt < 0 runs backwards). Safe whatever happened to x
    // before: the first force is always evaluated afresh.
    void step(State& x, scalar dt) {
        check_step(x, dt);
        run(x, dt, 1, false);
    }

    // n consecutive steps: forces and velocities carried over between steps,
    // and a step's last sub-step joined with the next step's first when they
    // are of one kind (the result differs from n calls of step() by rounding only).
    void steps(State& x, scalar dt, std::size_t n) {
        check_step(x, dt);
        run(x, dt, n, false);
    }

    // n more steps of the state this stepper advanced last, unchanged since:
    // the last force is carried over. The driver uses this between chunks.
    void resume_steps(State& x, scalar dt, std::size_t n) {
        check_step(x, dt);
        run(x, dt, n, true);
    }

    // The carried memory after the last run, and its restoration into a
    // stepper of the same Hamiltonian, table and options: the next
    // resume_steps() (or a driver with run_options::first_step) continues as
    // if never interrupted.
    stepper_memory<vector> memory() const {
        return {force_, velocity_, q_error_, p_error_, force_fresh_, velocity_fresh_, force_evaluations_,
                velocity_evaluations_};
    }
    void restore(const stepper_memory<vector>& m) {
        const Eigen::Index n = m.force.size();
        const bool sizes = m.velocity.size() == n && (!options_.compensated || (m.q_error.size() == n && m.p_error.size() == n));
        if (!sizes)
            throw invalid_argument("splitting_stepper::restore: memory of sizes " + std::to_string(m.force.size()) + ", " +
                                   std::to_string(m.velocity.size()) + ", " + std::to_string(m.q_error.size()) + ", " +
                                   std::to_string(m.p_error.size()) + (options_.compensated ? " (compensated)" : "") +
                                   "; expected force and velocity (and, compensated, both residuals) of one size");
        size_workspace(n);
        force_ = m.force;
        velocity_ = m.velocity;
        if (options_.compensated) {
            q_error_ = m.q_error;
            p_error_ = m.p_error;
        }
        force_fresh_ = m.force_fresh;
        velocity_fresh_ = m.velocity_fresh;
        force_evaluations_ = m.force_evaluations;
        velocity_evaluations_ = m.velocity_evaluations;
    }

    std::uint64_t force_evaluations() const { return force_evaluations_; }
    std::uint64_t velocity_evaluations() const { return velocity_evaluations_; }
    // Evaluations of J_F u by force-gradient kicks (0 for other tables).
    std::uint64_t force_derivative_evaluations() const { return force_derivative_evaluations_; }
    void reset_counters() { force_evaluations_ = velocity_evaluations_ = force_derivative_evaluations_ = 0; }

    const H& hamiltonian() const { return h_; }
    const table& method() const { return table_; }
    const stepper_options& options() const { return options_; }

private:
    void check_step(const State& x, scalar dt) {
        using std::isfinite;
        if (!isfinite(dt) || dt == scalar(0))
            throw invalid_argument("splitting_stepper: dt = " + std::to_string(static_cast<double>(primal(dt))) +
                                   "; expected a finite non-zero step size");
        check_state(h_, x, "splitting_stepper");
        if (force_.size() != x.q.size()) {  // once per dimension
            size_workspace(x.q.size());
            if constexpr (State::dimension == Eigen::Dynamic) check_output_sizes(x);
        }
    }

    void size_workspace(Eigen::Index n) {
        for (vector* v : {&force_, &velocity_, &q_error_, &p_error_, &increment_, &sum_}) {
            if (v != &force_ && v != &velocity_ && !options_.compensated) continue;
            v->resize(n);
            v->setZero();
        }
    }

    // A user's force or velocity that returns a vector of another size would
    // write past the state in the loop: tried once per new dimension, at the
    // state about to be stepped, before any step (not counted as evaluations).
    void check_output_sizes(const State& x) {
        const Eigen::Index n = x.q.size();
        force(h_, x.q, force_);
        velocity(h_, x.p, velocity_);
        for (auto [what, size] : {std::pair{"force", force_.size()}, std::pair{"velocity", velocity_.size()}})
            if (size != n) {
                const Eigen::Index got = size;
                force_.resize(0);  // checked again on the next call
                throw invalid_argument("splitting_stepper: the Hamiltonian's " + std::string(what) + " returned " +
                                       std::to_string(got) + " components for a state of dimension " +
                                       std::to_string(n) + "; expected equal dimensions");
            }
    }

    // Kahan summation: y += inc with the carried rounding error e.
    void add_compensated(vector& y, vector& e) {
        increment_ -= e;
        sum_ = y + increment_;
        e = (sum_ - y) - increment_;
        y = sum_;
    }

    // The generic loop. A table's sub-steps s0 .. s(L-1) alternate between
    // kick and drift (tables are canonical), and n steps are the stream
    //     s0,  (s1 .. s(L-1), s0) n - 1 times,  s1 .. s(L-1)
    // in which a table that ends with the kind it starts with (leapfrog KDK: a
    // half kick at each end) has s(L-1), s0 joined into one sub-step of the
    // summed size: one pass over the state less per step, which is what
    // memory-bound systems pay for. Every sub-step after s0 follows one of the
    // other kind, so it always needs a fresh force (or velocity): the loop
    // holds no test of a sub-step's kind or of a flag, and s0 alone reuses the
    // force of the previous run when resumed. Sub-step sizes weight*dt are
    // computed once per run; small fixed-size states, their force and velocity
    // run in locals the compiler keeps in registers (no aliasing with the
    // caller's state or the workspace). Everything here is forced inline: in a
    // large translation unit GCC otherwise leaves the per-sub-step calls out
    // of line whatever the user's flags.
    void run(State& x, scalar dt, std::size_t n, bool resume) {
        if (n == 0) {
            if (!resume) force_fresh_ = velocity_fresh_ = false;
            return;
        }
        if (!gradient_ops_.empty())
            return options_.compensated ? run_with_gradient<true>(x, dt, n, resume)
                                        : run_with_gradient<false>(x, dt, n, resume);
        const std::size_t L = weights_.size();
        for (std::size_t k = 1; k < L; ++k) body_[k - 1] = tail_[k - 1] = weights_[k] * dt;
        const scalar first = weights_[0] * dt;
        if constexpr (reference_velocity) velocity_is_p_ = &h_.velocity(x.p) == &x.p;
        body_.back() = joined_ ? weights_[L - 1] * dt + first : first;
        if constexpr (State::dimension != Eigen::Dynamic) {
            State y = x;
            vector f = force_, v = velocity_;
            options_.compensated ? run_loop<true>(y, f, v, first, n, resume) : run_loop<false>(y, f, v, first, n, resume);
            x = y;
            force_ = f;
            velocity_ = v;
        } else {
            options_.compensated ? run_loop<true>(x, force_, velocity_, first, n, resume)
                                 : run_loop<false>(x, force_, velocity_, first, n, resume);
        }
    }

    template <bool Compensated>
    [[gnu::always_inline]] inline void run_loop(State& x, vector& f, vector& v, scalar first, std::size_t n, bool resume) {
        // s0, reusing what the previous run left when it is still valid.
        std::uint64_t forces = 0, velocities = 0;
        if (first_is_kick_) {
            if (!(resume && force_fresh_)) force(h_, x.q, f), ++forces;
            kick<Compensated>(x, f, first);
        } else {
            const bool reuse = resume && velocity_fresh_ && !fused_velocity;
            reuse ? drift_with<Compensated>(x, v, first) : drift<Compensated>(x, v, first);
            velocities += !reuse;
        }
        const bool body_starts_with_kick = !first_is_kick_;
        if (body_starts_with_kick) repeat_body<Compensated, true>(x, f, v, n - 1);
        else repeat_body<Compensated, false>(x, f, v, n - 1);
        alternate<Compensated>(x, f, v, tail_.data(), tail_.size(), body_starts_with_kick);
        // Counted, not tallied in the loop: the body and the tail hold fixed numbers of each kind.
        const std::size_t body_kicks = tail_kicks_ + (joined_ ? 0 : first_is_kick_);
        const std::size_t body_drifts = tail_drifts_ + (joined_ ? 0 : !first_is_kick_);
        forces += (n - 1) * body_kicks + tail_kicks_;
        velocities += (n - 1) * body_drifts + tail_drifts_;
        force_fresh_ = last_is_kick_;
        velocity_fresh_ = !last_is_kick_ && !fused_velocity;
        force_evaluations_ += forces;
        velocity_evaluations_ += velocities;
    }

    // The body `steps` times over. It always holds an even number of
    // sub-steps (a joined table has an odd number L, and its body L - 1; any
    // other an even L, and its body L), so the sub-steps of all the steps run
    // as one flat loop over pairs of one shape (a loop over steps around a
    // loop over the body's pairs left leapfrog's single pair outside the inner
    // loop, and a small state went through memory at every sub-step).
    //
    // The shape is chosen by the state, and a body of the other shape is
    // rotated by one sub-step (its first before the loop, its last after):
    // - a small state runs pairs (drift, kick). The compiler keeps it in
    //   registers only where each q and f written in a pass is read later in
    //   the same pass: a store is forwarded to a load within one iteration,
    //   not across the loop's back edge when the force reads q through a
    //   pointer.
    // - a large state runs pairs (kick, drift), one pass over memory each
    //   (kick_and_drift).
    template <bool Compensated, bool KickFirst>
    [[gnu::always_inline]] inline void repeat_body(State& x, vector& f, vector& v, std::size_t steps) {
        const std::size_t m = body_.size(), per_step = m / 2;
        constexpr bool kick_first_pairs = !small_fixed;
        // Chunks of steps whose pairs a size_t counts (each chunk is whole steps).
        const std::size_t most = std::numeric_limits<std::size_t>::max() / per_step;
        if (KickFirst != kick_first_pairs && steps > 0) {
            for (std::size_t k = 0; k + 1 < m; ++k) rotated_[k] = body_[k + 1];
            rotated_[m - 1] = body_[0];
        }
        while (steps > 0) {
            const std::size_t chunk = std::min(steps, most), pairs = chunk * per_step;
            steps -= chunk;
            if constexpr (KickFirst == kick_first_pairs) {
                pair_loop<Compensated, kick_first_pairs>(x, f, v, body_.data(), m, pairs);
            } else {
                if constexpr (KickFirst) force(h_, x.q, f), kick<Compensated>(x, f, body_[0]);
                else drift<Compensated>(x, v, body_[0]);
                pair_loop<Compensated, kick_first_pairs>(x, f, v, rotated_.data(), m, pairs - 1);
                if constexpr (KickFirst) drift<Compensated>(x, v, body_[m - 1]);
                else force(h_, x.q, f), kick<Compensated>(x, f, body_[m - 1]);
            }
        }
    }

    // `pairs` pairs of sub-steps (h[j], h[j + 1]), j cycling through h[0..m):
    // (kick, drift) or (drift, kick), each with a fresh force or velocity.
    template <bool Compensated, bool KickFirst>
    [[gnu::always_inline]] inline void pair_loop(State& x, vector& f, vector& v, const scalar* h, std::size_t m,
                                                 std::size_t pairs) {
        for (std::size_t i = 0, j = 0; i < pairs; ++i, j = j + 2 == m ? 0 : j + 2) {
            if constexpr (KickFirst) {
                force(h_, x.q, f);
                kick_and_drift<Compensated>(x, f, v, h[j], h[j + 1]);
            } else {
                drift<Compensated>(x, v, h[j]);
                force(h_, x.q, f);
                kick<Compensated>(x, f, h[j + 1]);
            }
        }
    }

    // A force-gradient table, walked sub-step by sub-step (the force reused
    // while q has not moved). Each gradient kick costs a force and a force
    // derivative, so the walk's bookkeeping does not matter:
    //     p += h F + 2 g dt^3 J_F M^-1 F     (table.hpp; M^-1 F = velocity(F) for quadratic T),
    // the two terms added as two kicks.
    template <bool Compensated>
    void run_with_gradient(State& x, scalar dt, std::size_t n, bool resume) {
        if constexpr (differentiable_force<H, vector>) {
            const Eigen::Index dim = x.q.size();
            if (along_.size() != dim) along_.resize(dim), force_change_.resize(dim);
            bool fresh = resume && force_fresh_;
            const scalar dt3 = dt * dt * dt;
            std::uint64_t forces = 0, velocities = 0, derivatives = 0;
            for (std::size_t step = 0; step < n; ++step)
                for (const substep& o : gradient_ops_) {
                    const scalar h = static_cast<scalar>(o.weight) * dt;
                    if (o.kind == substep::drift) {
                        drift<Compensated>(x, velocity_, h);
                        ++velocities;
                        fresh = false;
                        continue;
                    }
                    if (!fresh) force(h_, x.q, force_), ++forces, fresh = true;
                    kick<Compensated>(x, force_, h);
                    if (o.gradient != 0) {
                        velocity(h_, force_, along_);
                        force_derivative(h_, x.q, along_, force_change_);
                        ++derivatives;
                        kick<Compensated>(x, force_change_, 2 * static_cast<scalar>(o.gradient) * dt3);
                    }
                }
            force_fresh_ = fresh;
            velocity_fresh_ = false;
            force_evaluations_ += forces;
            velocity_evaluations_ += velocities;
            force_derivative_evaluations_ += derivatives;
        }
    }

    // count alternating sub-steps of sizes h[0..count), the first a kick or a
    // drift, each with a fresh force or velocity.
    template <bool Compensated>
    [[gnu::always_inline]] inline void alternate(State& x, vector& f, vector& v, const scalar* h, std::size_t count,
                                                 bool starts_with_kick) {
        std::size_t i = 0;
        if (!starts_with_kick && count > 0) drift<Compensated>(x, v, h[i++]);
        for (; i + 1 < count; i += 2) {
            force(h_, x.q, f);
            kick_and_drift<Compensated>(x, f, v, h[i], h[i + 1]);
        }
        if (i < count) {
            force(h_, x.q, f);
            kick<Compensated>(x, f, h[i]);
        }
    }

    // p += h * force (Gould & Tobochnik eq. 3.74, the p half).
    template <bool Compensated>
    [[gnu::always_inline]] inline void kick(State& x, const vector& f, scalar h) {
        if constexpr (Compensated) {
            increment_ = h * f;
            add_compensated(x.p, p_error_);
        } else {
            x.p += h * f;
        }
    }

    // A kick and the drift after it. On a large state with velocity(p)
    // returning p itself (unit masses), in one pass over q, p and f instead of
    // two: memory-bound systems pay per pass. The same operations in the same
    // order as the two passes (tests/core/test_splitting_stepper.cpp compares them).
    template <bool Compensated>
    [[gnu::always_inline]] inline void kick_and_drift(State& x, const vector& f, vector& v, scalar hk, scalar hd) {
        if constexpr (!Compensated && reference_velocity && State::dimension == Eigen::Dynamic) {
            if (velocity_is_p_) {
                scalar* const q = x.q.data();
                scalar* const p = x.p.data();
                const scalar* const g = f.data();
                for (Eigen::Index i = 0, n = x.q.size(); i < n; ++i) {
                    p[i] += hk * g[i];
                    q[i] += hd * p[i];
                }
                return;
            }
        }
        kick<Compensated>(x, f, hk);
        drift<Compensated>(x, v, hd);
    }

    // velocity(p) returns a reference: to p itself (dT/dp = p) when run()
    // finds velocity_is_p_.
    static constexpr bool reference_velocity = requires(const H& h, const vector& p) {
        { h.velocity(p) } -> std::same_as<const vector&>;
    };

    // A small fixed-size state runs in locals the compiler keeps in registers
    // (run, repeat_body). Its updates are Eigen's packet operations: the
    // force may read q as packets (an Eigen expression) or as single numbers
    // (through q.data()), and a value stored as a packet forwards to both,
    // while single stores followed by a packet load stall the processor
    // (measured: a 2-D Eigen-expression force ran 1.2-1.6x the hand loop with
    // component-wise updates).
    static constexpr bool small_fixed = State::dimension != Eigen::Dynamic && State::dimension <= 16;

    // An analytic velocity that returns an expression (e.g. p / m) fuses into the drift.
    static constexpr bool fused_velocity = has_velocity_value<H, vector> && !has_velocity_into<H, vector>;

    // q += h * dT/dp(p) with dT/dp evaluated afresh (Gould & Tobochnik eq. 3.74, the q half).
    template <bool Compensated>
    [[gnu::always_inline]] inline void drift(State& x, vector& v, scalar h) {
        if constexpr (fused_velocity) {
            if constexpr (Compensated) {
                increment_.noalias() = h * h_.velocity(x.p);
                add_compensated(x.q, q_error_);
            } else {
                x.q.noalias() += h * h_.velocity(x.p);
            }
        } else {
            velocity(h_, x.p, v);
            drift_with<Compensated>(x, v, h);
        }
    }

    // q += h * v with v = dT/dp(p) already at hand.
    template <bool Compensated>
    [[gnu::always_inline]] inline void drift_with(State& x, const vector& v, scalar h) {
        if constexpr (Compensated) {
            increment_ = h * v;
            add_compensated(x.q, q_error_);
        } else {
            x.q += h * v;
        }
    }

    H h_;
    table table_;
    stepper_options options_;
    std::vector<scalar> weights_;      // the canonical sub-steps' weights, s0 first
    std::vector<scalar> body_, tail_, rotated_;  // sub-step sizes of the current run (see run, repeat_body)
    bool first_is_kick_ = true, last_is_kick_ = true, joined_ = false;
    bool velocity_is_p_ = false;
    std::size_t tail_kicks_ = 0, tail_drifts_ = 0;  // kinds among s1 .. s(L-1)
    vector force_, velocity_;
    vector q_error_, p_error_, increment_, sum_;  // compensated summation only
    bool force_fresh_ = false, velocity_fresh_ = false;
    std::uint64_t force_evaluations_ = 0, velocity_evaluations_ = 0, force_derivative_evaluations_ = 0;
    std::vector<substep> gradient_ops_;  // a force-gradient table's sub-steps (empty for other tables)
    vector along_, force_change_;        // M^-1 F and J_F M^-1 F (force-gradient tables only)
};

// Deduction helper: make_stepper<State>(h, method("leapfrog_kdk")).
template <class State, class H>
splitting_stepper<H, State> make_stepper(H h, table method, stepper_options options = {}) {
    return splitting_stepper<H, State>(std::move(h), std::move(method), options);
}

}  // namespace sympl
