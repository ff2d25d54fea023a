#pragma once
// Damped and driven systems run by any splitting table, with the table's order
// and an exact conformal symplectic structure:
//     dq/dt = dT/dp,   dp/dt = -dV/dq + f(t) - gamma p,   gamma >= 0.
// The vector field is split into two exactly solvable flows (McLachlan &
// Perlmutter 2001, "Conformal Hamiltonian systems", J. Geom. Phys. 39, 276;
// Bhatt, Floyd & Moore 2016, "Second order conformal symplectic schemes for
// damped Hamiltonian systems", J. Sci. Comput. 66, 1234):
//   - the damped drift, t advancing with it (time as a coordinate of extended
//     phase space, so that each kick sees the force at its sub-step's time):
//         q += (1 - e^{-gamma h}) / gamma * dT/dp(p),  p *= e^{-gamma h},  t += h,
//     exact when dT/dp is linear in p (T = p.M^-1.p / 2), which is checked;
//   - the kick, p += h (-dV/dq(q) + f(t)), exact since q and t stand still.
// Each is an exact flow, so a table keeps its order (the RKN tables theirs
// too) and the step contracts area by exactly e^{-gamma dt} per degree of
// freedom, as the true flow does: why, in docs/damped-driven.md.
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <tuple>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "../core/linear_velocity.hpp"
#include "../core/phase_space.hpp"
#include "../core/table.hpp"

namespace sympl {

// What the conformal stepper needs of a system: the damping rate gamma of
// dp/dt = ... - gamma p, the force on p at time t without the damping
// (-dV/dq + f(t)), and dq/dt = dT/dp, linear in p.
template <class S, class Vec>
concept conformal_system = requires(const S& s, const Vec& q, const Vec& p, scalar_of<Vec> t, Vec& out) {
    { s.damping_rate() } -> std::convertible_to<double>;
    s.driven_force(q, t, out);
    s.velocity(p, out);
};

// No driving force.
struct no_drive {};

// The driving force F0 cos(Omega t + phase) on every component. Its values at
// the kicks of a step follow from one cosine and one sine at the step's start
// by the angle-addition formulas, the sub-steps' angles worked out once per
// step size: a step pays two transcendental calls, not one per kick.
struct harmonic_drive {
    double amplitude = 0;  // F0
    double frequency = 0;  // Omega
    double phase = 0;
    template <class T> T operator()(T t) const {
        using std::cos;
        return T(amplitude) * cos(T(frequency) * t + T(phase));
    }
};

// A conformal system whose drive is harmonic: it gives the drive and the
// force without it, -dV/dq, and the stepper adds the drive itself.
template <class S, class Vec>
concept harmonically_driven = conformal_system<S, Vec> && requires(const S& s, const Vec& q, Vec& out) {
    { s.harmonic_drive_term() } -> std::convertible_to<harmonic_drive>;
    s.undriven_force(q, out);
};

// A separable Hamiltonian with damping gamma and a driving force f(t): a
// callable drive(t) returning one number (the same force on every component)
// or a vector of the state's size.
template <class H, class Drive = no_drive>
struct damped_driven {
    H hamiltonian;
    double damping = 0;  // gamma: dp/dt = -dV/dq + f(t) - gamma p
    Drive drive{};

    double damping_rate() const { return damping; }

    template <class Vec, class T>
    void driven_force(const Vec& q, T t, Vec& f) const {
        force(hamiltonian, q, f);
        if constexpr (!std::is_same_v<Drive, no_drive>) {
            using std::isfinite;
            const auto d = drive(t);
            if constexpr (std::is_convertible_v<decltype(d), scalar_of<Vec>>) {
                const scalar_of<Vec> g(d);
                if (!isfinite(g)) throw invalid_argument(bad_drive(t, g, -1));
                f.array() += g;
            } else {
                if (d.size() != f.size())
                    throw invalid_argument("damped_driven: the driving force has " + std::to_string(d.size()) +
                                           " components for a state of dimension " + std::to_string(f.size()) +
                                           "; expected equal dimensions");
                for (Eigen::Index i = 0; i < f.size(); ++i) {
                    if (!isfinite(d[i])) throw invalid_argument(bad_drive(t, d[i], i));
                    f[i] += d[i];
                }
            }
        }
    }
    template <class Vec>
    void velocity(const Vec& p, Vec& v) const {
        sympl::velocity(hamiltonian, p, v);
    }

    // A harmonic drive is added by the stepper (harmonically_driven).
    harmonic_drive harmonic_drive_term() const
        requires std::is_same_v<Drive, harmonic_drive>
    {
        return drive;
    }
    template <class Vec>
    void undriven_force(const Vec& q, Vec& f) const
        requires std::is_same_v<Drive, harmonic_drive>
    {
        force(hamiltonian, q, f);
    }

