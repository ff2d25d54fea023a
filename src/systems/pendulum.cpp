// The registry entry of the pendulum (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/pendulum.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry pendulum_entry() {
    return {
        .name = "pendulum",
        .description = "H = p^2/(2 m l^2) + m g l (1 - cos q); q0 = 1.2, p0 = 0.3",
        .parameters = {positive("mass", 1, "m"), positive("length", 1, "l"), positive("gravity", 1, "g")},
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {table, dprkn, odeint}, .classic = {"rk4"}};
            return runnable<1, own>(hamiltonians::pendulum{v.at("mass"), v.at("length"), v.at("gravity")}, {1.2, 0.3});
        },
        .period = {"small-amplitude period 2 pi sqrt(l / g)",
                   [](const parameter_values& v) {
                       return two_pi * std::sqrt(v.at("length") / v.at("gravity"));
                   }},
    };
}

}  // namespace sympl::app
