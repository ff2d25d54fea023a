#pragma once
// The embedded Runge-Kutta-Nystrom pair stepper, for q'' = F(q): dq/dt =
// M^-1 p, dp/dt = F(q), any pair P of rkn_tables.hpp. Not symplectic: for
// short, very accurate runs (an orbit to 1e-12 over a few periods), not for
// long ones, where the splitting methods keep the energy bounded and these do not.
//
// An s-stage RKN pair (Hairer, Norsett & Wanner, Solving ODE I, sect. II.14,
// eq. 14.8) with forces k_i = F(Q_i) and accelerations u_i = M^-1 k_i:
//     Q_i     = q + c_i h v + h^2 sum_j a_ij u_j          (v = M^-1 p)
//     q_new   = q + h v + h^2 sum_i b_i u_i,   p_new = p + h sum_i bp_i k_i,
// and the embedded pair (b_hat, bp_hat) of lower order gives the error
// estimate (Hairer, Norsett & Wanner I, eq. II.4.11); the step goes on with
// the higher order (local extrapolation). Step-size control is the one
// controlled driver's (drivers/controlled.hpp). Because the positions are built
// from accelerations, velocity(p) must be linear in p (T quadratic): checked
// once per dimension (core/linear_velocity.hpp).
//
// FSAL (first same as last): the last stage is evaluated at c = 1 with the
// weights b, so its force is F(q_new) and the next step's first force is
// reused: s - 1 forces per step. The stepper keeps the last force with the q
// it belongs to and reuses it whenever it is handed that q again (the next
// step, or a retry after a rejected step), so handing it any state is safe.
//
// Inside the last accepted step, interpolate(theta, out) gives the state at
// t + theta dt: by the pair's continuous extension where one is published
// (dprkn6: Dormand & Prince 1987), otherwise by a step of theta dt of the pair
// itself from the step's start (dprkn8, dprkn12), exact to the pair's accuracy
// at s - 1 forces per value (docs/dense-output.md).
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../core/carried_in_place.hpp"
#include "../core/carried_state.hpp"
#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "../core/linear_velocity.hpp"
#include "../core/phase_space.hpp"
#include "../core/quadratic_kinetic.hpp"
#include "../drivers/controlled.hpp"
#include "rkn_tables.hpp"

namespace sympl {

namespace detail {

// The root-mean-square norm of the error estimate (eq, ep) over q and p, each
// component in units of atol + rtol max(|x|, |y|) (Hairer, Norsett & Wanner I,
// eq. II.4.11), for a step from x to y.
template <class State, class Vector>
double scaled_error_norm(const State& x, const State& y, const Vector& eq, const Vector& ep, const control_options& o) {
    using scalar = typename State::scalar;
    using std::abs;
    using std::max;
    using std::sqrt;
    const Eigen::Index n = x.size();
    if (n == 0) return 0;
    const scalar atol(o.absolute_tolerance), rtol(o.relative_tolerance);
    scalar sum(0);
    for (Eigen::Index i = 0; i < n; ++i) {
        const scalar sq = atol + rtol * max(abs(x.q[i]), abs(y.q[i]));
        const scalar sp = atol + rtol * max(abs(x.p[i]), abs(y.p[i]));
        sum += (eq[i] / sq) * (eq[i] / sq) + (ep[i] / sp) * (ep[i] / sp);
    }
    return static_cast<double>(primal(sqrt(sum / scalar(2 * n))));
}

// A pair's continuous extension as weights of the powers theta^0..4 for q and
// for p. p's are those of q's derivative, (k + 2) b_dense[i][k]
// (rkn_tables.hpp), formed in long double: in double, the published values to
// the last bit. Zero for a pair without one.
template <class P, class scalar>
struct rkn_dense_weights {
    std::array<std::array<scalar, 5>, P::stages> b{}, bp{};
    rkn_dense_weights() {
        using wide = std::conditional_t<std::is_floating_point_v<scalar>, long double, scalar>;
        if constexpr (rkn_dense_table<P>)
            for (int i = 0; i < P::stages; ++i)
                for (int k = 0; k < 5; ++k) {
                    b[i][k] = coefficient_as<scalar>(P::b_dense[i][k]);
                    bp[i][k] = scalar(wide(k + 2) * coefficient_as<wide>(P::b_dense[i][k]));
                }
    }
};

// A force already evaluated, with the q it belongs to (k the force, u the
// acceleration M^-1 k): the start of the last attempt, and (FSAL) its end.
template <class vector>
struct known_force {
    vector q, k, u;
    bool valid = false;
    bool holds(const vector& x) const { return valid && q.size() == x.size() && q == x; }
    void keep(const vector& x, const vector& k_, const vector& u_) {
        q = x, k = k_, u = u_;
        valid = true;
    }
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.flag(self.valid);
        for (auto* v : {&self.q, &self.k, &self.u}) l.numbers(*v);
        l.check(self.k.size() == self.q.size() && self.u.size() == self.q.size(), "holds a force of another size");
    }
};

}  // namespace detail