    // T(p) + V(q): not conserved unless gamma = 0 and there is no drive.
    template <class Sc, int D>
    Sc energy(const phase_space<Sc, D>& x) const {
        return Sc(hamiltonian.kinetic(x.p)) + Sc(hamiltonian.potential(x.q));
    }

private:
    template <class T, class V>
    static std::string bad_drive(T t, V value, Eigen::Index component) {
        return "damped_driven: the driving force at t = " + detail::number_text(static_cast<long double>(primal(t))) +
               " is " + detail::number_text(static_cast<long double>(primal(value))) +
               (component >= 0 ? " (component " + std::to_string(component) + ")" : std::string()) +
               "; expected a finite force";
    }
};

// sympl::damped_driven_by(h, 0.1, [](double t) { return 0.5 * std::cos(0.7 * t); })
template <class H, class Drive = no_drive>
damped_driven<H, Drive> damped_driven_by(H hamiltonian, double damping, Drive drive = {}) {
    return {std::move(hamiltonian), damping, std::move(drive)};
}

template <class System, class State>
    requires phase_space_state<State> && conformal_system<System, typename State::vector>
class conformal_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    using vector = typename State::vector;

    conformal_stepper(System system, table method) : system_(std::move(system)), table_(std::move(method)) {
        using std::isfinite;
        const double gamma = system_.damping_rate();
        if (!isfinite(gamma) || gamma < 0)
            throw invalid_argument("conformal_stepper: damping rate gamma = " + detail::number_text(gamma) +
                                   "; expected a finite gamma >= 0 (dp/dt = ... - gamma p)");
        if (table_.has_force_gradient())
            throw invalid_argument("conformal_stepper: table '" + table_.name() +
                                   "' has force-gradient kicks, whose commutator term assumes no damping; expected a "
                                   "plain kick-drift table");
        gamma_ = scalar(gamma);
        ops_ = table_.substeps();
        if constexpr (harmonic) {
            drive_ = system_.harmonic_drive_term();
            if (!isfinite(drive_.amplitude) || !isfinite(drive_.frequency) || !isfinite(drive_.phase))
                throw invalid_argument("conformal_stepper: harmonic drive F0 = " + detail::number_text(drive_.amplitude) +
                                       ", Omega = " + detail::number_text(drive_.frequency) + ", phase = " +
                                       detail::number_text(drive_.phase) + "; expected finite values");
        }
    }

    // One step from time t: a time-aware stepper (fixed_step.hpp's drivers pass t).
    void step(State& x, scalar t, scalar dt) {
        check(x, dt);
        if (!(dt == sized_for_)) size_substeps(dt);
        // A table that ends and starts with a kick evaluates the force at the
        // end of a step where the next step starts: reused when the next step
        // starts from the state and time this one left (bit for bit).
        const bool reuse = last_kick_kept_ && t == last_kick_t_ && x.q == last_kick_q_;
        if constexpr (State::dimension != Eigen::Dynamic) {
            // Small fixed-size states run in locals the compiler keeps in registers.
            vector q = x.q, p = x.p, f, v;
            walk(q, p, f, v, t, reuse);
            x.q = q;
            x.p = p;
        } else {
            walk(x.q, x.p, force_, velocity_, t, reuse);
        }
    }

    std::uint64_t force_evaluations() const { return force_evaluations_; }
    std::uint64_t velocity_evaluations() const { return velocity_evaluations_; }
    void reset_counters() { force_evaluations_ = velocity_evaluations_ = 0; }
    const System& system() const { return system_; }
    const table& method() const { return table_; }

private:
    // The step's sub-steps in order: a kick p += h (F(q) + f(t + tau_k)), a
    // damped drift q += span v(p), p *= decay.
    void walk(vector& q, vector& p, vector& f, vector& v, scalar t, bool reuse) {
        scalar drive_cos{}, drive_sin{};
        if constexpr (harmonic) std::tie(drive_cos, drive_sin) = harmonic_drive_at(t);
        const std::size_t last = ops_.size() - 1;
        for (std::size_t k = 0; k <= last; ++k) {
            const scalar h = size_[k];
            if (ops_[k].kind == substep::drift) {
                system_.velocity(p, v);
                ++velocity_evaluations_;
                q += span_[k] * v;
                p *= decay_[k];
                continue;
            }
            if (k == 0 && reuse) {
                p += h * last_kick_force_;
                continue;
            }
            if constexpr (harmonic) {
                // F0 cos(Omega (t + tau_k) + phase), tau_k the kick's time into the step; at the
                // step's end evaluated afresh (and kept for the next step's start), so that a
                // step's first kick has the same bits whether it was carried over or not.
                system_.undriven_force(q, f);
                if (k == last)
                    f.array() += harmonic_drive_at(t + offset_[k]).first;
                else
                    f.array() += drive_cos * kick_cos_[k] - drive_sin * kick_sin_[k];
            } else {
                system_.driven_force(q, t + offset_[k], f);
            }
            ++force_evaluations_;
            p += h * f;
            if (k == last && ops_.front().kind == substep::kick) {
                last_kick_q_ = q;
                last_kick_force_ = f;
                last_kick_t_ = t + offset_[k];
                last_kick_kept_ = true;
            }
        }
    }

