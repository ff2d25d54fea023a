#pragma once
// The classic algorithms of Gould & Tobochnik, ch. 3 (eq. 3.xx below) and of
// Sandvik's lecture notes, on the same phase_space states as the splitting
// stepper, for comparison and teaching: euler, euler_cromer (eq. 3.74, M = 1),
// euler_richardson = rk2 (eqs. 3.43-3.44; Sandvik's midpoint method), rk4
// (Sandvik), velocity_verlet (eq. 3.48), half_step (eq. 3.37),
// leapfrog_two_step (eq. 3.47), damped_leapfrog (Sandvik, plain and
// corrected), predictor_corrector (eqs. 3.69-3.70).
// Each algorithm is a rule (its step, workspace and history) run by one
// classic_stepper (classic_stepper.hpp) over equations_of_motion: Newton's
// x'' = a(x, v, t) or a separable Hamiltonian through make_classic.
// Orders, energy factors and the derivations: docs/classic.md.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "../core/equations_of_motion.hpp"
#include "../core/error.hpp"
#include "../drivers/fixed_step.hpp"
#include "../core/phase_space.hpp"
#include "classic_stepper.hpp"

namespace sympl {

namespace detail {
// max_i |a_i - b_i|, 0 for empty vectors.
template <class Vec>
auto max_abs_difference(const Vec& a, const Vec& b) {
    return a.size() ? (a - b).cwiseAbs().maxCoeff() : typename Vec::Scalar(0);
}

// A Runge-Kutta stage: the rates (dq, dp) at x + c (dq0, dp0), time t + c.
template <class Eq, class State, class Vec, class T>
void rk_stage(Eq& eq, const State& x, T t, T c, const Vec& dq0, const Vec& dp0, Vec& q, Vec& p, Vec& dq, Vec& dp) {
    q = x.q + c * dq0;
    p = x.p + c * dp0;
    eq.rates(q, p, t + c, dq, dp);
}

// The drift and closing half kick of the Verlet forms (eqs. 3.48, 3.37b, 3.50):
// q += dt dq/dt(q, p_half) at mid-step, then a = dp/dt at the new q with
// velocity p_at, and p = p_half + a dt/2. `a` is the next step's a_n.
template <class Eq, class State, class Vec, class T>
void drift_and_half_kick(Eq& eq, State& x, const Vec& p_half, const Vec& p_at, T t, T dt, Vec& v, Vec& a) {
    eq.dq_dt(x.q, p_half, t + dt / 2, v);
    x.q += dt * v;
    eq.dp_dt(x.q, p_at, t + dt, a);
    x.p = p_half + (dt / 2) * a;
}

}  // namespace detail

// Euler: both updates from the old state; first order, energy grows.
template <class State>
struct euler_rule {
    static constexpr const char* name = "euler";
    using scalar = typename State::scalar;
    template <class Equations>
    void advance(Equations& eq, State& x, scalar t, scalar dt) {
        eq.rates(x.q, x.p, t, dq_, dp_);
        x.q += dt * dq_;
        x.p += dt * dp_;
    }

private:
    typename State::vector dq_, dp_;
};

// Euler-Cromer (Gould & Tobochnik, eq. 3.74 with M = 1): the position moves with
// the new velocity; first order, energy bounded. Also catalog entry "euler_cromer".
template <class State>
struct euler_cromer_rule {
    static constexpr const char* name = "euler_cromer";
    using scalar = typename State::scalar;
    template <class Equations>
    void advance(Equations& eq, State& x, scalar t, scalar dt) {
        eq.dp_dt(x.q, x.p, t, rate_);
        x.p += dt * rate_;
        eq.dq_dt(x.q, x.p, t + dt, rate_);
        x.q += dt * rate_;
    }

private:
    typename State::vector rate_;
};

// Richardson's estimate of the local error of two Euler half steps against one
// Euler step (the "bonus" after Gould & Tobochnik eq. 3.44; docs/classic.md).
template <class S>
struct local_error_estimate {
    S position{};  // max_i |x2 - x1|
    S momentum{};  // max_i |v2 - v1|
    S largest() const { return position > momentum ? position : momentum; }
};

// Euler-Richardson (Gould & Tobochnik, eqs. 3.43-3.44): an Euler step to the
// midpoint, then the whole step with the midpoint rates; the second-order
// Runge-Kutta midpoint method of Sandvik's lecture notes, hence rk2.
template <class State>
struct euler_richardson_rule {
    static constexpr const char* name = "euler_richardson";
    using scalar = typename State::scalar;
    template <class Equations>
    void advance(Equations& eq, State& x, scalar t, scalar dt) {
        eq.rates(x.q, x.p, t, f0_, g0_);
        detail::rk_stage(eq, x, t, dt / 2, f0_, g0_, q_mid_, p_mid_, f_mid_, g_mid_);
        using std::abs;
        estimate_.position = abs(dt) / 2 * detail::max_abs_difference(f_mid_, f0_);
        estimate_.momentum = abs(dt) / 2 * detail::max_abs_difference(g_mid_, g0_);
        x.q += dt * f_mid_;  // eq. 3.43
        x.p += dt * g_mid_;  // eq. 3.44
    }

