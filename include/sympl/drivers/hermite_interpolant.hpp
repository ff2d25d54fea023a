#pragma once
// The Hermite interpolant of one step, for any stepper on a separable
// Hamiltonian: the state at any time inside a step read off the states at
// both ends of the step and their time derivatives (Hairer, Norsett &
// Wanner, Solving ODE I, sec. II.6, "dense output"; the cubic is their eq. II.6.7).
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
//       multiple of the identity), once per step that is interpolated. The
//       linearity is probed once per dimension (core/linear_velocity.hpp).
//
// These are interpolation errors about exact end states; the interpolated
// state also carries the method's own error at the step ends (the total error
// at an output time is the step's error plus the interpolation error), so
// the interpolant's order matters only up to the method's.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "../core/linear_velocity.hpp"
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
        if (order_ == hermite_order::quintic && checked_dimension_ != x.q.size()) {
            check_linear_velocity<vector>([&](const vector& p, vector& v) { velocity(h_, p, v); }, x.q.size(),
                                          "step_interpolant", "the quintic Hermite interpolant");
            checked_dimension_ = x.q.size();
        }
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
                                       detail::number_text(static_cast<long double>(primal(curvature))) + "; expected > 0 (use hermite_order::cubic)");
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
    Eigen::Index checked_dimension_ = -1;
    std::uint64_t forces_ = 0, velocities_ = 0;
};

}  // namespace sympl
