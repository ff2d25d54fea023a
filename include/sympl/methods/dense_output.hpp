#pragma once
// Dense output for any fixed-step stepper on a separable Hamiltonian, without
// touching the step sequence: the state at any time inside a step is read off
// a Hermite interpolant through the states at both ends of the step and their
// time derivatives (Hairer, Norsett & Wanner, Solving ODE I, sec. II.6,
// "dense output"; the cubic is their eq. II.6.7).
//
//   hermite_order::cubic   (default) q and p each by the cubic Hermite
//       through (q, dq/dt = velocity(p)) and (p, dp/dt = force(q)) at both
//       ends: a continuous extension of order 3, its error O(dt^4):
//       |error| <= dt^4 / 384 * max |x''''| on the step. Any separable H.
//   hermite_order::quintic q by the quintic Hermite through q, q' = M^-1 p and
//       q'' = M^-1 F(q) at both ends: order 5, error O(dt^6):
//       |error| <= dt^6 / 46080 * max |q^(6)|. p is M times the derivative of
//       that quintic (a quartic matching p and dp/dt = F at both ends and the
//       step's displacement q1 - q0): order 4, error O(dt^5). It needs T
//       quadratic, T = p.M^-1 p / 2 with M symmetric positive definite, so that
//       velocity(p) = M^-1 p is linear; M (q1 - q0) is found by conjugate
//       gradients with velocity() as the operator (one iteration when M is a
//       multiple of the identity), once per step that is interpolated. Not
//       checked: a kinetic energy that is not quadratic gives wrong values.
//
// These are interpolation errors about exact end states; the interpolated
// state also carries the method's own error at the step ends (the total error
// at an output time is the step's error plus the interpolation error), so
// the interpolant's order matters only up to the method's.
//
// integrate_dense leaves the run as integrate_until (core/integrate.hpp) makes
// it without an observer, bit for bit, also for a splitting stepper, which
// joins the last sub-step of a step with the first of the next inside the
// chunks an unobserved run steps in (observing every step would split them
// and change the rounding): the step ends inside a chunk that holds output
// times are formed on a copy of the stepper (see integrate_dense).
// Forces and velocities at a step end are evaluated at most once each, only
// when an interpolation inside a neighbouring step needs them, and reused by
// the next step (the end of one step is the start of the next); their count is
// reported apart from the stepper's own.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <concepts>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "../core/integrate.hpp"
#include "../core/phase_space.hpp"

namespace sympl {

// The interpolant's order: its error inside a step of size dt about exact end
// states is O(dt^(order + 1)).
enum class hermite_order { cubic = 3, quintic = 5 };

// One step's interpolant, moved along a run: start(x, t) at the first state,
// then push(x, t) after every step (the previous end becomes the start).
// Derivatives at an end are computed lazily, once, when first needed.
template <class H, class State>
    requires phase_space_state<State> && separable_hamiltonian<H, typename State::vector>
class step_interpolant {
public:
    using scalar = typename State::scalar;
    using vector = typename State::vector;

    step_interpolant(const H& h, hermite_order order) : h_(h), order_(order) {
        if (order != hermite_order::cubic && order != hermite_order::quintic)
            throw invalid_argument("step_interpolant: order = " + std::to_string(static_cast<int>(order)) +
                                   "; expected hermite_order::cubic (3) or hermite_order::quintic (5)");
    }

    void start(const State& x, scalar t) {
        a_ = 0;
        end_[0].x = x;
        end_[0].t = t;
        end_[0].ready = false;
        end_[1].x = x;
        end_[1].t = t;
        end_[1].ready = false;
        mass_ready_ = false;
    }
    void push(const State& x, scalar t) {
        a_ = 1 - a_;  // the old end is the new start, with its derivatives
        end_[1 - a_].x = x;
        end_[1 - a_].t = t;
        end_[1 - a_].ready = false;
        mass_ready_ = false;
    }