    // The estimate of the last step.
    const local_error_estimate<scalar>& last_error_estimate() const { return estimate_; }

private:
    typename State::vector f0_, g0_, q_mid_, p_mid_, f_mid_, g_mid_;
    local_error_estimate<scalar> estimate_;
};

// Classic fourth-order Runge-Kutta for equations of motion (Sandvik's lecture
// notes, "RK formulas for equations of motion"; friction enters through dp/dt).
template <class State>
struct rk4_rule {
    static constexpr const char* name = "rk4";
    using scalar = typename State::scalar;
    template <class Equations>
    void advance(Equations& eq, State& x, scalar t, scalar dt) {
        eq.rates(x.q, x.p, t, l_[0], k_[0]);
        for (int i = 1; i < 4; ++i)  // k2, k3 at the midpoint; k4 at the end
            detail::rk_stage(eq, x, t, i < 3 ? dt / 2 : dt, l_[i - 1], k_[i - 1], q_, p_, l_[i], k_[i]);
        x.q += (dt / 6) * (l_[0] + 2 * l_[1] + 2 * l_[2] + l_[3]);
        x.p += (dt / 6) * (k_[0] + 2 * k_[1] + 2 * k_[2] + k_[3]);
    }

private:
    typename State::vector k_[4], l_[4], q_, p_;  // k: dp/dt, l: dq/dt (Sandvik's letters)
};

// Velocity Verlet (Gould & Tobochnik, eq. 3.48) as half kick - drift - half kick.
// One force per step when dp/dt does not depend on p; when it does, eq. 3.48b
// is implicit and a_{n+1} takes the Euler-predicted velocity v_n + a_n dt.
template <class State>
struct velocity_verlet_rule {
    static constexpr const char* name = "velocity_verlet";
    using scalar = typename State::scalar;
    template <class Equations>
    void advance(Equations& eq, State& x, scalar t, scalar dt) {
        constexpr bool reuses_force = !force_depends_on_velocity<typename Equations::system_type>();
        if (!(reuses_force && history_.continues(x, dt))) eq.dp_dt(x.q, x.p, t, a_);
        p_half_ = x.p + (dt / 2) * a_;
        if constexpr (!reuses_force) p_predicted_ = x.p + dt * a_;
        detail::drift_and_half_kick(eq, x, p_half_, reuses_force ? p_half_ : p_predicted_, t, dt, v_, a_);
        if constexpr (reuses_force) history_.remember(x, dt);
    }

