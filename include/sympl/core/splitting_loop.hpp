#pragma once
// The generic loop under splitting_stepper: n steps of a table (table.hpp) as
// one stream of alternating kicks p += c dt F(q) and drifts q += c dt dT/dp(p)
// (Gould & Tobochnik, eq. 3.74), each with a fresh force or velocity, a step's
// last sub-step joined with the next step's first when they are of one kind;
// force-gradient tables walked sub-step by sub-step. Compensated (Kahan 1965)
// summation on request. The loop's shape and why: docs/speed.md.
#include <algorithm>
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
#include "quadratic_kinetic.hpp"
#include "table.hpp"

namespace sympl {

struct stepper_options {
    // Compensated (Kahan) summation of the q and p increments: the rounding
    // error of each update is carried into the next, so roundoff no longer
    // grows with the number of steps (Kahan 1965; Hairer, Lubich & Wanner,
    // GNI ch. VIII.5).
    bool compensated = false;
};

namespace detail {

// The two updates of a splitting, p += h F (a kick) and q += h dT/dp (a drift), plain or with
// compensated summation, and a kick fused with the drift after it (Gould & Tobochnik eq. 3.74).
template <class H, class State>
struct substep_updates {
    using scalar = typename State::scalar;
    using vector = typename State::vector;

    explicit substep_updates(H hamiltonian) : h(std::move(hamiltonian)) {}

    // Kahan summation: y += increment with the carried rounding error e.
    void add_compensated(vector& y, vector& e) {
        increment -= e;
        sum = y + increment;
        e = (sum - y) - increment;
        y = sum;
    }

    // p += hs * force (Gould & Tobochnik eq. 3.74, the p half).
    template <bool Compensated>
    [[gnu::always_inline]] inline void kick(State& x, const vector& f, scalar hs) {
        if constexpr (Compensated) {
            increment = hs * f;
            add_compensated(x.p, p_error);
        } else {
            add_scaled(x.p, hs, f);
        }
    }

