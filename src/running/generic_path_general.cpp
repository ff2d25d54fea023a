// The generic path of any H(q, p) (generic_path.hpp): every kind it runs and
// the reference, compiled once for general_system<erased_general>; a unit of
// its own, so that it builds beside the separable one (generic_path.cpp).
#include "running/generic_path.hpp"

#include "running/runnable.hpp"

namespace sympl::app::detail {

run_function generic_run(erased_general h, energy_function energy) {
    return generic_runner(general_system<erased_general>{std::move(h)}, std::move(energy));
}

generic_parts generic_general(erased_general h, energy_function energy) {
    general_system<erased_general> sys{std::move(h)};
    return {.run = generic_run(sys.h, std::move(energy)),
            .reference_method = gauss_reference_method,
            .reference = reference_by_gauss(sys),
            // ensembles, sections and events run splitting tables: separable systems only
            .ensemble = {},
            .section = {},
            .events = {}};
}

}  // namespace sympl::app::detail
