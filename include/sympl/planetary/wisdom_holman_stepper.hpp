#pragma once
// The Wisdom-Holman splitting of a star and N planets (Wisdom & Holman 1991,
// AJ 102, 1528), run by any sympl::table: drift weights on the Kepler part,
// kick weights on the perturbation, as Laskar & Robutel 2001 (Celest. Mech.
// Dyn. Astron. 80, 39) assign A and B in SABA_n / SBAB_n. In democratic
// heliocentric coordinates (Duncan, Levison & Lee 1998, AJ 116, 2067) or
// Jacobi coordinates, chosen once at construction (split_coordinates.hpp);
// with a symplectic corrector (corrector.hpp), a kernel (kernels.hpp) and
// MEGNO (megno_tangent.hpp), and test particles (test_particles.hpp).
//
// The user's state is inertial, laid out as hamiltonians/outer_solar_system.hpp
// (q = x_0, y_0, z_0, x_1, ...; p_i = m_i v_i). The stepper converts on the way
// in and out and keeps its own state between calls: handed exactly the state
// it returned last, it goes on from its own coordinates (no round trip, the
// last forces reused). steps(x, dt, n) joins a step's last sub-step with the
// next step's first when they are of one kind. With a corrector, C^-1 is
// applied on the way in and C on the way out (WHT96), the uncorrected state
// kept to go on from. The derivation, the error terms and the measurements
// are in docs/planetary.md.
//
// Bad input is an invalid_argument naming the body: a non-positive or
// non-finite mass, a non-finite coordinate, a planet at the star's position or
// two planets at one position. A state that becomes non-finite during a run
// is returned as non-finite, as splitting_stepper does, for the drivers of
// fixed_step.hpp to report.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "../core/carried_state.hpp"
#include "../core/dual.hpp"
#include "../core/error.hpp"
#include "../core/phase_space.hpp"
#include "../core/table.hpp"
#include "coordinates.hpp"
#include "corrector.hpp"
#include "split_coordinates.hpp"
#include "test_particles/test_particle_run.hpp"
#include "test_particles/test_particles.hpp"
#include "wisdom_holman_flows.hpp"
#include "wisdom_holman_plan.hpp"

namespace sympl {

namespace detail {
// A Wisdom-Holman run's bodies and G: finite masses > 0, G > 0, a state of 3
// numbers per body; else invalid_argument. The table is the plan's to check
// (the constructor makes it once).
inline void check_wisdom_holman(const std::vector<double>& mass, double G, long dimension) {
    const std::string who = "wisdom_holman_stepper";
    check_masses(mass, who);
    if (!(std::isfinite(G) && G > 0))
        throw invalid_argument(who + ": G = " + number_text(G) + "; expected a finite G > 0");
    if (dimension != Eigen::Dynamic && std::size_t(dimension) != 3 * mass.size())
        throw invalid_argument(who + ": " + std::to_string(mass.size()) + " masses for a state of fixed dimension " +
                               std::to_string(dimension) + "; expected 3 degrees of freedom per body");
}

// Exactly the same numbers (the state a stepper returned last, handed back).
template <class State>
bool same_state(const State& a, const State& b) {
    return a.size() == b.size() && (a.q.array() == b.q.array()).all() && (a.p.array() == b.p.array()).all();
}
}  // namespace detail

template <class State>
    requires phase_space_state<State> && std::is_floating_point_v<typename State::scalar>
class wisdom_holman_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;

    // mass[0] is the star, mass[1..N] the planets (all finite and > 0), G > 0.
    wisdom_holman_stepper(std::vector<double> mass, double G, table method, wisdom_holman_options options = {})
        : mass_(std::move(mass)), G_(G), table_(std::move(method)), options_(options), flows_(make_flows()),
          test_particles_(mass_, G_, options_.coordinates) {
        const wisdom_holman_plan plan = plan_wisdom_holman(table_, options_, "wisdom_holman_stepper");
        ops_ = plan.substeps;
        lazy_ = plan.lazy_kernel;
        for (coefficient w : plan.corrector) corrector_weights_.push_back(static_cast<scalar>(w));
        for (const substep& o : ops_) weights_.push_back(static_cast<scalar>(o.weight));
        joined_weight_ = static_cast<scalar>(ops_.back().weight + ops_.front().weight);
        joined_ = ops_.size() > 1 && ops_.front().kind == ops_.back().kind;
    }

