#pragma once
// What a Wisdom-Holman stepper (wisdom_holman_stepper.hpp) carries for its
// test particles: the set in the inertial frame as of the last return, their
// flows in the coordinates the run chose (test_particles.hpp), their MEGNO,
// and the encounter tracker (encounters.hpp) that logs close approaches and
// removes the particles that collide or leave. Apart from the stepper, so
// that it holds the planets' run and this the passengers' bookkeeping.
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

#include "../../core/carried_state.hpp"
#include "encounters.hpp"
#include "../split_coordinates.hpp"
#include "test_particles.hpp"
#include "../wisdom_holman_plan.hpp"

namespace sympl {

template <class S>
class test_particle_run {
public:
    test_particle_run(const std::vector<double>& mass, double G, wh_coordinates coordinates)
        : mass_(mass), G_(G),
          flows_(coordinates == wh_coordinates::jacobi ? flows_type(std::in_place_index<1>, mass, G)
                                                       : flows_type(std::in_place_index<0>, mass, G)) {}

    void set(test_particle_set<S> particles, const std::string& who) {
        detail::check_test_particles(particles, who);
        particles_ = std::move(particles);
    }
    const test_particle_set<S>& particles() const { return particles_; }

    void start_megno() {
        std::visit([](auto& p) { p.start_megno(); }, flows_);
    }
    void stop_megno() {
        std::visit([](auto& p) { p.tangents().stop(); }, flows_);
    }
    std::vector<S> megno() const {
        return std::visit([](const auto& p) { return p.tangents().megno(); }, flows_);
    }

    void track_encounters(encounter_options options, S time) {
        tracker_ = encounter_tracker<S>(std::move(options), mass_, G_);
        tracker_.set_time(time);
    }
    const encounter_tracker<S>& encounters() const { return tracker_; }
    encounter_tracker<S>& encounters() { return tracker_; }
    bool tracking() const { return tracker_.on(); }

    // The particles' flows in the coordinates of the planets' `Flows`.
    template <class Flows>
    auto& flows_beside(Flows&) {
        using coordinates = std::decay_t<decltype(std::declval<Flows&>().coordinates())>;
        return std::get<test_particle_flows<S, coordinates>>(flows_);
    }

    // The particles loaded from / stored into the set, in the inertial frame
    // of the planets' inertial state x.
    template <class Flows, class State>
    void load(Flows& planets, const State& x) {
        flows_beside(planets).load(x, particles_);
    }
    template <class Flows, class State>
    void store(Flows& planets, const State& x) {
        flows_beside(planets).store(x, particles_);
    }

    // The tracker's first look before a run of steps, and its look after each
    // step: the particles it finds gone are removed (and logged by it). A step
    // whose last kick ran `ahead` past its end (joined with the next step's
    // first) is looked at as it was at its end (test_particle_flows::behind).
    template <class Flows>
    void begin(Flows& planets) {
        if (!tracker_.on()) return;
        auto& particles = flows_beside(planets);
        particles.keep_accelerations(true);
        particles.bodies(planets.state(), bodies_);
        tracker_.begin(particles.state(), bodies_);
    }
    template <class Flows>
    void after_step(Flows& planets, S dt, S ahead = 0) {
        if (!tracker_.on()) return;
        auto& particles = flows_beside(planets);
        if (ahead != 0) {
            particles.behind(planets.state(), ahead, planets_at_end_, at_end_);
            particles.bodies(planets_at_end_, bodies_);
            tracker_.after_step_taking(at_end_, bodies_, particles.id(), dt, gone_);  // at_end_ is scratch
        } else {
            particles.bodies(planets.state(), bodies_);
            tracker_.after_step(particles.state(), bodies_, particles.id(), dt, gone_);
        }
        if (std::find(gone_.begin(), gone_.end(), char(1)) != gone_.end()) particles.remove(gone_);
    }

    // The carried list's part (wisdom_holman_stepper::carried()): the set as
    // of the last return, the flows' particles and MEGNO tangents, and the
    // encounter logs.
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        auto& set = self.particles_;
        for (auto* v : set.parts()) l.numbers(*v);
        detail::carried_ids(l, set.id);
        for (const auto* v : set.parts())
            l.check(v->size() == set.id.size(), "holds test particles of unequal lengths");
        l.part(self.flows_);
        l.part(self.tracker_);
    }

private:
    using flows_type = std::variant<test_particle_flows<S, democratic_heliocentric_coordinates<S>>,
                                    test_particle_flows<S, jacobi_coordinates<S>>>;

    std::vector<double> mass_;
    double G_;
    flows_type flows_;
    test_particle_set<S> particles_;  // inertial, as of the last return (or as set)
    encounter_tracker<S> tracker_;
    std::array<std::vector<S>, 6> bodies_;  // the tracker's bodies in the particles' frame
    std::array<std::vector<S>, 6> planets_at_end_, at_end_;  // a joined step's end (after_step)
    std::vector<char> gone_;
};

}  // namespace sympl
