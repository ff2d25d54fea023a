// The registry row of the planar cluster: four equal bodies as two tight
// binaries on a wide circular orbit about each other, the initial state and
// period of examples/formulas/cluster.toml (which writes the same H as
// formulas). A scene's [initial] may give any even number of coordinates:
// the state's size is not fixed, so one program runs clusters of any size.
#include <cmath>

#include "planar_cluster.hpp"
#include "running/runnable.hpp"
#include "running/systems.hpp"

namespace my {

sympl::app::system_entry planar_cluster_entry() {
    using namespace sympl::app;
    return {
        .name = "planar_cluster",
        .description = "H = sum |p_i|^2/(2m) - sum_{i<j} G m^2/|q_i - q_j|, bodies in a plane; from two binaries "
                       "(separation 0.1) on a circular orbit about each other (separation 2)",
        .parameters = {positive("G", 1, "gravitational constant"), positive("m", 1, "mass of each body")},
        .build = [](const parameter_values& v) {
            using enum method_kind;
            // The kinds cluster.toml runs, compiled; any other runs on the generic path.
            constexpr compiled own{.kinds = {table, dprkn, odeint}};
            return runnable<Eigen::Dynamic, own>(
                planar_cluster{v.at("G"), v.at("m")},
                {1.05, 0, 0.95, 0, -1, 0.05, -1, -0.05,  // q: body i at (q[2i], q[2i+1])
                 0, 2.9431747586863373, 0, -1.5289611963132423, -2.23606797749979, -0.7071067811865476,
                 2.23606797749979, -0.7071067811865476});
        },
        .negative_potential = true,
        // The binaries' period, 2 pi sqrt(0.1^3 / (2 G m)): the fastest motion, which sets the step.
        .period = {"the binaries' period 2 pi sqrt(0.1^3 / (2 G m))",
                   [](const parameter_values& v) {
                       return 2 * std::acos(-1.0) * std::sqrt(0.1 * 0.1 * 0.1 / (2 * v.at("G") * v.at("m")));
                   }},
    };
}

}  // namespace my
