// The registry entry of the outer solar system (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/outer_solar_system.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry outer_solar_system_entry() {
    return {
        .name = "outer_solar_system",
        .description = "Sun and the five outer planets (Hairer, Lubich & Wanner, GNI Table 2.2); days, AU",
        .build = [](const parameter_values&) {
            using enum method_kind;
            constexpr compiled own{.kinds = {table, logh, odeint, wisdom_holman}, .classic = {"rk4"}, .extrapolated = true};
            const hamiltonians::outer_solar_system h{};
            return runnable<hamiltonians::outer_solar_system::dimension, own>(h, stacked(h.initial_state()));
        },
        .negative_potential = true,
        .period = {"Jupiter's orbital period, 4332.59 days (NASA planetary fact sheet)",
                   [](const parameter_values&) { return 4332.59; }},
        .coordinate_names = {"sun_x", "sun_y", "sun_z",
                             "jupiter_x", "jupiter_y", "jupiter_z",
                             "saturn_x", "saturn_y", "saturn_z",
                             "uranus_x", "uranus_y", "uranus_z",
                             "neptune_x", "neptune_y", "neptune_z",
                             "pluto_x", "pluto_y", "pluto_z"},
    };
}

}  // namespace sympl::app