    // What carries from one step to the next (classic_stepper::carried()).
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.part(self.history_);
        for (auto* v : {&self.a_, &self.p_half_, &self.v_, &self.p_predicted_}) l.numbers(*v);
    }

private:
    typename State::vector a_, p_half_, v_, p_predicted_;
    detail::step_history<State> history_;
};

// Half-step algorithm (Gould & Tobochnik, eq. 3.37): v_{n+1/2} = v_{n-1/2} + a_n dt,
// x_{n+1} = x_n + v_{n+1/2} dt, started by v_{1/2} = v_0 + a_0 dt/2 (eq. 3.37c);
// the velocity reported is v_{n+1/2} + a_{n+1} dt/2. A velocity-dependent a_n
// is taken at v_{n-1/2} (Sandvik's plain treatment; it costs an order).
template <class State>
struct half_step_rule {
    static constexpr const char* name = "half_step";
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    template <class Equations>
    void advance(Equations& eq, State& x, scalar t, scalar dt) {
        if (history_.continues(x, dt)) {
            p_half_ += dt * a_;  // eq. 3.37a, a_ = a(x_n, v_{n-1/2}, t_n) from the last step
        } else {
            eq.dp_dt(x.q, x.p, t, a_);
            p_half_ = x.p + (dt / 2) * a_;  // eq. 3.37c
        }
        detail::drift_and_half_kick(eq, x, p_half_, p_half_, t, dt, v_, a_);  // eq. 3.37b
        history_.remember(x, dt);
    }

    // v_{n+1/2} (p at the half step) of the last step.
    const vector& half_step_momentum() const { return p_half_; }

    // What carries from one step to the next (classic_stepper::carried()).
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.part(self.history_);
        for (auto* v : {&self.a_, &self.p_half_, &self.v_}) l.numbers(*v);
    }

private:
    vector a_, p_half_, v_;
    detail::step_history<State> history_;
};

// Leapfrog in the two-step position form (Gould & Tobochnik, eq. 3.47a; Sandvik's
// lecture notes): x_{n+1} = 2 x_n - x_{n-1} + a_n dt^2, started by the backward
// Taylor step (eq. 3.45). The velocity reported is eq. 3.50; eq. 3.47b's central
// difference, one step behind, is central_difference_velocity(). A
// velocity-dependent a_n is taken at v_{n-1/2} = (x_n - x_{n-1})/dt (Sandvik).
template <class State>
struct leapfrog_two_step_rule {
    static constexpr const char* name = "leapfrog_two_step";
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    template <class Equations>
        requires newtonian_form<typename Equations::system_type>
    void advance(Equations& eq, State& x, scalar t, scalar dt) {
        if (!history_.continues(x, dt)) {
            eq.dp_dt(x.q, x.p, t, a_);
            x_previous_ = x.q - dt * x.p + (dt * dt / 2) * a_;  // eq. 3.45
        }
        x_next_ = 2 * x.q - x_previous_ + (dt * dt) * a_;  // eq. 3.47a
        central_velocity_ = (x_next_ - x_previous_) / (2 * dt);  // eq. 3.47b at t_n
        central_time_ = t;
        x_previous_ = x.q;
        x.q = x_next_;
        v_half_ = (x.q - x_previous_) / dt;
        eq.dp_dt(x.q, v_half_, t + dt, a_);
        x.p = v_half_ + (dt / 2) * a_;  // eq. 3.50
        history_.remember(x, dt);
    }

    // v_n by eq. 3.47b, one step behind the state, and its time t_n.
    const vector& central_difference_velocity() const { return central_velocity_; }
    scalar central_difference_time() const { return central_time_; }

    // What carries from one step to the next (classic_stepper::carried()).
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.part(self.history_);
        for (auto* v : {&self.a_, &self.x_previous_, &self.x_next_, &self.v_half_, &self.central_velocity_})
            l.numbers(*v);
        l.number(self.central_time_);
    }

private:
    vector a_, x_previous_, x_next_, v_half_, central_velocity_;
    scalar central_time_{};
    detail::step_history<State> history_;
};

