#pragma once
// The generic path: what a system's registry entry does not compile for its
// own type runs here, on the system type-erased (erased_system.hpp) and
// dynamic-size states: every method kind but Wisdom-Holman and the charged
// pushers, the long-double reference, ensembles (one trajectory a lane) and
// Poincare sections. These templates are compiled twice in all
// (generic_path.cpp: once for separable systems, once for any H(q, p);
// the RKN pairs a third time, on states of one degree of freedom) instead
// of once per system; each force, velocity or H costs one indirect call
// more (docs/speed.md, "The generic path").
#include <functional>
#include <string>
#include <vector>

#include "running/erased_system.hpp"
#include "running/general_system.hpp"
#include "running/runnable_system.hpp"

namespace sympl::app::detail {

using energy_function = std::function<double(const std::vector<double>&)>;

// A system's runs (marked generic), reference, ensembles and sections on the
// generic path; ensembles and sections of separable systems only.
struct generic_parts {
    run_function run;
    std::string reference_method;
    reference_function reference;
    ensemble_function ensemble;
    section_function section;
    events_function events;
};

generic_parts generic_separable(erased_separable sys, energy_function energy);
generic_parts generic_general(erased_general h, energy_function energy);

// The runs alone (what the parts' run is), for the tests and the benchmark
// that compare it with a system's compiled runs.
run_function generic_run(erased_separable sys, energy_function energy);
run_function generic_run(erased_general h, energy_function energy);

template <class Sys>
inline constexpr bool is_general_system = false;
template <class H>
inline constexpr bool is_general_system<general_system<H>> = true;

// Sys's parts on the generic path: a separable H, or a general one as
// general_system<H>.
template <class Sys>
generic_parts generic_parts_of(const Sys& sys, energy_function energy) {
    if constexpr (is_general_system<Sys>)
        return generic_general(erased_general::of(sys.h), std::move(energy));
    else
        return generic_separable(erased_separable::of(sys), std::move(energy));
}

}  // namespace sympl::app::detail
