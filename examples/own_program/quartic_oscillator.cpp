// The registry row of the quartic oscillator: what `my_sympl systems` lists
// and what a scene's `system = "quartic_oscillator"` builds. Written like
// sympl's own rows (src/systems/*.cpp); sympl_add_program compiles it.
#include <cmath>

#include "quartic_oscillator.hpp"
#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace my {

sympl::app::system_entry quartic_oscillator_entry() {
    using namespace sympl::app;
    return {
        .name = "quartic_oscillator",
        .description = "H = p^2/2 + k q^4/4 from q0 = 1, p0 = 0 (an example of one's own system)",
        .parameters = {positive("stiffness", 1, "k")},
        .build = [](const parameter_values& v) {
            using enum method_kind;
            // What this program compiles for the type: the tables and RK4; any
            // other method a scene names runs on the generic path.
            constexpr compiled own{.kinds = {table}, .classic = {"rk4"}};
            return runnable<1, own>(quartic_oscillator{v.at("stiffness")}, {1.0, 0.0});
        },
        // At amplitude 1: T = Gamma(1/4)^2 / sqrt(pi k).
        .period = {"period Gamma(1/4)^2 / sqrt(pi k) at amplitude 1",
                   [](const parameter_values& v) {
                       return std::pow(std::tgamma(0.25), 2) / std::sqrt(std::acos(-1.0) * v.at("stiffness"));
                   }},
    };
}

}  // namespace my
