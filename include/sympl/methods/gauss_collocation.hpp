#pragma once
// The implicit Gauss-Legendre collocation Runge-Kutta methods with s = 1, 2, 3
// stages (orders 2s = 2, 4, 6; s = 1 is the implicit midpoint rule):
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

#include "../core/carried_state.hpp"
#include "../core/dual.hpp"
#include "../core/error.hpp"
#include "../core/general_hamiltonian.hpp"
#include "../core/hamiltonian.hpp"
#include "../drivers/fixed_step.hpp"
#include "../core/phase_space.hpp"
#include "gauss_newton.hpp"
#include "gauss_options.hpp"
#include "gauss_tableau.hpp"

namespace sympl {

template <class H, class State>
    requires phase_space_state<State> && gauss_collocation_system<H, typename State::vector>
class gauss_collocation_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    using real = detail::real_of<scalar>;  // the plain floating-point type under scalar
    using system_type =
        std::conditional_t<general_hamiltonian<H, vector>, H, separable_as_general<H>>;

    gauss_collocation_stepper(H hamiltonian, int stages, gauss_options options = {})
        : h_(wrap(std::move(hamiltonian))), tableau_(gauss_legendre_tableau(stages)), options_(options) {
        using std::isfinite;
        rtol_ = options_.tolerance ? *options_.tolerance : double(std::numeric_limits<real>::epsilon());
        if (!isfinite(rtol_) || !(rtol_ > 0))
            throw invalid_argument("gauss_collocation_stepper: tolerance = " + detail::number_text(rtol_) +
                                   "; expected a finite tolerance > 0");
        if (options_.absolute_tolerance && (!isfinite(*options_.absolute_tolerance) || *options_.absolute_tolerance < 0))
            throw invalid_argument("gauss_collocation_stepper: absolute_tolerance = " +
                                   detail::number_text(*options_.absolute_tolerance) +
                                   "; expected a finite tolerance >= 0 (or none: rtol times the largest component)");
        if (options_.max_iterations < 1)
            throw invalid_argument("gauss_collocation_stepper: max_iterations = " +
                                   std::to_string(options_.max_iterations) + "; expected at least 1");
        for (int i = 0; i < tableau_.stages; ++i) {
            c_[i] = real(tableau_.c[i]);
            d_[i] = real(tableau_.d[i]);
            for (int j = 0; j < tableau_.stages; ++j) a_[i][j] = real(tableau_.a[i][j]);
        }
        newton_mode_ = options_.iteration == gauss_iteration::newton;
        if constexpr (State::dimension != Eigen::Dynamic) size_workspace(State::dimension);
    }

    // One step of size dt (dt < 0 runs backwards). On integration_error x is unchanged.
    void step(State& x, scalar dt) { advance(x, std::numeric_limits<double>::quiet_NaN(), dt); }
    // The same with the time of the step's start, which only the error reports:
    // integrate.hpp's driver calls this one and adds the step's index.
    void step(State& x, scalar t, scalar dt) { advance(x, double(primal(t)), dt); }
    // Forget the last step's stages: the next step starts from Euler's polynomial.
    void reset() { have_stages_ = false; }

    int stages() const { return tableau_.stages; }
    int order() const { return tableau_.order; }
    const gauss_tableau& tableau() const { return tableau_; }
    double tolerance() const { return rtol_; }
    int max_iterations() const { return options_.max_iterations; }
    // Whether the next step iterates by simplified Newton (automatic: once fixed point contracted slowly).
    bool iterating_by_newton() const { return newton_mode_; }
    // Iterations of the last step's last attempt, and its relative correction
    // max_k |dZ_k| / (atol_k / rtol + |y_k|) (at most tolerance() unless stopped at the plateau).
    int last_iterations() const { return last_iterations_; }
    double last_residual() const { return last_residual_; }

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

