#pragma once
// The Wisdom-Holman splitting of a star and N planets in democratic
// heliocentric coordinates (Wisdom & Holman 1991, Astron. J. 102, 1528, for
// the idea; Duncan, Levison & Lee 1998, Astron. J. 116, 2067, sec. 2, for the
// coordinates and the split), run by any sympl::table.
//
// With heliocentric positions Q_i and barycentric momenta P_i (i = 1..N;
// planetary_coordinates.hpp), Q_0 the centre of mass and P_0 the total
// momentum, M = sum_j m_j, the Hamiltonian of the point masses is
// (Duncan, Levison & Lee 1998, eq. 4-7)
//     H = H_Kepler + H_interaction + H_jump + H_centre,
//     H_Kepler      = sum_i |P_i|^2 / (2 m_i) - G m_0 m_i / |Q_i|
//     H_interaction = - sum_{1 <= i < j} G m_i m_j / |Q_i - Q_j|
//     H_jump        = |sum_i P_i|^2 / (2 m_0)
//     H_centre      = |P_0|^2 / (2 M).
// H_Kepler is N independent Kepler problems about GM = G m_0 (velocity
// v_i = P_i / m_i), solved exactly by kepler_drift_all (kepler_drift.hpp).
// H_interaction (a function of the Q_i alone) is a kick; H_jump (a function
// of the P_i alone) moves every Q_i by the same vector dt sum_j P_j / m_0.
//
// The two commute: {H_interaction, H_jump} = -sum_i F_i . (sum_j P_j) / m_0 = 0
// because the interaction forces F_i are pairwise equal and opposite (sum F_i
// = 0), and the jump moves no Q_i - Q_j. So the flow of
// H_interaction + H_jump over t is exactly the kick by t followed by the jump
// by t, with no splitting error of its own; it is the "kick" of the table.
// (Duncan, Levison & Lee compose jump(h/2) interaction(h/2) Kepler(h)
// interaction(h/2) jump(h/2); by the commutation this is the kick-drift-kick
// leapfrog below, the same map.) H_centre commutes with everything and moves
// Q_0 uniformly; it is applied with each drift.
//
// The roles in a table (table.hpp): drift weights apply to the integrable
// part H_Kepler, kick weights to the perturbation H_interaction + H_jump, as
// Laskar & Robutel 2001 (Celest. Mech. Dyn. Astron. 80, 39) assign A
// (integrable) and B (perturbation) in SABA_n / SBAB_n. With planet masses of
// relative size eps, H_Kepler = O(eps) and the kick O(eps^2), so the leapfrog
// has relative energy error O(eps h^2) and SABA_n / SBAB_n
// O(eps h^(2n) + eps^2 h^2) (Laskar & Robutel 2001). Tables designed for
// T = p^2/2 (RKN) do not keep their extra order here: H_Kepler is not
// quadratic in P, and H_jump is not a function of Q.
//
// State: what the user sees is the inertial layout of
// hamiltonians/outer_solar_system.hpp (q = x_0, y_0, z_0, x_1, ...; p_i = m_i v_i).
// The stepper converts to democratic heliocentric coordinates on the way in
// and back on the way out, and keeps its internal state between calls: when
// step() or steps() is handed exactly the state it returned last, it goes on
// from its internal coordinates (no conversion, no rounding of a round trip,
// and the last interaction forces reused). steps(x, dt, n) also joins a
// step's last sub-step with the next step's first when they are of one kind
// (two kicks, or two Kepler drifts: both flows add), so the leapfrog costs one
// Kepler drift and one interaction evaluation per step.
//
// Bad input is an invalid_argument naming the body: a non-positive or
// non-finite mass, a non-finite coordinate, a planet at the star's position or
// two planets at one position. A state that becomes non-finite during a run
// (a blow-up) is returned as non-finite, as splitting_stepper does, for the
// drivers of integrate.hpp to report.
//
// Not done: the symplectic correctors of Wisdom, Holman & Touma (1996), Jacobi
// coordinates in this stepper, close encounters.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "../core/error.hpp"
#include "../core/phase_space.hpp"
#include "../core/table.hpp"
#include "kepler_drift.hpp"
#include "planetary_coordinates.hpp"