// Any pair P on a separable Hamiltonian with linear velocity(p).
template <class H, class State, rkn_pair_table P>
    requires phase_space_state<State> && separable_hamiltonian<H, typename State::vector>
class rkn_pair_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    using pair_type = P;
    static constexpr int stages = P::stages;
    static constexpr int error_order = P::embedded_order + 1;  // the estimate is O(dt^error_order)

    explicit rkn_pair_stepper(H hamiltonian)
        : h_(std::move(hamiltonian)), who_(std::string("rkn_pair_stepper<") + P::name + ">") {}

    // One step of size dt (dt < 0 runs backwards), with no error control.
    void step(State& x, scalar dt) {
        check(x, dt, "step");
        advance_trial(x, dt, false);
        accept(x);
    }

    // The trial step from x by dt, x untouched: returns the error estimate
    // in units of the tolerance (the root-mean-square norm of Hairer, Norsett
    // & Wanner I, eq. II.4.11, over q and p). accept(x) then moves x to it.
    // The pairs are autonomous: t is not used.
    double attempt(const State& x, scalar /*t*/, scalar dt, const control_options& o) {
        check(x, dt, "attempt");
        advance_trial(x, dt, true);
        return detail::scaled_error_norm(x, trial_, error_q_, error_p_, o);
    }
    void accept(State& x) {
        if (!trial_ready_)
            throw invalid_argument(who_ + "::accept: no trial step to accept; expected attempt() before");
        std::swap(x, trial_);  // trial_ now holds the state before the step (for dense output)
        trial_ready_ = false;
        dense_valid_ = true;
    }

    // The pair's continuous extension inside the last accepted step, at
    // t + theta dt with 0 <= theta <= 1 (rkn_tables.hpp, dprkn6).
    State dense_output(scalar theta) const
        requires rkn_dense_table<P>
    {
        check_theta(theta, "dense_output");
        State y = trial_;
        const scalar th = theta * dt_;
        vector uq = vector::Zero(y.size()), kp = vector::Zero(y.size());
        for (int i = 0; i < stages; ++i) {
            scalar wq(0), wp(0), power(1);
            for (int k = 0; k < 5; ++k, power *= theta) {
                wq += dense_.b[i][k] * power;
                wp += dense_.bp[i][k] * power;
            }
            uq += wq * w_.u[i];
            kp += wp * w_.k[i];
        }
        y.q = trial_.q + th * w_.v0 + (th * th) * uq;
        y.p = trial_.p + th * kp;
        return y;
    }

    // The state at t + theta dt inside the last accepted step: dense_output
    // where the pair has one, otherwise a step of theta dt from the step's
    // start (its forces counted in interpolation_force_evaluations()).
    void interpolate(scalar theta, State& out) {
        if constexpr (rkn_dense_table<P>) {
            out = dense_output(theta);
        } else {
            check_theta(theta, "interpolate");
            out = trial_;
            if (theta == scalar(0)) return;
            partial_.k[0] = w_.k[0];  // the start's force and velocity, from the step itself
            partial_.u[0] = w_.u[0];
            partial_.v0 = w_.v0;
            run_stages(trial_, theta * dt_, partial_, out, false);
        }
    }

    std::uint64_t force_evaluations() const { return force_evaluations_; }
    std::uint64_t velocity_evaluations() const { return velocity_evaluations_; }
    std::uint64_t interpolation_force_evaluations() const { return interpolation_forces_; }
    void reset_counters() { force_evaluations_ = velocity_evaluations_ = interpolation_forces_ = 0; }
    bool first_same_as_last() const { return co_.fsal; }
    const H& hamiltonian() const { return h_; }

    // What the stepper carries between steps: the forces it already has (at
    // the start of the last attempt and, FSAL, at its end), reused when
    // handed that q. A stepper given restore_carried(carried()) goes on bit
    // for bit with the same evaluation counts (a checkpoint). Restored in
    // place (carried_in_place.hpp): the stepper holds the caller's H.
    std::vector<scalar> carried() const
        requires std::is_floating_point_v<scalar>
    {
        return detail::carried_list<scalar>(*this);
    }
    void restore_carried(std::span<const scalar> values)
        requires std::is_floating_point_v<scalar>
    {
        detail::restore_carried_in_place<scalar>(*this, values, who_.c_str());
        for (const auto& f : known_)
            if (f.valid) resize_workspace(f.q.size());  // not size_workspace: it would forget them
    }
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        const auto& k = self.known_;
        for (auto& f : self.known_) l.part(f);
        l.check(!(k[0].valid && k[1].valid) || k[0].q.size() == k[1].q.size(), "holds forces of different sizes");
    }

    void check(const State& x, scalar dt, const char* who) const {
        using std::isfinite;
        if (!isfinite(dt) || dt == scalar(0))
            throw invalid_argument(who_ + "::" + who + ": dt = " + detail::number(dt) +
                                   "; expected a finite non-zero step size");
        check_state(h_, x, who_.c_str());  // no string built per step
    }