    // One step of size dt (dt < 0 runs backwards).
    void step(State& x, scalar dt) { steps(x, dt, 1); }

    // n steps of size dt, converted in and out once; a step's last sub-step
    // is joined with the next one's first when they are of one kind.
    void steps(State& x, scalar dt, std::size_t n) {
        if (!std::isfinite(dt) || dt == scalar(0))
            throw invalid_argument("wisdom_holman_stepper: dt = " + detail::number_text(dt) +
                                   "; expected a finite, non-zero step");
        std::visit([&](auto& flows) { run(flows, x, dt, n); }, flows_);
    }

    // Batched Kepler drifts of all planets (one per drift sub-step), and
    // evaluations of the planet-planet interaction.
    std::uint64_t kepler_drifts() const { return std::visit([](auto& f) { return f.kepler_drifts(); }, flows_); }
    std::uint64_t interaction_evaluations() const {
        return std::visit([](auto& f) { return f.interaction_evaluations(); }, flows_);
    }
    // The drivers' name (fixed_step.hpp) for the interaction evaluations.
    std::uint64_t force_evaluations() const { return interaction_evaluations(); }
    // Planets the batched drift left to its scalar solve (kepler_drift_all).
    std::uint64_t kepler_fallbacks() const {
        return std::visit([](auto& f) { return f.kepler_fallbacks(); }, flows_);
    }
    void reset_counters() {
        std::visit([](auto& f) { f.reset_counters(); }, flows_);
    }

    // The planets' MEGNO (Cincotta & Simo 2000) from now on: a tangent
    // (dQ_1, dv_1, ..., dQ_N, dv_N) rides along every drift and kick, sampled
    // at the end of every step, C and the centre of mass left out
    // (docs/planetary.md, "MEGNO"); `tangent` empty: every component 1 / sqrt(6N).
    void start_megno(std::span<const scalar> tangent = {}) { tangent_of(*this).start(tangent); }
    void stop_megno() { tangent_of(*this).stop(); }
    // <Y> over the steps since start_megno (NaN before the first), and Y at the last.
    scalar megno() const { return tangent_of(*this).megno(); }
    scalar megno_y() const { return tangent_of(*this).megno_y(); }
    // The tangent vector, in units of exp(tangent_log_scale()) (rescaled past 1e100).
    std::vector<scalar> tangent() const { return tangent_of(*this).values(); }
    scalar tangent_log_scale() const { return tangent_of(*this).log_scale(); }

    // Test particles (test_particles.hpp), in the inertial frame of the
    // state: set, they are loaded with the state at the next call of steps()
    // (the whole system loaded from it), and test_particles() holds them as
    // of the last return. The planets' run is the same, bit for bit, with or
    // without them.
    void set_test_particles(test_particle_set<scalar> particles) {
        test_particles_.set(std::move(particles), "wisdom_holman_stepper::set_test_particles");
        loaded_ = false;
    }
    const test_particle_set<scalar>& test_particles() const { return test_particles_.particles(); }
    // MEGNO per test particle from now on (its tangent vector in the
    // particle's (dQ, dv), the planets' run given); while on, steps() joins
    // no sub-steps across steps. <Y> per particle, in test_particles()'s order.
    void start_test_particle_megno() { test_particles_.start_megno(); }
    void stop_test_particle_megno() { test_particles_.stop_megno(); }
    std::vector<scalar> test_particle_megno() const { return test_particles_.megno(); }

