// The registry entry of the charged particle in a non-uniform magnetic field
// (see systems.hpp): its own translation unit. H(q, p) does not split.
#include <sympl/hamiltonians/charged_particle.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry charged_particle_entry() {
    return {
        .name = "charged_particle",
        .description = "H = |p - e A(q)|^2/(2m) + (k/2)|q|^2 in the plane, B_z = B0 (1 + |q|^2/L^2) (Goldstein sec. "
                       "8.1): not separable; q0 = (1, 0), p0 = (0.4, 1)",
        .parameters = {positive("mass", 1, "m"), positive("charge", 1, "e"), positive("field", 1, "B0, B_z at the origin"),
                       positive("field_length", 1, "L, where B_z doubles"),
                       nonnegative("confinement", 0, "k of the electrostatic well e phi = (k/2)|q|^2")},
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {gauss, tao, semiexplicit, odeint, charged}};
            return runnable<2, own>(hamiltonians::charged_particle{v.at("mass"), v.at("charge"), v.at("field"),
                                                           v.at("field_length"), v.at("confinement")},
                            {1.0, 0.0, 0.4, 1.0});
        },
        .period = {"cyclotron period 2 pi m / (e B0) at the origin",
                   [](const parameter_values& v) {
                       return two_pi * v.at("mass") / (v.at("charge") * v.at("field"));
                   }},
    };
}

}  // namespace sympl::app
