#pragma once
// The tangent vector of a Wisdom-Holman run and its MEGNO (Cincotta & Simo
// 2000, A&AS 147, 205; chaos_indicator.hpp): a change (dQ_i, dv_i) of the
// planets' coordinates carried by each Kepler drift's exact tangent map
// (kepler_tangent.hpp) and each kick's Jacobian (the coordinates'
// accelerations evaluated on dual numbers, dual.hpp; the jump's linear move;
// the lazy kernel's displaced positions), so the tangent map of the method
// itself, ln|tangent| sampled at the end of every step (docs/planetary.md, "MEGNO").
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "../analysis/chaos_indicator.hpp"
#include "../core/dual.hpp"
#include "../core/error.hpp"
#include "kepler/kepler_tangent.hpp"
#include "kernels.hpp"

namespace sympl {

template <class S>
class planetary_tangent {
public:
    using dual_t = dual<S, 1>;

    explicit planetary_tangent(std::size_t planets = 0) {
        for (auto* v : {&dx_, &dy_, &dz_, &dvx_, &dvy_, &dvz_}) v->assign(planets, S(0));
        for (auto& v : tq_) v.assign(planets, dual_t(0));
        ta_ = tq_;
    }

    // From now on, from `tangent` ((dQ_1, dv_1, ..., dQ_N, dv_N); empty: every
    // component 1 / sqrt(6N)).
    void start(std::span<const S> tangent) {
        const std::size_t n = dx_.size();
        const std::string who = "wisdom_holman_stepper::start_megno: ";
        if (!tangent.empty() && tangent.size() != 6 * n)
            throw invalid_argument(who + std::to_string(tangent.size()) + " tangent components for " +
                                   std::to_string(n) + " planets; expected 6 per planet (dQ, dv), " +
                                   std::to_string(6 * n));
        S norm2 = 0;
        for (std::size_t i = 0; i < n; ++i) {
            S* parts[] = {&dx_[i], &dy_[i], &dz_[i], &dvx_[i], &dvy_[i], &dvz_[i]};
            for (std::size_t c = 0; c < 6; ++c) {
                *parts[c] = tangent.empty() ? S(1) / std::sqrt(S(6 * n)) : tangent[6 * i + c];
                norm2 += *parts[c] * *parts[c];
            }
        }
        if (!(norm2 > 0) || !std::isfinite(norm2))
            throw invalid_argument(who + "|tangent|^2 = " + detail::number_text(norm2) +
                                   "; expected a finite, non-zero tangent vector");
        megno_ = megno_accumulator<S>{};
        megno_.last_log_norm = std::log(norm2) / 2;
        time_ = 0;
        log_scale_ = 0;
        started_ = true;
    }
    void stop() { started_ = false; }
    bool started() const { return started_; }
    // Whether the flows carry it now (not while the corrector's change of coordinates runs).
    bool on() const { return started_ && !paused_; }
    bool paused() const { return paused_; }
    void pause(bool p) { paused_ = p; }

    S megno() const { return megno_.mean(); }
    S megno_y() const { return megno_.y; }
    S log_scale() const { return log_scale_; }
    std::vector<S> values() const {
        std::vector<S> t;
        for (std::size_t i = 0; i < dx_.size(); ++i)
            for (S c : {dx_[i], dy_[i], dz_[i], dvx_[i], dvy_[i], dvz_[i]}) t.push_back(c);
        return t;
    }

    // One MEGNO sample at the end of a step of dt; rescaled past 1e200 or
    // below 1e-200, the growth kept in log_scale.
    void sample(S dt) {
        S norm2 = 0;
        for (std::size_t i = 0; i < dx_.size(); ++i)
            for (S c : {dx_[i], dy_[i], dz_[i], dvx_[i], dvy_[i], dvz_[i]}) norm2 += c * c;
        time_ += dt;
        megno_.add(time_, log_scale_ + std::log(norm2) / 2);
        if (norm2 > S(1e200) || norm2 < S(1e-200)) {
            const S f = 1 / std::sqrt(norm2);
            for (auto* v : {&dx_, &dy_, &dz_, &dvx_, &dvy_, &dvz_})
                for (S& c : *v) c *= f;
            log_scale_ += std::log(norm2) / 2;
        }
    }

    // The change over a kick of t at positions (x, y, z): dv += t J dQ, J the
    // interaction's Jacobian (lazy_h != 0: at the lazy kernel's displaced
    // positions, along the displaced tangent), then the coordinates' jump.
    template <class Coordinates>
    void kick(Coordinates& coords, const S* x, const S* y, const S* z, S t, S lazy_h) {
        const std::size_t n = dx_.size();
        for (std::size_t i = 0; i < n; ++i) tq_[0][i] = with(x[i], dx_[i]), tq_[1][i] = with(y[i], dy_[i]),
                                            tq_[2][i] = with(z[i], dz_[i]);
        accelerations(coords);
        if (lazy_h != S(0)) {
            const S d = static_cast<S>(lazy_kernel_displacement) * lazy_h * lazy_h;
            for (std::size_t c = 0; c < 3; ++c)
                for (std::size_t i = 0; i < n; ++i) tq_[c][i] += d * ta_[c][i];
            accelerations(coords);
        }
        for (std::size_t i = 0; i < n; ++i)
            dvx_[i] += t * ta_[0][i].grad[0], dvy_[i] += t * ta_[1][i].grad[0], dvz_[i] += t * ta_[2][i].grad[0];
        coords.jump(t, dvx_.data(), dvy_.data(), dvz_.data(), dx_.data(), dy_.data(), dz_.data());
    }

    // The change over a Kepler drift of t from positions x and velocities v
    // (a drift the tangent map refuses leaves a NaN tangent).
    template <class Coordinates>
    void kepler(const Coordinates& coords, const std::array<const std::vector<S>*, 6>& state, S t) {
        for (std::size_t i = 0; i < dx_.size(); ++i) {
            const S r[3] = {(*state[0])[i], (*state[1])[i], (*state[2])[i]};
            const S v[3] = {(*state[3])[i], (*state[4])[i], (*state[5])[i]};
            S dr[3] = {dx_[i], dy_[i], dz_[i]}, dv[3] = {dvx_[i], dvy_[i], dvz_[i]};
            try {
                kepler_drift_tangent(r, v, dr, dv, coords.kepler_gm(i), t);
            } catch (const invalid_argument&) {
                for (int c = 0; c < 3; ++c) dr[c] = dv[c] = std::numeric_limits<S>::quiet_NaN();
            }
            dx_[i] = dr[0], dy_[i] = dr[1], dz_[i] = dr[2], dvx_[i] = dv[0], dvy_[i] = dv[1], dvz_[i] = dv[2];
        }
    }

private:
    static dual_t with(S value, S change) {
        dual_t d(value);
        d.grad[0] = change;
        return d;
    }

    template <class Coordinates>
    void accelerations(Coordinates& coords) {
        coords.accelerations(tq_[0].data(), tq_[1].data(), tq_[2].data(), ta_[0].data(), ta_[1].data(),
                             ta_[2].data());
    }

    std::vector<S> dx_, dy_, dz_, dvx_, dvy_, dvz_;
    std::array<std::vector<dual_t>, 3> tq_, ta_;  // dual positions and accelerations of a kick
    megno_accumulator<S> megno_;
    S time_ = 0, log_scale_ = 0;
    bool started_ = false, paused_ = false;
};

}  // namespace sympl
