// The registry entry of the plane Kepler problem (see systems.hpp): its own translation unit.
#include <sympl/hamiltonians/kepler.hpp>

#include "running/runnable.hpp"
#include "running/systems.hpp"

#include "output/format.hpp"

namespace sympl::app {

system_entry kepler_entry() {
    return {
        .name = "kepler",
        .description = "H = |p|^2/2 - mu/|q| (Hairer, Lubich & Wanner, GNI ch. I.2.3), plane orbit from pericentre; "
                       "exact for mu = 1",
        .parameters = {positive("mu", 1, "G M; give mu or scale, not both"),
                       of_initial_state({.name = "eccentricity", .value = 0.5, .low = 0, .high = 1, .high_open = true,
                                         .meaning = "orbit eccentricity e"}),
                       positive("scale", 1,
                                "length unit L: q -> L q, p -> L p, mu -> mu L^3 (the same orbit in other units)")},
        .exact = true,
        .build = [](const parameter_values& v) {
            using enum method_kind;
            constexpr compiled own{.kinds = {table, logh, dprkn, odeint}, .classic = {"rk4"}, .extrapolated = true};
            const double e = v.at("eccentricity"), L = v.at("scale"), mu = v.at("mu");
            if (mu != 1 && L != 1)
                throw invalid_argument("kepler: mu = " + shortest(mu) + " and scale = " + shortest(L) +
                                       "; expected one of them left at 1");
            const auto scaled = [L](std::vector<double> x) {
                for (double& c : x) c *= L;
                return x;
            };
            std::function<std::vector<double>(double)> exact;
            if (mu == 1) exact = [e, scaled](double t) { return scaled(stacked(hamiltonians::kepler::exact_state(e, t))); };
            return runnable<2, own>(hamiltonians::kepler{mu * L * L * L},
                                 scaled(stacked(hamiltonians::kepler::initial_state(e))), exact);
        },
        .negative_potential = true,
        // The pericentre start of unit speed sqrt((1+e)/(1-e)) has a = mu (1-e) / (2 mu - 1 - e) (vis-viva):
        // a = L at mu = 1; none when unbound.
        .period = {"orbital period 2 pi sqrt(a^3 / mu) (2 pi at mu = 1, any scale)",
                   [](const parameter_values& v) {
                       const double mu = v.at("mu"), e = v.at("eccentricity"), L = v.at("scale");
                       const double a = L * mu * (1 - e) / (2 * mu - 1 - e);
                       return a > 0 ? two_pi * std::sqrt(a * a * a / (mu * L * L * L)) : 0.0;
                   }},
    };
}

}  // namespace sympl::app