    scalar t0() const { return end_[a_].t; }
    scalar t1() const { return end_[1 - a_].t; }
    const State& x0() const { return end_[a_].x; }
    const State& x1() const { return end_[1 - a_].x; }
    hermite_order order() const { return order_; }

    // The interpolated state at t (inside [t0, t1]; a few roundings beyond is
    // extrapolated by the same polynomial). At t0 and t1 the end states exactly.
    void evaluate(scalar t, State& out) {
        const end& e0 = end_[a_];
        const end& e1 = end_[1 - a_];
        if (t == e1.t) {
            out = e1.x;
            return;
        }
        if (t == e0.t) {
            out = e0.x;
            return;
        }
        evaluate_fraction((t - e0.t) / (e1.t - e0.t), out);
    }
    // The same at t0 + th (t1 - t0): th = 0 and 1 give the end states exactly.
    // A root sought in th is not limited by the rounding of t (events.hpp).
    void evaluate_fraction(scalar th, State& out) {
        const end& e0 = end_[a_];
        const end& e1 = end_[1 - a_];
        if (th == scalar(1)) {
            out = e1.x;
            return;
        }
        if (th == scalar(0)) {
            out = e0.x;
            return;
        }
        prepare(end_[a_]);
        prepare(end_[1 - a_]);
        const scalar h = e1.t - e0.t, u = 1 - th;
        out = e0.x;
        if (order_ == hermite_order::cubic) {
            // Basis of HNW I eq. II.6.7 written out: values and slopes at 0 and 1.
            const scalar h00 = (1 + 2 * th) * u * u, h01 = th * th * (3 - 2 * th);
            const scalar h10 = th * u * u * h, h11 = -th * th * u * h;
            out.q = h00 * e0.x.q + h01 * e1.x.q + h10 * e0.v + h11 * e1.v;
            out.p = h00 * e0.x.p + h01 * e1.x.p + h10 * e0.f + h11 * e1.f;
            return;
        }
        // Quintic Hermite basis on [0, 1]: value, first and second derivative at 0 and at 1.
        const scalar t2 = th * th, t3 = t2 * th, t4 = t3 * th, t5 = t4 * th;
        const scalar v0 = 1 - 10 * t3 + 15 * t4 - 6 * t5, v1 = 1 - v0;
        const scalar d0 = th - 6 * t3 + 8 * t4 - 3 * t5, d1 = -4 * t3 + 7 * t4 - 3 * t5;
        const scalar s0 = (t2 - 3 * t3 + 3 * t4 - t5) / 2, s1 = (t3 - 2 * t4 + t5) / 2;
        out.q = v0 * e0.x.q + v1 * e1.x.q + (h * d0) * e0.v + (h * d1) * e1.v + (h * h * s0) * e0.a +
                (h * h * s1) * e1.a;
        // p = M dq/dt: the derivatives of the basis, M applied term by term
        // (M v = p, M a = F at the ends, M (q1 - q0) solved for once per step).
        if (!mass_ready_) mass_displacement(e0, e1, h);
        const scalar w = 30 * t2 * u * u;
        const scalar dd0 = 1 - 18 * t2 + 32 * t3 - 15 * t4, dd1 = -12 * t2 + 28 * t3 - 15 * t4;
        const scalar ds0 = th - scalar(4.5) * t2 + 6 * t3 - scalar(2.5) * t4, ds1 = scalar(1.5) * t2 - 4 * t3 + scalar(2.5) * t4;
        out.p = (w / h) * m_dq_ + dd0 * e0.x.p + dd1 * e1.x.p + (h * ds0) * e0.f + (h * ds1) * e1.f;
    }
    State evaluate(scalar t) {
        State out = end_[a_].x;
        evaluate(t, out);
        return out;
    }

    // Evaluations spent by the interpolation (not by the stepper).
    std::uint64_t force_evaluations() const { return forces_; }
    std::uint64_t velocity_evaluations() const { return velocities_; }

private:
    struct end {
        State x;
        scalar t{};
        vector v, f, a;  // dq/dt, dp/dt, and (quintic) d2q/dt2 = M^-1 F
        bool ready = false;
    };