namespace sympl {

template <class State>
    requires phase_space_state<State> && std::is_floating_point_v<typename State::scalar>
class wisdom_holman_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;

    // mass[0] is the star, mass[1..N] the planets (all finite and > 0), G > 0.
    wisdom_holman_stepper(std::vector<double> mass, double G, table method)
        : mass_(std::move(mass)), G_(G), table_(std::move(method)) {
        const std::string who = "wisdom_holman_stepper: ";
        if (mass_.size() < 2)
            throw invalid_argument(who + std::to_string(mass_.size()) +
                                   " masses; expected a star and at least one planet");
        for (std::size_t i = 0; i < mass_.size(); ++i)
            if (!(std::isfinite(mass_[i]) && mass_[i] > 0))
                throw invalid_argument(who + "mass of body " + std::to_string(i) + " = " +
                                       detail::number_text(mass_[i]) + "; expected a finite mass > 0");
        if (!(std::isfinite(G_) && G_ > 0))
            throw invalid_argument(who + "G = " + detail::number_text(G_) + "; expected a finite G > 0");
        if (State::dimension != Eigen::Dynamic && std::size_t(State::dimension) != 3 * mass_.size())
            throw invalid_argument(who + std::to_string(mass_.size()) + " masses for a state of fixed dimension " +
                                   std::to_string(State::dimension) + "; expected 3 degrees of freedom per body");
        if (table_.has_force_gradient())
            throw invalid_argument(who + "table '" + table_.name() +
                                   "' has force-gradient kicks; expected a table of plain kicks and drifts");
        ops_ = table_.substeps();
        for (const substep& o : ops_) weights_.push_back(static_cast<scalar>(o.weight));
        joined_weight_ = static_cast<scalar>(ops_.back().weight + ops_.front().weight);
        joined_ = ops_.size() > 1 && ops_.front().kind == ops_.back().kind;
        const std::size_t n = mass_.size() - 1;
        for (auto* v : {&x_, &y_, &z_, &vx_, &vy_, &vz_, &ax_, &ay_, &az_}) v->assign(n, scalar(0));
        total_mass_ = 0;
        for (double m : mass_) total_mass_ += scalar(m);
        gm_ = scalar(G_) * scalar(mass_[0]);
    }

    // One step of size dt (dt < 0 runs backwards).
    void step(State& x, scalar dt) { steps(x, dt, 1); }

    // n steps of size dt, converted in and out once; a step's last sub-step
    // is joined with the next one's first when they are of one kind.
    void steps(State& x, scalar dt, std::size_t n) {
        if (!std::isfinite(dt) || dt == scalar(0))
            throw invalid_argument("wisdom_holman_stepper: dt = " + detail::number_text(dt) +
                                   "; expected a finite, non-zero step");
        load(x);
        const std::size_t L = ops_.size();
        for (std::size_t k = 0; k < n && finite_; ++k)
            for (std::size_t j = 0; j < L && finite_; ++j) {
                if (joined_ && k > 0 && j == 0) continue;  // done with the previous step's last sub-step
                const scalar w = (joined_ && j == L - 1 && k + 1 < n) ? joined_weight_ : weights_[j];
                if (ops_[j].kind == substep::kick) kick(w * dt);
                else drift(w * dt);
            }
        store(x);
    }

    // Batched Kepler drifts of all planets (one per drift sub-step), and
    // evaluations of the planet-planet interaction.
    std::uint64_t kepler_drifts() const { return kepler_drifts_; }
    std::uint64_t interaction_evaluations() const { return interaction_evaluations_; }
    // The drivers' name (integrate.hpp) for the interaction evaluations.
    std::uint64_t force_evaluations() const { return interaction_evaluations_; }
    // Planets the batched drift left to its scalar solve (kepler_drift_all).
    std::uint64_t kepler_fallbacks() const { return kepler_fallbacks_; }
    void reset_counters() { kepler_drifts_ = interaction_evaluations_ = kepler_fallbacks_ = 0; }