// Leapfrog with a velocity-dependent force m a = F(x, t) - G(v) (Sandvik's
// lecture notes, "Leapfrog/Verlet method including damping") in the half-step
// form: plain takes G at v_{n-1/2} (first order); corrected takes it at the
// central-difference v_n of a predicted x^_{n+1} (second order, one F and two
// G per step). Formulas: docs/classic.md.
enum class damping_treatment { plain, corrected };

template <class State>
struct damped_leapfrog_rule {
    static constexpr const char* name = "damped_leapfrog";
    using scalar = typename State::scalar;
    explicit damped_leapfrog_rule(damping_treatment treatment = damping_treatment::corrected) : treatment_(treatment) {}

    template <class Equations>
        requires damped_newtonian_form<typename Equations::system_type, State>
    void advance(Equations& eq, State& x, scalar t, scalar dt) {
        const auto& s = eq.system;
        const scalar inv_m = scalar(1) / scalar(s.mass);
        if (!history_.continues(x, dt)) {
            s.force(x.q, t, force_);
            ++eq.forces;
            s.drag(x.p, drag_);
            v_half_ = x.p + (dt / 2 * inv_m) * (force_ - drag_);  // eq. 3.37c
        } else {
            // force_ = F(x_n, t_n) and drag_ = G(v_{n-1/2}) come from the last step.
            if (treatment_ == damping_treatment::corrected) {
                v_hat_ = v_half_ + (dt * inv_m) * (force_ - drag_);
                x_hat_ = x.q + dt * v_hat_;
                v_n_ = (x_hat_ - x_previous_) / (2 * dt);
                s.drag(v_n_, drag_);
            }
            v_half_ += (dt * inv_m) * (force_ - drag_);
        }
        x_previous_ = x.q;
        x.q += dt * v_half_;
        s.force(x.q, t + dt, force_);
        ++eq.forces;
        s.drag(v_half_, drag_);
        x.p = v_half_ + (dt / 2 * inv_m) * (force_ - drag_);
        history_.remember(x, dt);
    }

    damping_treatment treatment() const { return treatment_; }

    // What carries from one step to the next (classic_stepper::carried()).
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.part(self.history_);
        for (auto* v : {&self.force_, &self.drag_, &self.v_half_, &self.v_hat_, &self.x_hat_, &self.v_n_,
                        &self.x_previous_})
            l.numbers(*v);
    }

private:
    damping_treatment treatment_;
    typename State::vector force_, drag_, v_half_, v_hat_, x_hat_, v_n_, x_previous_;
    detail::step_history<State> history_;
};

// Predictor-corrector (Gould & Tobochnik, eqs. 3.69-3.70): predict from x_{n-1}
// and the rates at x_n, correct by the trapezoidal rule, and repeat until two
// successive corrections differ by less than tolerance * (1 + max|x|).
// Converged, this is the trapezoidal rule: second order, symmetric. A fresh
// start takes x_{-1} from one backward Euler step.
struct predictor_corrector_options {
    double tolerance = 1e-12;
    int max_iterations = 50;
};

template <class State>
struct predictor_corrector_rule {
    static constexpr const char* name = "predictor_corrector";
    using scalar = typename State::scalar;
    explicit predictor_corrector_rule(predictor_corrector_options options = {}) : options_(options) {
        if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
            throw invalid_argument("predictor_corrector: tolerance = " + detail::number(options.tolerance) +
                                   "; expected a finite tolerance > 0");
        if (options.max_iterations < 1)
            throw invalid_argument("predictor_corrector: max_iterations = " + std::to_string(options.max_iterations) +
                                   "; expected >= 1");
    }

