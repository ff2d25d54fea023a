// The registry entry of two particles on a spring (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/two_particle_spring.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry two_particle_spring_entry() {
    return {
        .name = "two_particle_spring",
        .description = "two particles joined by a spring (Gould & Tobochnik eq. 3.72); exact",
        .parameters = {positive("mass", 1, "each particle's mass"), positive("stiffness", 1, "spring constant k")},
        .exact = true,
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {table, odeint}, .classic = {"rk4"}};
            const hamiltonians::two_particle_spring h{v.at("mass"), v.at("stiffness")};
            return runnable<4, own>(h, stacked(hamiltonians::two_particle_spring::initial_state()),
                            exact_flow(h, hamiltonians::two_particle_spring::initial_state()));
        },
        .period = {"period 2 pi sqrt(m / (2 k)) of the relative motion",
                   [](const parameter_values& v) {
                       return two_pi * std::sqrt(v.at("mass") / (2 * v.at("stiffness")));
                   }},
    };
}

}  // namespace sympl::app
