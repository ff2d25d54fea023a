// The registry entry of H = (1 + q^2)(1 + p^2)/2, the non-separable test
// problem of Tao 2016 (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/product_hamiltonian.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry product_hamiltonian_entry() {
    return {
        .name = "product_hamiltonian",
        .description = "H = (1 + q^2)(1 + p^2)/2, one degree of freedom (Tao 2016; Jayawardana & Ohsawa 2023): not "
                       "separable, its period depends on H; started at (q, p) = (-3, 0)",
        .parameters = {of_initial_state(any("q", -3, "starting q (Tao's -3)")),
                       of_initial_state(any("p", 0, "starting p"))},
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {gauss, tao, semiexplicit, odeint}};
            return runnable<1, own>(hamiltonians::product_hamiltonian{}, {v.at("q"), v.at("p")});
        },
        .period = {"small-oscillation period 2 pi about the origin",
                   [](const parameter_values&) { return two_pi; }},
    };
}

}  // namespace sympl::app