    void prepare(end& e) {
        if (e.ready) return;
        velocity(h_, e.x.p, e.v);
        force(h_, e.x.q, e.f);
        velocities_ += 1;
        forces_ += 1;
        if (order_ == hermite_order::quintic) {
            velocity(h_, e.f, e.a);
            velocities_ += 1;
        }
        e.ready = true;
    }

    // m_dq_ = M (q1 - q0): velocity(y) = q1 - q0 solved by conjugate gradients
    // (Hestenes & Stiefel 1952) from y = dt (p0 + p1)/2 + dt^2 (F0 - F1)/12,
    // the trapezoidal rule with its end correction (already O(dt^5) close).
    void mass_displacement(const end& e0, const end& e1, scalar h) {
        using std::sqrt;
        const vector target = e1.x.q - e0.x.q;
        m_dq_ = (h / 2) * (e0.x.p + e1.x.p) + (h * h / 12) * (e0.f - e1.f);
        velocity(h_, m_dq_, image_);
        ++velocities_;
        residual_ = target - image_;
        const scalar eps = std::numeric_limits<scalar>::epsilon();
        const scalar tol = 64 * eps * (target.norm() + image_.norm());
        scalar rr = residual_.squaredNorm();
        direction_ = residual_;
        const Eigen::Index limit = target.size() + 4;
        for (Eigen::Index k = 0; k < limit && sqrt(rr) > tol; ++k) {
            velocity(h_, direction_, image_);
            ++velocities_;
            const scalar curvature = direction_.dot(image_);
            if (!(curvature > 0))
                throw invalid_argument("step_interpolant: quintic order needs velocity(p) = M^-1 p with M symmetric "
                                       "positive definite, but d.velocity(d) = " +
                                       detail::number(curvature) + "; expected > 0 (use hermite_order::cubic)");
            const scalar alpha = rr / curvature;
            m_dq_ += alpha * direction_;
            residual_ -= alpha * image_;
            const scalar next = residual_.squaredNorm();
            direction_ = residual_ + (next / rr) * direction_;
            rr = next;
        }
        mass_ready_ = true;
    }

