#pragma once
// MEGNO per test particle (Cincotta & Simo 2000, A&AS 147, 205;
// chaos_indicator.hpp): a tangent vector (dQ, dv) per particle, the planets'
// run given, carried by each Kepler drift's exact tangent map
// (kepler_tangent.hpp) and each kick's Jacobian (the particles' field on dual
// numbers, dual.hpp), ln|tangent| sampled at the end of every step; the
// particles' counterpart of megno_tangent.hpp (docs/planetary.md, "Test particles").
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <vector>

#include "../../analysis/chaos_indicator.hpp"
#include "../../core/carried_state.hpp"
#include "../../core/dual.hpp"
#include "../../core/error.hpp"
#include "../kepler/kepler_tangent.hpp"

namespace sympl {

namespace detail {
// v less the elements marked in gone, in order (v untouched when not one per mark).
template <class V>
void remove_marked(V& v, const std::vector<char>& gone) {
    if (v.size() != gone.size()) return;
    std::size_t j = 0;
    for (std::size_t i = 0; i < v.size(); ++i)
        if (!gone[i]) v[j++] = v[i];
    v.resize(j);
}
}  // namespace detail

template <class S>
class test_particle_tangents {
public:
    using dual_t = dual<S, 1>;
    using arrays = std::array<std::vector<S>, 6>;

    // From now on for n particles, each tangent with every component 1 / sqrt(6).
    void start(std::size_t n) {
        for (auto& v : dq_) v.clear();
        megno_.clear(), log_scale_.clear();
        started_ = true;
        resize(n);
        time_ = 0;
    }
    void stop() { started_ = false; }
    bool started() const { return started_; }
    void pause(bool p) { paused_ = p; }
    bool paused() const { return paused_; }
    // Whether the flows carry it now (not while the corrector's change of coordinates runs).
    bool on() const { return started_ && !paused_; }
    // n particles: the new ones start as in start().
    void resize(std::size_t n) {
        const std::size_t old = megno_.size();
        for (auto& v : dq_) v.resize(n, S(1) / std::sqrt(S(6)));
        megno_.resize(n), log_scale_.resize(n, S(0));
        for (std::size_t i = old; i < n; ++i) megno_[i].last_log_norm = 0;
    }
    void remove(const std::vector<char>& gone) {
        for (auto& v : dq_) detail::remove_marked(v, gone);
        detail::remove_marked(megno_, gone), detail::remove_marked(log_scale_, gone);
    }

    // <Y> per particle (NaN before the first sample).
    std::vector<S> megno() const {
        std::vector<S> m;
        for (const auto& a : megno_) m.push_back(a.mean());
        return m;
    }

    // One sample per particle at the end of a step of dt (rescaled past 1e+-200).
    void sample(S dt) {
        time_ += dt;
        for (std::size_t i = 0; i < megno_.size(); ++i) {
            S norm2 = 0;
            for (const auto& v : dq_) norm2 += v[i] * v[i];
            megno_[i].add(time_, log_scale_[i] + std::log(norm2) / 2);
            if (norm2 > S(1e200) || norm2 < S(1e-200)) {
                const S f = 1 / std::sqrt(norm2);
                for (auto& v : dq_) v[i] *= f;
                log_scale_[i] += std::log(norm2) / 2;
            }
        }
    }

    // Over a Kepler drift of t about gm from the particles' state q (Q, v)
    // before it (a drift the tangent map refuses leaves a NaN tangent).
    void kepler(const arrays& q, S gm, S t) {
        for (std::size_t i = 0; i < megno_.size(); ++i) {
            const S r[3] = {q[0][i], q[1][i], q[2][i]}, v[3] = {q[3][i], q[4][i], q[5][i]};
            S dr[3] = {dq_[0][i], dq_[1][i], dq_[2][i]}, dv[3] = {dq_[3][i], dq_[4][i], dq_[5][i]};
            try {
                kepler_drift_tangent(r, v, dr, dv, gm, t);
            } catch (const invalid_argument&) {
                for (int c = 0; c < 3; ++c) dr[c] = dv[c] = std::numeric_limits<S>::quiet_NaN();
            }
            for (std::size_t c = 0; c < 3; ++c) dq_[c][i] = dr[c], dq_[c + 3][i] = dv[c];
        }
    }

    // Over a kick of t at the particles' positions q: dv += t J dQ, J the
    // Jacobian of field(x, a, moved) (the acceleration a at dual positions
    // x); with move != 0 (the lazy kernel) at x + move a(x), field(.., true).
    template <class Field>
    void kick(const arrays& q, S t, S move, Field&& field) {
        for (std::size_t i = 0; i < megno_.size(); ++i) {
            dual_t x[3], a[3];
            for (std::size_t c = 0; c < 3; ++c) x[c] = dual_t(q[c][i]), x[c].grad[0] = dq_[c][i];
            field(x, a, false);
            if (move != S(0)) {
                for (std::size_t c = 0; c < 3; ++c) x[c] += move * a[c];
                field(x, a, true);
            }
            for (std::size_t c = 0; c < 3; ++c) dq_[c + 3][i] += t * a[c].grad[0];
        }
    }

    // What the tangents carry between steps (a checkpoint): on or not, the
    // time, and per particle the tangent, its scale and MEGNO's sums.
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.flag(self.started_);
        l.number(self.time_);
        for (auto& v : self.dq_) l.numbers(v);
        l.numbers(self.log_scale_);
        std::size_t n = self.megno_.size();
        l.whole(n, "holds a MEGNO count unlike its tangents'");
        l.check(n == self.log_scale_.size(), "holds a MEGNO count unlike its tangents'");
        if constexpr (!std::is_const_v<Self>) self.megno_.assign(n, {});
        for (auto& a : self.megno_) {
            for (auto* v : {&a.weighted_growth, &a.sum_y, &a.last_log_norm, &a.y}) l.number(*v);
            l.whole(a.samples, "holds a bad MEGNO sample count");
        }
        for (const auto& v : self.dq_) l.check(v.size() == self.megno_.size(), "holds tangents of unequal lengths");
    }
    // Particles with a tangent.
    std::size_t size() const { return megno_.size(); }

private:
    arrays dq_;  // (dQ, dv) per particle
    std::vector<megno_accumulator<S>> megno_;
    std::vector<S> log_scale_;
    S time_ = 0;
    bool started_ = false, paused_ = false;
};

}  // namespace sympl
