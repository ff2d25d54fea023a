// A Python system's construction and its single runs (system.hpp).
#include "python/system.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "methods/run_plan.hpp"
#include "output/format.hpp"
#include "python/methods_by_name.hpp"
#include "running/systems.hpp"

namespace sympl::app::python {

system::system(const std::string& name, const std::map<std::string, double>& parameters, const py::object& q0,
               const py::object& p0) {
    std::vector<double> q, p;
    if (!q0.is_none()) q = vector_of(q0, "q0");
    if (!p0.is_none()) p = vector_of(p0, "p0");
    if (q.empty() != p.empty()) throw invalid_argument("give both q0 and p0, or neither (the system's default)");
    sys_ = make_system(name, parameters, q, p, "python");
    name_ = name;
    for (const auto& [key, value] : parameters) identity_ += key + "=" + shortest(value) + ";";
    // A formula system's formulas, so that one defined otherwise under the
    // same name (in another process) is another system to a checkpoint.
    if (const std::string defined = scene_system_definition(name); !defined.empty()) identity_ += "\n" + defined;
}

double system::energy(const py::object& x) const {
    const std::vector<double> v = vector_of(x, "x");
    if (v.size() != sys_.x0.size())
        throw invalid_argument("x has " + std::to_string(v.size()) + " numbers; expected q then p, " +
                               std::to_string(sys_.x0.size()));
    if (!sys_.energy) throw invalid_argument(name_ + " has no energy (it is not a Hamiltonian system)");
    return sys_.energy(v);
}

py::dict system::run(const std::string& method, double t_end, double dt, double t0, double tolerance,
                     const py::object& x0, bool energy, std::size_t energy_every, std::size_t trajectory_every,
                     const py::object& times, int order, bool timing, bool observe, const std::string& checkpoint,
                     std::size_t checkpoint_every, bool resume) const {
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
    // Rows of every trajectory_every-th step as numbers, straight from the
    // run's own states (no text); dense rows at `times` come as the
    // program writes them.
    std::vector<double> rows;
    std::size_t step = 0;
    if (trajectory_every) {
        rq.trajectory_every = 0;
        rq.each_step = [&](double t, const std::vector<double>& state) {
            if (step++ % trajectory_every != 0) return;
            rows.push_back(t);
            rows.insert(rows.end(), state.begin(), state.end());
        };
    }
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
    out["trajectory"] = trajectory_every ? array_of(std::move(rows), 1 + sys_.x0.size())
                                         : rows_of(trajectory.str(), 1 + sys_.x0.size());
    return out;
}

void system::check_memory(const method_spec& m, double span, double dt, std::size_t energy_every,
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

void system::checkpointed(const method_spec& m, const std::string& method, run_request& rq, double t0, double t_end,
                          const std::vector<double>& x, const std::string& file, std::size_t every, bool resume,
                          std::optional<checkpoint_record>& from) const {
    if (file.empty() || every == 0)
        throw invalid_argument("checkpoint = '" + file + "', checkpoint_every = " + std::to_string(every) +
                               "; expected a file name and a number of steps > 0 (resume too)");
    if (const std::string why = why_not_resumable(m); !why.empty()) throw invalid_argument(why);
    if (rq.trajectory || rq.each_step || rq.energy_series_every)
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

py::dict system::ending_of(const std::string& method, const run_result& r) {
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

run_request system::rq_of(double dt, double tolerance, std::size_t energy_every, std::size_t trajectory_every,
                          const py::object& times, bool timing) {
    if (energy_every || trajectory_every || !times.is_none() || timing)
        throw invalid_argument(
            "observe=False runs with nothing watched; expected no energy_every, "
            "trajectory_every, times or timing with it");
    run_request rq;
    rq.dt = dt;
    rq.tolerance = tolerance;
    return rq;
}

py::dict system::final_only(const method_spec& m, const std::string& method, run_request rq, double t0, double t_end,
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

}  // namespace sympl::app::python
