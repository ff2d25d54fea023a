#pragma once
// Pihajoki's extended phase space of two copies (q, p), (x, y) for a
// non-separable H(q, p), with the Hamiltonian H(q, y) + H(x, p), whose two
// parts have exact explicit flows phi_A (drift x, kick p) and phi_B (drift q,
// kick y) (Pihajoki 2015, Celest. Mech. Dyn. Astron. 121, 211): the extended
// state, the flows composed (detail::extended_flows, shared with
// semiexplicit.hpp), and Tao's explicit method, tao_stepper: the copies bound
// by omega (|q - x|^2 + |p - y|^2)/2, whose flow phi_C rotates their
// difference; A(dt/2) B(dt/2) C(dt) B(dt/2) A(dt/2) (Tao 2016, Phys. Rev. E
// 94, 043303).
// Higher orders: symmetric compositions of the second-order map (Yoshida 1990;
// Suzuki 1990) read off any table that composes leapfrog steps; other tables
// are refused. Formulas and measurements: docs/nonseparable.md.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "../core/carried_in_place.hpp"
#include "../core/carried_state.hpp"
#include "../core/dual.hpp"
#include "../core/error.hpp"
#include "../core/general_hamiltonian.hpp"
#include "../core/phase_space.hpp"
#include "../core/table.hpp"
#include "catalog_forms.hpp"

namespace sympl {

// A point of the extended phase space: the original copy (q, p) and the
// second copy (x, y).
template <class S = double, int Dim = Eigen::Dynamic>
struct extended_state {
    using vector = Eigen::Matrix<S, Dim, 1>;
    vector q, p, x, y;

    extended_state() = default;
    // Both copies at the point of the original phase space.
    explicit extended_state(const phase_space<S, Dim>& z) : q(z.q), p(z.p), x(z.q), y(z.p) {}
};


// Options of tao_stepper (Tao 2016).
struct tao_options {
    // The binding omega of omega * H_C (a frequency: 1 / time). 20 is the value
    // Jayawardana & Ohsawa 2023 give Tao's method on H = (1 + q^2)(1 + p^2)/2,
    // whose own angular frequencies stay below about 10 there. The rule: a few
    // times the problem's fastest angular frequency, and dt << omega^(-1/l)
    // for a method of order l (Tao 2016). tao_options_for(h, x) picks it.
    double omega = 20;
    // kappa, momentum per position: the binding is
    //     H_C = (kappa |q - x|^2 + |p - y|^2 / kappa) / 2,
    // Tao's with the copies' differences measured in the state's own units
    // (1: Tao's; the outer solar system needs about 2e-7, momenta 1e-5 beside
    // positions of 40). Its flow is still an exact rotation.
    double momentum_scale = 1;
    // kappa per component (empty: momentum_scale for all), for states whose
    // components differ in mass: kappa_k |q_k - x_k|^2 + |p_k - y_k|^2 / kappa_k.
    std::vector<double> momentum_scales{};
    // The copies are declared unbound, and the run stopped, when
    //     |q - x| sqrt(kappa) + |p - y| / sqrt(kappa)
    //         > divergence_limit * (1 + |q| sqrt(kappa) + |p| / sqrt(kappa))
    // (Euclidean norms): the two copies are two approximations of the same
    // solution, so beyond 10% of the state's size neither is one.
    double divergence_limit = 0.1;
};

namespace detail {

template <class S>
using primal_scalar = std::decay_t<decltype(primal(std::declval<S>()))>;

// Euclidean norm of the plain values (derivative parts of dual numbers ignored).
template <class V>
auto primal_norm(const V& v) {
    using P = primal_scalar<typename V::Scalar>;
    P s = 0;
    for (Eigen::Index i = 0; i < v.size(); ++i) s += primal(v[i]) * primal(v[i]);
    using std::sqrt;
    return sqrt(s);
}

template <class V>
bool all_finite(const V& v) {
    using std::isfinite;
    for (Eigen::Index i = 0; i < v.size(); ++i)
        if (!isfinite(v[i])) return false;
    return true;
}

template <class S>
void check_step_size(S dt, const char* who) {
    using std::isfinite;
    if (!isfinite(primal(dt)) || primal(dt) == 0)
        throw invalid_argument(std::string(who) + ": dt = " + number_text(static_cast<long double>(primal(dt))) +
                               "; expected a finite, non-zero step size");
}

// The shared part of tao_stepper and semiexplicit_stepper: H, the composition, the exact partial flows
// and the evaluation counters.
template <class H, class State>
class extended_flows {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    using extended = extended_state<scalar, State::dimension>;
    using P = primal_scalar<scalar>;

