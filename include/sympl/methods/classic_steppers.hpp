#pragma once
// The classic algorithms of Gould & Tobochnik (ch. 3) and Sandvik's lecture notes, on the same phase_space states as
// the splitting stepper, for comparison and teaching:
//   euler, euler_cromer, half_step (Gould & Tobochnik eq. 3.37), euler_richardson
//   (eqs. 3.43-3.44) = rk2 (the midpoint method of Sandvik's lecture notes), rk4
//   (Sandvik), velocity_verlet (eq. 3.48), leapfrog_two_step (eq. 3.47),
//   damped_leapfrog (Sandvik, plain and corrected), predictor_corrector
//   (Gould & Tobochnik eqs. 3.69-3.70).
// Each runs on equations_of_motion (equations_of_motion.hpp): Newton's
// x'' = a(x, v, t) with damping and driving, or any separable Hamiltonian
// (make_classic wraps it). Each algorithm is a rule (its step and workspace);
// one classic_stepper runs any rule, with step(x, t, dt) (dt < 0 runs
// backwards), and counts the evaluations of dp/dt (force_evaluations) and dq/dt.
//
// Multistep methods (half-step, two-step leapfrog, damped leapfrog,
// predictor-corrector) keep their history inside the stepper. It is used only
// when x is bitwise the state this stepper returned last and dt is unchanged;
// otherwise the method starts afresh with its self-starting step, so handing a
// stepper another state is always safe.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>

#include "../core/equations_of_motion.hpp"
#include "../core/error.hpp"
#include "../drivers/fixed_step.hpp"
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

private:
    detail::counted_equations<System> eq_;
};

// Euler: both updates from the old state; first order, energy grows.
template <class State>
struct euler_rule {
    static constexpr const char* name = "euler";
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    template <class Equations>
    void advance(Equations& eq_, State& x, scalar t, scalar dt) {
        eq_.dq_dt(x.q, x.p, t, dq_);
        eq_.dp_dt(x.q, x.p, t, dp_);
        x.q += dt * dq_;
        x.p += dt * dp_;
    }

private:
    vector dq_, dp_;
};
template <class System, class State>
using euler = classic_stepper<System, State, euler_rule>;

// Euler-Cromer: the position moves with the new velocity (Gould & Tobochnik, eq. 3.74
// with M = 1); first order, energy bounded. Also catalog entry "euler_cromer".
template <class State>
struct euler_cromer_rule {
    static constexpr const char* name = "euler_cromer";
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    template <class Equations>
    void advance(Equations& eq_, State& x, scalar t, scalar dt) {
        eq_.dp_dt(x.q, x.p, t, rate_);
        x.p += dt * rate_;
        eq_.dq_dt(x.q, x.p, t + dt, rate_);
        x.q += dt * rate_;
    }

private:
    vector rate_;
};
template <class System, class State>
using euler_cromer = classic_stepper<System, State, euler_cromer_rule>;

// Euler-Richardson (Gould & Tobochnik, eqs. 3.43-3.44): the step to the midpoint by
// Euler, then the whole step with the midpoint rates. Identical to the
// second-order Runge-Kutta midpoint method (Sandvik's lecture notes; Gould & Tobochnik say so after eq. 3.44),
// hence the alias rk2 below.
//
// Error estimate (the "bonus" after eq. 3.44): x1 is one Euler step
// q + dt f0, x2 two Euler half steps q + dt (f0 + f_mid)/2, and 2 x2 - x1 is
// exactly the Euler-Richardson result. |x2 - x1| = dt |f_mid - f0| / 2 is
// Richardson's estimate of the local error of x2, and an upper bound for that
// of the Euler-Richardson step as dt -> 0. (In pair form x1 has no a dt^2/2
// term: eq. 3.38 with it exists only for dq/dt = p.)
template <class S>
struct local_error_estimate {
    S position{};  // max_i |x2 - x1|
    S momentum{};  // max_i |v2 - v1|
    S largest() const { return position > momentum ? position : momentum; }
};

template <class State>
struct euler_richardson_rule {
    static constexpr const char* name = "euler_richardson";
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    template <class Equations>
    void advance(Equations& eq_, State& x, scalar t, scalar dt) {
        eq_.dq_dt(x.q, x.p, t, f0_);
        eq_.dp_dt(x.q, x.p, t, g0_);
        q_mid_ = x.q + (dt / 2) * f0_;
        p_mid_ = x.p + (dt / 2) * g0_;
        eq_.dq_dt(q_mid_, p_mid_, t + dt / 2, f_mid_);
        eq_.dp_dt(q_mid_, p_mid_, t + dt / 2, g_mid_);
        using std::abs;
        estimate_.position = x.size() ? abs(dt) / 2 * (f_mid_ - f0_).cwiseAbs().maxCoeff() : scalar(0);
        estimate_.momentum = x.size() ? abs(dt) / 2 * (g_mid_ - g0_).cwiseAbs().maxCoeff() : scalar(0);
        x.q += dt * f_mid_;  // eq. 3.43
        x.p += dt * g_mid_;  // eq. 3.44
    }

