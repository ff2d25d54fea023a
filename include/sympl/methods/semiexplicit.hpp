#pragma once
// Jayawardana & Ohsawa's semiexplicit method for a non-separable H(q, p):
// in Pihajoki's extended phase space (extended_phase_space.hpp), the map
// A(dt/2) B(dt) A(dt/2) inside the symmetric projection onto q = x, p = y
// (Hairer 2000, BIT 40, 726), symplectic in the original space (Jayawardana &
// Ohsawa 2023, Math. Comp. 92, 251; Ohsawa 2023, arXiv:2208.10546). Higher
// orders: symmetric compositions of it read off any table that composes
// leapfrog steps. Formulas and measurements: docs/nonseparable.md.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include "../core/error.hpp"
#include "../core/general_hamiltonian.hpp"
#include "../core/table.hpp"
#include "extended_phase_space.hpp"

namespace sympl {

// Options of semiexplicit_stepper (Jayawardana & Ohsawa 2023).
struct semiexplicit_options {
    // The projection's multiplier is iterated until each half of its update is
    // below tolerance times its half of the state, |q| or |p|; 0 means to
    // rounding (8 machine epsilons), which keeps the step symplectic to rounding.
    double tolerance = 0;
    // Beyond this many iterations the step is reported as failed (the
    // iteration contracts by O(dt |d^2 H|) per sweep: too large a dt fails).
    int max_iterations = 50;
};

// The semiexplicit method of Jayawardana & Ohsawa (2023) of any even order,
// over a state of the original phase space. Every step starts both copies at
// the state, so nothing is carried between steps.
template <class H, class State>
    requires general_hamiltonian<H, typename State::vector>
class semiexplicit_stepper : public detail::extended_flows<H, State> {
    using base = detail::extended_flows<H, State>;
    using typename base::P;

public:
    using typename base::extended, typename base::scalar, typename base::state_type, typename base::vector;

    semiexplicit_stepper(H h, const table& t, semiexplicit_options o = {})
        : base(std::move(h), t, "semiexplicit_stepper"), options_(o) {
        using std::isfinite;
        if (!isfinite(o.tolerance) || o.tolerance < 0)
            throw invalid_argument("semiexplicit_stepper: tolerance = " + detail::number_text(o.tolerance) +
                                   "; expected a finite tolerance >= 0 (0 = to rounding)");
        if (o.max_iterations < 1)
            throw invalid_argument("semiexplicit_stepper: max_iterations = " + std::to_string(o.max_iterations) +
                                   "; expected at least 1");
    }

    // Iterations of the projection: in all, and the most in one step.
    std::uint64_t projection_iterations() const { return iterations_; }
    int max_projection_iterations() const { return max_iterations_seen_; }
    // divergence() is |q - x| + |p - y| of the unprojected copies, 2 |mu_q| + 2 |mu_p|.

    // Times in its messages count from the stepper's first step.
    void step(state_type& x, scalar dt) { advance(x, dt, this->elapsed_ + primal(dt)); }
    // The same with the time at the start of the step (the drivers of fixed_step.hpp call this one).
    void step(state_type& x, scalar t, scalar dt) { advance(x, dt, primal(t) + primal(dt)); }

private:
    // Pihajoki's symmetric map composed: A(g/2) B(g) A(g/2) per weight g,
    // neighbouring A's merged (J&O 2023).
    void map(extended& z, P dt) {
        bool cached = false;
        this->compose(z, dt, cached, [&](P h) { this->flow_B(z, h, cached); });
    }

    void advance(state_type& x, scalar dt, P t_end) {
        detail::check_step_size(dt, "semiexplicit_stepper");
        check_reads_once(this->h_, x, "semiexplicit_stepper");
        // Each half of the multiplier against its own half of the state (momenta
        // of 1e-5 beside positions of 40 would otherwise be judged on the positions).
        const P size_q = detail::primal_norm(x.q), size_p = detail::primal_norm(x.p);
        const P scale_q = size_q > 0 ? size_q : P(1), scale_p = size_p > 0 ? size_p : P(1);
        const P eps = std::numeric_limits<P>::epsilon();
        const P tol = options_.tolerance > 0 ? P(options_.tolerance) : 8 * eps;
        vector mu_q = vector::Zero(x.q.size()), mu_p = vector::Zero(x.p.size());
        extended z;
        P update = std::numeric_limits<P>::infinity(), previous = update;
        int k = 0;
        bool converged = false;
        while (k < options_.max_iterations) {
            // z~0 = z0 + (mu, -mu); z~1 = Phi(z~0); z1 = z~1 + (mu, -mu) (J&O 2023).
            z.q = x.q + mu_q;
            z.p = x.p + mu_p;
            z.x = x.q - mu_q;
            z.y = x.p - mu_p;
            map(z, primal(dt));
            ++k;
            // g(z1) = (q1 - x1, p1 - y1) = (Q - X + 2 mu_q, P - Y + 2 mu_p); dg/dmu = 4 I + O(dt).
            const vector dq = (z.q - z.x + scalar(2) * mu_q) / scalar(4);
            const vector dp = (z.p - z.y + scalar(2) * mu_p) / scalar(4);
            mu_q -= dq;
            mu_p -= dp;
            using std::isfinite;
            previous = update;
            update = std::max(detail::primal_norm(dq) / scale_q, detail::primal_norm(dp) / scale_p);
            if (!isfinite(update)) break;
            // To rounding: below the tolerance, or stalled at the rounding floor.
            if (update <= tol || (options_.tolerance == 0 && update >= previous && update <= 1e3 * tol)) {
                converged = true;
                break;
            }
        }
        iterations_ += std::uint64_t(k);
        max_iterations_seen_ = std::max(max_iterations_seen_, k);
        const auto at = [&] { return this->where(t_end, primal(dt)); };
        if (!converged)
            throw integration_error("semiexplicit_stepper: the projection onto q = x, p = y did not converge at " + at() +
                                        ": the last update of its multiplier was " +
                                        (std::isfinite(update) ? detail::number_text(update) : std::string("not finite")) +
                                        " after " + std::to_string(k) + " iterations, tolerance " +
                                        detail::number_text(tol) +
                                        "; expected a smaller dt (the iteration contracts by O(dt |d2H|)); the "
                                        "state is left at the start of the step",
                                    this->steps_ + 1, double(t_end - primal(dt)));
        // The projected point: both copies agree to the tolerance; their mean is
        // independent of the last update of mu.
        vector q1 = (z.q + z.x) / scalar(2), p1 = (z.p + z.y) / scalar(2);
        if (!detail::all_finite(q1) || !detail::all_finite(p1))
            throw integration_error("semiexplicit_stepper: " + at() + " produced a non-finite state; the state is left "
                                                                    "at the start of the step",
                                    this->steps_ + 1, double(t_end - primal(dt)));
        x.q = std::move(q1);
        x.p = std::move(p1);
        this->count_step(2 * (detail::primal_norm(mu_q) + detail::primal_norm(mu_p)), primal(dt));
    }

    semiexplicit_options options_;
    std::uint64_t iterations_ = 0;
    int max_iterations_seen_ = 0;
};

template <class State, class H>
semiexplicit_stepper<H, State> make_semiexplicit_stepper(H h, const table& t, semiexplicit_options o = {}) {
    return semiexplicit_stepper<H, State>(std::move(h), t, o);
}

}  // namespace sympl
