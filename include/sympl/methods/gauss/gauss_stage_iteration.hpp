#pragma once
// The stage equations of the s-stage Gauss-Legendre method (gauss_collocation.hpp)
//     Z_i = dt sum_j a_ij f(y0 + Z_j),   f(y) = (dH/dp, -dH/dq),
// and one attempt at solving them (GNI sec. VIII.6): the starting values
// (Euler's, or the last step's polynomial extrapolated: gauss_tableau.hpp),
// fixed-point or simplified Newton iteration (gauss_newton.hpp), and the stop
// when the correction, scaled componentwise by atol + rtol |y|, is below 1 or
// stops decreasing at the rounding plateau; then the update y1 = y0 + sum_i d_i Z_i.
// Which attempts a step makes, and what it carries, is the stepper's.
// The rules, their reasons and measurements: docs/nonseparable.md.
#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>

#include <Eigen/Core>

#include "../../core/dual.hpp"
#include "../../core/error.hpp"
#include "../../core/general_hamiltonian.hpp"
#include "../../core/hamiltonian.hpp"
#include "../../core/phase_space.hpp"
#include "gauss_newton.hpp"
#include "gauss_options.hpp"
#include "gauss_tableau.hpp"

namespace sympl::detail {

template <class H, class State>
    requires phase_space_state<State> && gauss_collocation_system<H, typename State::vector>
class gauss_stage_iteration {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    using real = real_of<scalar>;  // the plain floating-point type under scalar
    using system_type =
        std::conditional_t<general_hamiltonian<H, vector>, H, separable_as_general<H>>;

protected:
    gauss_stage_iteration(H hamiltonian, int stages, gauss_options options)
        : h_(wrap(std::move(hamiltonian))), tableau_(gauss_legendre_tableau(stages)), options_(options) {
        rtol_ = checked_relative_tolerance(options_, double(std::numeric_limits<real>::epsilon()));
        for (int i = 0; i < tableau_.stages; ++i) {
            c_[i] = real(tableau_.c[i]);
            d_[i] = real(tableau_.d[i]);
            for (int j = 0; j < tableau_.stages; ++j) a_[i][j] = real(tableau_.a[i][j]);
        }
        if constexpr (State::dimension != Eigen::Dynamic) size_workspace(State::dimension);
    }

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
        size_scratch(n);
        z_.setZero(2 * n, tableau_.stages);  // zeros only so that carried() before a step writes numbers
        compensation_.setZero(2 * n);
    }
    // All but the stage values and the compensation (which a carried list restores).
    void size_scratch(Eigen::Index n) {
        n_ = n;
        const int s = tableau_.stages;
        newton_.resize(n, s);
        dz_.resize(2 * n, s);
        f_.resize(2 * n, s);
        delta_.resize(2 * n);
        ymax_.resize(2 * n);
        yq_.resize(n);
        yp_.resize(n);
        gq_.resize(n);
        gp_.resize(n);
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
    void start_extrapolated(real h, real h_prev) {
        const real r = h / h_prev;
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
            const real e = scaled_correction(x, z_, dz_, ymax_, real(rtol_), options_.absolute_tolerance);
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

    system_type h_;
    gauss_tableau tableau_;
    gauss_options options_;
    double rtol_ = 0;
    std::array<real, max_gauss_stages> c_{}, d_{};
    std::array<std::array<real, max_gauss_stages>, max_gauss_stages> a_{}, beta_{};
    real beta_ratio_ = 0;
    Eigen::Index n_ = -1;
    frozen_newton<real, State::dimension> newton_;
    stage_matrix z_, dz_, f_;
    column delta_, compensation_;
    real_column ymax_;
    vector yq_, yp_, gq_, gp_;
    std::uint64_t dH_dq_evaluations_ = 0, dH_dp_evaluations_ = 0, iterations_ = 0;
};

}  // namespace sympl::detail