    // The estimate of the last step.
    const local_error_estimate<scalar>& last_error_estimate() const { return estimate_; }

private:
    vector f0_, g0_, q_mid_, p_mid_, f_mid_, g_mid_;
    local_error_estimate<scalar> estimate_;
};
template <class System, class State>
using euler_richardson = classic_stepper<System, State, euler_richardson_rule>;

template <class System, class State>
using rk2 = euler_richardson<System, State>;

// Classic fourth-order Runge-Kutta for equations of motion (Sandvik's lecture notes, "RK
// formulas for equations of motion"; friction enters through dp/dt).
template <class State>
struct rk4_rule {
    static constexpr const char* name = "rk4";
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    template <class Equations>
    void advance(Equations& eq_, State& x, scalar t, scalar dt) {
        const scalar half = dt / 2;
        eq_.dq_dt(x.q, x.p, t, l_[0]);
        eq_.dp_dt(x.q, x.p, t, k_[0]);
        for (int i = 1; i < 4; ++i) {
            const scalar c = i < 3 ? half : dt;  // k2, k3 at the midpoint; k4 at the end
            q_ = x.q + c * l_[i - 1];
            p_ = x.p + c * k_[i - 1];
            eq_.dq_dt(q_, p_, t + c, l_[i]);
            eq_.dp_dt(q_, p_, t + c, k_[i]);
        }
        x.q += (dt / 6) * (l_[0] + 2 * l_[1] + 2 * l_[2] + l_[3]);
        x.p += (dt / 6) * (k_[0] + 2 * k_[1] + 2 * k_[2] + k_[3]);
    }

private:
    vector k_[4], l_[4], q_, p_;  // k: dp/dt, l: dq/dt (Sandvik's letters)
};
template <class System, class State>
using rk4 = classic_stepper<System, State, rk4_rule>;

// Velocity Verlet (Gould & Tobochnik, eq. 3.48): x_{n+1} = x_n + v_n dt + a_n dt^2/2,
// v_{n+1} = v_n + (a_n + a_{n+1}) dt/2, written in pair form as
// half kick - drift - half kick (the KDK leapfrog). One force per step when
// dp/dt does not depend on p (a_{n+1} is the next a_n). When it does,
// eq. 3.48b is implicit in v_{n+1}: a_{n+1} takes the Euler-predicted
// velocity v_n + a_n dt, whose O(dt^2) error keeps the method second order.
template <class State>
struct velocity_verlet_rule {
    static constexpr const char* name = "velocity_verlet";
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    template <class Equations>
    void advance(Equations& eq_, State& x, scalar t, scalar dt) {
        constexpr bool reuses_force = !force_depends_on_velocity<typename Equations::system_type>();
        if (!(reuses_force && history_.continues(x, dt))) eq_.dp_dt(x.q, x.p, t, a_);
        p_half_ = x.p + (dt / 2) * a_;
        eq_.dq_dt(x.q, p_half_, t + dt / 2, v_);
        x.q += dt * v_;  // eq. 3.48a
        if constexpr (reuses_force) {
            eq_.dp_dt(x.q, p_half_, t + dt, a_);
        } else {
            p_predicted_ = x.p + dt * a_;
            eq_.dp_dt(x.q, p_predicted_, t + dt, a_);
        }
        x.p = p_half_ + (dt / 2) * a_;  // eq. 3.48b
        if constexpr (reuses_force) history_.remember(x, dt);
    }

private:
    vector a_, p_half_, v_, p_predicted_;
    detail::step_history<State> history_;
};
template <class System, class State>
using velocity_verlet = classic_stepper<System, State, velocity_verlet_rule>;