    extended_flows(H h, const table& t, const char* who)
        : h_(std::move(h)), weights_(leapfrog_composition_weights(t, who)) {}

    const H& hamiltonian() const { return h_; }
    int order() const { return weights_.order; }
    const composition_weights& weights() const { return weights_; }
    // dH/dq evaluations (one per partial flow of A or B, reused where the point is unchanged).
    std::uint64_t force_evaluations() const { return evaluations_; }
    // dH/dp evaluations: as many (each partial flow needs both gradients at one point).
    std::uint64_t velocity_evaluations() const { return evaluations_; }
    // |q - x| + |p - y| of the last step (each stepper says of what), and the largest so far.
    P divergence() const { return divergence_; }
    P max_divergence() const { return max_divergence_; }
    std::size_t steps_taken() const { return steps_; }

protected:
    // The composed map: per weight g, A(g dt/2) middle(g dt) A(g dt/2), each
    // A merged with its neighbour into one exact flow.
    template <class Middle>
    void compose(extended& z, P dt, bool& cached, Middle middle) {
        const auto& g = weights_.gamma;
        P pending_A = P(g.front()) / 2 * dt;
        for (std::size_t i = 0; i < g.size(); ++i) {
            const P h = P(g[i]) * dt;
            flow_A(z, pending_A, cached);
            middle(h);
            pending_A = h / 2 + (i + 1 < g.size() ? P(g[i + 1]) / 2 * dt : P(0));
        }
        flow_A(z, pending_A, cached);
    }

    // Names the step about to be counted, for error messages.
    std::string where(P t_end, P dt) const {
        return "step " + std::to_string(steps_ + 1) + " (t = " + number_text(t_end) + " at its end, dt = " +
               number_text(dt) + ")";
    }
    void count_step(P divergence, P dt) {
        divergence_ = divergence;
        max_divergence_ = std::max(max_divergence_, divergence);
        ++steps_;
        elapsed_ += dt;
    }

    // phi_A(t): the flow of H(q, y); q, y fixed. `cached`: the gradients at
    // this (q, y) are still in gq_, gp_ from the last phi_A.
    void flow_A(extended& z, P t, bool& cached) {
        if (!cached) {
            sympl::dH_dq(h_, z.q, z.y, gq_);
            sympl::dH_dp(h_, z.q, z.y, gp_);
            ++evaluations_;
        }
        z.p -= scalar(t) * gq_;
        z.x += scalar(t) * gp_;
        cached = true;
    }
    // phi_B(t): the flow of H(x, p); x, p fixed.
    void flow_B(extended& z, P t, bool& cached) {
        sympl::dH_dq(h_, z.x, z.p, gq_);
        sympl::dH_dp(h_, z.x, z.p, gp_);
        ++evaluations_;
        z.q += scalar(t) * gp_;
        z.y -= scalar(t) * gq_;
        cached = false;
    }

    H h_;
    composition_weights weights_;
    vector gq_, gp_;
    std::uint64_t evaluations_ = 0;
    std::size_t steps_ = 0;
    P elapsed_ = 0, divergence_ = 0, max_divergence_ = 0;
};
}  // namespace detail

// ---- Tao 2016 ------------------------------------------------------------------

// Tao's explicit method of any even order, over a state of the original phase
// space; the second copy (x, y) is kept inside and carried from step to step
// as long as the state handed in is the one the last step returned (otherwise
// both copies restart at the state). The result is the first copy (q, p).
template <class H, class State>
    requires general_hamiltonian<H, typename State::vector>
class tao_stepper : public detail::extended_flows<H, State> {
    using base = detail::extended_flows<H, State>;
    using typename base::P;

public:
    using typename base::extended, typename base::scalar, typename base::state_type, typename base::vector;