    const H& h_;
    hermite_order order_;
    end end_[2];
    int a_ = 0;  // index of the start of the current step
    vector m_dq_, image_, residual_, direction_;
    bool mass_ready_ = false;
    std::uint64_t forces_ = 0, velocities_ = 0;
};

// What integrate_dense did: integrate_until's summary (steps, time, the
// stepper's own evaluations) and what the dense output cost on top.
struct dense_summary : run_summary {
    std::uint64_t extra_force_evaluations = 0;     // at step ends, for the interpolant
    std::uint64_t extra_velocity_evaluations = 0;  // at step ends (and quintic: M^-1 F, the solve for M dq)
    std::size_t outputs = 0;                       // callbacks made
    // Steps made a second time, on a copy of the stepper, to form the step
    // ends inside a chunk that holds output times (integrate_dense), and their cost.
    std::size_t replayed_steps = 0;
    std::uint64_t replay_force_evaluations = 0;
    std::uint64_t replay_velocity_evaluations = 0;
};

namespace detail {
// Times must be finite, inside [t0, t_end] and sorted (ties allowed).
template <class T>
void check_output_times(std::span<const T> times, T t0, T t_end, const char* who) {
    using std::isfinite;
    if (!isfinite(t0) || !isfinite(t_end) || !(t_end > t0))
        throw invalid_argument(std::string(who) + ": t_end = " + number(t_end) + " with t0 = " + number(t0) +
                               "; expected finite times with t_end > t0");
    for (std::size_t i = 0; i < times.size(); ++i) {
        const T t = times[i];
        const std::string name = std::string(who) + ": output_times[" + std::to_string(i) + "] = " + number(t);
        if (!isfinite(t) || t < t0 || t > t_end)
            throw invalid_argument(name + "; expected a finite time in [t0, t_end] = [" + number(t0) + ", " +
                                   number(t_end) + "]");
        if (i > 0 && t < times[i - 1])
            throw invalid_argument(name + " is before output_times[" + std::to_string(i - 1) + "] = " +
                                   number(times[i - 1]) + "; expected times sorted in increasing order");
    }
}
}  // namespace detail

namespace detail {
// A stepper whose steps(x, dt, n) or resume_steps differs from n calls of
// step() by rounding (a splitting stepper joins the last sub-step of a step
// with the first of the next; a processed stepper processes once per call):
// observing every step would change its run. Time-aware steppers are stepped
// one at a time by the drivers, observed or not.
template <class S>
concept groups_steps = !time_aware_stepper<S> && (requires(S s, typename S::state_type& x, typename S::scalar dt) {
    s.steps(x, dt, std::size_t(1));
} || requires(S s, typename S::state_type& x, typename S::scalar dt) { s.resume_steps(x, dt, std::size_t(1)); });
}  // namespace detail

// Runs stepper from x at t0 up to t_end with steps of dt and calls
// callback(state, t) at each of output_times (sorted, within [t0, t_end])
// with the state interpolated there (the end state itself when t is a step
// end). h is the Hamiltonian the stepper runs.
//
// The run is integrate_until(stepper, x, t0, t_end, dt) without an observer,
// bit for bit: the same steps grouped the same way, the same final x and the
// same run_summary. A stepper that groups steps (detail::groups_steps: a
// splitting, processed or Wisdom-Holman stepper) is run by integrate_until in
// its chunks of run_options::check_every steps, observed only at the chunk
// ends (which does not change how the steps group; integrate.hpp, first_step),
// and the step ends inside a chunk that holds output times are made by a copy
// of the stepper, replayed from the chunk's start: steps(m) up to the start of
// the step holding an output time, then steps(1) (the chunk's last step ends
// on the run's own state). Those inner step ends differ from the run's
// (which never forms them) by rounding only; the replay costs at most a
// chunk's steps per chunk holding outputs, counted in replayed_steps and
// replay_*_evaluations. So Stepper must be copyable, and a copy must step
// independently of the original. Other steppers (time-aware ones, or with
// step() only) are observed at every step, which is their unobserved run.
template <fixed_step_stepper Stepper, class H, class Callback>
    requires separable_hamiltonian<H, typename Stepper::state_type::vector>
dense_summary integrate_dense(Stepper& stepper, const H& h, typename Stepper::state_type& x,
                              typename Stepper::scalar t0, typename Stepper::scalar t_end,
                              typename Stepper::scalar dt, std::span<const typename Stepper::scalar> output_times,
                              Callback&& callback, hermite_order order = hermite_order::cubic) {
    using T = typename Stepper::scalar;
    using State = typename Stepper::state_type;
    const char* who = "integrate_dense";
    const auto plan = detail::until_plan(t0, t_end, dt, who);
    detail::check_output_times<T>(output_times, t0, t_end, who);
    step_interpolant<H, State> dense(h, order);
    State out = x;
    std::size_t next = 0;
    const auto emit = [&] {
        dense.evaluate(output_times[next], out);
        callback(std::as_const(out), output_times[next]);
        ++next;
    };
    dense_summary r;
    if constexpr (!detail::groups_steps<Stepper>) {
        bool started = false;
        auto observer = [&](const State& s, T t) {
            if (!started) {
                dense.start(s, t);
                started = true;
            } else {
                dense.push(s, t);
            }
            while (next < output_times.size() && output_times[next] <= t) emit();
        };
        static_cast<run_summary&>(r) = integrate_until(stepper, x, t0, t_end, dt, observer);
        // The last step ends at t0 + n dt, which may fall short of t_end by a
        // rounding when dt divides the span: the last polynomial covers the rest.
        while (next < output_times.size()) emit();
    } else {
        static_assert(std::copy_constructible<Stepper>,
                      "integrate_dense replays chunks of a stepper that groups steps on a copy of it: "
                      "expected a copyable stepper");
        const std::size_t n = plan.n, last = plan.rest > T(0) ? n + 1 : n;  // index of the last step end
        const auto time_of = [&](std::size_t i) { return i <= n ? t0 + T(i) * dt : t_end; };
        run_options chunks;  // integrate_until's defaults, observed once per chunk
        chunks.observe_every = chunks.check_every;
        const std::size_t chunk = chunks.check_every;
        std::optional<Stepper> shadow;
        State start = x, y = x;
        std::size_t start_index = 0, dense_end = 0;  // dense_end: the interpolant's end, when it is a run state
        // m steps of the copy from step index `from`, y its state.
        const auto replay = [&](std::size_t from, std::size_t m) {
            if (!shadow) shadow.emplace(stepper);
            const auto f = detail::forces(*shadow), v = detail::velocities(*shadow);
            detail::advance(*shadow, y, t0, dt, from, m, false);
            r.replay_force_evaluations += detail::forces(*shadow) - f;
            r.replay_velocity_evaluations += detail::velocities(*shadow) - v;
            r.replayed_steps += m;
        };
        bool started = false;
        auto observer = [&](const State& s, T t) {
            if (!started) {
                started = true;
                dense.start(s, t);
                while (next < output_times.size() && output_times[next] <= t) emit();
                start = s;
                return;
            }
            const std::size_t i1 = start_index < n ? std::min(start_index + chunk, n) : n + 1;
            // The last chunk also takes times beyond its end by a rounding (see above).
            const auto inside = [&] { return next < output_times.size() && (output_times[next] <= t || i1 == last); };
            if (inside()) {
                std::size_t cur = start_index;
                if (dense_end != cur) dense.start(start, time_of(cur));
                y = start;
                while (inside()) {
                    const T tau = output_times[next];
                    if (tau == t && cur < i1) {  // the chunk's end: the run's own state, nothing to replay
                        callback(std::as_const(s), tau);
                        ++next;
                        continue;
                    }
                    std::size_t target = cur;  // the step (target - 1, target] holding tau
                    while (target < i1 && tau > time_of(target)) ++target;
                    if (target > cur) {
                        if (target - 1 > cur) {  // the steps before it in one call, as the run makes them
                            replay(cur, target - 1 - cur);
                            dense.start(y, time_of(target - 1));
                        }
                        if (target == i1) {
                            dense.push(s, t);
                        } else {
                            replay(target - 1, 1);
                            dense.push(y, time_of(target));
                        }
                        cur = target;
                    }
                    emit();
                }
                dense_end = cur;
            }
            start = s;
            start_index = i1;
        };
        static_cast<run_summary&>(r) = integrate_until(stepper, x, t0, t_end, dt, observer, chunks);
    }
    r.outputs = output_times.size();
    r.extra_force_evaluations = dense.force_evaluations();
    r.extra_velocity_evaluations = dense.velocity_evaluations();
    return r;
}

// The same with the stepper's own Hamiltonian (steppers with hamiltonian():
// splitting_stepper, rkn_pair_stepper, processed steppers).
template <fixed_step_stepper Stepper, class Callback>
    requires requires(const Stepper& s) { s.hamiltonian(); }
dense_summary integrate_dense(Stepper& stepper, typename Stepper::state_type& x, typename Stepper::scalar t0,
                              typename Stepper::scalar t_end, typename Stepper::scalar dt,
                              std::span<const typename Stepper::scalar> output_times, Callback&& callback,
                              hermite_order order = hermite_order::cubic) {
    return integrate_dense(stepper, stepper.hamiltonian(), x, t0, t_end, dt, output_times,
                           std::forward<Callback>(callback), order);
}

}  // namespace sympl
