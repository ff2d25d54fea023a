#pragma once
// The implicit Gauss-Legendre collocation Runge-Kutta methods with s = 1 .. 6
// stages (orders 2s = 2 .. 12; s = 1 is the implicit midpoint rule):
// symplectic for any H(q, p), separable or not, and symmetric (Butcher 1964;
// Hairer, Lubich & Wanner, Geometric Numerical Integration, 2nd ed. 2006,
// sec. II.1.3, Thm. VI.4.3). One step solves the stage equations
//     Z_i = dt sum_j a_ij f(y0 + Z_j),   f(y) = (dH/dp, -dH/dq),
// as GNI sec. VIII.6 and its code GNI_IRK2 do: the starting values from the
// last step's collocation polynomial (gauss_tableau.hpp), fixed-point iteration
// while it contracts fast and simplified Newton with a frozen Jacobian where it
// pays (gauss_newton.hpp), iterated until the correction, scaled componentwise
// by atol + rtol |y|, is below 1 or stops decreasing (the rounding plateau);
// then y1 = y0 + sum_i d_i Z_i, d^T = b^T A^-1, Kahan-summed on request.
// One attempt at the stage equations: gauss_stage_iteration.hpp; here, which
// attempts a step makes and what is carried from step to step.
// The rules, their reasons and measurements: docs/nonseparable.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "../../core/carried_in_place.hpp"
#include "../../core/carried_state.hpp"
#include "../../core/dual.hpp"
#include "../../core/error.hpp"
#include "../../core/general_hamiltonian.hpp"
#include "../../core/hamiltonian.hpp"
#include "../../drivers/fixed_step.hpp"
#include "../../core/phase_space.hpp"
#include "gauss_options.hpp"
#include "gauss_stage_iteration.hpp"
#include "gauss_tableau.hpp"

namespace sympl {

template <class H, class State>
    requires phase_space_state<State> && gauss_collocation_system<H, typename State::vector>
class gauss_collocation_stepper : public detail::gauss_stage_iteration<H, State> {
    using base = detail::gauss_stage_iteration<H, State>;
    using typename base::column, typename base::outcome, typename base::real;
    using base::h_, base::tableau_, base::options_, base::rtol_, base::a_, base::newton_, base::z_, base::compensation_;
    using base::start_euler, base::prepare_newton, base::iterate, base::update;
    using base::dH_dq_evaluations_, base::dH_dp_evaluations_, base::iterations_;

public:
    using typename base::scalar, typename base::state_type, typename base::system_type, typename base::vector;

    gauss_collocation_stepper(H hamiltonian, int stages, gauss_options options = {})
        : base(std::move(hamiltonian), stages, options) {
        newton_mode_ = options_.iteration == gauss_iteration::newton;
    }

    // One step of size dt (dt < 0 runs backwards). On integration_error x is unchanged.
    void step(State& x, scalar dt) { advance(x, std::numeric_limits<double>::quiet_NaN(), dt); }
    // The same with the time of the step's start, which only the error reports:
    // fixed_step.hpp's driver calls this one and adds the step's index.
    void step(State& x, scalar t, scalar dt) { advance(x, double(primal(t)), dt); }
    // Forget the last step's stages: the next step starts from Euler's polynomial.
    void reset() { have_stages_ = false; }

    int stages() const { return tableau_.stages; }
    int order() const { return tableau_.order; }
    const gauss_tableau& tableau() const { return tableau_; }
    double tolerance() const { return rtol_; }
    int max_iterations() const { return options_.max_iterations; }
    std::uint64_t force_evaluations() const { return dH_dq_evaluations_; }     // dH/dq
    std::uint64_t velocity_evaluations() const { return dH_dp_evaluations_; }  // dH/dp
    std::uint64_t jacobian_evaluations() const { return newton_.jacobian_evaluations(); }
    std::uint64_t factorizations() const { return newton_.factorizations(); }
    std::uint64_t iterations() const { return iterations_; }  // all attempts of all steps
    void reset_counters() {
        dH_dq_evaluations_ = dH_dp_evaluations_ = iterations_ = 0;
        newton_.reset_counters();
    }
    const system_type& system() const { return h_; }
    // Whether the next step iterates by simplified Newton (automatic: once fixed point contracted slowly).
    bool iterating_by_newton() const { return newton_mode_; }
    // Iterations of the last step's last attempt, and its relative correction
    // max_k |dZ_k| / (atol_k / rtol + |y_k|) (at most tolerance() unless stopped at the plateau).
    int last_iterations() const { return last_iterations_; }
    double last_residual() const { return last_residual_; }

