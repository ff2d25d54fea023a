// The Python module `sympl` (docs/python.md): the program's systems (built-in
// by name, or written as formulas), its methods by name, a run's results as
// numpy arrays, and the work-precision report, over the same code as the
// `sympl` program: a run from Python is the program's run, compiled for the
// system as the program compiles it. Errors arrive as ValueError (bad input:
// the program's message) or RuntimeError (anything else); the GIL is released
// while anything runs.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include <sympl/methods/catalog.hpp>

#include "commands/check_table.hpp"

#include "formulas/formula_entry.hpp"
#include "python/arrays.hpp"
#include "python/figures.hpp"
#include "python/force_callable.hpp"
#include "python/methods_by_name.hpp"
#include "python/system.hpp"
#include "methods/method_kinds.hpp"
#include "output/format.hpp"
#include "reading/scene.hpp"
#include "report/report.hpp"
#include "running/systems.hpp"

namespace py = pybind11;

namespace sympl::app::python {

namespace {

// A table of one's own (a scene's [[table]]): usable by its name in run()
// and ensemble(), composable.
struct py_table {
    table t;
    static py_table make(const std::string& name, const std::vector<double>& kick, const std::vector<double>& drift,
                         int order, const std::string& convention) {
        if (name.empty()) throw invalid_argument("a table needs a name");
        if (order < 0 || order > 100) throw invalid_argument("order = " + std::to_string(order) + "; expected 0..100 (0: unknown)");
        const std::vector<coefficient> k(kick.begin(), kick.end()), d(drift.begin(), drift.end());
        py_table p{convention == "seed"          ? from_seed(name, k, d, order)
                   : convention == "drift-first" ? from_drift_first(name, d, k, order)
                   : convention == "kick-first"  ? table(name, k, d, order)
                                                 : throw invalid_argument("convention '" + convention +
                                                                          "'; expected kick-first, drift-first or seed")};
        add_python_table(p.t);
        return p;
    }
    static py_table of(table t) {
        add_python_table(t);
        return {std::move(t)};
    }
};

// check-table's verdict on coefficients, as `sympl check-table --json` gives it.
py::object checked_table(const std::vector<double>& kick, const std::vector<double>& drift,
                         const std::string& convention) {
    const auto text = [](const std::vector<double>& v) {
        std::string out;
        for (double x : v) out += (out.empty() ? "" : ",") + shortest(x);
        return out;
    };
    std::ostringstream printed;
    std::streambuf* const saved = std::cout.rdbuf(printed.rdbuf());
    try {
        check_table(text(kick), text(drift), convention, true);
    } catch (...) {
        std::cout.rdbuf(saved);
        throw;
    }
    std::cout.rdbuf(saved);
    return py::module_::import("json").attr("loads")(printed.str());
}

system from_formulas(const std::string& T, const std::string& V, const std::string& H, const py::object& q0,
                     const py::object& p0, const std::map<std::string, double>& parameters,
                     const std::vector<std::string>& coordinates, const std::vector<std::string>& momenta,
                     const std::string& period, const std::string& name, const std::vector<std::string>& exact_q,
                     const std::vector<std::string>& exact_p) {
    formulas::formula_texts t;
    t.name = name, t.T = T, t.V = V, t.H = H, t.period = period;
    t.exact_q = exact_q, t.exact_p = exact_p;
    t.parameters.assign(parameters.begin(), parameters.end());
    t.coordinates = coordinates, t.momenta = momenta;
    t.q0 = vector_of(q0, "q0");
    t.p0 = vector_of(p0, "p0");
    try {
        formulas::define_formula_system(t);
    } catch (const formulas::formula_input_error& e) {
        throw invalid_argument(e.key + (e.column ? ", column " + std::to_string(e.column) : std::string()) + ": " +
                               e.what());
    }
    return system(name, {}, py::none(), py::none());
}

py::list systems_list() {
    py::list out;
    for (const auto& e : systems()) {
        py::dict d;
        d["name"] = e.name;
        d["description"] = e.description;
        py::dict parameters;
        for (const auto& p : e.parameters) parameters[py::str(p.name)] = p.value;
        d["parameters"] = parameters;
        d["period"] = e.period.meaning;
        out.append(d);
    }
    return out;
}

// A CSV file the report wrote, column by column: numbers as float arrays
// (an empty field NaN), the rest as lists of strings (a field in quotes may
// hold commas).
py::dict csv_columns(const std::string& path) {
    std::ifstream in(path);
    std::string line;
    std::getline(in, line);
    std::vector<std::string> header;
    {
        std::stringstream h(line);
        for (std::string c; std::getline(h, c, ',');) header.push_back(c);
    }
    std::vector<std::vector<std::string>> cells(header.size());
    while (std::getline(in, line)) {
        std::vector<std::string> fields;
        std::string field;
        bool quoted = false;
        for (char c : line) {
            if (c == '"') quoted = !quoted;
            else if (c == ',' && !quoted) fields.push_back(std::move(field)), field.clear();
            else field += c;
        }
        fields.push_back(field);
        for (std::size_t k = 0; k < header.size(); ++k) cells[k].push_back(k < fields.size() ? fields[k] : "");
    }
    py::dict columns;
    for (std::size_t k = 0; k < header.size(); ++k) {
        std::vector<double> numbers;
        bool numeric = false;  // every field a number or empty (NaN), at least one a number
        for (const auto& c : cells[k]) {
            if (c.empty()) {
                numbers.push_back(std::nan(""));
                continue;
            }
            char* end = nullptr;
            const double v = std::strtod(c.c_str(), &end);
            numeric = *end == '\0';
            if (!numeric) break;
            numbers.push_back(v);
        }
        if (numeric) columns[py::str(header[k])] = array_of(numbers);
        else columns[py::str(header[k])] = cells[k];
    }
    return columns;
}

// A scene given as a dict, as its TOML file would hold it: tables, arrays,
// strings, numbers and booleans, nested at most 16 deep.
toml::table toml_of(const py::dict& d, const std::string& where, int depth);
toml::array toml_array_of(const py::handle& list, const std::string& where, int depth);

void put(const py::handle& v, const std::string& where, int depth, const auto& add) {
    if (depth > 16) throw invalid_argument(where + ": nested deeper than 16; expected a scene's tables and arrays");
    if (py::isinstance<py::bool_>(v)) add(v.cast<bool>());
    else if (py::isinstance<py::int_>(v)) add(v.cast<std::int64_t>());
    else if (py::isinstance<py::float_>(v)) add(v.cast<double>());
    else if (py::isinstance<py::str>(v)) add(v.cast<std::string>());
    else if (py::isinstance<py::dict>(v)) add(toml_of(v.cast<py::dict>(), where, depth + 1));
    else if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) add(toml_array_of(v, where, depth + 1));
    else if (py::hasattr(v, "tolist")) put(v.attr("tolist")(), where, depth, add);  // numpy arrays and scalars
    else
        throw py::type_error(where + ": a value of type " + std::string(py::str(v.get_type().attr("__name__"))) +
                             "; expected a table (dict), an array (list), a string, a number or a boolean");
}
toml::array toml_array_of(const py::handle& list, const std::string& where, int depth) {
    toml::array a;
    std::size_t k = 0;
    for (const py::handle item : list)
        put(item, where + "[" + std::to_string(k++) + "]", depth, [&](auto&& x) { a.push_back(std::move(x)); });
    return a;
}
toml::table toml_of(const py::dict& d, const std::string& where, int depth) {
    toml::table t;
    for (const auto& [key, value] : d) {
        if (!py::isinstance<py::str>(key)) throw py::type_error(where + ": a key that is not a string; expected names");
        const std::string name = key.cast<std::string>();
        put(value, where + "['" + name + "']", depth, [&](auto&& x) { t.insert_or_assign(name, std::move(x)); });
    }
    return t;
}

// The report over scene files (none: the built-in set), written to `out` as
// the program writes it; its work-precision rows returned as columns, and
// with plots the figures of plot_report, defined in `self` (this module,
// under the name it was loaded as).
py::dict report(const py::module_& self, const py::list& scene_list, const std::string& out, bool quick, bool plots,
                int threads) {
    // Files by path, dicts as their TOML text (the program's reader checks both alike).
    std::vector<std::pair<std::string, std::string>> scenes;  // (path, "") or (name, text)
    for (std::size_t k = 0; k < scene_list.size(); ++k) {
        const py::handle item = scene_list[k];
        if (py::isinstance<py::str>(item)) {
            scenes.emplace_back(item.cast<std::string>(), "");
        } else if (py::isinstance<py::dict>(item)) {
            const std::string where = "scenes[" + std::to_string(k) + "]";
            std::ostringstream text;
            text << toml_of(item.cast<py::dict>(), where, 0);
            scenes.emplace_back(where, text.str());
        } else {
            throw py::type_error("scenes[" + std::to_string(k) + "]: expected a scene file's path or a dict");
        }
    }
    report_options o;
    o.out_dir = out;
    o.quick = quick;
    o.plots = plots;
    o.threads = threads;
    std::ostringstream printed;
    {
        py::gil_scoped_release released;
        std::vector<scene> s;
        for (const auto& [f, text] : scenes) s.push_back(text.empty() ? load_scene(f, quick) : parse_scene(text, f, quick));
        o.studies = scenes.empty();
        if (s.empty()) s = default_scenes(quick);
        run_report(s, o, printed);
    }
    py::dict result;
    result["work_precision"] = csv_columns(out + "/work_precision.csv");
    result["time_to_accuracy"] = csv_columns(out + "/time_to_accuracy.csv");
    result["summary"] = printed.str();
    result["directory"] = out;
    // plots: the program's gnuplot PNGs, and matplotlib's figures where it is installed.
    result["figures"] = plots ? figures_of(self, result) : py::dict();
    return result;
}

}  // namespace

}  // namespace sympl::app::python

