#pragma once
// The flows a Wisdom-Holman step is made of, on the planets' state in one
// coordinate system (split_coordinates.hpp) held as structure of arrays:
// the kick (interaction, then jump: they commute, Duncan, Levison & Lee 1998,
// AJ 116, 2067, sec. 2), the lazy implementer's kernel in its place (Wisdom,
// Holman & Touma 1996, eq. 10.6), the Kepler drift (kepler_lanes.hpp) and the
// centre of mass's uniform motion. The tangent vector, when started, rides
// along (megno_tangent.hpp). Why the split is what it is: docs/planetary.md.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "../core/carried_state.hpp"
#include "../core/error.hpp"
#include "kernels.hpp"
#include "megno_tangent.hpp"
#include "split_coordinates.hpp"

namespace sympl {

template <class S, class Coordinates>
class wisdom_holman_flows {
public:
    using vector3 = Eigen::Matrix<S, 3, 1>;
    // The planets' coordinates and velocities, and the interaction's
    // accelerations: what the corrector's round trip keeps.
    using planet_state = std::array<std::vector<S>, 9>;
    using kept_type = std::pair<planet_state, bool>;

    wisdom_holman_flows(const std::vector<double>& mass, double G)
        : coords_(mass, G), tangent_(mass.size() - 1) {
        for (auto& v : state_) v.assign(mass.size() - 1, S(0));
        for (auto* v : {&kept_x_, &kept_y_, &kept_z_}) v->assign(mass.size() - 1, S(0));
        for (double m : mass) total_mass_ += S(m);
    }

    // The flow of H_interaction + H_jump over t: kick, then jump (they commute).
    void kick(S t) {
        if (tangent_.on()) tangent_.kick(coords_, x(), y(), z(), t, S(0));
        if (!forces_fresh_) accelerations();
        for (std::size_t i = 0; i < planets(); ++i)
            vx()[i] += t * ax()[i], vy()[i] += t * ay()[i], vz()[i] += t * az()[i];
        // The jump keeps every Q_i - Q_j (to rounding): the forces stay fresh.
        coords_.jump(t, vx(), vy(), vz(), x(), y(), z());
    }

    // The lazy implementer's kernel in place of the leapfrog's kick(t), h the
    // step: the kick by the accelerations at the positions moved by
    // lazy_kernel_displacement h^2 times the accelerations there.
    void lazy_kick(S t, S h) {
        if (tangent_.on()) tangent_.kick(coords_, x(), y(), z(), t, h);
        if (!forces_fresh_) accelerations();
        const S d = static_cast<S>(lazy_kernel_displacement) * h * h;
        for (std::size_t i = 0; i < planets(); ++i) {
            kept_x_[i] = x()[i], kept_y_[i] = y()[i], kept_z_[i] = z()[i];
            x()[i] += d * ax()[i], y()[i] += d * ay()[i], z()[i] += d * az()[i];
        }
        accelerations();
        for (std::size_t i = 0; i < planets(); ++i) {
            x()[i] = kept_x_[i], y()[i] = kept_y_[i], z()[i] = kept_z_[i];
            vx()[i] += t * ax()[i], vy()[i] += t * ay()[i], vz()[i] += t * az()[i];
        }
        forces_fresh_ = false;  // they are the displaced positions'
    }

    // The flow of H_Kepler + H_centre over t.
    void drift(S t) {
        kepler(t);
        centre_ += (t / total_mass_) * momentum_;
    }

    // The flow of H_Kepler over t.
    void kepler(S t) {
        if (tangent_.on() && finite_)
            tangent_.kepler(coords_, {&state_[0], &state_[1], &state_[2], &state_[3], &state_[4], &state_[5]}, t);
        try {
            kepler_fallbacks_ += coords_.kepler({state_[0], state_[1], state_[2], state_[3], state_[4], state_[5]}, t);
        } catch (const invalid_argument&) {
            // Only a state gone non-finite (or a planet driven into the star)
            // gets here: hand back a non-finite state, as a blow-up.
            finite_ = false;
            for (std::size_t k = 0; k < 6; ++k) state_[k].assign(planets(), std::numeric_limits<S>::quiet_NaN());
        }
        ++kepler_drifts_;
        forces_fresh_ = false;
    }