    // Close encounters and losses of the test particles (encounters.hpp),
    // checked after every step from now on (steps() then joins kicks across
    // steps, not drifts); the time of the logs runs from `time`, advanced by dt
    // per step. Removed particles leave test_particles() and the MEGNO list.
    void track_encounters(encounter_options options, scalar time = 0) {
        test_particles_.track_encounters(std::move(options), time);
    }
    const encounter_tracker<scalar>& encounters() const { return test_particles_.encounters(); }
    encounter_tracker<scalar>& encounters() { return test_particles_.encounters(); }

    // Steps per call the drivers should take at least: C (4K drifts, 4K - 1
    // interactions) at every return kept under 1/32 of the run; 1 without C.
    std::size_t steps_per_check() const {
        const std::size_t per_step = std::max<std::size_t>(1, ops_.size() - (joined_ ? 1 : 0));
        return corrector_weights_.empty() ? 1 : 32 * 8 * corrector_weights_.size() / per_step + 1;
    }

    // What the stepper carries between calls (its coordinates and last forces,
    // the state it returned, the dt of its C^-1, the test particles, their
    // MEGNO and encounter logs; not the planets' tangent): restored, it goes
    // on bit for bit. Read into a copy: a list that does not fit leaves it as it was.
    std::vector<scalar> carried() const { return detail::carried_list<scalar>(*this); }
    void restore_carried(std::span<const scalar> values) {
        detail::restore_carried_list<scalar>(*this, values, "wisdom_holman_stepper");
    }
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.flag(self.loaded_);
        l.number(self.corrected_dt_);
        l.numbers(self.last_.q);
        l.numbers(self.last_.p);
        const std::size_t n = std::size_t(self.last_.q.size());
        l.check(std::size_t(self.last_.p.size()) == n && (!self.loaded_ || n == 3 * self.mass_.size()),
                "holds a state of another size than the bodies'");
        l.part(self.flows_);
        l.part(self.test_particles_);
    }

    const table& method() const { return table_; }
    const wisdom_holman_options& options() const { return options_; }
    const std::vector<double>& masses() const { return mass_; }
    double G() const { return G_; }