    tao_stepper(H h, const table& t, tao_options o = {}) : base(std::move(h), t, "tao_stepper"), options_(o) {
        using std::isfinite;
        if (!isfinite(o.omega) || !(o.omega > 0))
            throw invalid_argument("tao_stepper: omega = " + detail::number_text(o.omega) +
                                   "; expected a finite binding frequency > 0 (Tao 2016 uses 20)");
        if (!isfinite(o.momentum_scale) || !(o.momentum_scale > 0))
            throw invalid_argument("tao_stepper: momentum_scale = " + detail::number_text(o.momentum_scale) +
                                   "; expected a finite momentum per position > 0 (1: Tao's binding)");
        for (const double k : o.momentum_scales)
            if (!isfinite(k) || !(k > 0))
                throw invalid_argument("tao_stepper: momentum_scales holds " + detail::number_text(k) +
                                       "; expected finite momenta per position > 0");
        if (!isfinite(o.divergence_limit) || !(o.divergence_limit > 0))
            throw invalid_argument("tao_stepper: divergence_limit = " + detail::number_text(o.divergence_limit) +
                                   "; expected a finite relative limit > 0 (default 0.1)");
    }

    double omega() const { return options_.omega; }
    // divergence(), max_divergence() and steps_taken() count from when the copies were made.
    const extended& extended_point() const { return z_; }

    // Forget the second copy: the next step starts both copies at its state.
    void reset() { bound_ = false; }

    // One step; on a lost binding or a non-finite value x is left as it was and
    // integration_error names the step, the time, the divergence and omega.
    // Times in its messages count from when the copies were made.
    void step(state_type& x, scalar dt) { advance(x, dt, nullptr); }
    // The same with the time at the start of the step (the drivers of fixed_step.hpp call this one).
    void step(state_type& x, scalar t, scalar dt) {
        const P t0 = primal(t);
        advance(x, dt, &t0);
    }

    // What the stepper carries between steps (the second copy and the state
    // it returned last, the gradients kept, its step count and divergences):
    // a stepper of the same H, table and options given restore_carried(carried())
    // and handed that state goes on bit for bit (a checkpoint). Restored in
    // place (carried_in_place.hpp): the stepper holds the caller's H.
    std::vector<scalar> carried() const
        requires std::is_floating_point_v<scalar>
    {
        return detail::carried_list<scalar>(*this);
    }
    void restore_carried(std::span<const scalar> values)
        requires std::is_floating_point_v<scalar>
    {
        detail::restore_carried_in_place<scalar>(*this, values, "tao_stepper");
    }
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        auto& z = self.z_;
        auto& last = self.last_;
        l.flag(self.bound_);
        l.flag(self.cached_);
        for (auto* v : {&z.q, &z.p, &z.x, &z.y, &last.q, &last.p, &self.gq_, &self.gp_}) l.numbers(*v);
        l.whole(self.steps_, "holds a bad step count");
        for (auto* v : {&self.elapsed_, &self.divergence_, &self.max_divergence_}) l.number(*v);
        for (auto* v : {&z.p, &z.x, &z.y, &last.q, &last.p})
            l.check(v->size() == z.q.size(), "holds copies of different sizes");
    }

    // One step of the map in the extended phase space, no checks (for
    // measuring it, e.g. its symplecticity there).
    void step_extended(extended& z, scalar dt) {
        detail::check_step_size(dt, "tao_stepper");
        bool cached = false;
        map(z, primal(dt), cached);
    }

private:
    // Tao 2016's second-order map, composed: A(g/2) B(g/2) C(g) B(g/2) A(g/2) per weight g,
    // neighbouring A's merged (one exact flow), the first A reusing the last
    // A's gradients when the copies carry over (q and y have not moved since).
    void map(extended& z, P dt, bool& cached) {
        this->compose(z, dt, cached, [&](P h) {
            this->flow_B(z, h / 2, cached);
            flow_C(z, h);
            this->flow_B(z, h / 2, cached);
        });
    }