    // What the next step reads beyond the state: the last step's stage values
    // and the state they end at, its step size, the iteration's mode, the
    // frozen Newton Jacobian and the update's compensation. A stepper of the
    // same H, stages and options given restore_carried(carried()) and handed
    // that state goes on bit for bit (a checkpoint); the counters are not carried.
    std::vector<scalar> carried() const
        requires std::is_floating_point_v<scalar>
    {
        std::vector<scalar> out;
        detail::carried_writer<scalar> w{out};
        w.flag(have_stages_);
        w.flag(newton_mode_);
        w.number(h_prev_);
        for (const auto* v : {&last_q_, &last_p_}) w.numbers(*v);
        w.numbers(z_);
        w.numbers(compensation_);
        newton_.write_carried(w);
        return out;
    }
    // A list that does not fit is refused by name; one refused past its stage
    // values leaves the stepper as reset() does.
    void restore_carried(std::span<const scalar> values)
        requires std::is_floating_point_v<scalar>
    {
        detail::carried_reader<scalar> r{values, "gauss_collocation_stepper"};
        const bool have = r.flag(), newton = r.flag();
        const real h_prev = r.number();
        vector q, p;
        r.numbers(q);
        r.numbers(p);
        std::vector<scalar> z;
        r.numbers(z);
        column compensation;
        r.numbers(compensation);
        const Eigen::Index n = q.size();
        if (p.size() != n || Eigen::Index(z.size()) != 2 * n * tableau_.stages || compensation.size() != 2 * n)
            r.refuse("holds stage values of another size than its state's");
        size_workspace(n);
        newton_.read_carried(r, a_);
        r.done();
        z_ = Eigen::Map<const Eigen::Matrix<scalar, Eigen::Dynamic, Eigen::Dynamic>>(z.data(), 2 * n, tableau_.stages);
        compensation_ = compensation;
        last_q_ = std::move(q);
        last_p_ = std::move(p);
        h_prev_ = h_prev;
        newton_mode_ = newton;
        have_stages_ = have;
    }

private:
    static constexpr int rows = State::dimension == Eigen::Dynamic ? Eigen::Dynamic : 2 * State::dimension;
    // One column per stage: Z_i = (dq, dp); fixed storage for fixed sizes.
    using stage_matrix = Eigen::Matrix<scalar, rows, Eigen::Dynamic, Eigen::ColMajor, rows, max_gauss_stages>;
    using column = Eigen::Matrix<scalar, rows, 1>;
    using real_column = Eigen::Matrix<real, rows, 1>;

    struct outcome {
        bool converged = false;
        int iterations = 0;
        real correction = 0;  // relative, as last_residual()
        real contraction = 0;  // the mean ratio of successive corrections well above rounding
    };

    static system_type wrap(H h) {
        if constexpr (std::is_same_v<system_type, H>) return h;
        else return system_type{std::move(h)};
    }

