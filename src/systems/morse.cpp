// The registry entry of the Morse oscillator (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/morse.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry morse_entry() {
    return {
        .name = "morse",
        .description = "Morse 1929: H = p^2/(2m) + D (1 - exp(-a (q - r0)))^2; q0 = 0.5, p0 = 0.4; exact while bound (E < D)",
        .parameters = {positive("mass", 1, "m"), positive("depth", 1, "well depth D"), positive("width", 1, "a, inverse width"),
                       any("position", 0, "r0, the minimum")},
        .exact = true,
        .build = [](const parameter_values& v) {
            constexpr compiled own{};  // no built-in scene: every method on the generic path
            const hamiltonians::morse h{v.at("mass"), v.at("depth"), v.at("width"), v.at("position")};
            const phase_space<double, 1> x0(one_dof(0.5), one_dof(0.4));
            const bool bound = energy(h, x0) < h.depth;
            return runnable<1, own>(h, stacked(x0), bound ? exact_flow(h, x0) : nullptr);
        },
        .period = {"small-oscillation period 2 pi / (a sqrt(2 D / m))",
                   [](const parameter_values& v) {
                       return two_pi / (v.at("width") * std::sqrt(2 * v.at("depth") / v.at("mass")));
                   }},
    };
}

}  // namespace sympl::app
