#pragma once
// Time-transformed stepping in the extended phase space: the logarithmic
// Hamiltonian (LogH) of Mikkola & Tanikawa 1999 (MNRAS 310, 745) and Preto &
// Tremaine 1999 (AJ 118, 2532). Time t becomes a coordinate with momentum
// p_t = -H0 on the orbit, and in a fictitious time s the separable
//     Lambda(Q, P) = ln(T(p) + p_t) - ln(-V(q)),   Q = (q, t), P = (p, p_t),
// generates the same orbit, so any kick-drift table runs on it unchanged as
// logh<H> in a splitting_stepper and keeps its order; the physical step is
// dt = ds / (-V), short at the pericentre. It needs V(q) < 0 along the orbit
// and T + p_t > 0; a state where either fails is an invalid_argument naming
// the value. The flows and what is measured of them: docs/eccentric-orbits.md.
//
//   auto X = sympl::to_extended(kepler, x0);               // (q, 0), (p, -H(x0))
//   sympl::splitting_stepper<sympl::logh<Kepler>, decltype(X)> s({kepler}, method("blanes_moan_s6"));
//   sympl::integrate_to_time(s, X, t_end, ds);             // lands on t_end exactly
//   auto x = sympl::physical_state(X);
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "../drivers/fixed_step.hpp"
#include "../core/phase_space.hpp"

namespace sympl {

// Degrees of freedom with time added, and with it removed.
constexpr int extended_dimension(int d) { return d == Eigen::Dynamic ? Eigen::Dynamic : d + 1; }
constexpr int physical_dimension(int d) { return d == Eigen::Dynamic ? Eigen::Dynamic : d - 1; }

// A system that computes -dV/dq and V(q) together (for LogH, which needs both at every kick).
template <class H, class Vec>
concept has_force_and_potential = requires(const H& h, const Vec& q, Vec& f) {
    { h.force_and_potential(q, f) } -> std::convertible_to<scalar_of<Vec>>;
};

// The logarithmic Hamiltonian of `system` on extended vectors (q, t) and (p, p_t).
template <class H>
struct logh {
    H system;

    template <class Vec>
    using inner_vector = Eigen::Matrix<scalar_of<Vec>, physical_dimension(Vec::RowsAtCompileTime), 1>;

