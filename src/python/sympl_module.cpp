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

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include <sympl/methods/catalog.hpp>

#include "commands/check_table.hpp"

#include "formulas/formula_entry.hpp"
#include "python/figures.hpp"
#include "python/force_callable.hpp"
#include "methods/method_kinds.hpp"
#include "methods/run_plan.hpp"
#include "output/checkpoint.hpp"
#include "output/format.hpp"
#include "reading/near_names.hpp"
#include "reading/scene.hpp"
#include "report/report.hpp"
#include "running/systems.hpp"

namespace py = pybind11;

namespace sympl::app::python {

namespace {

py::array_t<double> array_of(const std::vector<double>& v) {
    py::array_t<double> a(py::ssize_t(v.size()));
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

std::vector<double> vector_of(const py::handle& h, const char* what) {
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(h);
    if (!a || a.ndim() != 1)
        throw invalid_argument(std::string(what) + ": expected a one-dimensional sequence of numbers");
    return std::vector<double>(a.data(), a.data() + a.size());
}

// Rows of numbers a run wrote as CSV text (its trajectory), as a 2-d array.
py::array_t<double> rows_of(const std::string& csv, std::size_t columns) {
    std::vector<double> values;
    const char* at = csv.c_str();
    while (*at) {
        char* end = nullptr;
        values.push_back(std::strtod(at, &end));
        at = end;
        while (*at == ',' || *at == '\n') ++at;
    }
    const std::size_t rows = columns ? values.size() / columns : 0;
    py::array_t<double> a({py::ssize_t(rows), py::ssize_t(columns)});
    std::copy(values.begin(), values.begin() + std::ptrdiff_t(rows * columns), a.mutable_data());
    return a;
}

// The tables Python made (sympl.Table), by name, for method names to use
// (as a scene's [[table]]s): one per name in a process.
std::mutex tables_mutex;
std::map<std::string, table>& python_tables() {
    static std::map<std::string, table> tables;
    return tables;
}

void add_python_table(const table& t) {
    std::lock_guard lock(tables_mutex);
    auto& tables = python_tables();
    if (const auto found = tables.find(t.name()); found != tables.end()) {
        if (found->second.kick() == t.kick() && found->second.drift() == t.drift()) return;
        throw invalid_argument("a second table named '" + t.name() + "' with other coefficients; expected each name once");
    }
    if (resolve_method(t.name(), {})) throw invalid_argument("table name '" + t.name() + "' is already a method; expected a new name");
    tables.emplace(t.name(), t);
}

method_spec method_named(const std::string& name) {
    std::map<std::string, table> tables;
    {
        std::lock_guard lock(tables_mutex);
        tables = python_tables();
    }
    std::optional<method_spec> m = resolve_method(name, tables);
    if (m) return *m;
    std::vector<std::string> names;
    for (const auto& t : catalog()) names.push_back(t.name());
    for (const auto& n : method_names_beside_tables()) names.push_back(n);
    for (const auto& [n, t] : tables) names.push_back(n);
    const std::string hint = did_you_mean_method(name, tables);
    throw invalid_argument("unknown method '" + name + "'; " + (hint.empty() ? did_you_mean(name, names) : hint) +
                           "expected a catalog name (sympl.tables()), logh(<table>), extrapolated(<table>, k), "
                           "compensated(<table>), tao(<table>), semiexplicit(<table>), or another of sympl.methods()");
}

// A system as Python holds it: the program's runnable system and its name.
class system {
public:
    system(const std::string& name, const std::map<std::string, double>& parameters, const py::object& q0,
           const py::object& p0) {
        std::vector<double> q, p;
        if (!q0.is_none()) q = vector_of(q0, "q0");
        if (!p0.is_none()) p = vector_of(p0, "p0");
        if (q.empty() != p.empty()) throw invalid_argument("give both q0 and p0, or neither (the system's default)");
        sys_ = make_system(name, parameters, q, p, "python");
        name_ = name;
        for (const auto& [key, value] : parameters) identity_ += key + "=" + shortest(value) + ";";
    }

    // A system whose force is a Python callable (force_callable.hpp).
    system(std::shared_ptr<const force_callables> c, std::vector<double> x0, std::string name)
        : sys_(callable_runnable(c, std::move(x0))), name_(std::move(name)), callables_(std::move(c)) {}

    const std::string& name() const { return name_; }
    std::size_t degrees_of_freedom() const { return sys_.degrees_of_freedom; }
    py::array_t<double> x0() const { return array_of(sys_.x0); }
    double energy(const py::object& x) const {
        const std::vector<double> v = vector_of(x, "x");
        if (v.size() != sys_.x0.size())
            throw invalid_argument("x has " + std::to_string(v.size()) + " numbers; expected q then p, " +
                                   std::to_string(sys_.x0.size()));
        if (!sys_.energy) throw invalid_argument(name_ + " has no energy (it is not a Hamiltonian system)");
        return sys_.energy(v);
    }

    py::dict run(const std::string& method, double t_end, double dt, double t0, double tolerance, const py::object& x0,
                 bool energy, std::size_t energy_every, std::size_t trajectory_every, const py::object& times,
                 int order, bool timing, bool observe, const std::string& checkpoint, std::size_t checkpoint_every,
                 bool resume) const {
        const method_spec m = method_named(method);
        std::vector<double> x = x0.is_none() ? sys_.x0 : vector_of(x0, "x0");
        if (x.size() != sys_.x0.size())
            throw invalid_argument("x0 has " + std::to_string(x.size()) + " numbers; expected q then p, " +
                                   std::to_string(sys_.x0.size()));
        if (!(std::isfinite(t0) && std::isfinite(t_end) && t_end > t0))
            throw invalid_argument("t_end = " + shortest(t_end) + " after t0 = " + shortest(t0) +
                                   "; expected finite times, t_end > t0");
        const bool adaptive_kind = adaptive(m);
        if (!adaptive_kind && !(dt > 0 && std::isfinite(dt)))
            throw invalid_argument("dt = " + shortest(dt) + "; expected a finite step > 0 for " + method);
        if (!adaptive_kind && (t_end - t0) / dt > default_max_steps)
            throw invalid_argument("a run of " + shortest((t_end - t0) / dt) + " steps; expected at most " +
                                   shortest(default_max_steps) + " (a larger dt or a shorter span)");
        if (adaptive_kind && !(tolerance > 0 && tolerance < 1))
            throw invalid_argument("tolerance = " + shortest(tolerance) + "; expected a value in (0, 1)");
        check_memory(m, t_end - t0, dt, observe && energy && sys_.energy ? energy_every : 0,
                     observe ? trajectory_every : 0,
                     observe && py::hasattr(times, "__len__") ? py::len(times) : 0);  // a bad `times` is named below
        if (!observe && (!checkpoint.empty() || checkpoint_every || resume))
            throw invalid_argument("observe=False with checkpoints; expected checkpoints of an observed run");
        if (!observe) return final_only(m, method, rq_of(dt, tolerance, energy_every, trajectory_every, times, timing),
                                        t0, t_end, x);
        run_request rq = rq_of(dt, tolerance, 0, 0, py::none(), false);
        rq.energy = energy && sys_.energy;
        rq.energy_series_every = energy_every;
        rq.trajectory_every = trajectory_every;
        rq.timing_repeats = timing ? 3 : 0;
        std::ostringstream trajectory;
        trajectory.precision(17);
        if (!times.is_none()) {
            // Dense output (dense-output.md): the states at these times, read off
            // the Hermite interpolant of the step that holds each.
            if (trajectory_every) throw invalid_argument("times and trajectory_every both choose the trajectory's rows; expected one");
            if (order != 3 && order != 5) throw invalid_argument("order = " + std::to_string(order) + "; expected 3 or 5");
            rq.output_times = vector_of(times, "times");
            for (std::size_t k = 0; k < rq.output_times.size(); ++k)
                if (!(rq.output_times[k] >= t0 && rq.output_times[k] <= t_end) || (k && rq.output_times[k] <= rq.output_times[k - 1]))
                    throw invalid_argument("times[" + std::to_string(k) + "] = " + shortest(rq.output_times[k]) +
                                           "; expected increasing times in [t0, t_end]");
            rq.output_order = order;
            rq.trajectory = &trajectory;
        }
        if (trajectory_every) rq.trajectory = &trajectory;
        std::optional<checkpoint_record> from;
        if (!checkpoint.empty() || checkpoint_every || resume)
            checkpointed(m, method, rq, t0, t_end, x, checkpoint, checkpoint_every, resume, from);
        run_result r;
        {
            py::gil_scoped_release released;
            r = sys_.run(m, rq, t0, t_end, x);
        }
        py::dict out = ending_of(method, r);
        out["max_energy_error"] = r.max_energy_error;
        out["seconds"] = r.seconds;
        py::array_t<double> s({py::ssize_t(r.energy_series.size()), py::ssize_t(2)});
        double* row = s.mutable_data();
        for (const auto& [t, e] : r.energy_series) *row++ = t, *row++ = e;
        out["energy_series"] = s;
        out["trajectory"] = rows_of(trajectory.str(), 1 + sys_.x0.size());
        return out;
    }

    // What a run would hold, refused above the scenes' budget with the
    // figures: Gauss's matrices, the energy series (a vector of pairs, then
    // its array: 48 bytes a row) and the trajectory (17-digit text, then its
    // array: 33 bytes a number). The rows are counted for steps in physical
    // time; an adaptive or LogH run's steps are its own and are not.
    void check_memory(const method_spec& m, double span, double dt, std::size_t energy_every,
                      std::size_t trajectory_every, std::size_t times) const {
        const double steps = steps_in_physical_time(m) ? span / dt : 0;
        memory_estimate held = run_memory(m, sys_.degrees_of_freedom, steps, energy_every);
        if (energy_every) held.bytes += (steps / double(energy_every) + 1) * 16;
        const double rows = trajectory_every && steps > 0 ? steps / double(trajectory_every) + 1 : double(times);
        if (rows > 0) {
            held.bytes += rows * double(1 + sys_.x0.size()) * 33;
            held.what += std::string(held.what.empty() ? "" : ", and ") + "a trajectory of " + format_number(rows, 3) +
                         " rows";
        }
        if (!(held.bytes <= memory_budget_bytes))
            throw invalid_argument("a run that would hold " + format_number(held.bytes / double(1 << 30), 3) + " GiB (" +
                                   held.what + "); expected at most " +
                                   format_number(memory_budget_bytes / double(1 << 30), 3) +
                                   " GiB (a larger energy_every, trajectory_every or dt, or a shorter span)");
    }

    // A run's checkpoints (checkpoint.hpp): written to `file` every `every`
    // steps, and with `resume` the run continues from the file where it
    // exists, bit for bit, once the file is held to this run (its system,
    // start, span, method and step: the identity) and its fields checked.
    void checkpointed(const method_spec& m, const std::string& method, run_request& rq, double t0, double t_end,
                      const std::vector<double>& x, const std::string& file, std::size_t every, bool resume,
                      std::optional<checkpoint_record>& from) const {
        if (file.empty() || every == 0)
            throw invalid_argument("checkpoint = '" + file + "', checkpoint_every = " + std::to_string(every) +
                                   "; expected a file name and a number of steps > 0 (resume too)");
        if (const std::string why = why_not_resumable(m); !why.empty()) throw invalid_argument(why);
        if (rq.trajectory || rq.energy_series_every)
            throw invalid_argument("checkpoints with trajectory_every, times or energy_every; expected checkpoints of "
                                   "a run whose results are its final state and largest energy error");
        std::string identity = "python\n" + name_ + "\n" + identity_ + "\n" + shortest(t0) + "\n" + shortest(t_end) +
                               "\n" + shortest(rq.tolerance);
        for (double v : x) identity += "\n" + shortest(v);
        const std::string hash = fnv1a_hex(identity);
        if (resume && std::filesystem::exists(file)) {
            try {
                from = read_checkpoint(file, hash, method, rq.dt);
                check_checkpoint_fields(*from, file, x.size(), t0, t_end,
                                        steps_in_physical_time(m) && m.extrapolation_columns == 0);
            } catch (const sympl::error& e) {
                throw invalid_argument(e.what());
            }
            rq.checkpoint.resume = &*from;
            rq.checkpoint.resume_file = file;
        }
        rq.checkpoint.every_steps = every;
        rq.checkpoint.save = [file, hash, method, dt = rq.dt](checkpoint_record& record) {
            record.scene_hash = hash;
            record.method = method;
            record.dt = dt;
            write_checkpoint(file, record);
        };
    }

    // What every run returns: how it ended.
    static py::dict ending_of(const std::string& method, const run_result& r) {
        py::dict out;
        out["method"] = method;
        out["stable"] = r.stable;
        out["failure"] = r.failure;
        out["steps"] = r.steps;
        out["force_evaluations"] = r.force_evaluations;
        out["final_state"] = array_of(r.final_state);
        out["generic_path"] = r.generic;
        return out;
    }

    // The upward crossings of q[0] = 0 (a Poincare section) of `steps` steps
    // of dt by a splitting table, as rows of q then p (interpolated to the
    // plane, poincare_section.hpp).
    py::array_t<double> section(const std::string& method, double dt, std::size_t steps, const py::object& x0) const {
        if (!sys_.section)
            throw invalid_argument(name_ + " has no Poincare section here; expected a separable Hamiltonian H = T(p) + "
                                           "V(q)");
        const method_spec m = method_named(method);
        if (m.kind != method_kind::table || !m.coefficients || m.extrapolation_columns || m.compensated)
            throw invalid_argument("section method '" + method + "'; expected a plain splitting table");
        if (!(dt > 0 && std::isfinite(dt))) throw invalid_argument("dt = " + shortest(dt) + "; expected a finite step > 0");
        if (steps == 0 || double(steps) > default_max_steps)
            throw invalid_argument("steps = " + std::to_string(steps) + "; expected 1 .. " + shortest(default_max_steps));
        const std::vector<double> x = x0.is_none() ? sys_.x0 : vector_of(x0, "x0");
        if (x.size() != sys_.x0.size())
            throw invalid_argument("x0 has " + std::to_string(x.size()) + " numbers; expected q then p, " +
                                   std::to_string(sys_.x0.size()));
        std::vector<std::vector<double>> crossings;
        {
            py::gil_scoped_release released;
            crossings = sys_.section(*m.coefficients, dt, steps, x);
        }
        py::array_t<double> out({py::ssize_t(crossings.size()), py::ssize_t(x.size())});
        for (std::size_t i = 0; i < crossings.size(); ++i)
            std::copy(crossings[i].begin(), crossings[i].end(), out.mutable_data(py::ssize_t(i), 0));
        return out;
    }

    // SciPy's `terminal`: True stops at the first crossing; its count form
    // (stop after N, SciPy 1.14) is not offered, so N > 1 is refused.
    static bool terminal_of(const py::handle g, std::size_t k) {
        if (!py::hasattr(g, "terminal")) return false;
        const py::object t = g.attr("terminal");
        if (py::isinstance<py::bool_>(t)) return t.cast<bool>();
        if (py::isinstance<py::int_>(t) && (t.cast<long long>() == 0 || t.cast<long long>() == 1))
            return t.cast<long long>() == 1;
        throw invalid_argument("events[" + std::to_string(k) + "].terminal = " + py::repr(t).cast<std::string>() +
                               "; expected True or False (stopping after a count of crossings is not offered)");
    }

    // Events of a splitting table's or an RKN pair's run (drivers/events.hpp)
    // as SciPy's solve_ivp takes them: callables g(t, q, p) with optional
    // attributes `terminal` (stop at the first crossing) and `direction` (> 0
    // rising, < 0 falling, 0 both). A controlled pair steps to `tolerance`
    // from a first step dt. Each g is called with the GIL held, at every step
    // end and inside Brent's search: the slow path, as a Python force is.
    py::dict events(const std::string& method, double t_end, double dt, const py::list& gs, double t0,
                    const py::object& x0, double tolerance) const {
        if (!sys_.events)
            throw invalid_argument(name_ + " has no events here; expected a separable Hamiltonian H = T(p) + V(q)");
        const method_spec m = method_named(method);
        if (const std::string why = why_not(m, sys_.form); !why.empty()) throw invalid_argument(why);
        if (!(dt > 0 && std::isfinite(dt))) throw invalid_argument("dt = " + shortest(dt) + "; expected a finite step > 0");
        if (!(std::isfinite(t0) && std::isfinite(t_end) && t_end > t0))
            throw invalid_argument("t0 = " + shortest(t0) + ", t_end = " + shortest(t_end) +
                                   "; expected finite times with t_end > t0");
        if (!adaptive(m) && (t_end - t0) / dt > default_max_steps)
            throw invalid_argument("(t_end - t0) / dt = " + shortest((t_end - t0) / dt) + " steps; expected at most " +
                                   shortest(default_max_steps));
        if (adaptive(m) && !(tolerance > 0 && tolerance < 1))
            throw invalid_argument("tolerance = " + shortest(tolerance) + "; expected a value in (0, 1)");
        if (gs.empty()) throw invalid_argument("events: an empty list; expected one callable g(t, q, p) or more");
        const std::vector<double> x = x0.is_none() ? sys_.x0 : vector_of(x0, "x0");
        if (x.size() != sys_.x0.size())
            throw invalid_argument("x0 has " + std::to_string(x.size()) + " numbers; expected q then p, " +
                                   std::to_string(sys_.x0.size()));
        const std::size_t n = x.size() / 2;
        std::vector<event_spec> specs;
        for (const py::handle g : gs) {
            if (!PyCallable_Check(g.ptr()))
                throw py::type_error("events: " + std::string(py::str(py::type::of(g)).cast<std::string>()) +
                                     " is not callable; expected callables g(t, q, p)");
            event_spec e;
            e.stop = terminal_of(g, specs.size());
            const double d = py::hasattr(g, "direction") ? g.attr("direction").cast<double>() : 0.0;
            e.direction = d > 0 ? 1 : d < 0 ? -1 : 0;
            // The callable held through a pointer whose last owner takes the
            // GIL to let it go: copies of e.g, made where the GIL is released,
            // then never touch a Python reference count.
            const std::shared_ptr<py::object> f(new py::object(py::reinterpret_borrow<py::object>(g)),
                                                [](py::object* o) {
                                                    py::gil_scoped_acquire held;
                                                    delete o;
                                                });
            e.g = [f, n](double t, const std::vector<double>& y) {
                py::gil_scoped_acquire held;
                py::array_t<double> q(py::ssize_t(n), y.data()), p(py::ssize_t(n), y.data() + n);
                return (*f)(t, q, p).cast<double>();
            };
            specs.push_back(std::move(e));
        }
        event_outcome o;
        {
            py::gil_scoped_release released;
            o = sys_.events(m, dt, tolerance, t0, t_end, x, specs);
        }
        py::list t_events, q_events, p_events;
        for (std::size_t k = 0; k < specs.size(); ++k) {
            std::vector<const event_outcome::hit*> mine;
            for (const auto& h : o.hits)
                if (h.event == k) mine.push_back(&h);
            py::array_t<double> t(py::ssize_t(mine.size())), q({py::ssize_t(mine.size()), py::ssize_t(n)}),
                p({py::ssize_t(mine.size()), py::ssize_t(n)});
            for (std::size_t i = 0; i < mine.size(); ++i) {
                t.mutable_at(py::ssize_t(i)) = mine[i]->t;
                std::copy_n(mine[i]->x.begin(), n, q.mutable_data(py::ssize_t(i), 0));
                std::copy_n(mine[i]->x.begin() + long(n), n, p.mutable_data(py::ssize_t(i), 0));
            }
            t_events.append(t), q_events.append(q), p_events.append(p);
        }
        py::dict out;
        out["t_events"] = t_events;
        out["q_events"] = q_events;
        out["p_events"] = p_events;
        out["stopped"] = o.stopped;
        out["t"] = o.t;
        out["final_state"] = py::array_t<double>(py::ssize_t(o.x.size()), o.x.data());
        return out;
    }

    // The request's step and tolerance; run(observe=False) takes nothing that watches the run.
    static run_request rq_of(double dt, double tolerance, std::size_t energy_every, std::size_t trajectory_every,
                             const py::object& times, bool timing) {
        if (energy_every || trajectory_every || !times.is_none() || timing)
            throw invalid_argument("observe=False runs with nothing watched; expected no energy_every, "
                                   "trajectory_every, times or timing with it");
        run_request rq;
        rq.dt = dt;
        rq.tolerance = tolerance;
        return rq;
    }

    // One run with nothing observed, as the program's timed runs: the final
    // state, steps, forces, the relative energy error at the end, and the
    // wall time of the call inside C++ (the GIL released).
    py::dict final_only(const method_spec& m, const std::string& method, run_request rq, double t0, double t_end,
                        const std::vector<double>& x) const {
        rq.observed = false;
        rq.timing_repeats = 0;
        run_result r;
        double seconds = 0;
        {
            py::gil_scoped_release released;
            const auto start = std::chrono::steady_clock::now();
            r = sys_.run(m, rq, t0, t_end, x);
            seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        py::dict out = ending_of(method, r);
        out["seconds"] = seconds;
        double error = -1;
        if (r.stable && sys_.energy) {
            const double e0 = sys_.energy(x), e1 = sys_.energy(r.final_state);
            error = std::fabs(e1 - e0) / (e0 != 0 ? std::fabs(e0) : 1.0);
        }
        out["final_energy_error"] = error;
        return out;
    }

    // Many starts (rows of q then p) by one table over [t0, t_end] in steps
    // of dt, on threads: the program's ensemble runner (ensembles.md); for a
    // Python force, the rows in lockstep, one call for all of them
    // (force_callable.hpp).
    py::dict ensemble(const py::array_t<double, py::array::c_style | py::array::forcecast>& starts,
                      const std::string& method, double t_end, double dt, double t0, std::size_t sample_every,
                      bool megno, int threads) const {
        if (!sys_.ensemble && !callables_)
            throw invalid_argument(name_ + " is not a separable Hamiltonian H = T(p) + V(q); an ensemble runs splitting "
                                           "tables on one");
        if (megno && callables_) throw invalid_argument("megno=True needs the force's derivative; a Python force gives none");
        const method_spec m = method_named(method);
        if (m.kind != method_kind::table || !m.coefficients || m.extrapolation_columns || m.compensated)
            throw invalid_argument("ensemble method '" + method + "'; expected a plain splitting table");
        const std::size_t width = sys_.x0.size();
        if (starts.ndim() != 2 || std::size_t(starts.shape(1)) != width || starts.shape(0) == 0)
            throw invalid_argument("starts: expected rows of " + std::to_string(width) + " numbers (q then p)");
        if (!(dt > 0 && std::isfinite(dt) && std::isfinite(t0) && std::isfinite(t_end) && t_end > t0))
            throw invalid_argument("dt = " + shortest(dt) + " over t = " + shortest(t0) + " .. " + shortest(t_end) +
                                   "; expected dt > 0 and t_end > t0, all finite");
        const double steps = std::ceil((t_end - t0) / dt - 1e-9);
        const std::size_t count = std::size_t(starts.shape(0));
        if (!(steps * double(count) <= 1e4 * default_max_steps))
            throw invalid_argument(std::to_string(count) + " starts of " + shortest(steps) + " steps; expected at most " +
                                   shortest(1e4 * default_max_steps) + " trajectory-steps");
        std::vector<std::vector<double>> x(count);
        for (std::size_t i = 0; i < count; ++i) x[i].assign(starts.data(i, 0), starts.data(i, 0) + width);
        ensemble_request rq;
        rq.method = m.coefficients;
        rq.t0 = t0;
        rq.dt = dt;
        rq.steps = std::size_t(steps);
        rq.sample_every = std::max<std::size_t>(1, std::min<std::size_t>(sample_every, rq.steps));
        rq.megno = megno;
        rq.threads = threads;
        std::vector<ensemble_row> rows;
        double seconds = 0;
        {
            py::gil_scoped_release released;  // a Python force's calls take it back
            const auto start = std::chrono::steady_clock::now();
            rows = callables_ ? callable_ensemble(*callables_, x, rq) : sys_.ensemble(rq, x);
            seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        }
        const auto length = static_cast<py::ssize_t>(count);
        py::array_t<bool> stable(length);
        py::array_t<double> error(length), indicator(length);
        py::array_t<double> final_states({length, static_cast<py::ssize_t>(width)});
        for (std::size_t i = 0; i < count; ++i) {
            stable.mutable_data()[i] = rows[i].stable;
            error.mutable_data()[i] = rows[i].max_energy_error;
            indicator.mutable_data()[i] = megno ? rows[i].megno : std::nan("");
            for (std::size_t k = 0; k < width; ++k)
                final_states.mutable_data(py::ssize_t(i), py::ssize_t(k))[0] =
                    k < rows[i].final_state.size() ? rows[i].final_state[k] : std::nan("");
        }
        py::dict out;
        out["stable"] = stable;
        out["max_energy_error"] = error;
        out["megno"] = indicator;
        out["final_states"] = final_states;
        out["steps"] = rq.steps;
        out["seconds"] = seconds;  // the runs' wall time inside C++
        return out;
    }

private:
    runnable_system sys_;
    std::string name_;
    std::string identity_;  // the parameters as given, for a checkpoint's identity
    std::shared_ptr<const force_callables> callables_;  // a Python force's system only
};

system from_force(const py::object& force, const py::object& q0, const py::object& p0, const py::object& masses,
                  const py::object& potential, const std::string& name) {
    if (!PyCallable_Check(force.ptr())) throw py::type_error("force: expected a callable force(q) -> array like q");
    if (!potential.is_none() && !PyCallable_Check(potential.ptr()))
        throw py::type_error("potential: expected a callable potential(q) -> float, or None");
    auto c = std::make_shared<force_callables>();
    c->force = force;
    c->potential = potential;
    std::vector<double> x = vector_of(q0, "q0");
    const std::vector<double> p = vector_of(p0, "p0");
    if (x.size() != p.size() || x.empty())
        throw invalid_argument("q0 has " + std::to_string(x.size()) + " numbers and p0 " + std::to_string(p.size()) +
                               "; expected the same number, at least one");
    c->masses = masses.is_none() ? std::vector<double>(x.size(), 1.0) : vector_of(masses, "masses");
    if (c->masses.size() != x.size())
        throw invalid_argument("masses has " + std::to_string(c->masses.size()) + " numbers; expected one per "
                               "coordinate, " + std::to_string(x.size()));
    x.insert(x.end(), p.begin(), p.end());
    return system(std::move(c), std::move(x), name);
}

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

// The report over scene files (none: the built-in set), written to `out` as
// the program writes it; its work-precision rows returned as columns.
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

py::dict report(const py::list& scene_list, const std::string& out, bool quick, bool plots, int threads) {
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
    result["figures"] = plots ? figures_of(py::module_::import("sympl"), result) : py::dict();
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
             "A splitting table's or an RKN pair's run with events, as SciPy's solve_ivp takes them: callables "
             "g(t, q, p), with optional attributes terminal (stop at the first crossing) and direction (> 0 rising, "
             "< 0 falling); each crossing located by Brent's method on the cubic Hermite interpolant of the step, "
             "or on a controlled pair's own interpolation (dprkn8_controlled: steps to `tolerance`, dt its first "
             "trial step). A dict: t_events, q_events, p_events (a list per event), stopped, t and final_state "
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
    m.def("report", &report, py::arg("scenes") = py::list(), py::arg("out") = "sympl-report",
          py::arg("quick") = true, py::arg("plots") = false, py::arg("threads") = 0,
          "The work-precision report over scenes, files or dicts as their TOML holds them (none: the built-in set), "
          "written to `out` as `sympl report` writes it; returns work_precision.csv and time_to_accuracy.csv as "
          "columns, and with plots=True the program's gnuplot PNGs and, where matplotlib is installed, `figures`: "
          "plot_report()'s two Figures (final_error, max_energy_error), saved beside them");
}
