#pragma once
// The report's figures drawn with matplotlib, where it is installed
// (figures.cpp; docs/python.md, "Figures").
#include <pybind11/eval.h>
#include <pybind11/pybind11.h>

namespace sympl::app::python {

namespace py = pybind11;

// Defines sympl.plot_report(result, measure="final_error", path=None) in the
// module: matplotlib is imported only when it is called.
void add_figures(py::module_& m);

// report(plots=True)'s figures: {"final_error": Figure, "max_energy_error":
// Figure}, each also saved beside the report's files; empty without matplotlib.
py::dict figures_of(const py::module_& m, const py::dict& result);

}  // namespace sympl::app::python
