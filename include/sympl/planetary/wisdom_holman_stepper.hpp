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
// integrate.hpp to report.
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
#include "encounters.hpp"
#include "split_coordinates.hpp"
#include "test_particles.hpp"
#include "wisdom_holman_flows.hpp"
#include "wisdom_holman_plan.hpp"

namespace sympl {

template <class State>
    requires phase_space_state<State> && std::is_floating_point_v<typename State::scalar>
class wisdom_holman_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    // The tangent vector rides as the derivative part of these (MEGNO).
    using tangent_scalar = dual<scalar, 1>;

    // mass[0] is the star, mass[1..N] the planets (all finite and > 0), G > 0.
    wisdom_holman_stepper(std::vector<double> mass, double G, table method, wisdom_holman_options options = {})
        : mass_(std::move(mass)), G_(G), table_(std::move(method)), options_(options), flows_(make_flows()),
          particle_flows_(make_particle_flows()) {
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
    std::uint64_t kepler_drifts() const { return visit([](auto& f) { return f.kepler_drifts(); }); }
    std::uint64_t interaction_evaluations() const {
        return visit([](auto& f) { return f.interaction_evaluations(); });
    }
    // The drivers' name (integrate.hpp) for the interaction evaluations.
    std::uint64_t force_evaluations() const { return interaction_evaluations(); }
    // Planets the batched drift left to its scalar solve (kepler_drift_all).
    std::uint64_t kepler_fallbacks() const { return visit([](auto& f) { return f.kepler_fallbacks(); }); }
    void reset_counters() {
        std::visit([](auto& f) { f.reset_counters(); }, flows_);
    }

    // MEGNO (Cincotta & Simo 2000; chaos_indicator.hpp) from now on: a
    // tangent vector of the planets' coordinates in the stepper,
    // (dQ_1, dv_1, ..., dQ_N, dv_N), 6N numbers, rides along every drift and
    // kick, and ln|tangent| is sampled at the end of every step. The
    // corrector's C, a change of coordinates, is left out; the centre of mass
    // too. `tangent` empty: every component 1 / sqrt(6N). While it is on,
    // steps() joins no sub-steps across steps, and the tangent's work is not
    // counted in the counters.
    void start_megno(std::span<const scalar> tangent = {}) { tangent_state().start(tangent); }
    void stop_megno() { tangent_state().stop(); }
    // <Y> over the steps since start_megno (NaN before the first), and Y at the last.
    scalar megno() const { return tangent_state().megno(); }
    scalar megno_y() const { return tangent_state().megno_y(); }
    // The tangent vector, in units of exp(tangent_log_scale()) (rescaled past 1e100).
    std::vector<scalar> tangent() const { return tangent_state().values(); }
    scalar tangent_log_scale() const { return tangent_state().log_scale(); }

    // Test particles (test_particles.hpp), in the inertial frame of the
    // state: set, they are loaded with the state at the next call of steps()
    // (the whole system loaded from it), and test_particles() holds them as
    // of the last return. The planets' run is the same, bit for bit, with or
    // without them.
    void set_test_particles(test_particle_set<scalar> particles) {
        detail::check_test_particles(particles, "wisdom_holman_stepper::set_test_particles");
        particles_ = std::move(particles);
        loaded_ = false;
    }
    const test_particle_set<scalar>& test_particles() const { return particles_; }
    // MEGNO per test particle from now on (its tangent vector in the
    // particle's (dQ, dv), the planets' run given); while on, steps() joins
    // no sub-steps across steps. <Y> per particle, in test_particles()'s order.
    void start_test_particle_megno() {
        std::visit([](auto& p) { p.start_megno(); }, particle_flows_);
    }
    void stop_test_particle_megno() {
        std::visit([](auto& p) { p.tangents().stop(); }, particle_flows_);
    }
    std::vector<scalar> test_particle_megno() const {
        return std::visit([](const auto& p) { return p.tangents().megno(); }, particle_flows_);
    }

    // Close encounters and losses of the test particles (encounters.hpp),
    // checked after every step from now on (steps() then joins no sub-steps
    // across steps); the time of the logs runs from `time`, advanced by dt per
    // step. Removed particles leave test_particles() and the MEGNO list.
    void track_encounters(encounter_options options, scalar time = 0) {
        tracker_ = encounter_tracker<scalar>(std::move(options), mass_, G_);
        tracker_.set_time(time);
    }
    const encounter_tracker<scalar>& encounters() const { return tracker_; }
    encounter_tracker<scalar>& encounters() { return tracker_; }

    // Steps per call the drivers of integrate.hpp should take at least: C
    // (4K Kepler drifts and 4K - 1 interactions) is applied at every return,
    // so chunks of 32 (8K / sub-steps per step) steps keep it under 1/32 of
    // the run; 1 without a corrector.
    std::size_t steps_per_check() const {
        const std::size_t per_step = std::max<std::size_t>(1, ops_.size() - (joined_ ? 1 : 0));
        return corrector_weights_.empty() ? 1 : 32 * 8 * corrector_weights_.size() / per_step + 1;
    }

    // What the stepper carries between calls: its own coordinates and last
    // forces, the state it returned last and the dt of its C^-1. A stepper of
    // the same masses, G, table and options given restore_carried(carried())
    // and handed that state goes on bit for bit (a checkpoint), test
    // particles and their MEGNO included (the planets' MEGNO tangent is not carried).
    std::vector<scalar> carried() const {
        std::vector<scalar> out;
        detail::carried_writer<scalar> w{out};
        w.flag(loaded_);
        w.number(corrected_dt_);
        w.numbers(last_.q);
        w.numbers(last_.p);
        visit([&](const auto& f) { f.write_carried(w); });
        // The test particles: as of the last return (inertial) and in the flows.
        for (const auto* v : particles_.parts()) w.numbers(*v);
        w.number(scalar(particles_.id.size()));
        for (std::uint64_t i : particles_.id) w.number(scalar(i));
        std::visit([&](const auto& p) { p.write_carried(w); }, particle_flows_);
        return out;
    }
    void restore_carried(std::span<const scalar> values) {
        detail::carried_reader<scalar> r{values, "wisdom_holman_stepper"};
        const bool loaded = r.flag();
        const scalar corrected_dt = r.number();
        State last;
        r.numbers(last.q);
        r.numbers(last.p);
        if (last.q.size() != last.p.size() || (loaded && std::size_t(last.q.size()) != 3 * mass_.size()))
            r.refuse("holds a state of another size than the bodies'");
        flows_type flows = flows_;  // the stepper untouched by a list that does not fit
        std::visit([&](auto& f) { f.read_carried(r); }, flows);
        test_particle_set<scalar> particles;
        for (auto* v : particles.parts()) r.numbers(*v);
        test_particle_flows<scalar, democratic_heliocentric_coordinates<scalar>>::read_ids(r, particles.id);
        for (const auto* v : particles.parts())
            if (v->size() != particles.id.size()) r.refuse("holds test particles of unequal lengths");
        particle_flows_type particle_flows = particle_flows_;
        std::visit([&](auto& p) { p.read_carried(r); }, particle_flows);
        r.done();
        flows_ = std::move(flows);
        particles_ = std::move(particles);
        particle_flows_ = std::move(particle_flows);
        loaded_ = loaded;
        corrected_dt_ = corrected_dt;
        last_ = std::move(last);
    }

    const table& method() const { return table_; }
    const wisdom_holman_options& options() const { return options_; }
    const std::vector<double>& masses() const { return mass_; }
    double G() const { return G_; }

private:
    using democratic_flows = wisdom_holman_flows<scalar, democratic_heliocentric_coordinates<scalar>>;
    using jacobi_flows = wisdom_holman_flows<scalar, jacobi_coordinates<scalar>>;
    using flows_type = std::variant<democratic_flows, jacobi_flows>;
    using particle_flows_type = std::variant<test_particle_flows<scalar, democratic_heliocentric_coordinates<scalar>>,
                                             test_particle_flows<scalar, jacobi_coordinates<scalar>>>;

    // The masses, G and the state's dimension checked, and the coordinates chosen: once.
    flows_type make_flows() const {
        const std::string who = "wisdom_holman_stepper";
        detail::check_masses(mass_, who);
        if (!(std::isfinite(G_) && G_ > 0))
            throw invalid_argument(who + ": G = " + detail::number_text(G_) + "; expected a finite G > 0");
        if (State::dimension != Eigen::Dynamic && std::size_t(State::dimension) != 3 * mass_.size())
            throw invalid_argument(who + ": " + std::to_string(mass_.size()) +
                                   " masses for a state of fixed dimension " + std::to_string(State::dimension) +
                                   "; expected 3 degrees of freedom per body");
        plan_wisdom_holman(table_, options_, who);  // refuses what does not fit, before any work
        if (options_.coordinates == wh_coordinates::jacobi)
            return flows_type(std::in_place_type<jacobi_flows>, mass_, G_);
        return flows_type(std::in_place_type<democratic_flows>, mass_, G_);
    }

    particle_flows_type make_particle_flows() const {
        if (options_.coordinates == wh_coordinates::jacobi)
            return particle_flows_type(std::in_place_index<1>, mass_, G_);
        return particle_flows_type(std::in_place_index<0>, mass_, G_);
    }
    // The test particles' flows in the coordinates of `flows`, and both together.
    template <class Flows>
    auto& particles_of(Flows&) {
        using coordinates = std::decay_t<decltype(std::declval<Flows&>().coordinates())>;
        return std::get<test_particle_flows<scalar, coordinates>>(particle_flows_);
    }
    template <class Flows>
    auto with_particles(Flows& flows) {
        auto& p = particles_of(flows);
        return with_test_particles<Flows, std::decay_t<decltype(p)>, scalar>{flows, p};
    }

    template <class F>
    auto visit(F f) const {
        return std::visit(f, flows_);
    }
    planetary_tangent<scalar>& tangent_state() {
        return std::visit([](auto& f) -> planetary_tangent<scalar>& { return f.tangent(); }, flows_);
    }
    const planetary_tangent<scalar>& tangent_state() const {
        return std::visit([](auto& f) -> const planetary_tangent<scalar>& { return f.tangent(); }, flows_);
    }

    // The steps themselves, in the coordinates chosen at construction.
    template <class Flows>
    void run(Flows& flows, State& x, scalar dt, std::size_t n) {
        load(flows, x, dt);
        const std::size_t L = ops_.size();
        auto both = with_particles(flows);
        auto& particles = particles_of(flows);
        // With MEGNO on, every step ends at its own end, where it is sampled.
        const bool megno = flows.tangent().started(), particles_megno = particles.tangents().started();
        const bool join = joined_ && !megno && !particles_megno && !tracker_.on();
        if (tracker_.on()) {
            particles.bodies(flows.state(), bodies_);
            tracker_.begin(particles.state(), bodies_);
        }
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
            if (tracker_.on() && flows.finite()) {
                particles.bodies(flows.state(), bodies_);
                tracker_.after_step(particles.state(), bodies_, particles.id(), dt, gone_);
                if (std::find(gone_.begin(), gone_.end(), char(1)) != gone_.end()) particles.remove(gone_);
            }
        }
        store(flows, x, dt);
    }

