// The generic path of separable systems (generic_path.hpp): every kind it
// runs, the reference, ensembles and sections, compiled once for
// erased_separable. Any H(q, p): generic_path_general.cpp.
#include "running/generic_path.hpp"

#include "running/runnable.hpp"

namespace sympl::app::detail {

run_function generic_run(erased_separable sys, energy_function energy) {
    return generic_runner(std::move(sys), std::move(energy));
}

generic_parts generic_separable(erased_separable sys, energy_function energy) {
    return {.run = generic_run(sys, std::move(energy)),
            .reference_method = splitting_reference_method,
            .reference = reference_by_splitting(sys),
            .ensemble = ensemble_of<Eigen::Dynamic, 1>(sys),
            .section = section_of<Eigen::Dynamic>(sys)};
}

}  // namespace sympl::app::detail