    // Only where the system takes the vectors (a system of fixed scalar type
    // then leaves LogH without the force's derivative, not without LogH).
    template <class Vec>
        requires separable_hamiltonian<H, inner_vector<Vec>>
    scalar_of<Vec> kinetic(const Vec& P) const {
        using std::log;
        return log(positive_kinetic(P, inner_vector<Vec>(P.head(P.size() - 1))));
    }
    template <class Vec>
        requires separable_hamiltonian<H, inner_vector<Vec>>
    scalar_of<Vec> potential(const Vec& Q) const {
        using std::log;
        return -log(negative_potential(Q, scalar_of<Vec>(system.potential(inner_vector<Vec>(Q.head(Q.size() - 1))))));
    }
    // (dT/dp, 1) / (T + p_t)
    template <class Vec>
    void velocity(const Vec& P, Vec& v) const {
        scratch<Vec> local;  // empty (no allocation) for dynamic vectors
        scratch<Vec>& w = workspace(local);
        w.p = inner(P);
        sympl::velocity(system, w.p, w.g);
        const auto scale = 1 / positive_kinetic(P, w.p);
        inner(v) = scale * w.g;
        v[v.size() - 1] = scale;
    }
    // (-dV/dq, 0) / (-V)
    template <class Vec>
    void force(const Vec& Q, Vec& f) const {
        using S = scalar_of<Vec>;
        scratch<Vec> local;  // empty (no allocation) for dynamic vectors
        scratch<Vec>& w = workspace(local);
        w.q = inner(Q);
        S v;
        if constexpr (has_force_and_potential<H, inner_vector<Vec>>) {
            v = S(system.force_and_potential(w.q, w.g));
        } else {
            sympl::force(system, w.q, w.g);
            v = S(system.potential(w.q));
        }
        const S scale = 1 / negative_potential(Q, v);
        inner(f) = scale * w.g;
        f[f.size() - 1] = S(0);
    }

private:
    template <class Vec>
    struct scratch {
        inner_vector<Vec> q, p, g;
    };
    // The physical part (q or p) of an extended vector, fixed-size when it is.
    template <class Vec>
    static auto inner(Vec& x) {
        if constexpr (Vec::RowsAtCompileTime != Eigen::Dynamic) return x.template head<Vec::RowsAtCompileTime - 1>();
        else return x.head(x.size() - 1);
    }
    // Fixed-size vectors use the caller's local workspace (registers, no
    // aliasing with the state); dynamic ones one per thread and vector type,
    // so no step allocates once it is sized.
    template <class Vec>
    static scratch<Vec>& workspace(scratch<Vec>& local) {
        if constexpr (Vec::RowsAtCompileTime != Eigen::Dynamic) {
            return local;
        } else {
            thread_local scratch<Vec> shared;
            return shared;
        }
    }
    // -V, checked: the transformation needs V < 0.
    template <class Vec, class S>
    static S negative_potential(const Vec& Q, S v) {
        if (!(v < S(0)))
            throw invalid_argument("logh: V(q) = " + detail::number(v) +
                                   " at t = " + detail::number(Q[Q.size() - 1]) +
                                   "; the logarithmic time transformation needs V(q) < 0 along the orbit");
        return -v;
    }
    // T + p_t, checked: the transformation needs T + p_t > 0 (p_t = -H0).
    template <class Vec, class Inner>
    scalar_of<Vec> positive_kinetic(const Vec& P, const Inner& p) const {
        using S = scalar_of<Vec>;
        const S w = S(system.kinetic(p)) + P[P.size() - 1];
        if (!(w > S(0)))
            throw invalid_argument("logh: T(p) + p_t = " + detail::number(w) +
                                   "; the logarithmic time transformation needs T(p) - H0 > 0 along the orbit");
        return w;
    }
};

// (q, p) at time t -> the extended state ((q, t), (p, -H(q, p))).
template <class H, class S, int D>
phase_space<S, extended_dimension(D)> to_extended(const H& system, const phase_space<S, D>& x, S t = S(0)) {
    const Eigen::Index n = x.size();
    phase_space<S, extended_dimension(D)> X(n + 1);
    X.q.head(n) = x.q;
    X.p.head(n) = x.p;
    X.q[n] = t;
    X.p[n] = -energy(system, x);
    return X;
}

// The physical state (q, p) of an extended state, and its time.
template <class S, int D>
phase_space<S, physical_dimension(D)> physical_state(const phase_space<S, D>& X) {
    const Eigen::Index n = X.size() - 1;
    return phase_space<S, physical_dimension(D)>(X.q.head(n), X.p.head(n));
}
template <class S, int D>
S physical_time(const phase_space<S, D>& X) {
    return X.q[X.size() - 1];
}

struct time_transformed_options {
    std::size_t max_steps = 1000000000;  // fictitious steps before the run is refused as endless
    // Resume a run after its step `first_step` (a checkpoint): X is the
    // extended state after it and the stepper holds the memory it had there
    // (splitting_stepper::restore), so the next step carries its last force
    // over as the uninterrupted run's did; steps count on from first_step.
    std::size_t first_step = 0;
};

namespace detail {

// X overshot `target` in a step of ds from `before`: finds h in (0, ds) with
// t(h) = target and leaves X at it, its time set to target exactly.
// t(h) - target is negative at 0 and positive at ds; the Illinois variant of
// regula falsi keeps that bracket and converges superlinearly (Dowell &
// Jarratt 1971), where a plain secant can leave the bracket on a long, curved
// step. `slack` widens the tolerance for a stepper whose rounding it magnifies
// (extrapolation.hpp); step_from_before(X, h) redoes the step with h.
template <class S, int D, class Step>
void land_on_time(phase_space<S, D>& X, const phase_space<S, D>& before, S ds, S target, S slack,
                  std::size_t step_number, const Step& step_from_before) {
    using std::abs;
    const S tb = physical_time(before), tolerance = 2 * slack * std::numeric_limits<S>::epsilon() * abs(target);
    S a = 0, fa = tb - target, b = ds, fb = physical_time(X) - target, f1 = fb;
    int kept = 0;  // which end stayed twice in a row (-1 a, +1 b)
    for (int i = 0; i < 100 && abs(f1) > tolerance; ++i) {
        S h = b - fb * (b - a) / (fb - fa);
        if (!(h > a && h < b)) h = a + (b - a) / 2;
        if (!(h > a && h < b)) break;  // the bracket is down to adjacent numbers
        X = before;
        step_from_before(X, h);
        f1 = physical_time(X) - target;
        if (f1 < S(0)) {
            a = h, fa = f1;
            if (kept == 1) fb /= 2;
            kept = 1;
        } else {
            b = h, fb = f1;
            if (kept == -1) fa /= 2;
            kept = -1;
        }
    }
    if (abs(f1) > 4 * tolerance)
        throw integration_error("integrate_to_time: could not land on t = " + detail::number(target) + " (missed by " +
                                    detail::number(f1) + ")",
                                step_number, static_cast<double>(primal(tb)));
    X.q[X.size() - 1] = target;  // within 2 eps: time lands exactly
}

}  // namespace detail

// Runs a stepper of logh<H> on the extended state X from its time to t_end in
// fictitious steps of ds, landing exactly on t_end and on each observation
// time in between (the step that would pass one is shortened to end on it,
// its length found by the secant method). observer(X, t) is called after
// every step. Returns steps (landing steps count once), force evaluations
// (including those of the landing iterations) and the time reached; resumed
// (options.first_step), the steps of this call.
template <class Stepper, class S, int D, class Observer = no_observer>
run_summary integrate_to_time(Stepper& stepper, phase_space<S, D>& X, S t_end, S ds, Observer&& observer = {},
                              const std::vector<S>& observation_times = {}, time_transformed_options options = {}) {
    using std::abs;
    using std::isfinite;
    const S t0 = physical_time(X);
    if (!isfinite(ds) || !(ds > S(0)))
        throw invalid_argument("integrate_to_time: ds = " + detail::number(ds) + "; expected a finite step > 0");
    check_time_span("integrate_to_time", t0, t_end);
    std::vector<S> targets;
    for (S t : observation_times)
        if (t > t0 && t < t_end) targets.push_back(t);
    std::sort(targets.begin(), targets.end());
    targets.push_back(t_end);

    const std::uint64_t forces0 = detail::forces(stepper);
    run_summary r;
    r.steps = options.first_step;
    bool carried = options.first_step > 0;  // the stepper's last force belongs to X
    const auto step = [&](phase_space<S, D>& x, S h, bool resume) {
        if (resume) stepper.resume_steps(x, h, 1);
        else stepper.step(x, h);
    };
    const auto check = [&](const phase_space<S, D>& x, const phase_space<S, D>& before, S h) {
        if (!is_finite(x))
            throw blow_up(r.steps + 1, static_cast<long double>(primal(physical_time(before))),
                          static_cast<long double>(primal(h)), " (fictitious step; physical time at its start)");
    };
    for (const S target : targets) {
        while (physical_time(X) < target) {
            if (r.steps >= options.max_steps)
                throw invalid_argument("integrate_to_time: " + std::to_string(r.steps) + " steps of ds = " +
                                       detail::number(ds) + " reached t = " + detail::number(physical_time(X)) +
                                       " of t_end = " + detail::number(t_end) + "; max_steps is " +
                                       std::to_string(options.max_steps));
            const phase_space<S, D> before = X;
            step(X, ds, carried);
            check(X, before, ds);
            carried = true;
            if (physical_time(X) > target) {
                S slack = 1;  // an extrapolated step magnifies its inner rounding, and the noise in t(h)
                if constexpr (requires { stepper.amplification(); }) slack = S(stepper.amplification());
                detail::land_on_time(X, before, ds, target, slack, r.steps + 1, [&](phase_space<S, D>& x, S h) {
                    step(x, h, false);
                    check(x, before, h);
                });
            }
            ++r.steps;
            if (detail::observing(observer)) observer(std::as_const(X), physical_time(X));
        }
    }
    r.steps -= options.first_step;
    r.force_evaluations = detail::forces(stepper) - forces0;
    r.velocity_evaluations = 0;
    r.t = static_cast<double>(primal(physical_time(X)));
    return r;
}

}  // namespace sympl