// Half-step algorithm (Gould & Tobochnik, eq. 3.37): v_{n+1/2} = v_{n-1/2} + a_n dt,
// x_{n+1} = x_n + v_{n+1/2} dt, started with the Euler half step
// v_{1/2} = v_0 + a_0 dt/2 (eq. 3.37c). The velocity reported at t_{n+1} is
// v_{n+1/2} + a_{n+1} dt/2, where a_{n+1} is the force the next step needs
// anyway: one force per step. A velocity-dependent a_n is taken at v_{n-1/2},
// the plain treatment of Sandvik's lecture notes, which costs an order (see damped_leapfrog).
template <class State>
struct half_step_rule {
    static constexpr const char* name = "half_step";
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    template <class Equations>
    void advance(Equations& eq_, State& x, scalar t, scalar dt) {
        if (history_.continues(x, dt)) {
            p_half_ += dt * a_;  // eq. 3.37a, a_ = a(x_n, v_{n-1/2}, t_n) from the last step
        } else {
            eq_.dp_dt(x.q, x.p, t, a_);
            p_half_ = x.p + (dt / 2) * a_;  // eq. 3.37c
        }
        eq_.dq_dt(x.q, p_half_, t + dt / 2, v_);
        x.q += dt * v_;  // eq. 3.37b
        eq_.dp_dt(x.q, p_half_, t + dt, a_);
        x.p = p_half_ + (dt / 2) * a_;
        history_.remember(x, dt);
    }

    // v_{n+1/2} (p at the half step) of the last step.
    const vector& half_step_momentum() const { return p_half_; }

private:
    vector a_, p_half_, v_;
    detail::step_history<State> history_;
};
template <class System, class State>
using half_step = classic_stepper<System, State, half_step_rule>;

// Leapfrog in the two-step position form (Gould & Tobochnik, eq. 3.47a; Sandvik's lecture notes):
// x_{n+1} = 2 x_n - x_{n-1} + a_n dt^2. Self-starting: a fresh start takes
// x_{-1} from the backward Taylor step (eq. 3.45), which makes the first step
// eq. 3.48a. The velocity reported with x_{n+1} is eq. 3.50,
// (x_{n+1} - x_n)/dt + a_{n+1} dt/2 (a_{n+1} is the next step's a_n);
// central_difference_velocity() is eq. 3.47b, v_n = (x_{n+1} - x_{n-1})/(2 dt).
// A velocity-dependent a_n is taken at v_{n-1/2} = (x_n - x_{n-1})/dt, the
// plain treatment of Sandvik's lecture notes.
template <class State>
struct leapfrog_two_step_rule {
    static constexpr const char* name = "leapfrog_two_step";
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    template <class Equations>
        requires newtonian_form<typename Equations::system_type>
    void advance(Equations& eq_, State& x, scalar t, scalar dt) {
        if (!history_.continues(x, dt)) {
            eq_.dp_dt(x.q, x.p, t, a_);
            x_previous_ = x.q - dt * x.p + (dt * dt / 2) * a_;  // eq. 3.45
        }
        x_next_ = 2 * x.q - x_previous_ + (dt * dt) * a_;  // eq. 3.47a
        central_velocity_ = (x_next_ - x_previous_) / (2 * dt);  // eq. 3.47b at t_n
        central_time_ = t;
        x_previous_ = x.q;
        x.q = x_next_;
        v_half_ = (x.q - x_previous_) / dt;
        eq_.dp_dt(x.q, v_half_, t + dt, a_);
        x.p = v_half_ + (dt / 2) * a_;  // eq. 3.50
        history_.remember(x, dt);
    }

    // v_n by eq. 3.47b, one step behind the state, and its time t_n.
    const vector& central_difference_velocity() const { return central_velocity_; }
    scalar central_difference_time() const { return central_time_; }

private:
    vector a_, x_previous_, x_next_, v_half_, central_velocity_;
    scalar central_time_{};
    detail::step_history<State> history_;
};
template <class System, class State>
using leapfrog_two_step = classic_stepper<System, State, leapfrog_two_step_rule>;

// Leapfrog with a velocity-dependent force m a = F(x, t) - G(v) (Sandvik's lecture notes,
// "Leapfrog/Verlet method including damping"), in the half-step form
// v_{n+1/2} = v_{n-1/2} + a_n dt, x_{n+1} = x_n + v_{n+1/2} dt.
//   plain:     a_n = [F(x_n, t_n) - G(v_{n-1/2})]/m; the O(dt) error of that
//              velocity makes x's step error O(dt^3): first order globally.
//   corrected: v^_{n+1/2} = v_{n-1/2} + dt [F_n - G(v_{n-1/2})]/m,
//              x^_{n+1} = x_n + dt v^_{n+1/2}, v_n = (x^_{n+1} - x_{n-1})/(2 dt),
//              a_n = [F_n - G(v_n)]/m: second order restored, one F and two G per step.
// Started from (x_0, v_0) with a_0 at the known v_0 and v_{1/2} by eq. 3.37c.
// The velocity reported at t_{n+1} is v_{n+1/2} + dt [F_{n+1} - G(v_{n+1/2})]/(2m),
// both forces being the next step's.
enum class damping_treatment { plain, corrected };

template <class State>
struct damped_leapfrog_rule {
    static constexpr const char* name = "damped_leapfrog";
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    explicit damped_leapfrog_rule(damping_treatment treatment = damping_treatment::corrected) : treatment_(treatment) {}