    template <class Equations>
    void advance(Equations& eq, State& x, scalar t, scalar dt) {
        eq.rates(x.q, x.p, t, f_n_, g_n_);
        if (!history_.continues(x, dt)) {
            q_previous_ = x.q - dt * f_n_;
            p_previous_ = x.p - dt * g_n_;
        }
        q_ = q_previous_ + (2 * dt) * f_n_;  // eq. 3.69
        p_ = p_previous_ + (2 * dt) * g_n_;
        const scalar change = correct(eq, x, t, dt);
        if (iterations_ > options_.max_iterations) {
            iterations_ = options_.max_iterations;
            throw integration_error("predictor_corrector: no convergence in " +
                                        std::to_string(options_.max_iterations) + " iterations at t = " +
                                        detail::number(t) + " with dt = " + detail::number(dt) +
                                        " (last change " + detail::number(change) + ", tolerance " +
                                        detail::number(options_.tolerance) +
                                        "); expected a smaller dt or more iterations; the state is left at t",
                                    0, static_cast<double>(primal(t)));
        }
        q_previous_ = x.q;
        p_previous_ = x.p;
        x.q = q_;
        x.p = p_;
        history_.remember(x, dt);
    }

    // Corrector iterations of the last step.
    int last_iterations() const { return iterations_; }
    const predictor_corrector_options& options() const { return options_; }

private:
    // Eq. 3.70 iterated on (q_, p_) until the change is below the tolerance;
    // iterations_ > max_iterations when it is not. Returns the last change.
    template <class Equations>
    scalar correct(Equations& eq, const State& x, scalar t, scalar dt) {
        scalar change = 0;
        for (iterations_ = 1; iterations_ <= options_.max_iterations; ++iterations_) {
            eq.dp_dt(q_, p_, t + dt, g_);
            p_corrected_ = x.p + (dt / 2) * (g_n_ + g_);  // eq. 3.70a
            eq.dq_dt(q_, p_corrected_, t + dt, f_);
            q_corrected_ = x.q + (dt / 2) * (f_n_ + f_);  // eq. 3.70b
            change = std::max(detail::max_abs_difference(q_corrected_, q_), detail::max_abs_difference(p_corrected_, p_));
            q_.swap(q_corrected_);
            p_.swap(p_corrected_);
            using std::isfinite;
            if (!isfinite(change)) break;  // blown up: the driver reports where
            const scalar scale = 1 + (x.size() ? q_.cwiseAbs().maxCoeff() : scalar(0));
            if (change <= scalar(options_.tolerance) * scale) break;
        }
        return change;
    }

    predictor_corrector_options options_;
    typename State::vector f_n_, g_n_, f_, g_, q_, p_, q_corrected_, p_corrected_, q_previous_, p_previous_;
    int iterations_ = 0;
    detail::step_history<State> history_;

public:
    // What carries from one step to the next (classic_stepper::carried()).
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.part(self.history_);
        for (auto* v : {&self.f_n_, &self.g_n_, &self.f_, &self.g_, &self.q_, &self.p_, &self.q_corrected_,
                        &self.p_corrected_, &self.q_previous_, &self.p_previous_})
            l.numbers(*v);
    }
};

// The steppers: one classic_stepper per rule.
template <class System, class State> using euler = classic_stepper<System, State, euler_rule>;
template <class System, class State> using euler_cromer = classic_stepper<System, State, euler_cromer_rule>;
template <class System, class State> using euler_richardson = classic_stepper<System, State, euler_richardson_rule>;
template <class System, class State> using rk2 = euler_richardson<System, State>;
template <class System, class State> using rk4 = classic_stepper<System, State, rk4_rule>;
template <class System, class State> using velocity_verlet = classic_stepper<System, State, velocity_verlet_rule>;
template <class System, class State> using half_step = classic_stepper<System, State, half_step_rule>;
template <class System, class State> using leapfrog_two_step = classic_stepper<System, State, leapfrog_two_step_rule>;
template <class System, class State> using damped_leapfrog = classic_stepper<System, State, damped_leapfrog_rule>;
template <class System, class State> using predictor_corrector = classic_stepper<System, State, predictor_corrector_rule>;

}  // namespace sympl
