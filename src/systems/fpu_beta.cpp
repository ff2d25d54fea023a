// The registry entry of the FPU beta chain (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/fpu_beta.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

#include <cmath>
#include <numbers>

namespace sympl::app {

system_entry fpu_beta_entry() {
    return {
        .name = "fpu_beta",
        .description = "Fermi, Pasta & Ulam 1955 beta chain, fixed ends; started in its lowest mode, amplitude 1",
        .parameters = {count("n", 32, 1, "number of masses"), nonnegative("beta", 1, "quartic coupling")},
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {table, dprkn, odeint}, .classic = {"rk4"}};
            const auto n = std::size_t(v.at("n"));
            std::vector<double> x0(2 * n, 0.0);
            const double pi = std::numbers::pi;
            for (std::size_t k = 0; k < n; ++k) x0[k] = std::sin(pi * double(k + 1) / double(n + 1));
            return runnable<Eigen::Dynamic, own>(hamiltonians::fpu_beta{v.at("beta")}, x0);
        },
        .period = {"period of the lowest linear mode, pi / sin(pi / (2 (n + 1)))",
                   [](const parameter_values& v) {
                       return std::numbers::pi / std::sin(std::numbers::pi / (2 * (v.at("n") + 1)));
                   }},
    };
}

}  // namespace sympl::app
