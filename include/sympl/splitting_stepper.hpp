#pragma once
// One generic loop that runs any table (table.hpp) on any separable
// Hamiltonian and any phase_space state.
//
// Per sub-step: a kick p += c*dt*force(q) or a drift q += c*dt*velocity(p)
// (Gould & Tobochnik, eq. 3.74). A force is evaluated only when q has moved since the
// last one, so the last force of a step is reused by the next (leapfrog KDK
// costs one force per step), and likewise for velocities. The workspace is
// sized once; no step allocates.
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "error.hpp"
#include "hamiltonian.hpp"
#include "phase_space.hpp"
#include "table.hpp"

namespace sympl {

struct stepper_options {
    // Compensated (Kahan) summation of the q and p increments: the rounding
    // error of each update is carried into the next, so roundoff no longer
    // grows with the number of steps (Kahan 1965; Hairer, Lubich & Wanner,
    // GNI ch. VIII.5).
    bool compensated = false;
};

// What a run carries from one step to the next besides q and p: the last
// force and velocity (reused when q or p has not moved), the compensated
// summation's residuals, and the counters. Saved with the state after step k,
// it lets a run continue bit for bit, in this process or another (checkpoints).
template <class Vector>
struct stepper_memory {
    Vector force, velocity, q_error, p_error;  // residuals: empty unless compensated
    bool force_fresh = false, velocity_fresh = false;
    std::uint64_t force_evaluations = 0, velocity_evaluations = 0;
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
        for (const substep& s : table_.substeps())
            ops_.push_back({s.kind == substep::kick, static_cast<scalar>(s.weight), scalar(0)});
        if constexpr (State::dimension != Eigen::Dynamic) size_workspace(State::dimension);
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
    void reset_counters() { force_evaluations_ = velocity_evaluations_ = 0; }

    const H& hamiltonian() const { return h_; }
    const table& method() const { return table_; }
    const stepper_options& options() const { return options_; }

private:
    struct op {
        bool is_kick;
        scalar weight;
        scalar step;  // weight * dt of the current run
    };

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

    // The generic loop: n steps of the table. Flags and counters live in
    // registers during the run (a fresh force is needed only after q moved);
    // the sub-step sizes weight*dt are computed once per run, and the choice of
    // compensated summation once, outside the loop.
    void run(State& x, scalar dt, std::size_t n, bool resume) {
        for (std::size_t k = 0; k < ops_.size(); ++k) ops_[k].step = ops_[k].weight * dt;
        if constexpr (State::dimension != Eigen::Dynamic) {
            // Small fixed-size states run in locals the compiler keeps in
            // registers: no aliasing with the caller's state or the workspace.
            State y = x;
            vector f = force_;
            options_.compensated ? run_loop<true>(y, f, n, resume) : run_loop<false>(y, f, n, resume);
            x = y;
            force_ = f;
        } else {
            options_.compensated ? run_loop<true>(x, force_, n, resume) : run_loop<false>(x, force_, n, resume);
        }
    }

    template <bool Compensated>
    void run_loop(State& x, vector& f, std::size_t n, bool resume) {
        bool force_fresh = resume && force_fresh_, velocity_fresh = resume && velocity_fresh_;
        std::uint64_t forces = 0, velocities = 0;
        const op* const first = ops_.data();
        const op* const last = first + ops_.size();
        const auto apply = [&](const op& s, scalar h) {
            if (s.is_kick) {
                if (!force_fresh) {
                    force(h_, x.q, f);
                    ++forces;
                    force_fresh = true;
                }
                kick<Compensated>(x, f, h);
                velocity_fresh = false;
            } else {
                velocities += drift<Compensated>(x, h, velocity_fresh);
                force_fresh = false;
            }
        };
        // When a table ends with the kind of sub-step it starts with (leapfrog
        // KDK: a half kick at each end), the end of one step and the start of
        // the next are one sub-step of the summed size: one pass over the
        // state less per step, which is what memory-bound systems pay for.
        const bool join = n > 1 && last - first > 1 && first->is_kick == (last - 1)->is_kick;
        if (!join) {
            for (std::size_t i = 0; i < n; ++i)
                for (const op* s = first; s != last; ++s) apply(*s, s->step);
        } else {
            const scalar joined = (last - 1)->step + first->step;
            for (const op* s = first; s != last - 1; ++s) apply(*s, s->step);
            for (std::size_t i = 1; i < n; ++i) {
                apply(*first, joined);
                for (const op* s = first + 1; s != last - 1; ++s) apply(*s, s->step);
            }
            apply(*(last - 1), (last - 1)->step);
        }
        force_fresh_ = force_fresh;
        velocity_fresh_ = velocity_fresh;
        force_evaluations_ += forces;
        velocity_evaluations_ += velocities;
    }

    template <bool Compensated>
    void kick(State& x, const vector& f, scalar h) {
        if constexpr (Compensated) {
            increment_ = h * f;
            add_compensated(x.p, p_error_);
        } else {
            x.p += h * f;
        }
    }

    // Returns the number of velocity evaluations made (0 or 1).
    template <bool Compensated>
    int drift(State& x, scalar h, bool& velocity_fresh) {
        if constexpr (has_velocity_value<H, vector> && !has_velocity_into<H, vector>) {
            // An analytic velocity that returns an expression (e.g. p / m) fuses into the update.
            if constexpr (Compensated) {
                increment_.noalias() = h * h_.velocity(x.p);
                add_compensated(x.q, q_error_);
            } else {
                x.q.noalias() += h * h_.velocity(x.p);
            }
            return 1;
        }
        int evaluated = 0;
        if (!velocity_fresh) {
            velocity(h_, x.p, velocity_);
            velocity_fresh = true;
            evaluated = 1;
        }
        if constexpr (Compensated) {
            increment_ = h * velocity_;
            add_compensated(x.q, q_error_);
        } else {
            x.q += h * velocity_;
        }
        return evaluated;
    }

    H h_;
    table table_;
    stepper_options options_;
    std::vector<op> ops_;
    vector force_, velocity_;
    vector q_error_, p_error_, increment_, sum_;  // compensated summation only
    bool force_fresh_ = false, velocity_fresh_ = false;
    std::uint64_t force_evaluations_ = 0, velocity_evaluations_ = 0;
};

// Deduction helper: make_stepper<State>(h, method("leapfrog_kdk")).
template <class State, class H>
splitting_stepper<H, State> make_stepper(H h, table method, stepper_options options = {}) {
    return splitting_stepper<H, State>(std::move(h), std::move(method), options);
}

}  // namespace sympl
