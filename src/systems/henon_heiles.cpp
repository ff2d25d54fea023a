// The registry entry of the Henon-Heiles system (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/henon_heiles.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry henon_heiles_entry() {
    return {
        .name = "henon_heiles",
        .description = "Henon & Heiles 1964; started on the surface of section q1 = 0 at the given energy",
        .parameters = {of_initial_state({.name = "energy", .value = 1.0 / 6, .low = 0, .high = 1.0 / 6, .low_open = true,
                                         .meaning = "H; bounded motion up to 1/6"}),
                       of_initial_state(any("q2", 0.1, "starting q2")), of_initial_state(any("p2", 0, "starting p2"))},
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {table, dprkn, odeint}, .classic = {"rk4"}, .ensembles = true};
            return runnable<2, own>(hamiltonians::henon_heiles{},
                            stacked(hamiltonians::henon_heiles::initial_state(v.at("energy"), v.at("q2"), v.at("p2"))));
        },
        .period = {"small-oscillation period 2 pi (H = |p|^2/2 + |q|^2/2 + cubic)",
                   [](const parameter_values&) { return two_pi; }},
    };
}

}  // namespace sympl::app