private:
    using democratic_flows = wisdom_holman_flows<scalar, democratic_heliocentric_coordinates<scalar>>;
    using jacobi_flows = wisdom_holman_flows<scalar, jacobi_coordinates<scalar>>;
    using flows_type = std::variant<democratic_flows, jacobi_flows>;

    // Everything checked before any work, and the coordinates chosen: once.
    flows_type make_flows() const {
        detail::check_wisdom_holman(mass_, G_, State::dimension);
        if (options_.coordinates == wh_coordinates::jacobi)
            return flows_type(std::in_place_type<jacobi_flows>, mass_, G_);
        return flows_type(std::in_place_type<democratic_flows>, mass_, G_);
    }

    // The planets' flows and the test particles' together.
    template <class Flows>
    auto with_particles(Flows& flows) {
        auto& p = test_particles_.flows_beside(flows);
        return with_test_particles<Flows, std::decay_t<decltype(p)>, scalar>{flows, p};
    }

    template <class Self>
    static auto& tangent_of(Self& self) {
        return std::visit([](auto& f) -> auto& { return f.tangent(); }, self.flows_);
    }

    // The steps themselves, in the coordinates chosen at construction.
    template <class Flows>
    void run(Flows& flows, State& x, scalar dt, std::size_t n) {
        load(flows, x, dt);
        const std::size_t L = ops_.size();
        auto both = with_particles(flows);
        auto& particles = test_particles_.flows_beside(flows);
        // With MEGNO on, every step ends at its own end, where it is sampled.
        const bool megno = flows.tangent().started(), particles_megno = particles.tangents().started();
        // The tracker looks at a step's end behind a joined kick (it is linear
        // in its time); a joined drift it could not look behind so cheaply.
        const bool join = joined_ && !megno && !particles_megno &&
                          (!test_particles_.tracking() || ops_.back().kind == substep::kick);
        test_particles_.begin(flows);
        for (std::size_t k = 0; k < n && flows.finite(); ++k) {
            for (std::size_t j = 0; j < L && flows.finite(); ++j) {
                if (join && k > 0 && j == 0) continue;  // done with the previous step's last sub-step
                const scalar w = (join && j == L - 1 && k + 1 < n) ? joined_weight_ : weights_[j];
                if (ops_[j].kind == substep::kick) {
                    if (lazy_) both.lazy_kick(w * dt, dt);
                    else both.kick(w * dt);
                } else {
                    both.drift(w * dt);
                }
            }
            if (megno && flows.finite()) flows.tangent().sample(dt);
            if (particles_megno && flows.finite()) particles.tangents().sample(dt);
            const scalar ahead = join && k + 1 < n ? weights_.front() * dt : scalar(0);  // the next step's kick
            if (flows.finite()) test_particles_.after_step(flows, dt, ahead);
        }
        store(flows, x, dt);
    }

    // C (direction +1) or C^-1 (-1); a change of coordinates, not part of the
    // run: the tangent stays.
    template <class Flows>
    void correct(Flows& flows, int direction, scalar dt) {
        auto& particles = test_particles_.flows_beside(flows);
        const bool paused = flows.tangent().paused(), particles_paused = particles.tangents().paused();
        flows.tangent().pause(true);
        particles.tangents().pause(true);
        auto both = with_particles(flows);
        apply_corrector(both, corrector_weights_, direction, dt);
        flows.tangent().pause(paused);
        particles.tangents().pause(particles_paused);
    }

    // Inertial -> the chosen coordinates, unless x is what this stepper
    // returned last (and, with a corrector, for steps of the same dt), then
    // C^-1 into the leapfrog's coordinates.
    template <class Flows>
    void load(Flows& flows, const State& x, scalar dt) {
        if (loaded_ && detail::same_state(x, last_) && (corrector_weights_.empty() || dt == corrected_dt_)) return;
        detail::checked_finite_bodies(x, mass_, "wisdom_holman_stepper");
        flows.load(flows.coordinates().split(x));
        test_particles_.load(flows, x);
        loaded_ = true;
        if (!corrector_weights_.empty()) {
            correct(flows, -1, dt);
            corrected_dt_ = dt;
        }
    }

    // C out of the leapfrog's coordinates, back to inertial, into x; x is
    // remembered for the next call, the uncorrected state kept to go on from.
    template <class Flows>
    void store(Flows& flows, State& x, scalar dt) {
        const bool corrected = !corrector_weights_.empty() && flows.finite();
        auto& particles = test_particles_.flows_beside(flows);
        auto kept = corrected ? flows.keep() : typename Flows::kept_type{};
        auto kept_particles = corrected ? particles.keep() : decltype(particles.keep()){};
        if (corrected) correct(flows, +1, dt);
        State y = x;
        flows.store(y);
        x = flows.coordinates().join(y);
        test_particles_.store(flows, x);
        last_ = x;
        loaded_ = flows.finite();
        if (corrected) flows.restore(std::move(kept)), particles.restore(std::move(kept_particles));
    }

    std::vector<double> mass_;
    double G_;
    table table_;
    wisdom_holman_options options_;
    flows_type flows_;
    test_particle_run<scalar> test_particles_;  // and their MEGNO and encounters
    std::vector<scalar> corrector_weights_;  // c_1..c_K, empty without a corrector
    scalar corrected_dt_ = 0;                // the dt of the C^-1 applied at the last load
    std::vector<substep> ops_;
    std::vector<scalar> weights_;
    scalar joined_weight_ = 0;
    bool joined_ = false, lazy_ = false, loaded_ = false;
    State last_;
};

// The stepper for a system with members `mass` (star first) and `G`, e.g.
// hamiltonians::outer_solar_system: make_wisdom_holman<State>(system, method("saba_2")).
template <class State, class System>
wisdom_holman_stepper<State> make_wisdom_holman(const System& system, table method,
                                                wisdom_holman_options options = {}) {
    return wisdom_holman_stepper<State>(std::vector<double>(std::begin(system.mass), std::end(system.mass)),
                                        double(system.G), std::move(method), options);
}

}  // namespace sympl