private:
    // The stages' forces k and accelerations u, the start's velocity v0.
    struct workspace {
        std::array<vector, stages> k, u;
        vector v0, Q, sum;
        void resize(Eigen::Index n) {
            v0.resize(n), Q.resize(n), sum.resize(n);
            for (int i = 0; i < stages; ++i) k[i].resize(n), u[i].resize(n);
        }
    };

    void check_theta(scalar theta, const char* who) const {
        if (!dense_valid_)
            throw invalid_argument(who_ + "::" + who + ": no accepted step yet; expected a step before");
        using std::isfinite;
        if (!isfinite(theta) || theta < scalar(0) || theta > scalar(1))
            throw invalid_argument(who_ + "::" + who + ": theta = " + detail::number(theta) +
                                   "; expected 0 <= theta <= 1");
    }

    void size_workspace(Eigen::Index n) {
        if (resize_workspace(n)) known_[0].valid = known_[1].valid = false;
    }
    // Whether the workspace was of another size.
    bool resize_workspace(Eigen::Index n) {
        if (w_.v0.size() == n) return false;
        w_.resize(n), partial_.resize(n);
        error_q_.resize(n), error_p_.resize(n);
        trial_ = State(n);
        return true;
    }

    // own: an evaluation of the run's steps, else of an interpolation.
    void force_at(workspace& w, const vector& q, int i, bool own) {
        force(h_, q, w.k[i]);
        recognised_velocity(h_, kinetic_, w.k[i], w.u[i]);
        if (own) ++force_evaluations_, ++velocity_evaluations_;
        else ++interpolation_forces_;
    }

    // Stages 2..s of a step of dt from x (w.k[0], w.u[0], w.v0 are x's) and
    // the new state. The step of a small system is bound by latency, the
    // chain force -> acceleration -> next stage's position -> force: so the
    // terms already known are summed first (at the scale of the increment,
    // then added to q once) and only the newest one, times h^2 a_{i,i-1},
    // is added after its force is in (as many roundings at q's scale as
    // q + (c h v + h^2 sum) would take, two operations on the chain, not four).
    void run_stages(const State& x, scalar dt, workspace& w, State& out, bool own) {
        const scalar h2 = dt * dt;
        for (int i = 1; i < stages; ++i) {
            w.sum = (co_.c[i] * dt) * w.v0;
            for (int j = 0; j + 1 < i; ++j)
                if (co_.a[i][j] != scalar(0)) w.sum += (h2 * co_.a[i][j]) * w.u[j];
            w.Q = x.q + w.sum;
            if (co_.a[i][i - 1] != scalar(0)) w.Q += (h2 * co_.a[i][i - 1]) * w.u[i - 1];
            force_at(w, w.Q, i, own);
        }
        if (co_.fsal) {
            out.q = w.Q;  // stage s is q_new itself
        } else {
            w.sum = dt * w.v0;
            for (int i = 0; i < stages; ++i)
                if (co_.b[i] != scalar(0)) w.sum += (h2 * co_.b[i]) * w.u[i];
            out.q = x.q + w.sum;
        }
        w.sum.setZero();  // p_new: one rounding at p's scale, the last force's term added to the sum
        for (int i = 0; i < stages; ++i)
            if (co_.bp[i] != scalar(0)) w.sum += (dt * co_.bp[i]) * w.k[i];
        out.p = x.p + w.sum;
    }

    void advance_trial(const State& x, scalar dt, bool estimate) {
        const Eigen::Index n = x.size();
        size_workspace(n);
        recognised_velocity(h_, kinetic_, x.p, w_.v0);
        ++velocity_evaluations_;
        if (known_[0].holds(x.q)) {
            w_.k[0] = known_[0].k, w_.u[0] = known_[0].u;
        } else if (known_[1].holds(x.q)) {
            w_.k[0] = known_[1].k, w_.u[0] = known_[1].u;
        } else {
            force_at(w_, x.q, 0, true);
        }
        if (checked_dimension_ != n) {
            check_linear_velocity<vector>([&](const vector& p, vector& v) { velocity(h_, p, v); }, n, who_,
                                          "a Runge-Kutta-Nystrom method (use a splitting method for other kinetic "
                                          "energies)");
            checked_dimension_ = n;
        }
        run_stages(x, dt, w_, trial_, true);
        // The start's force is kept for a retry of this step (after a rejection).
        known_[0].keep(x.q, w_.k[0], w_.u[0]);
        if (estimate) {
            error_q_.setZero();
            error_p_.setZero();
            for (int i = 0; i < stages; ++i) {
                error_q_ += (co_.b[i] - co_.b_hat[i]) * w_.u[i];
                error_p_ += (co_.bp[i] - co_.bp_hat[i]) * w_.k[i];
            }
            error_q_ *= dt * dt;
            error_p_ *= dt;
        }
        if (co_.fsal)  // the next step starts from q_new, whose force is stage s's
            known_[1].keep(trial_.q, w_.k[stages - 1], w_.u[stages - 1]);
        else
            known_[1].valid = false;
        dt_ = dt;
        dense_valid_ = false;
        trial_ready_ = true;
    }

    H h_;
    quadratic_kinetic<vector> kinetic_;  // a generic T found quadratic: M^-1 p, not a gradient per stage
    std::string who_;
    rkn_coefficients<P, scalar> co_;
    detail::rkn_dense_weights<P, scalar> dense_;
    workspace w_, partial_;  // the step's stages; a partial step's (interpolate)
    std::array<detail::known_force<vector>, 2> known_;
    vector error_q_, error_p_;
    State trial_;
    scalar dt_{};
    Eigen::Index checked_dimension_ = -1;
    bool dense_valid_ = false, trial_ready_ = false;
    std::uint64_t force_evaluations_ = 0, velocity_evaluations_ = 0, interpolation_forces_ = 0;
};

template <rkn_pair_table P, class State, class H>
rkn_pair_stepper<H, State, P> make_rkn_stepper(H hamiltonian) {
    return rkn_pair_stepper<H, State, P>(std::move(hamiltonian));
}

}  // namespace sympl
