#pragma once
// A scene's [system] of formulas as the program's other systems: a registry
// entry (systems.hpp) built from the parsed formulas, so that `run`,
// `report`, `ensemble`, checkpoints and resume take it by its name as they
// take a built-in one. Its runs go through the generic path
// (generic_path.hpp) with the formulas' machine code behind each call.
#include <memory>
#include <string>
#include <vector>

#include "formulas/formula.hpp"
#include "formulas/formula_system.hpp"
#include "running/systems.hpp"

namespace sympl::app::formulas {

struct formula_definition {
    std::string name;
    std::shared_ptr<const formula> T, V, H;  // T and V, or H alone
    names known;                             // parameters, coordinates, dimension
    std::vector<double> parameter_values;    // the defaults, in known.parameters' order
    std::vector<double> q0, p0;
    std::shared_ptr<const formula> period;   // of the parameters; null: none
};

system_entry formula_entry(formula_definition d);

// The runnable system of prepared formulas from x0 (formula_runnable.cpp).
runnable_system formula_runnable(std::shared_ptr<const prepared_formulas> f, std::vector<double> x0);

// Whether T is a homogeneous quadratic in p (sums of products of two
// momenta with constant factors): then dq/dt is linear in p and the RKN
// pairs apply (requirements.hpp).
bool quadratic_in_p(const formula& T);

}  // namespace sympl::app::formulas
