// The registry entry of the periodic Toda lattice (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/toda.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

#include <cmath>
#include <numbers>

namespace sympl::app {

system_entry toda_entry() {
    return {
        .name = "toda",
        .description = "periodic Toda lattice (Toda 1967); q = 0, p_k = cos(2 pi k / n)",
        .parameters = {count("n", 8, 2, "number of masses")},
        .build = [](const parameter_values& v) {
            constexpr compiled own{};  // no built-in scene: every method on the generic path
            const auto n = std::size_t(v.at("n"));
            std::vector<double> x0(2 * n, 0.0);
            for (std::size_t k = 0; k < n; ++k) x0[n + k] = std::cos(2 * std::numbers::pi * double(k) / double(n));
            return runnable<Eigen::Dynamic, own>(hamiltonians::toda{}, x0);
        },
        .period = {"period of the lowest linear mode, pi / sin(pi / n)",
                   [](const parameter_values& v) {
                       return std::numbers::pi / std::sin(std::numbers::pi / v.at("n"));
                   }},
    };
}

}  // namespace sympl::app