    template <class Equations>
        requires damped_newtonian_form<typename Equations::system_type, State>
    void advance(Equations& eq_, State& x, scalar t, scalar dt) {
        const auto& s = eq_.system;
        const scalar inv_m = scalar(1) / scalar(s.mass);
        if (!history_.continues(x, dt)) {
            s.force(x.q, t, force_);
            ++eq_.forces;
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
        ++eq_.forces;
        s.drag(v_half_, drag_);
        x.p = v_half_ + (dt / 2 * inv_m) * (force_ - drag_);
        history_.remember(x, dt);
    }

    damping_treatment treatment() const { return treatment_; }

private:
    damping_treatment treatment_;
    vector force_, drag_, v_half_, v_hat_, x_hat_, v_n_, x_previous_;
    detail::step_history<State> history_;
};
template <class System, class State>
using damped_leapfrog = classic_stepper<System, State, damped_leapfrog_rule>;

// Predictor-corrector (Gould & Tobochnik, eqs. 3.69-3.70): predict x_p = x_{n-1} + 2 v_n dt
// (and likewise v_p = v_{n-1} + 2 a_n dt, for velocity-dependent forces), then
// correct v_{n+1} = v_n + (a_p + a_n) dt/2, x_{n+1} = x_n + (v_{n+1} + v_n) dt/2,
// and repeat with the corrected values until two successive positions and
// velocities differ by less than tolerance * (1 + max|x|). Converged, this is
// the trapezoidal rule: second order, symmetric. A fresh start takes x_{-1}
// from one backward Euler step; only the number of iterations depends on it.
struct predictor_corrector_options {
    double tolerance = 1e-12;
    int max_iterations = 50;
};

template <class State>
struct predictor_corrector_rule {
    static constexpr const char* name = "predictor_corrector";
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    explicit predictor_corrector_rule(predictor_corrector_options options = {}) : options_(options) {
        if (!(options.tolerance > 0) || !std::isfinite(options.tolerance))
            throw invalid_argument("predictor_corrector: tolerance = " + detail::number(options.tolerance) +
                                   "; expected a finite tolerance > 0");
        if (options.max_iterations < 1)
            throw invalid_argument("predictor_corrector: max_iterations = " + std::to_string(options.max_iterations) +
                                   "; expected >= 1");
    }

    template <class Equations>
    void advance(Equations& eq_, State& x, scalar t, scalar dt) {
        eq_.dq_dt(x.q, x.p, t, f_n_);
        eq_.dp_dt(x.q, x.p, t, g_n_);
        if (!history_.continues(x, dt)) {
            q_previous_ = x.q - dt * f_n_;
            p_previous_ = x.p - dt * g_n_;
        }
        q_ = q_previous_ + (2 * dt) * f_n_;  // eq. 3.69
        p_ = p_previous_ + (2 * dt) * g_n_;
        using std::abs;
        scalar change = 0;
        for (iterations_ = 1; iterations_ <= options_.max_iterations; ++iterations_) {
            eq_.dp_dt(q_, p_, t + dt, g_);
            p_corrected_ = x.p + (dt / 2) * (g_n_ + g_);  // eq. 3.70a
            eq_.dq_dt(q_, p_corrected_, t + dt, f_);
            q_corrected_ = x.q + (dt / 2) * (f_n_ + f_);  // eq. 3.70b
            change = x.size() ? std::max((q_corrected_ - q_).cwiseAbs().maxCoeff(),
                                         (p_corrected_ - p_).cwiseAbs().maxCoeff())
                              : scalar(0);
            q_.swap(q_corrected_);
            p_.swap(p_corrected_);
            using std::isfinite;
            if (!isfinite(change)) break;  // blown up: the driver reports where
            const scalar scale = 1 + (x.size() ? q_.cwiseAbs().maxCoeff() : scalar(0));
            if (change <= scalar(options_.tolerance) * scale) break;
        }
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
    predictor_corrector_options options_;
    vector f_n_, g_n_, f_, g_, q_, p_, q_corrected_, p_corrected_, q_previous_, p_previous_;
    int iterations_ = 0;
    detail::step_history<State> history_;
};
template <class System, class State>
using predictor_corrector = classic_stepper<System, State, predictor_corrector_rule>;

// A classic stepper for a system or a separable Hamiltonian:
//   auto s = make_classic<rk4, phase_space<double, 1>>(hamiltonians::pendulum{});
template <template <class, class> class Method, class State, class System, class... Options>
auto make_classic(System system, Options&&... options) {
    auto equations = equations_of<State>(std::move(system));
    return Method<decltype(equations), State>(std::move(equations), std::forward<Options>(options)...);
}

}  // namespace sympl
