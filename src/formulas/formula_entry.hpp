#pragma once
// A scene's [system] of formulas as the program's other systems: a registry
// entry (systems.hpp) built from the parsed formulas, so that `run`,
// `report`, `ensemble`, checkpoints and resume take it by its name as they
// take a built-in one. Its runs go through the generic path
// (generic_path.hpp) with the formulas' machine code behind each call.
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
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
    // The exact solution through (q0, p0): q then p, formulas of t and the
    // parameters ("t" the last parameter); empty: none.
    std::vector<std::shared_ptr<const formula>> exact;
};

system_entry formula_entry(formula_definition d);

// A system of formulas as a scene's [system] table or Python gives it: the
// texts, before anything is read.
struct formula_texts {
    std::string name = "formulas";
    std::string T, V, H;   // T and V, or H
    std::string period;    // a formula of the parameters; empty: none
    std::vector<std::pair<std::string, double>> parameters;
    std::vector<std::string> coordinates, momenta;  // empty: q[i] and p[i]; momenta empty: "p" + coordinate
    std::vector<double> q0, p0;
    // The exact solution q(t), p(t) through the initial state, formulas of t
    // and the parameters; both empty: none.
    std::vector<std::string> exact_q, exact_p;
};

// What is wrong with one of formula_texts' values: its key ("T",
// "parameters", "coordinates", "name", "initial", "exact_q[2]"), the column inside a
// formula (0: the value as a whole) and the message.
struct formula_input_error : std::runtime_error {
    formula_input_error(std::string key, std::size_t column, const std::string& what)
        : std::runtime_error(what), key(std::move(key)), column(column) {}
    std::string key;
    std::size_t column;
};

// Reads and checks the texts (every formula parsed, held to the variables
// it may use, finite at the initial state with every index checked), and
// adds the system to the program's by its name (add_scene_system).
const system_entry& define_formula_system(const formula_texts& t);

// The runnable system of prepared formulas from x0 (formula_runnable.cpp).
runnable_system formula_runnable(std::shared_ptr<const prepared_formulas> f, std::vector<double> x0);

// Whether T is a homogeneous quadratic in p (sums of products of two
// momenta with constant factors): then dq/dt is linear in p and the RKN
// pairs apply (requirements.hpp).
bool quadratic_in_p(const formula& T);

}  // namespace sympl::app::formulas
