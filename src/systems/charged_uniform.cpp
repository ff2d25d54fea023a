// The registry entry of the charged particle in uniform E and B (see
// systems.hpp): its own translation unit. H(q, p) does not split.
#include <cmath>

#include <sympl/hamiltonians/charged_uniform.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace sympl::app {

system_entry charged_uniform_entry() {
    return {
        .name = "charged_uniform",
        .description = "H = |p - e B x q/2|^2/(2m) - e E.q in space, B = (0, 0, B), E = (E_x, 0, 0): gyration at e B/m "
                       "and the E x B drift (0, -E_x/B, 0) (Jackson sec. 12.3); relativistic with speed_of_light > 0; "
                       "not separable; q0 = (1, 0, 0), v0 = (0, 1, 0.1)",
        .parameters = {positive("mass", 1, "m"), positive("charge", 1, "e"), positive("field", 1, "B along z"),
                       any("electric_x", 0.1, "E along x"),
                       nonnegative("speed_of_light", 0, "c; 0: Newton's motion")},
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {gauss, odeint, charged}};
            hamiltonians::charged_uniform h{.mass = v.at("mass"), .charge = v.at("charge"),
                                            .electric = {v.at("electric_x"), 0, 0},
                                            .magnetic = {0, 0, v.at("field")},
                                            .speed_of_light = v.at("speed_of_light")};
            // p = gamma m v + e A(q0) with A(q0) = B x q0 / 2 = (0, B/2, 0).
            const double speed2 = 1.01, c = h.speed_of_light;
            const double gm = h.mass / (c > 0 ? std::sqrt(1 - speed2 / (c * c)) : 1.0);
            return runnable<3, own>(h, {1.0, 0.0, 0.0, 0.0, gm + h.charge * v.at("field") / 2, gm * 0.1});
        },
        // gamma = 1 / sqrt(1 - |v0|^2 / c^2) with |v0|^2 = 1.01, the start's.
        .period = {"gyration period 2 pi gamma m / (e B) at the start (Jackson sec. 12.2)",
                   [](const parameter_values& v) {
                       const double c = v.at("speed_of_light");
                       const double gamma = c > 0 ? 1 / std::sqrt(1 - 1.01 / (c * c)) : 1.0;
                       return two_pi * gamma * v.at("mass") / (v.at("charge") * v.at("field"));
                   }},
    };
}

}  // namespace sympl::app