    void size_workspace(Eigen::Index n) {
        n_ = n;
        const int s = tableau_.stages;
        newton_.resize(n, s);
        z_.setZero(2 * n, s);  // zeros only so that carried() before a step writes numbers
        dz_.resize(2 * n, s);
        f_.resize(2 * n, s);
        delta_.resize(2 * n);
        compensation_.setZero(2 * n);
        ymax_.resize(2 * n);
        yq_.resize(n);
        yp_.resize(n);
        gq_.resize(n);
        gp_.resize(n);
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
        if (x.size() != n_) size_workspace(x.size());
        const bool continued = have_stages_ && x.q == last_q_ && x.p == last_p_;
        if (!continued) compensation_.setZero();
        // First attempt: the last step's polynomial extrapolated (GNI sec. VIII.6.1)
        // where this step continues it, the current iteration.
        const bool extrapolated = continued && std::fabs(double(h / h_prev_)) <= 4;
        const bool newton = newton_mode_;
        bool fresh_jacobian = false;
        if (extrapolated) start_extrapolated(h);
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

    // The q and p halves of a stage column (fixed sizes known at compile time).
    template <class Col>
    static auto q_half(Col&& c, Eigen::Index n) {
        if constexpr (State::dimension != Eigen::Dynamic) return c.template head<State::dimension>();
        else return c.head(n);
    }
    template <class Col>
    static auto p_half(Col&& c, Eigen::Index n) {
        if constexpr (State::dimension != Eigen::Dynamic) return c.template tail<State::dimension>();
        else return c.tail(n);
    }

    // F_i = f(y0 + Z_i), f = (dH/dp, -dH/dq).
    void evaluate(const State& x) {
        const Eigen::Index n = n_;
        for (int i = 0; i < tableau_.stages; ++i) {
            yq_ = x.q + q_half(z_.col(i), n);
            yp_ = x.p + p_half(z_.col(i), n);
            sympl::dH_dq(h_, yq_, yp_, gq_);
            sympl::dH_dp(h_, yq_, yp_, gp_);
            q_half(f_.col(i), n) = gp_;
            p_half(f_.col(i), n) = -gq_;
        }
        dH_dq_evaluations_ += std::uint64_t(tableau_.stages);
        dH_dp_evaluations_ += std::uint64_t(tableau_.stages);
    }

    // Z_i = c_i dt f(y0), the stage values of Euler's polynomial: one evaluation.
    void start_euler(const State& x, const scalar& dt) {
        const Eigen::Index n = n_;
        sympl::dH_dq(h_, x.q, x.p, gq_);
        sympl::dH_dp(h_, x.q, x.p, gp_);
        ++dH_dq_evaluations_;
        ++dH_dp_evaluations_;
        for (int i = 0; i < tableau_.stages; ++i) {
            q_half(z_.col(i), n) = (dt * scalar(c_[i])) * gp_;
            p_half(z_.col(i), n) = (-dt * scalar(c_[i])) * gq_;
        }
    }

    // Z_i = sum_j beta_ij Z_j of the last step (gauss_tableau.hpp), beta for r = h / h_prev.
    void start_extrapolated(real h) {
        const real r = h / h_prev_;
        if (r != beta_ratio_) {
            const auto beta = gauss_extrapolation(tableau_, (long double)(r));
            for (int i = 0; i < tableau_.stages; ++i)
                for (int j = 0; j < tableau_.stages; ++j) beta_[i][j] = real(beta[i][j]);
            beta_ratio_ = r;
        }
        for (int i = 0; i < tableau_.stages; ++i) {
            dz_.col(i) = scalar(beta_[i][0]) * z_.col(0);
            for (int j = 1; j < tableau_.stages; ++j) dz_.col(i) += scalar(beta_[i][j]) * z_.col(j);
        }
        z_.swap(dz_);
    }

    // The frozen Jacobian (at y0 when `refresh` or none yet) and the factors
    // for this h; returns whether the Jacobian was evaluated here.
    bool prepare_newton(const State& x, real h, const scalar& dt, double t, bool refresh) {
        if (refresh) newton_.jacobian_at(h_, x.q, x.p);
        factor_newton(h, dt, t);
        return refresh;
    }
    void prepare_newton_at(const vector& q, const vector& p, real h, const scalar& dt, double t) {
        newton_.jacobian_at(h_, q, p);
        factor_newton(h, dt, t);
    }
    void factor_newton(real h, const scalar& dt, double t) {
        if (!newton_.factored_for(h)) {
            const Eigen::Index bad = newton_.factor(a_, h);
            if (bad >= 0)
                throw integration_error(
                    "gauss_collocation_stepper: the Newton matrix I - dt A (x) J is singular or not finite at dt = " +
                        detail::number(dt) + " (pivot " + detail::number_text(newton_.pivot(bad)) +
                        "); expected a finite Jacobian of the vector field", 0, t);
        }
    }

    // Iterates from z_ until the correction is within tolerance or stops
    // decreasing at the rounding plateau, at most max_iterations times.
    // refresh_h: refresh the Jacobian at the stages' mean every iteration (the last attempt).
    outcome iterate(const State& x, const scalar& dt, bool newton, real refresh_h = 0, double t = 0) {
        const int s = tableau_.stages;
        const real plateau = real(gauss_rounding_plateau / rtol_);  // in units of the tolerance
        outcome o;
        real previous = std::numeric_limits<real>::infinity(), first = 0, last = 0, best = previous;
        int ratios = 0, since_best = 0;
        while (o.iterations < options_.max_iterations) {
            ++o.iterations;
            ++iterations_;
            evaluate(x);
            // The residual -Z + dt (A (x) I) F: the fixed point's correction, Newton's right-hand side.
            for (int i = 0; i < s; ++i) {
                dz_.col(i) = -z_.col(i);
                for (int j = 0; j < s; ++j) dz_.col(i) += (dt * scalar(a_[i][j])) * f_.col(j);
            }
            if (refresh_h != real(0)) {
                yq_ = x.q + q_half(z_.rowwise().mean(), n_);
                yp_ = x.p + p_half(z_.rowwise().mean(), n_);
                newton_.mark_stale();
                prepare_newton_at(yq_, yp_, refresh_h, dt, t);
            }
            if (newton) {
                Eigen::Map<Eigen::Matrix<scalar, Eigen::Dynamic, 1>> flat(dz_.data(), dz_.size());
                newton_.solve(flat);
            }
            z_ += dz_;
            const real e = scaled_correction(x);
            o.correction = e * real(rtol_);
            if (!(e <= std::numeric_limits<real>::max())) return o;  // not finite: diverged
            // theta, the contraction of this iteration, for choosing the iteration
            // (never for stopping early: what an unconverged iteration leaves is a
            // smooth function of the state, and sums up over the steps as a drift).
            const bool second = o.iterations > 1;
            const real theta = second ? e / previous : real(0);
            if (second && previous > 1024) {  // well above rounding: for the geometric mean of theta
                first = first > 0 ? first : previous;
                last = e;
                ++ratios;
            }
            // Converged: the correction within tolerance and what is left after it,
            // about theta / (1 - theta) times it (Hairer & Wanner, Solving ODEs II,
            // sec. IV.8, eq. (8.10)), below an eighth of it; or at the plateau.
            const bool within = e <= 1 && (!second || (theta < 1 && theta / (1 - theta) * e <= real(0.125)));
            // The plateau: no new smallest correction twice running (a zigzag
            // that still converges makes a new one every other iteration).
            if (e < best) {
                best = e;
                since_best = 0;
            } else {
                ++since_best;
            }
            if (within || (since_best >= 2 && best <= plateau)) {
                o.converged = true;
                break;
            }
            previous = e;
        }
        if (ratios > 0) o.contraction = std::pow(last / first, real(1) / real(ratios));
        return o;
    }

    // max over stages and components of |dZ_ik| / (atol_k + rtol y_k), y_k the
    // largest |component| of y0 and the stages, in units of rtol; a NaN kept.
    real scaled_correction(const State& x) {
        const int s = tableau_.stages;
        const Eigen::Index n = n_;
        real block[2] = {0, 0};
        for (Eigen::Index k = 0; k < 2 * n; ++k) {
            const scalar& y0 = k < n ? x.q[k] : x.p[k - n];
            real y = real(detail::magnitude(y0));
            for (int i = 0; i < s; ++i) y = detail::nan_max(y, real(detail::magnitude(y0 + z_(k, i))));
            ymax_[k] = y;
            block[k >= n] = detail::nan_max(block[k >= n], y);
        }
        const real rtol = real(rtol_);
        real worst = 0;
        for (Eigen::Index k = 0; k < 2 * n; ++k) {
            const real scale = options_.absolute_tolerance ? real(*options_.absolute_tolerance) + rtol * ymax_[k]
                                                           : rtol * (ymax_[k] + block[k >= n]);
            real v = 0;
            for (int i = 0; i < s; ++i) v = detail::nan_max(v, real(detail::magnitude(dz_(k, i))));
            worst = detail::nan_max(worst, scale > 0 ? v / scale : (v == 0 ? real(0) : v / scale));
        }
        return worst;
    }

    // y1 = y0 + sum_i d_i Z_i (GNI sec. VIII.6), Kahan-compensated on request.
    void update(State& x) {
        const Eigen::Index n = n_;
        delta_ = scalar(d_[0]) * z_.col(0);
        for (int i = 1; i < tableau_.stages; ++i) delta_ += scalar(d_[i]) * z_.col(i);
        if (!options_.compensated) {
            x.q += q_half(delta_, n);
            x.p += p_half(delta_, n);
            return;
        }
        for (Eigen::Index k = 0; k < 2 * n; ++k) {
            scalar& y = k < n ? x.q[k] : x.p[k - n];
            const scalar add = delta_[k] - compensation_[k];
            const scalar sum = y + add;
            compensation_[k] = (sum - y) - add;
            y = sum;
        }
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

    system_type h_;
    gauss_tableau tableau_;
    gauss_options options_;
    double rtol_ = 0;
    std::array<real, max_gauss_stages> c_{}, d_{};
    std::array<std::array<real, max_gauss_stages>, max_gauss_stages> a_{}, beta_{};
    real beta_ratio_ = 0, h_prev_ = 0;
    Eigen::Index n_ = -1;
    detail::frozen_newton<real, State::dimension> newton_;
    stage_matrix z_, dz_, f_;
    column delta_, compensation_;
    real_column ymax_;
    vector yq_, yp_, gq_, gp_, last_q_, last_p_;
    bool have_stages_ = false, newton_mode_ = false;
    int last_iterations_ = 0;
    double last_residual_ = 0;
    std::uint64_t dH_dq_evaluations_ = 0, dH_dp_evaluations_ = 0, iterations_ = 0;
};

// Deduction helper: make_gauss_collocation<State>(h, 3) is the 6th-order method.
template <class State, class H>
gauss_collocation_stepper<H, State> make_gauss_collocation(H h, int stages, gauss_options options = {}) {
    return gauss_collocation_stepper<H, State>(std::move(h), stages, options);
}

}  // namespace sympl
