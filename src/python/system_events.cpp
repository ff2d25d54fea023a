// A Python system's Poincare sections, events and ensembles (system.hpp).
#include "python/system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "methods/run_plan.hpp"
#include "output/format.hpp"
#include "python/methods_by_name.hpp"

namespace sympl::app::python {

py::array_t<double> system::section(const std::string& method, double dt, std::size_t steps,
                                    const py::object& x0) const {
    if (!sys_.section)
        throw invalid_argument(name_ +
                               " has no Poincare section here; expected a separable Hamiltonian H = T(p) + "
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

bool system::terminal_of(const py::handle g, std::size_t k) {
    if (!py::hasattr(g, "terminal")) return false;
    const py::object t = g.attr("terminal");
    if (py::isinstance<py::bool_>(t)) return t.cast<bool>();
    if (py::isinstance<py::int_>(t) && (t.cast<long long>() == 0 || t.cast<long long>() == 1))
        return t.cast<long long>() == 1;
    throw invalid_argument("events[" + std::to_string(k) + "].terminal = " + py::repr(t).cast<std::string>() +
                           "; expected True or False (stopping after a count of crossings is not offered)");
}

py::dict system::events(const std::string& method, double t_end, double dt, const py::list& gs, double t0,
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

py::dict system::ensemble(const py::array_t<double, py::array::c_style | py::array::forcecast>& starts,
                          const std::string& method, double t_end, double dt, double t0, std::size_t sample_every,
                          bool megno, int threads) const {
    if (!sys_.ensemble && !callables_)
        throw invalid_argument(name_ +
                               " is not a separable Hamiltonian H = T(p) + V(q); an ensemble runs splitting "
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

}  // namespace sympl::app::python