    // C (direction +1) or C^-1 (-1); a change of coordinates, not part of the
    // run: the tangent stays.
    template <class Flows>
    void correct(Flows& flows, int direction, scalar dt) {
        auto& particles = particles_of(flows);
        const bool paused = flows.tangent().paused(), particles_paused = particles.tangents().paused();
        flows.tangent().pause(true);
        particles.tangents().pause(true);
        auto both = with_particles(flows);
        apply_corrector(both, corrector_weights_, direction, dt);
        flows.tangent().pause(paused);
        particles.tangents().pause(particles_paused);
    }

    static bool same(const State& a, const State& b) {
        return a.size() == b.size() && (a.q.array() == b.q.array()).all() && (a.p.array() == b.p.array()).all();
    }

    // Inertial -> the chosen coordinates, unless x is what this stepper
    // returned last (and, with a corrector, for steps of the same dt), then
    // C^-1 into the leapfrog's coordinates.
    template <class Flows>
    void load(Flows& flows, const State& x, scalar dt) {
        if (loaded_ && same(x, last_) && (corrector_weights_.empty() || dt == corrected_dt_)) return;
        detail::checked_finite_bodies(x, mass_, "wisdom_holman_stepper");
        flows.load(flows.coordinates().split(x));
        particles_of(flows).load(x, particles_);
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
        auto& particles = particles_of(flows);
        auto kept = corrected ? flows.keep() : typename Flows::kept_type{};
        auto kept_particles = corrected ? particles.keep() : decltype(particles.keep()){};
        if (corrected) correct(flows, +1, dt);
        State y = x;
        flows.store(y);
        x = flows.coordinates().join(y);
        particles.store(x, particles_);
        last_ = x;
        loaded_ = flows.finite();
        if (corrected) flows.restore(std::move(kept)), particles.restore(std::move(kept_particles));
    }

    std::vector<double> mass_;
    double G_;
    table table_;
    wisdom_holman_options options_;
    flows_type flows_;
    particle_flows_type particle_flows_;
    test_particle_set<scalar> particles_;  // inertial, as of the last return (or as set)
    encounter_tracker<scalar> tracker_;
    std::array<std::vector<scalar>, 6> bodies_;  // the tracker's bodies in the particles' frame
    std::vector<char> gone_;
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
