// The registry entry of the planar double pendulum in canonical coordinates
// (see systems.hpp): its own translation unit. H(q, p) does not split.
#include <sympl/hamiltonians/double_pendulum.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry double_pendulum_entry() {
    return {
        .name = "double_pendulum",
        .description = "H = p^T M(q)^-1 p / 2 + V(q), q the two angles from the vertical (Stachowiak & Okada 2006): "
                       "not separable; q0 = (1, 0.5), p0 = (0.2, -0.1)",
        .parameters = {positive("mass1", 1, "m1"), positive("mass2", 1, "m2"), positive("length1", 1, "l1"),
                       positive("length2", 1, "l2"), positive("gravity", 1, "g")},
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {gauss, tao, semiexplicit, odeint}};
            return runnable<2, own>(hamiltonians::double_pendulum{v.at("mass1"), v.at("mass2"), v.at("length1"),
                                                          v.at("length2"), v.at("gravity")},
                            {1.0, 0.5, 0.2, -0.1});
        },
        .period = {"time scale 2 pi sqrt(l1 / g) (the upper pendulum alone, small amplitude)",
                   [](const parameter_values& v) {
                       return two_pi * std::sqrt(v.at("length1") / v.at("gravity"));
                   }},
    };
}

}  // namespace sympl::app