    // From y in these coordinates (Q_0, P_0, then Q_i, P_i per planet).
    template <class State>
    void load(const State& y) {
        for (std::size_t i = 0; i < planets(); ++i) {
            const Eigen::Index c = Eigen::Index(3 * (i + 1));
            const S m = coords_.momentum_mass(i);
            x()[i] = y.q[c], this->y()[i] = y.q[c + 1], z()[i] = y.q[c + 2];
            vx()[i] = y.p[c] / m, vy()[i] = y.p[c + 1] / m, vz()[i] = y.p[c + 2] / m;
        }
        centre_ = y.q.template segment<3>(0);
        momentum_ = y.p.template segment<3>(0);
        forces_fresh_ = false;
        finite_ = true;
    }

    // Into y in these coordinates.
    template <class State>
    void store(State& y) const {
        y.q.template segment<3>(0) = centre_;
        y.p.template segment<3>(0) = momentum_;
        for (std::size_t i = 0; i < planets(); ++i) {
            const Eigen::Index c = Eigen::Index(3 * (i + 1));
            const S m = coords_.momentum_mass(i);
            y.q[c] = state_[0][i], y.q[c + 1] = state_[1][i], y.q[c + 2] = state_[2][i];
            y.p[c] = m * state_[3][i], y.p[c + 1] = m * state_[4][i], y.p[c + 2] = m * state_[5][i];
        }
    }

    // The state and whether its forces are fresh, kept and given back around the corrector.
    kept_type keep() const { return {state_, forces_fresh_}; }
    void restore(kept_type&& kept) {
        state_ = std::move(kept.first);
        forces_fresh_ = kept.second;
    }

    // What the flows carry between steps (the planets' state and forces, the
    // centre of mass, whether the forces and the state are good), for
    // wisdom_holman_stepper::carried(); the tangent is not carried.
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        for (auto& v : self.state_) l.numbers_of_size(v);
        l.numbers(self.centre_);
        l.numbers(self.momentum_);
        l.flag(self.forces_fresh_);
        l.flag(self.finite_);
    }

    const Coordinates& coordinates() const { return coords_; }
    // Q_i, v_i and the accelerations, as the test particles' kicks read them.
    const planet_state& state() const { return state_; }
    planetary_tangent<S>& tangent() { return tangent_; }
    const planetary_tangent<S>& tangent() const { return tangent_; }
    bool finite() const { return finite_; }
    std::uint64_t kepler_drifts() const { return kepler_drifts_; }
    std::uint64_t interaction_evaluations() const { return interaction_evaluations_; }
    std::uint64_t kepler_fallbacks() const { return kepler_fallbacks_; }
    void reset_counters() { kepler_drifts_ = interaction_evaluations_ = kepler_fallbacks_ = 0; }

private:
    std::size_t planets() const { return state_[0].size(); }
    S* x() { return state_[0].data(); }
    S* y() { return state_[1].data(); }
    S* z() { return state_[2].data(); }
    S* vx() { return state_[3].data(); }
    S* vy() { return state_[4].data(); }
    S* vz() { return state_[5].data(); }
    S* ax() { return state_[6].data(); }
    S* ay() { return state_[7].data(); }
    S* az() { return state_[8].data(); }

    void accelerations() {
        coords_.accelerations(x(), y(), z(), ax(), ay(), az());
        ++interaction_evaluations_;
        forces_fresh_ = true;
    }

    Coordinates coords_;
    planet_state state_;  // Q_i, v_i = P_i / momentum_mass(i), interaction accelerations
    std::vector<S> kept_x_, kept_y_, kept_z_;  // positions kept by the lazy kernel
    vector3 centre_ = vector3::Zero(), momentum_ = vector3::Zero();
    S total_mass_ = 0;
    bool forces_fresh_ = false, finite_ = true;
    std::uint64_t kepler_drifts_ = 0, interaction_evaluations_ = 0, kepler_fallbacks_ = 0;
    planetary_tangent<S> tangent_;
};

}  // namespace sympl