    const table& method() const { return table_; }
    const std::vector<double>& masses() const { return mass_; }
    double G() const { return G_; }

private:
    std::size_t planets() const { return mass_.size() - 1; }

    // The interaction accelerations a_i = sum_{j != i} G m_j (Q_j - Q_i) / |Q_j - Q_i|^3.
    void accelerations() {
        const std::size_t n = planets();
        for (std::size_t i = 0; i < n; ++i) ax_[i] = ay_[i] = az_[i] = 0;
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i + 1; j < n; ++j) {
                const scalar dx = x_[j] - x_[i], dy = y_[j] - y_[i], dz = z_[j] - z_[i];
                const scalar r2 = dx * dx + dy * dy + dz * dz;
                const scalar k = scalar(G_) / (r2 * std::sqrt(r2));
                const scalar ki = k * scalar(mass_[j + 1]), kj = k * scalar(mass_[i + 1]);
                ax_[i] += ki * dx, ay_[i] += ki * dy, az_[i] += ki * dz;
                ax_[j] -= kj * dx, ay_[j] -= kj * dy, az_[j] -= kj * dz;
            }
        ++interaction_evaluations_;
        forces_fresh_ = true;
    }

    // The flow of H_interaction + H_jump over t: kick, then jump (they commute).
    void kick(scalar t) {
        if (!forces_fresh_) accelerations();
        const std::size_t n = planets();
        scalar px = 0, py = 0, pz = 0;
        for (std::size_t i = 0; i < n; ++i) {
            vx_[i] += t * ax_[i], vy_[i] += t * ay_[i], vz_[i] += t * az_[i];
            const scalar m(mass_[i + 1]);
            px += m * vx_[i], py += m * vy_[i], pz += m * vz_[i];
        }
        const scalar s = t / scalar(mass_[0]);
        for (std::size_t i = 0; i < n; ++i) x_[i] += s * px, y_[i] += s * py, z_[i] += s * pz;
        // The jump keeps every Q_i - Q_j (to rounding): the forces stay fresh.
    }

    // The flow of H_Kepler + H_centre over t.
    void drift(scalar t) {
        try {
            kepler_fallbacks_ += kepler_drift_all<scalar>({x_, y_, z_, vx_, vy_, vz_}, gm_, t);
        } catch (const invalid_argument&) {
            // Only a state gone non-finite (or a planet driven into the star)
            // gets here: hand back a non-finite state, as a blow-up.
            finite_ = false;
            for (auto* v : {&x_, &y_, &z_, &vx_, &vy_, &vz_}) v->assign(planets(), std::numeric_limits<scalar>::quiet_NaN());
        }
        centre_ += (t / total_mass_) * momentum_;
        ++kepler_drifts_;
        forces_fresh_ = false;
    }

    static bool same(const State& a, const State& b) {
        return a.size() == b.size() && (a.q.array() == b.q.array()).all() && (a.p.array() == b.p.array()).all();
    }

    void check(const State& x) const {
        const std::string who = "wisdom_holman_stepper: ";
        const std::size_t bodies = mass_.size();
        if (std::size_t(x.size()) != 3 * bodies)
            throw invalid_argument(who + "a state of " + std::to_string(x.size()) + " degrees of freedom for " +
                                   std::to_string(bodies) + " bodies; expected 3 per body, " +
                                   std::to_string(3 * bodies));
        const char* axis[] = {"x", "y", "z"};
        for (std::size_t i = 0; i < bodies; ++i)
            for (int k = 0; k < 3; ++k) {
                const Eigen::Index c = Eigen::Index(3 * i) + k;
                if (!std::isfinite(x.q[c]))
                    throw invalid_argument(who + "position " + axis[k] + " of body " + std::to_string(i) + " = " +
                                           detail::number_text(x.q[c]) + "; expected a finite number");
                if (!std::isfinite(x.p[c]))
                    throw invalid_argument(who + "momentum " + axis[k] + " of body " + std::to_string(i) + " = " +
                                           detail::number_text(x.p[c]) + "; expected a finite number");
            }
        for (std::size_t i = 1; i < bodies; ++i)
            for (std::size_t j = 0; j < i; ++j) {
                const auto d = (x.q.template segment<3>(Eigen::Index(3 * i)) - x.q.template segment<3>(Eigen::Index(3 * j))).eval();
                if (!(d.squaredNorm() > 0))
                    throw invalid_argument(who + "body " + std::to_string(i) + " is at the position of body " +
                                           std::to_string(j) + (j == 0 ? " (the star)" : "") + ", (" +
                                           detail::number_text(x.q[Eigen::Index(3 * i)]) + ", " +
                                           detail::number_text(x.q[Eigen::Index(3 * i) + 1]) + ", " +
                                           detail::number_text(x.q[Eigen::Index(3 * i) + 2]) +
                                           "); expected distinct positions");
            }
    }

    // Inertial -> democratic heliocentric, unless x is what this stepper returned last.
    void load(const State& x) {
        if (loaded_ && same(x, last_)) return;
        check(x);
        const State y = to_democratic_heliocentric(x, std::span<const double>(mass_));
        for (std::size_t i = 0; i < planets(); ++i) {
            const Eigen::Index c = Eigen::Index(3 * (i + 1));
            const scalar m(mass_[i + 1]);
            x_[i] = y.q[c], y_[i] = y.q[c + 1], z_[i] = y.q[c + 2];
            vx_[i] = y.p[c] / m, vy_[i] = y.p[c + 1] / m, vz_[i] = y.p[c + 2] / m;
        }
        centre_ = y.q.template segment<3>(0);
        momentum_ = y.p.template segment<3>(0);
        forces_fresh_ = false;
        finite_ = true;
        loaded_ = true;
    }

    // Democratic heliocentric -> inertial, into x; remembered for the next call.
    void store(State& x) {
        State y = x;
        y.q.template segment<3>(0) = centre_;
        y.p.template segment<3>(0) = momentum_;
        for (std::size_t i = 0; i < planets(); ++i) {
            const Eigen::Index c = Eigen::Index(3 * (i + 1));
            const scalar m(mass_[i + 1]);
            y.q[c] = x_[i], y.q[c + 1] = y_[i], y.q[c + 2] = z_[i];
            y.p[c] = m * vx_[i], y.p[c + 1] = m * vy_[i], y.p[c + 2] = m * vz_[i];
        }
        x = from_democratic_heliocentric(y, std::span<const double>(mass_));
        last_ = x;
        loaded_ = finite_;
    }

    std::vector<double> mass_;
    double G_;
    table table_;
    std::vector<substep> ops_;
    std::vector<scalar> weights_;
    scalar joined_weight_ = 0;
    bool joined_ = false;
    scalar total_mass_ = 0, gm_ = 0;
    // Planets, structure of arrays: heliocentric Q_i, v_i = P_i / m_i, interaction accelerations.
    std::vector<scalar> x_, y_, z_, vx_, vy_, vz_, ax_, ay_, az_;
    Eigen::Matrix<scalar, 3, 1> centre_ = Eigen::Matrix<scalar, 3, 1>::Zero();
    Eigen::Matrix<scalar, 3, 1> momentum_ = Eigen::Matrix<scalar, 3, 1>::Zero();
    bool forces_fresh_ = false, loaded_ = false, finite_ = true;
    State last_;
    std::uint64_t kepler_drifts_ = 0, interaction_evaluations_ = 0, kepler_fallbacks_ = 0;
};

// The stepper for a system with members `mass` (star first) and `G`, e.g.
// hamiltonians::outer_solar_system: make_wisdom_holman<State>(system, method("saba_2")).
template <class State, class System>
wisdom_holman_stepper<State> make_wisdom_holman(const System& system, table method) {
    return wisdom_holman_stepper<State>(std::vector<double>(std::begin(system.mass), std::end(system.mass)),
                                        double(system.G), std::move(method));
}

}  // namespace sympl
