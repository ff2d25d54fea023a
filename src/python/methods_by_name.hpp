#pragma once
// Methods by name from Python: the names scenes take, and the tables Python
// made (sympl.Table), one per name in a process, as a scene's [[table]]s.
#include <string>

#include <sympl/core/table.hpp>

#include "methods/method_kinds.hpp"

namespace sympl::app::python {

// A table made in Python, usable by its name from then on; the same name
// again with other coefficients, or a method's name, is refused.
void add_python_table(const table& t);

// The method of that name (a table of Python's among them); an unknown name
// is refused with the nearest names.
method_spec method_named(const std::string& name);

}  // namespace sympl::app::python
