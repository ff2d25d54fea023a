// The registry entry of the stiff FPU problem (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/stiff_fpu.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry stiff_fpu_entry() {
    return {
        .name = "stiff_fpu",
        .description = "stiff Fermi-Pasta-Ulam runnable_system (Hairer, Lubich & Wanner, GNI ch. I.5.1) with its initial data",
        .parameters = {positive("omega", 50, "stiff springs' frequency"), count("pairs", 3, 1, "number of stiff pairs m")},
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {table, odeint}, .classic = {"rk4"}};
            const hamiltonians::stiff_fpu h{v.at("omega")};
            return runnable<Eigen::Dynamic, own>(h, stacked(h.initial_state<double, Eigen::Dynamic>(int(v.at("pairs")))));
        },
        .period = {"stiff springs' period 2 pi / omega (the fast time scale)",
                   [](const parameter_values& v) { return two_pi / v.at("omega"); }},
    };
}

}  // namespace sympl::app
