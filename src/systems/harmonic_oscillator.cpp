// The registry entry of the harmonic oscillator (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/harmonic_oscillator.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry harmonic_oscillator_entry() {
    return {
        .name = "harmonic_oscillator",
        .description = "H = p^2/(2m) + m omega^2 q^2/2 (Sandvik's lecture notes); q0 = 1, p0 = 0",
        .parameters = {positive("mass", 1, "m"), positive("omega", 1, "angular frequency")},
        .exact = true,
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {table, dprkn, odeint}, .classic = {"rk4"}};
            const hamiltonians::harmonic_oscillator h{v.at("mass"), v.at("omega")};
            const phase_space<double, 1> x0(one_dof(1.0), one_dof(0.0));
            return runnable<1, own>(h, stacked(x0), exact_flow(h, x0));
        },
        .period = {"period 2 pi / omega",
                   [](const parameter_values& v) { return two_pi / v.at("omega"); }},
    };
}

}  // namespace sympl::app