    // phi_C(t) of omega * H_C: the difference of the copies rotated by 2 omega t,
    // their sum fixed (Tao 2016).
    void flow_C(extended& z, P t) {
        using std::cos;
        using std::sin;
        const P angle = 2 * P(options_.omega) * t;
        const P c = cos(angle), s = sin(angle);
        for (Eigen::Index k = 0; k < z.q.size(); ++k) {
            // The differences in units where the binding is Tao's: sqrt(kappa) dq, dp / sqrt(kappa).
            const P root = root_kappa(k);
            const scalar sum_q = z.q[k] + z.x[k], sum_p = z.p[k] + z.y[k];
            const scalar dq = scalar(root) * (z.q[k] - z.x[k]), dp = (z.p[k] - z.y[k]) / scalar(root);
            const scalar rq = (scalar(c) * dq + scalar(s) * dp) / scalar(root);
            const scalar rp = scalar(root) * (scalar(c) * dp - scalar(s) * dq);
            z.q[k] = (sum_q + rq) / scalar(2);
            z.x[k] = (sum_q - rq) / scalar(2);
            z.p[k] = (sum_p + rp) / scalar(2);
            z.y[k] = (sum_p - rp) / scalar(2);
        }
    }
    P root_kappa(Eigen::Index k) const {
        using std::sqrt;
        return sqrt(P(options_.momentum_scales.empty() ? options_.momentum_scale : options_.momentum_scales[k]));
    }
    // sqrt(sum_k kappa_k a_k^2) and sqrt(sum_k b_k^2 / kappa_k): the norms in the binding's units.
    template <class V>
    P kappa_norm(const V& a, bool momentum) const {
        P sum = 0;
        for (Eigen::Index k = 0; k < a.size(); ++k) {
            const P r = root_kappa(k), v = primal(a[k]) * (momentum ? 1 / r : r);
            sum += v * v;
        }
        using std::sqrt;
        return sqrt(sum);
    }

    void advance(state_type& x, scalar dt, const P* t_start) {
        detail::check_step_size(dt, "tao_stepper");
        check_reads_once(this->h_, x, "tao_stepper");
        if (!options_.momentum_scales.empty() && Eigen::Index(options_.momentum_scales.size()) != x.q.size())
            throw invalid_argument("tao_stepper: momentum_scales has " + std::to_string(options_.momentum_scales.size()) +
                                   " entries for a state of dimension " + std::to_string(x.q.size()) +
                                   "; expected one per component");
        const bool carry = bound_ && x.q.size() == last_.q.size() && x.q == last_.q && x.p == last_.p;
        extended z = carry ? z_ : extended(x);
        bool cached = carry && cached_;
        if (!carry) {
            this->steps_ = 0;
            this->elapsed_ = 0;
            this->max_divergence_ = 0;
        }
        const P t_end = (t_start ? *t_start : this->elapsed_) + primal(dt);
        map(z, primal(dt), cached);
        const P d = kappa_norm(vector(z.q - z.x), false) + kappa_norm(vector(z.p - z.y), true);
        const P size = 1 + kappa_norm(z.q, false) + kappa_norm(z.p, true);
        using std::isfinite;
        const bool finite = detail::all_finite(z.q) && detail::all_finite(z.p) && detail::all_finite(z.x) &&
                            detail::all_finite(z.y) && isfinite(d);
        if (!finite || d > P(options_.divergence_limit) * size) {
            bound_ = false;
            const std::string at = this->where(t_end, primal(dt));
            if (!finite)
                throw integration_error("tao_stepper: " + at + " produced a non-finite state with omega = " +
                                            detail::number_text(options_.omega) +
                                            "; the state is left at the start of the step",
                                        this->steps_ + 1, double(t_end - primal(dt)));
            throw integration_error(
                "tao_stepper: the copies came apart at " + at + ": |q - x| + |p - y| (in the binding's units) = " + detail::number_text(d) +
                    " > " + detail::number_text(options_.divergence_limit) + " * (1 + |q| + |p|) = " +
                    detail::number_text(P(options_.divergence_limit) * size) + " with omega = " +
                    detail::number_text(options_.omega) +
                    "; expected omega a few times the fastest frequency of H and dt << omega^(-1/order) (Tao 2016); "
                    "the state is left at the start of the step",
                this->steps_ + 1, double(t_end - primal(dt)));
        }
        z_ = std::move(z);
        cached_ = cached;
        bound_ = true;
        this->count_step(d, primal(dt));
        x.q = z_.q;
        x.p = z_.p;
        last_ = x;
    }

    tao_options options_;
    extended z_;
    state_type last_;
    bool bound_ = false, cached_ = false;
};

template <class State, class H>
tao_stepper<H, State> make_tao_stepper(H h, const table& t, tao_options o = {}) {
    return tao_stepper<H, State>(std::move(h), t, o);
}

}  // namespace sympl
