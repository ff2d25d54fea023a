// The registry entry of the double well (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/double_well.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry double_well_entry() {
    return {
        .name = "double_well",
        .description = "H = p^2/2 + barrier (q^2 - 1)^2; q0 = 0.5, p0 = 0.3",
        .parameters = {nonnegative("barrier", 1, "barrier height at q = 0")},
        .build = [](const parameter_values& v) {
            constexpr compiled own{};  // no built-in scene: every method on the generic path
            return runnable<1, own>(hamiltonians::double_well{v.at("barrier")}, {0.5, 0.3});
        },
        .period = {"small-oscillation period in a well, 2 pi / sqrt(8 barrier) (none at barrier 0)",
                   [](const parameter_values& v) { return two_pi / std::sqrt(8 * v.at("barrier")); }},
    };
}

}  // namespace sympl::app
