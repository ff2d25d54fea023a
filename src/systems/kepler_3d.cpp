// The registry entry of the Kepler orbit in space (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/kepler.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry kepler_3d_entry() {
    return {
        .name = "kepler_3d",
        .description = "the Kepler orbit turned into space by the classical angles (mu = 1); exact",
        .parameters = {of_initial_state({.name = "eccentricity", .value = 0.5, .low = 0, .high = 1, .high_open = true,
                                         .meaning = "orbit eccentricity e"}),
                       of_initial_state(any("inclination", 0.3, "rad")),
                       of_initial_state(any("node", 0.5, "longitude of the ascending node, rad")),
                       of_initial_state(any("periapsis", 0.7, "argument of pericentre, rad"))},
        .exact = true,
        .build = [](const parameter_values& v) {
            constexpr compiled own{};  // no built-in scene: every method on the generic path
            const double e = v.at("eccentricity"), i = v.at("inclination"), o = v.at("node"), w = v.at("periapsis");
            return runnable<3, own>(hamiltonians::kepler{}, stacked(hamiltonians::kepler::initial_state_3d(e, i, o, w)),
                            [=](double t) { return stacked(hamiltonians::kepler::exact_state_3d(e, i, o, w, t)); });
        },
        .negative_potential = true,
        .period = {"orbital period 2 pi (a = 1, mu = 1)",
                   [](const parameter_values&) { return two_pi; }},
    };
}

}  // namespace sympl::app