    // F0 cos(Omega t + phase) and F0 sin(Omega t + phase), the last pair kept.
    std::pair<scalar, scalar> harmonic_drive_at(scalar t) {
        using std::cos;
        using std::sin;
        if (!(t == drive_time_)) {
            const scalar angle = scalar(drive_.frequency) * t + scalar(drive_.phase);
            drive_at_ = {scalar(drive_.amplitude) * cos(angle), scalar(drive_.amplitude) * sin(angle)};
            drive_time_ = t;
        }
        return drive_at_;
    }

    // Per sub-step its size h and, for drifts, e^{-gamma h} and
    // (1 - e^{-gamma h}) / gamma (= h when gamma = 0, and without the
    // cancellation of 1 - e^{-x} at small x): worked out once per step size,
    // not once per step, since they cost two exponentials each.
    void size_substeps(scalar dt) {
        using std::exp;
        using std::expm1;
        using std::cos;
        using std::sin;
        for (std::vector<scalar>* v : {&size_, &decay_, &span_, &offset_, &kick_cos_, &kick_sin_}) v->resize(ops_.size());
        scalar into_step(0);  // the sub-step's time from the step's start
        for (std::size_t k = 0; k < ops_.size(); ++k) {
            const scalar h = scalar(ops_[k].weight) * dt;
            size_[k] = h;
            decay_[k] = gamma_ == scalar(0) ? scalar(1) : scalar(exp(-gamma_ * h));
            span_[k] = gamma_ == scalar(0) ? h : scalar(-expm1(-gamma_ * h) / gamma_);
            // The drifts' weights sum to 1: a final kick is at the step's end, t + dt.
            offset_[k] = k + 1 == ops_.size() ? dt : into_step;
            if constexpr (harmonic) {
                kick_cos_[k] = cos(scalar(drive_.frequency) * offset_[k]);
                kick_sin_[k] = sin(scalar(drive_.frequency) * offset_[k]);
            }
            if (ops_[k].kind == substep::drift) into_step += h;
        }
        sized_for_ = dt;
    }

    void check(const State& x, scalar dt) {
        using std::isfinite;
        if (!isfinite(dt) || dt == scalar(0))
            throw invalid_argument("conformal_stepper: dt = " + detail::number_text(static_cast<long double>(primal(dt))) +
                                   "; expected a finite non-zero step size");
        if (x.q.size() != x.p.size())
            throw invalid_argument("conformal_stepper: q has " + std::to_string(x.q.size()) + " components but p has " +
                                   std::to_string(x.p.size()) + "; expected equal dimensions");
        if (checked_dimension_ != x.q.size()) {
            // The Hamiltonian's generic code must not read past the state (checked_reads.hpp).
            if constexpr (requires { system_.hamiltonian; }) check_reads(system_.hamiltonian, x, "conformal_stepper");
            force_.resize(x.q.size());
            velocity_.resize(x.q.size());
            if (gamma_ != scalar(0)) check_linear_velocity(x.q.size());
            checked_dimension_ = x.q.size();
        }
    }

    // The damped drift integrates dT/dp(p e^{-gamma s}) in closed form only
    // when dT/dp is linear (core/linear_velocity.hpp).
    void check_linear_velocity(Eigen::Index n) {
        sympl::check_linear_velocity<vector>([&](const vector& p, vector& v) { system_.velocity(p, v); }, n,
                                             "conformal_stepper",
                                             "the damped drift with damping gamma = " +
                                                 detail::number_text(static_cast<long double>(primal(gamma_))));
    }

    static constexpr bool harmonic = harmonically_driven<System, vector>;

    System system_;
    harmonic_drive drive_{};
    table table_;
    std::vector<substep> ops_;
    scalar gamma_{};
    vector force_, velocity_;
    Eigen::Index checked_dimension_ = -1;
    scalar sized_for_ = scalar(0);  // the step size size_, decay_ and span_ hold (0: none yet)
    std::vector<scalar> size_, decay_, span_, offset_, kick_cos_, kick_sin_;
    // q, force and time of the last step's final kick, once kept: a flag, not
    // the vectors' size, which a fixed-size state has from the start (its
    // first step compared x.q with uninitialised memory).
    vector last_kick_q_, last_kick_force_;
    scalar last_kick_t_{};
    bool last_kick_kept_ = false;
    scalar drive_time_ = scalar(std::numeric_limits<double>::quiet_NaN());  // the time drive_at_ holds
    std::pair<scalar, scalar> drive_at_{};
    std::uint64_t force_evaluations_ = 0, velocity_evaluations_ = 0;
};

template <class State, class System>
conformal_stepper<System, State> make_conformal_stepper(System system, table method) {
    return conformal_stepper<System, State>(std::move(system), std::move(method));
}

}  // namespace sympl