PYBIND11_MODULE(sympl, m) {
    using namespace sympl::app::python;
    namespace app = sympl::app;
    m.doc() = "sympl: symplectic integration of Hamiltonian systems (docs/python.md)";
    // The library's errors as Python's: bad input is a ValueError with the
    // program's message, a failed run a RuntimeError.
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const sympl::invalid_argument& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const sympl::invalid_table& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        } catch (const app::scene_error& e) {
            PyErr_SetString(PyExc_ValueError, e.what());
        }
    });
    m.def("systems", &systems_list, "The built-in systems: name, description, parameters with defaults, period");
    m.def(
        "tables", [] {
            std::vector<std::string> names;
            for (const auto& t : sympl::catalog()) names.push_back(t.name());
            return names;
        },
        "The catalog's splitting tables by name");
    m.def("methods", &app::method_names_beside_tables, "Method names beside the tables (rk4, dprkn8, odeint_dopri5, ...)");
    py::class_<sympl::app::python::system>(m, "System", "A system the program runs: built-in by name, or from formulas")
        .def(py::init<const std::string&, const std::map<std::string, double>&, const py::object&, const py::object&>(),
             py::arg("name"), py::arg("parameters") = std::map<std::string, double>{}, py::arg("q0") = py::none(),
             py::arg("p0") = py::none())
        .def_static("from_formulas", &from_formulas, py::arg("T") = "", py::arg("V") = "", py::arg("H") = "",
                    py::arg("q0"), py::arg("p0"), py::arg("parameters") = std::map<std::string, double>{},
                    py::arg("coordinates") = std::vector<std::string>{},
                    py::arg("momenta") = std::vector<std::string>{}, py::arg("period") = "",
                    py::arg("name") = "formulas", py::arg("exact_q") = std::vector<std::string>{},
                    py::arg("exact_p") = std::vector<std::string>{},
                    "A system of formulas, as a scene's [system] table (docs/formulas.md)")
        .def_static("from_force", &from_force, py::arg("force"), py::arg("q0"), py::arg("p0"),
                    py::arg("masses") = py::none(), py::arg("potential") = py::none(),
                    py::arg("name") = "python_force",
                    "H = sum p^2 / (2 m) + V(q) with F = -dV/dq a Python callable force(q) (and V potential(q) for "
                    "energies): the slow path, a call into Python per force (docs/python.md). In ensemble() all "
                    "rows move in lockstep: q arrives as an array of shape (rows, n), one call per kick")
        .def_property_readonly("name", &sympl::app::python::system::name)
        .def_property_readonly("degrees_of_freedom", &sympl::app::python::system::degrees_of_freedom)
        .def_property_readonly("x0", &sympl::app::python::system::x0, "The initial state, q then p")
        .def("energy", &sympl::app::python::system::energy, py::arg("x"))
        .def("run", &sympl::app::python::system::run, py::arg("method"), py::arg("t_end"), py::arg("dt") = 0.0,
             py::arg("t0") = 0.0, py::arg("tolerance") = 1e-8, py::arg("x0") = py::none(), py::arg("energy") = true,
             py::arg("energy_every") = 0, py::arg("trajectory_every") = 0, py::arg("times") = py::none(),
             py::arg("order") = 3, py::arg("timing") = false, py::arg("observe") = true,
             py::arg("checkpoint") = "", py::arg("checkpoint_every") = 0, py::arg("resume") = false,
             "One run of a method by name: a dict of steps, force_evaluations, final_state, max_energy_error, "
             "energy_series (t, error rows), trajectory (t, q, p rows: every trajectory_every steps, or at `times` by "
             "Hermite interpolation of order 3 or 5), seconds (timing=True), generic_path. observe=False: one run "
             "with nothing watched, at the program's timed speed: final_state, steps, force_evaluations, "
             "final_energy_error, seconds (the call's wall time). checkpoint='file', checkpoint_every=N: the "
             "run's state written every N steps (the program's checkpoints); resume=True continues from the file "
             "where it exists, bit for bit")
        .def("section", &sympl::app::python::system::section, py::arg("method"), py::arg("dt"), py::arg("steps"),
             py::arg("x0") = py::none(),
             "The upward crossings of q[0] = 0 (a Poincare section) of `steps` steps of dt by a splitting table: "
             "rows of q then p")
        .def("events", &sympl::app::python::system::events, py::arg("method"), py::arg("t_end"), py::arg("dt"),
             py::arg("events"), py::arg("t0") = 0.0, py::arg("x0") = py::none(), py::arg("tolerance") = 1e-8,
             "A run with events by any method but Wisdom-Holman's and the charged pushers, as SciPy's solve_ivp "
             "takes them: callables g(t, q, p), with optional attributes terminal (stop at the first crossing) and "
             "direction (> 0 rising, < 0 falling); each crossing located by Brent's method on the cubic Hermite "
             "interpolant of the method's own step, or on a controlled RKN pair's own interpolation "
             "(dprkn8_controlled: steps to `tolerance`, dt its first trial step; Odeint's controlled steppers: "
             "`tolerance`, dt unused). A dict: t_events, q_events, p_events (a list per event), stopped, t and final_state "
             "(where the run ended)")
        .def("ensemble", &sympl::app::python::system::ensemble, py::arg("starts"), py::arg("method"), py::arg("t_end"),
             py::arg("dt"), py::arg("t0") = 0.0, py::arg("sample_every") = 10, py::arg("megno") = false,
             py::arg("threads") = 0,
             "Rows of starts (q then p) run by one table on threads, the GIL released: stable, max_energy_error, "
             "megno, final_states, seconds (the runs' wall time inside C++)");
    py::class_<py_table>(m, "Table", "A splitting table of one's own, usable by its name (a scene's [[table]])")
        .def(py::init(&py_table::make), py::arg("name"), py::arg("kick"), py::arg("drift"), py::arg("order") = 0,
             py::arg("convention") = "kick-first")
        .def_property_readonly("name", [](const py_table& p) { return p.t.name(); })
        .def_property_readonly("order", [](const py_table& p) { return p.t.order(); })
        .def_property_readonly("kick", [](const py_table& p) {
            return std::vector<double>(p.t.kick().begin(), p.t.kick().end());
        })
        .def_property_readonly("drift", [](const py_table& p) {
            return std::vector<double>(p.t.drift().begin(), p.t.drift().end());
        })
        .def("adjoint", [](const py_table& p) { return py_table::of(sympl::adjoint(p.t)); })
        .def("triple_jump", [](const py_table& p) { return py_table::of(sympl::triple_jump(p.t)); })
        .def("suzuki", [](const py_table& p) { return py_table::of(sympl::suzuki_fractal(p.t)); })
        .def("then", [](const py_table& a, const py_table& b, double fraction) {
                 return py_table::of(sympl::concatenate(a.t, b.t, fraction));
             }, py::arg("other"), py::arg("fraction") = 0.5, "This table for `fraction` of the step, then `other`");
    m.def("check_table", &checked_table, py::arg("kick"), py::arg("drift"), py::arg("convention") = "kick-first",
          "The order conditions and the measured order of coefficients, as `sympl check-table --json`");
    sympl::app::python::add_figures(m);
    // The module by the name it was loaded under (`sympl`, or `pkg.sympl`
    // inside a user's package), looked up when the figures are drawn.
    m.def("report",
          [self = m.attr("__name__").cast<std::string>()](const py::list& scenes, const std::string& out, bool quick,
                                                          bool plots, int threads) {
              return report(py::module_::import(self.c_str()), scenes, out, quick, plots, threads);
          },
          py::arg("scenes") = py::list(), py::arg("out") = "sympl-report",
          py::arg("quick") = true, py::arg("plots") = false, py::arg("threads") = 0,
          "The work-precision report over scenes, files or dicts as their TOML holds them (none: the built-in set), "
          "written to `out` as `sympl report` writes it; returns work_precision.csv and time_to_accuracy.csv as "
          "columns, and with plots=True the program's gnuplot PNGs and, where matplotlib is installed, `figures`: "
          "plot_report()'s two Figures (final_error, max_energy_error), saved beside them");
}
