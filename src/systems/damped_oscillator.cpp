// The registry entry of the damped, driven oscillator (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/damped_driven_oscillator.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry damped_oscillator_entry() {
    return {
        .name = "damped_oscillator",
        .description = "m x'' = -k x - b v + F0 cos(Omega t): not Hamiltonian; classic methods, Odeint, and the "
                       "splitting tables with exact damped drifts (gamma = b/m); x0 = 1, v0 = 0; exact",
        .parameters = {positive("mass", 1, "m"), positive("stiffness", 1, "k"), nonnegative("damping", 0.3, "b"),
                       any("drive_amplitude", 0, "F0"), nonnegative("drive_frequency", 0, "Omega")},
        .exact = true,
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {table, classic, odeint}};
            const hamiltonians::damped_driven_oscillator o{v.at("mass"), v.at("stiffness"), v.at("damping"),
                                                           v.at("drive_amplitude"), v.at("drive_frequency")};
            const phase_space<double, 1> x0(one_dof(1.0), one_dof(0.0));
            return runnable<1, own>(o, stacked(x0), exact_flow(o, x0));
        },
        .period = {"undamped period 2 pi sqrt(m / k)",
                   [](const parameter_values& v) {
                       return two_pi * std::sqrt(v.at("mass") / v.at("stiffness"));
                   }},
    };
}

}  // namespace sympl::app