    // A kick and the drift after it; on a large state whose velocity(p) is p
    // itself, one pass over q, p and f instead of two, the same operations in
    // the same order.
    template <bool Compensated>
    [[gnu::always_inline]] inline void kick_and_drift(State& x, const vector& f, vector& v, scalar hk, scalar hd) {
        if constexpr (!Compensated && (reference_velocity || says_velocity_is_p) &&
                      State::dimension == Eigen::Dynamic) {
            if (velocity_is_p) {
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

    // q += hs * dT/dp(p) with dT/dp evaluated afresh (Gould & Tobochnik eq. 3.74, the q half).
    template <bool Compensated>
    [[gnu::always_inline]] inline void drift(State& x, vector& v, scalar hs) {
        if constexpr (fused_velocity) {
            if constexpr (Compensated) {
                increment.noalias() = hs * h.velocity(x.p);
                add_compensated(x.q, q_error);
            } else {
                add_scaled(x.q, hs, h.velocity(x.p));
            }
        } else {
            velocity_of(x.p, v);
            drift_with<Compensated>(x, v, hs);
        }
    }

    // q += hs * v with v = dT/dp(p) already at hand.
    template <bool Compensated>
    [[gnu::always_inline]] inline void drift_with(State& x, const vector& v, scalar hs) {
        if constexpr (Compensated) {
            increment = hs * v;
            add_compensated(x.q, q_error);
        } else {
            add_scaled(x.q, hs, v);
        }
    }

    // y += c x. On a small fixed-size state written out coefficient by
    // coefficient, the same operations as Eigen's packet loop, and always
    // inline: GCC leaves Eigen's own assignment out of line once a large unit
    // has spent its inlining budget, at up to 1.9x the cost of a step
    // (docs/layout.md, "Inlining").
    template <class X>
    [[gnu::always_inline]] static inline void add_scaled(vector& y, scalar c, const X& x) {
        if constexpr (small_fixed && std::is_floating_point_v<scalar>) {
            for (int i = 0; i < State::dimension; ++i) y[i] += c * x[i];
        } else {
            y += c * x;
        }
    }

    // velocity(p) returns a reference: to p itself (dT/dp = p) when run() finds velocity_is_p.
    static constexpr bool reference_velocity = requires(const H& hh, const vector& p) {
        { hh.velocity(p) } -> std::same_as<const vector&>;
    };
    // A system whose type cannot say it (one behind function pointers, such as
    // the program's generic path) may say at run time that dT/dp = p.
    static constexpr bool says_velocity_is_p = requires(const H& hh) {
        { hh.velocity_is_p() } -> std::same_as<bool>;
    };
    // A small fixed-size state runs in registers, updated by Eigen's packet operations (docs/speed.md).
    static constexpr bool small_fixed = State::dimension != Eigen::Dynamic && State::dimension <= 16;
    // An analytic velocity that returns an expression (e.g. p / m) fuses into the drift.
    static constexpr bool fused_velocity = has_velocity_value<H, vector> && !has_velocity_into<H, vector>;

    // dT/dp: a product by the inverse mass where T was recognised as quadratic
    // (quadratic_kinetic.hpp, once per dimension), else the Hamiltonian's own
    // velocity or a gradient of its generic T.
    [[gnu::always_inline]] inline void velocity_of(const vector& p, vector& v) {
        if constexpr (generic_kinetic) {
            if (kinetic.applies()) {
                kinetic.velocity(p, v);
                return;
            }
        }
        sympl::velocity(h, p, v);
    }
    static constexpr bool generic_kinetic = !has_analytic_velocity<H, vector> && std::is_floating_point_v<scalar>;

    H h;
    vector q_error, p_error, increment, sum;  // compensated summation only
    quadratic_kinetic<vector> kinetic;
    bool velocity_is_p = false;
};

// A user's force or velocity that returns a vector of another size would
// write past the state in the loop: tried once per new dimension, at the
// state about to be stepped, before any step (not counted as evaluations).
// On a mismatch `force` is emptied, so that the next call checks again.
template <class H, class State, class Vector>
void check_output_sizes(const H& h, const State& x, Vector& force, Vector& velocity) {
    const Eigen::Index n = x.q.size();
    sympl::force(h, x.q, force);
    sympl::velocity(h, x.p, velocity);
    for (auto [what, size] : {std::pair{"force", force.size()}, std::pair{"velocity", velocity.size()}})
        if (size != n) {
            const Eigen::Index got = size;
            force.resize(0);
            throw invalid_argument("splitting_stepper: the Hamiltonian's " + std::string(what) + " returned " +
                                   std::to_string(got) + " components for a state of dimension " + std::to_string(n) +
                                   "; expected equal dimensions");
        }
}

template <bool Compensated, class Loop, class State>
void walk_force_gradient(Loop& loop, State& x, typename State::scalar dt, std::size_t n, bool fresh);

// The table's sub-steps, the workspace, what the last run left (its last force
// and velocity, and whether they are those of the state it returned) and the
// evaluation counts. splitting_stepper decides what may be reused.
template <class H, class State>
struct splitting_loop : substep_updates<H, State> {
    using base = substep_updates<H, State>;
    using typename base::scalar;
    using typename base::vector;
    using base::h, base::q_error, base::p_error, base::increment, base::sum, base::velocity_is_p;
    using base::reference_velocity, base::says_velocity_is_p, base::small_fixed, base::fused_velocity;

    splitting_loop(H hamiltonian, table t, stepper_options o)
        : base(std::move(hamiltonian)), method(std::move(t)), options(o) {
        const auto ops = method.substeps();  // canonical: kinds alternate, no zero weights
        first_is_kick = ops.front().kind == substep::kick;
        last_is_kick = ops.back().kind == substep::kick;
        joined = ops.size() > 1 && ops.front().kind == ops.back().kind;
        for (const substep& s : ops) {
            weights.push_back(static_cast<scalar>(s.weight));
            (s.kind == substep::kick ? kicks : drifts) += 1;
        }
        sizes.resize(ops.size());
        body.resize(joined ? ops.size() - 1 : ops.size());
        rotated.resize(body.size());
        if (method.has_force_gradient()) {
            if constexpr (!differentiable_force<H, vector>)
                throw invalid_argument("splitting_stepper: table '" + method.name() +
                                       "' has force-gradient kicks, which need the force's derivative J_F u; "
                                       "expected a Hamiltonian with force_derivative(q, u, df) or a potential "
                                       "templated on its scalar (differentiated twice by dual numbers)");
            gradient_ops = ops;
        }
    }

    void size_workspace(Eigen::Index n) {
        for (vector* v : {&force, &velocity, &q_error, &p_error, &increment, &sum}) {
            // Unused residuals stay empty, or zero where fixed-size: memory() hands them to checkpoints.
            if (v != &force && v != &velocity && !options.compensated && vector::SizeAtCompileTime == Eigen::Dynamic)
                continue;
            v->resize(n);
            v->setZero();
        }
        force_fresh = velocity_fresh = p_before_valid = false;
    }

    // n steps. have_force: `force` is F(x.q), so a first kick takes it as it
    // is; have_velocity: likewise `velocity` for a first drift; join (with
    // have_force, where p_before_last_kick is valid and dt is p_before_dt): x
    // is the state the last run returned, whose last kick is joined with this
    // run's first as in steps(n). Small fixed-size states run in locals kept
    // in registers.
    [[gnu::always_inline]] inline void run(State& x, scalar dt, std::size_t n, bool have_force, bool have_velocity,
                                           bool join = false) {
        if (n == 0) {
            force_fresh = force_fresh && have_force;
            velocity_fresh = velocity_fresh && have_velocity;
            p_before_valid = p_before_valid && have_force;
            return;
        }
        p_before_valid = false;
        if (!gradient_ops.empty())
            return options.compensated ? walk_force_gradient<true>(*this, x, dt, n, have_force)
                                       : walk_force_gradient<false>(*this, x, dt, n, have_force);
        const std::size_t L = weights.size();
        if (n > 1) {
            for (std::size_t k = 0; k < L; ++k) sizes[k] = weights[k] * dt;
            for (std::size_t k = 1; k < L; ++k) body[k - 1] = sizes[k];
            body.back() = joined ? sizes[L - 1] + sizes[0] : sizes[0];
        }
        if constexpr (reference_velocity) velocity_is_p = &h.velocity(x.p) == &x.p;
        else if constexpr (says_velocity_is_p) velocity_is_p = h.velocity_is_p();
        const bool reuse_v = have_velocity && !fused_velocity;
        if constexpr (State::dimension != Eigen::Dynamic) {
            State y = x;
            vector f = force, v = velocity;
            options.compensated ? run_loop<true>(y, f, v, dt, n, have_force, reuse_v, false)
                                : run_loop<false>(y, f, v, dt, n, have_force, reuse_v, join);
            x = y;
            force = f;
            velocity = v;
        } else {
            options.compensated ? run_loop<true>(x, force, velocity, dt, n, have_force, reuse_v, false)
                                : run_loop<false>(x, force, velocity, dt, n, have_force, reuse_v, false);
        }
        // Counted, not tallied in the loop: the body and the ends hold fixed numbers of each kind.
        const std::size_t body_kicks = kicks - (joined && first_is_kick), body_drifts = drifts - (joined && !first_is_kick);
        forces_counted += (n - 1) * body_kicks + kicks - (first_is_kick && have_force);
        velocities_counted += (n - 1) * body_drifts + drifts - (!first_is_kick && reuse_v);
        force_fresh = last_is_kick;
        // A pass that drifted by p itself (kick_and_drift) left `velocity` as it was.
        const bool drifted_by_p = velocity_is_p && !options.compensated && State::dimension == Eigen::Dynamic;
        velocity_fresh = !last_is_kick && !fused_velocity && !drifted_by_p;
    }

    // One step of a small state handed back as the last run returned it, with
    // the same dt: what run(x, dt, 1, true, false, true) does, without its
    // general set-up, a large part of a call's cost on a 2-D state. Not forced
    // inline: forced, it crowded the force out of the caller's loop (both
    // measured in docs/speed.md, "Figures behind choices in the code").
    void joined_step(State& x, scalar dt) {
        const std::size_t L = weights.size();
        State y = x;
        vector f = force, v = velocity;
        y.p = p_before_last_kick;
        this->template kick<false>(y, f, weights[L - 1] * dt + weights[0] * dt);
        alternate<false>(y, f, v, weights.data() + 1, dt, L - 2, false, false, false);
        p_before_last_kick = y.p;
        sympl::force(h, y.q, f);
        this->template kick<false>(y, f, weights[L - 1] * dt);
        x = y;
        force = f;
        velocity = v;
        forces_counted += kicks - 1;
        velocities_counted += drifts;
        force_fresh = true;
        velocity_fresh = false;
    }

    // The stream s0, (body) n - 1 times, s1 .. s(L-1); one step is s0 .. s(L-1)
    // as one alternating run, so a kick and the drift after it share a pass.
    // A small state of a kick-first joined table keeps p before its last kick
    // (`apart`), so that the next call can start from it with the joined kick
    // (join): a loop of step() is then steps(n) bit for bit.
    template <bool Compensated>
    [[gnu::always_inline]] inline void run_loop(State& x, vector& f, vector& v, scalar dt, std::size_t n, bool have_f,
                                                bool have_v, bool join) {
        const std::size_t L = sizes.size();
        const std::size_t apart = small_fixed && !Compensated && joined && first_is_kick ? 1 : 0;
        std::size_t done = 0;  // sub-steps of the first step already run
        if (join) {
            x.p = p_before_last_kick;
            this->template kick<Compensated>(x, f, weights[L - 1] * dt + weights[0] * dt);
            done = 1;
        }
        if (n == 1) {
            alternate<Compensated>(x, f, v, weights.data() + done, dt, L - apart - done, first_is_kick == (done == 0),
                                   have_f && !done, have_v && !done);
        } else {
            if (!done) alternate<Compensated>(x, f, v, weights.data(), dt, 1, first_is_kick, have_f, have_v);
            if (first_is_kick) repeat_body<Compensated, false>(x, f, v, n - 1);
            else repeat_body<Compensated, true>(x, f, v, n - 1);
            alternate<Compensated>(x, f, v, weights.data() + 1, dt, L - 1 - apart, !first_is_kick, false, false);
        }
        if (apart) {
            p_before_last_kick = x.p;
            p_before_valid = true;
            p_before_dt = dt;
            sympl::force(h, x.q, f);
            this->template kick<Compensated>(x, f, weights[L - 1] * dt);
        }
    }

    // The body `steps` times over as one flat loop over pairs of sub-steps
    // (the body holds an even number), in the shape the state runs fastest
    // (docs/speed.md): (drift, kick) for a small fixed-size state, (kick,
    // drift) otherwise; a body of the other shape rotated by one sub-step.
    template <bool Compensated, bool KickFirst>
    [[gnu::always_inline]] inline void repeat_body(State& x, vector& f, vector& v, std::size_t steps) {
        const std::size_t m = body.size(), per_step = m / 2;
        constexpr bool kick_first_pairs = !small_fixed;
        // Chunks of steps whose pairs a size_t counts (each chunk is whole steps).
        const std::size_t most = std::numeric_limits<std::size_t>::max() / per_step;
        if (KickFirst != kick_first_pairs) {
            for (std::size_t k = 0; k + 1 < m; ++k) rotated[k] = body[k + 1];
            rotated[m - 1] = body[0];
        }
        while (steps > 0) {
            const std::size_t chunk = std::min(steps, most), pairs = chunk * per_step;
            steps -= chunk;
            if constexpr (KickFirst == kick_first_pairs) {
                pair_loop<Compensated, kick_first_pairs>(x, f, v, body.data(), m, pairs);
            } else {
                if constexpr (KickFirst) sympl::force(h, x.q, f), this->template kick<Compensated>(x, f, body[0]);
                else this->template drift<Compensated>(x, v, body[0]);
                pair_loop<Compensated, kick_first_pairs>(x, f, v, rotated.data(), m, pairs - 1);
                if constexpr (KickFirst) this->template drift<Compensated>(x, v, body[m - 1]);
                else sympl::force(h, x.q, f), this->template kick<Compensated>(x, f, body[m - 1]);
            }
        }
    }

    // `pairs` pairs (h[j], h[j + 1]), j cycling through h[0..m), each sub-step
    // with a fresh force or velocity.
    template <bool Compensated, bool KickFirst>
    [[gnu::always_inline]] inline void pair_loop(State& x, vector& f, vector& v, const scalar* hs, std::size_t m,
                                                 std::size_t pairs) {
        for (std::size_t i = 0, j = 0; i < pairs; ++i, j = j + 2 == m ? 0 : j + 2) {
            if constexpr (KickFirst) {
                sympl::force(h, x.q, f);
                this->template kick_and_drift<Compensated>(x, f, v, hs[j], hs[j + 1]);
            } else {
                this->template drift<Compensated>(x, v, hs[j]);
                sympl::force(h, x.q, f);
                this->template kick<Compensated>(x, f, hs[j + 1]);
            }
        }
    }

    // count alternating sub-steps of sizes w[0..count) dt, the first a kick or
    // a drift, with a fresh force or velocity except a first one already at hand.
    template <bool Compensated>
    [[gnu::always_inline]] inline void alternate(State& x, vector& f, vector& v, const scalar* w, scalar dt,
                                                 std::size_t count, bool starts_with_kick, bool have_f, bool have_v) {
        std::size_t i = 0;
        if (!starts_with_kick && count > 0) {
            have_v ? this->template drift_with<Compensated>(x, v, w[0] * dt) : this->template drift<Compensated>(x, v, w[0] * dt);
            ++i;
        }
        for (; i + 1 < count; i += 2, have_f = false) {
            if (!have_f) sympl::force(h, x.q, f);
            this->template kick_and_drift<Compensated>(x, f, v, w[i] * dt, w[i + 1] * dt);
        }
        if (i < count) {
            if (!have_f) sympl::force(h, x.q, f);
            this->template kick<Compensated>(x, f, w[i] * dt);
        }
    }

    table method;
    stepper_options options;
    std::vector<scalar> weights;             // the canonical sub-steps' weights, s0 first
    std::vector<scalar> sizes, body, rotated;  // sub-step sizes of the current run
    bool first_is_kick = true, last_is_kick = true, joined = false;
    std::size_t kicks = 0, drifts = 0;
    vector force, velocity;
    vector p_before_last_kick;    // small fixed-size states of kick-first joined tables (run_loop)
    bool p_before_valid = false;  // p_before_last_kick is that of the state the last run returned
    scalar p_before_dt{};         // and the step size of that run: only a run of the same dt joins
    bool force_fresh = false, velocity_fresh = false;  // force / velocity are those of the state the last run returned
    std::uint64_t forces_counted = 0, velocities_counted = 0, derivatives_counted = 0;
    std::vector<substep> gradient_ops;  // a force-gradient table's sub-steps (empty for other tables)
    vector along, force_change;         // M^-1 F and J_F M^-1 F (force-gradient tables only)
};

// A force-gradient table, walked sub-step by sub-step (the force reused
// while q has not moved): p += h F + 2 g dt^3 J_F M^-1 F (table.hpp), the two
// terms as two kicks, M^-1 F = velocity(F) for quadratic T.
template <bool Compensated, class Loop, class State>
void walk_force_gradient(Loop& loop, State& x, typename State::scalar dt, std::size_t n, bool fresh) {
    using scalar = typename State::scalar;
    if constexpr (differentiable_force<decltype(loop.h), typename State::vector>) {
        const Eigen::Index dim = x.q.size();
        if (loop.along.size() != dim) loop.along.resize(dim), loop.force_change.resize(dim);
        const scalar dt3 = dt * dt * dt;
        for (std::size_t step = 0; step < n; ++step)
            for (const substep& o : loop.gradient_ops) {
                const scalar hs = static_cast<scalar>(o.weight) * dt;
                if (o.kind == substep::drift) {
                    loop.template drift<Compensated>(x, loop.velocity, hs);
                    ++loop.velocities_counted;
                    fresh = false;
                    continue;
                }
                if (!fresh) sympl::force(loop.h, x.q, loop.force), ++loop.forces_counted, fresh = true;
                loop.template kick<Compensated>(x, loop.force, hs);
                if (o.gradient != 0) {
                    loop.velocity_of(loop.force, loop.along);
                    force_derivative(loop.h, x.q, loop.along, loop.force_change);
                    ++loop.derivatives_counted;
                    loop.template kick<Compensated>(x, loop.force_change, 2 * static_cast<scalar>(o.gradient) * dt3);
                }
            }
        loop.force_fresh = fresh;
        loop.velocity_fresh = false;
    }
}

}  // namespace detail
}  // namespace sympl