    // What the next step reads beyond the state: the last step's stage values
    // and the state they end at, its step size, the iteration's mode, the
    // frozen Newton Jacobian and the update's compensation. A stepper of the
    // same H, stages and options given restore_carried(carried()) and handed
    // that state goes on bit for bit (a checkpoint); the counters are not carried.
    // Restored in place (carried_in_place.hpp): the stepper holds the caller's
    // H and Newton factors s^2 times the size of the Jacobian carried.
    std::vector<scalar> carried() const
        requires std::is_floating_point_v<scalar>
    {
        return detail::carried_list<scalar>(*this);
    }
    void restore_carried(std::span<const scalar> values)
        requires std::is_floating_point_v<scalar>
    {
        detail::restore_carried_in_place<scalar>(*this, values, "gauss_collocation_stepper");
    }
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.flag(self.have_stages_);
        l.flag(self.newton_mode_);
        l.number(self.h_prev_);
        l.numbers(self.last_q_);
        l.numbers(self.last_p_);
        auto z = detail::carried_elements(self.z_);
        l.numbers(z);
        l.numbers(self.compensation_);
        const Eigen::Index n = self.last_q_.size();
        const int s = self.tableau_.stages;
        l.check(self.last_p_.size() == n && z.size() == 2 * n * s && self.compensation_.size() == 2 * n,
                "holds stage values of another size than its state's");
        if constexpr (!std::is_const_v<Self>) {
            self.size_scratch(n);  // the Newton part is read at this size
            z.shape(2 * n, s);
        }
        l.part(self.newton_);
        if constexpr (!std::is_const_v<Self>)
            l.check(self.newton_.refactor(self.a_), "holds a Newton Jacobian whose matrix is singular");
    }

private:
    void size_workspace(Eigen::Index n) {
        base::size_workspace(n);
        last_q_.resize(n);
        last_p_.resize(n);
        have_stages_ = false;
    }

    void advance(State& x, double t, scalar dt) {
        using std::isfinite;
        const real h = primal(dt);
        if (!isfinite(h) || h == real(0))
            throw invalid_argument("gauss_collocation_stepper: dt = " + detail::number(dt) +
                                   "; expected a finite non-zero step size");
        check_state(h_, x, "gauss_collocation_stepper");
        if (x.size() != this->n_) size_workspace(x.size());
        const bool continued = have_stages_ && x.q == last_q_ && x.p == last_p_;
        if (!continued) compensation_.setZero();
        // First attempt: the last step's polynomial extrapolated (GNI sec. VIII.6.1)
        // where this step continues it, the current iteration.
        const bool extrapolated = continued && std::fabs(double(h / h_prev_)) <= 4;
        const bool newton = newton_mode_;
        bool fresh_jacobian = false;
        if (extrapolated) this->start_extrapolated(h, h_prev_);
        else start_euler(x, dt);
        if (newton) fresh_jacobian = prepare_newton(x, h, dt, t, !newton_.has_jacobian());
        outcome o = iterate(x, dt, newton);
        // Second attempt, once: Euler's start and simplified Newton with the
        // Jacobian at y0 (fixed_point: fixed point from Euler's start).
        if (!o.converged && options_.iteration != gauss_iteration::fixed_point && !(newton && fresh_jacobian && !extrapolated)) {
            start_euler(x, dt);
            prepare_newton(x, h, dt, t, true);
            o = iterate(x, dt, true);
            if (o.converged && options_.iteration == gauss_iteration::automatic) newton_mode_ = true;
        } else if (!o.converged && options_.iteration == gauss_iteration::fixed_point && extrapolated) {
            start_euler(x, dt);
            o = iterate(x, dt, false);
        }
        // Last attempt, where a Jacobian at y0 is too far from the stages (a
        // step across a close encounter): Newton with the Jacobian refreshed at
        // the stages' mean every iteration (for s = 1 Newton's method itself).
        if (!o.converged && options_.iteration != gauss_iteration::fixed_point) {
            start_euler(x, dt);
            o = iterate(x, dt, true, h, t);
            newton_.mark_stale();
        }
        last_iterations_ = o.iterations;
        last_residual_ = double(o.correction);
        if (!o.converged) fail(o, dt, t);
        if (options_.iteration == gauss_iteration::automatic && !newton_mode_ &&
            o.contraction > real(gauss_newton_switch))
            newton_mode_ = true;
        if (newton_mode_ && o.contraction > real(gauss_jacobian_refresh)) newton_.mark_stale();
        update(x);
        last_q_ = x.q;
        last_p_ = x.p;
        have_stages_ = true;
        h_prev_ = h;
    }

    [[noreturn]] void fail(const outcome& o, const scalar& dt, double t) const {
        using std::isfinite;
        const int s = tableau_.stages;
        throw integration_error(
            "gauss_collocation_stepper: the stage equations of the " + std::to_string(s) +
                "-stage Gauss-Legendre method did not converge " +
                (std::isnan(t) ? std::string() : "from t = " + detail::number_text(t) + " ") + "at dt = " +
                detail::number(dt) + ": relative correction " + detail::number_text(o.correction) +
                (isfinite(o.correction) ? "" : " (the iteration diverged)") + " after " +
                std::to_string(o.iterations) + " iteration" + (o.iterations == 1 ? "" : "s") +
                (options_.iteration == gauss_iteration::fixed_point ? " of fixed point" : " of simplified Newton") +
                "; expected at most the tolerance " + detail::number_text(rtol_) + " within max_iterations = " +
                std::to_string(options_.max_iterations) + " (reduce dt, or raise max_iterations or the tolerance)",
            0, t);
    }

    real h_prev_ = 0;
    vector last_q_, last_p_;
    bool have_stages_ = false, newton_mode_ = false;
    int last_iterations_ = 0;
    double last_residual_ = 0;
};

// Deduction helper: make_gauss_collocation<State>(h, 3) is the 6th-order method.
template <class State, class H>
gauss_collocation_stepper<H, State> make_gauss_collocation(H h, int stages, gauss_options options = {}) {
    return gauss_collocation_stepper<H, State>(std::move(h), stages, options);
}

}  // namespace sympl
