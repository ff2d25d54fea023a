// The registry entry of the relativistic pendulum (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/relativistic_pendulum.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry relativistic_pendulum_entry() {
    return {
        .name = "relativistic_pendulum",
        .description = "H = m c^2 sqrt(1 + p^2/(m c)^2) + k (1 - cos q): a non-quadratic T; q0 = 1.2, p0 = 0.9",
        .parameters = {positive("mass", 1, "m"), positive("c", 1, "speed of light"), positive("k", 1, "restoring torque")},
        .build = [](const parameter_values& v) {
            constexpr compiled own{};  // no built-in scene: every method on the generic path
            return runnable<1, own>(hamiltonians::relativistic_pendulum{v.at("mass"), v.at("c"), v.at("k")}, {1.2, 0.9});
        },
        .kinetic_not_quadratic = true,
        .period = {"small-amplitude, slow period 2 pi sqrt(m / k)",
                   [](const parameter_values& v) { return two_pi * std::sqrt(v.at("mass") / v.at("k")); }},
    };
}

}  // namespace sympl::app
