#pragma once
// A system as Python holds it (sympl.System, docs/python.md): the program's
// runnable system and its name; its runs (system.cpp) and its sections,
// events and ensembles (system_events.cpp) return numpy arrays, with the GIL
// released while anything runs.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "output/checkpoint.hpp"
#include "python/arrays.hpp"
#include "python/force_callable.hpp"
#include "running/runnable_system.hpp"

namespace sympl::app::python {

class system {
public:
    system(const std::string& name, const std::map<std::string, double>& parameters, const py::object& q0,
           const py::object& p0);

    // A system whose force is a Python callable (force_callable.hpp).
    system(std::shared_ptr<const force_callables> c, std::vector<double> x0, std::string name)
        : sys_(callable_runnable(c, std::move(x0))), name_(std::move(name)), callables_(std::move(c)) {}

    const std::string& name() const { return name_; }
    std::size_t degrees_of_freedom() const { return sys_.degrees_of_freedom; }
    py::array_t<double> x0() const { return array_of(sys_.x0); }
    double energy(const py::object& x) const;

    // One run of a method by name (the module's docstring says what it returns).
    py::dict run(const std::string& method, double t_end, double dt, double t0, double tolerance, const py::object& x0,
                 bool energy, std::size_t energy_every, std::size_t trajectory_every, const py::object& times,
                 int order, bool timing, bool observe, const std::string& checkpoint, std::size_t checkpoint_every,
                 bool resume) const;

    // The upward crossings of q[0] = 0 (a Poincare section) of `steps` steps
    // of dt by a splitting table, as rows of q then p (interpolated to the
    // plane, poincare_section.hpp).
    py::array_t<double> section(const std::string& method, double dt, std::size_t steps, const py::object& x0) const;

    // Events of a splitting table's or an RKN pair's run (drivers/events.hpp)
    // as SciPy's solve_ivp takes them: callables g(t, q, p) with optional
    // attributes `terminal` (stop at the first crossing) and `direction` (> 0
    // rising, < 0 falling, 0 both). A controlled pair steps to `tolerance`
    // from a first step dt. Each g is called with the GIL held, at every step
    // end and inside Brent's search: the slow path, as a Python force is.
    py::dict events(const std::string& method, double t_end, double dt, const py::list& gs, double t0,
                    const py::object& x0, double tolerance) const;

    // Many starts (rows of q then p) by one table over [t0, t_end] in steps
    // of dt, on threads: the program's ensemble runner (ensembles.md); for a
    // Python force, the rows in lockstep, one call for all of them
    // (force_callable.hpp).
    py::dict ensemble(const py::array_t<double, py::array::c_style | py::array::forcecast>& starts,
                      const std::string& method, double t_end, double dt, double t0, std::size_t sample_every,
                      bool megno, int threads) const;

private:
    // What a run would hold, refused above the scenes' budget with the
    // figures: Gauss's matrices, the energy series (a vector of pairs, then
    // its array: 48 bytes a row) and the trajectory (17-digit text, then its
    // array: 33 bytes a number). The rows are counted for steps in physical
    // time; an adaptive or LogH run's steps are its own and are not.
    void check_memory(const method_spec& m, double span, double dt, std::size_t energy_every,
                      std::size_t trajectory_every, std::size_t times) const;

    // A run's checkpoints (checkpoint.hpp): written to `file` every `every`
    // steps, and with `resume` the run continues from the file where it
    // exists, bit for bit, once the file is held to this run (its system,
    // start, span, method and step: the identity) and its fields checked.
    void checkpointed(const method_spec& m, const std::string& method, run_request& rq, double t0, double t_end,
                      const std::vector<double>& x, const std::string& file, std::size_t every, bool resume,
                      std::optional<checkpoint_record>& from) const;

    // What every run returns: how it ended.
    static py::dict ending_of(const std::string& method, const run_result& r);

    // SciPy's `terminal`: True stops at the first crossing; its count form
    // (stop after N, SciPy 1.14) is not offered, so N > 1 is refused.
    static bool terminal_of(const py::handle g, std::size_t k);

    // The request's step and tolerance; run(observe=False) takes nothing that watches the run.
    static run_request rq_of(double dt, double tolerance, std::size_t energy_every, std::size_t trajectory_every,
                             const py::object& times, bool timing);

    // One run with nothing observed, as the program's timed runs: the final
    // state, steps, forces, the relative energy error at the end, and the
    // wall time of the call inside C++ (the GIL released).
    py::dict final_only(const method_spec& m, const std::string& method, run_request rq, double t0, double t_end,
                        const std::vector<double>& x) const;

    runnable_system sys_;
    std::string name_;
    std::string identity_;  // the parameters as given, for a checkpoint's identity
    std::shared_ptr<const force_callables> callables_;  // a Python force's system only
};

// A system whose force is a Python callable (force_callable.hpp).
system from_force(const py::object& force, const py::object& q0, const py::object& p0, const py::object& masses,
                  const py::object& potential, const std::string& name);

}  // namespace sympl::app::python
