// A system whose force is a Python callable (force_callable.hpp).
#include "python/force_callable.hpp"

#include <pybind11/numpy.h>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <string>
#include <utility>

#include <Eigen/Core>

#include "output/format.hpp"
#include "running/generic_path.hpp"
#include "running/run_context.hpp"

namespace py = pybind11;

namespace sympl::app::python {

namespace {

// q as numpy sees it: (lanes, n) or (n,), read-only, over the state's own
// numbers (no copy; the view lives for the call only).
py::array view_of(const force_callables& c, const double* q, std::size_t n) {
    const py::str no_owner;  // a base object: numpy then wraps the pointer instead of copying
    py::array a = c.lanes > 1 ? py::array_t<double>({py::ssize_t(c.lanes), py::ssize_t(n)}, q, no_owner)
                              : py::array_t<double>({py::ssize_t(n)}, q, no_owner);
    a.attr("setflags")(py::arg("write") = false);
    return a;
}

std::string shape_text(const py::array& a) {
    std::string s = "(";
    for (py::ssize_t k = 0; k < a.ndim(); ++k) s += (k ? ", " : "") + std::to_string(a.shape(k));
    return s + (a.ndim() == 1 ? ",)" : ")");
}

// H = sum p^2 / (2 m) + V(q) with the force from Python: doubles only (a
// dual number or a long double is refused where it is asked for).
class callable_force {
public:
    explicit callable_force(std::shared_ptr<const force_callables> c) : c_(std::move(c)) {
        inverse_mass_.resize(Eigen::Index(c_->masses.size() * c_->lanes));
        for (std::size_t lane = 0; lane < c_->lanes; ++lane)
            for (std::size_t i = 0; i < c_->masses.size(); ++i)
                inverse_mass_[Eigen::Index(lane * c_->masses.size() + i)] = 1.0 / c_->masses[i];
        unit_ = (inverse_mass_.array() == 1.0).all();
    }

    template <class V>
        requires std::same_as<V, Eigen::VectorXd>
    double kinetic(const V& p) const {
        return 0.5 * (p.array().square() * inverse_mass_.array()).sum();
    }
    template <class V>
        requires std::same_as<V, Eigen::VectorXd>
    double potential(const V& q) const {
        double sum = 0;
        for (double v : lane_potentials(*c_, q.data(), c_->masses.size())) sum += v;
        return sum;
    }
    template <class V>
        requires std::same_as<V, Eigen::VectorXd>
    void force(const V& q, V& f) const {
        const std::size_t n = c_->masses.size();
        f.resize(q.size());
        py::gil_scoped_acquire gil;
        const py::object out = c_->force(view_of(*c_, q.data(), n));
        const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(out);
        if (!a || std::size_t(a.size()) != std::size_t(q.size()))
            throw invalid_argument("force(q) returned " + (a ? "shape " + shape_text(a) : std::string("no array")) +
                                   " for q of shape " + shape_text(view_of(*c_, q.data(), n)) +
                                   "; expected the same shape as q");
        const double* data = a.data();
        for (Eigen::Index i = 0; i < q.size(); ++i) {
            f[i] = data[i];
            if (!std::isfinite(data[i]) && c_->first_bad_lane < 0) c_->first_bad_lane = long(std::size_t(i) / n);
        }
    }
    template <class V>
        requires std::same_as<V, Eigen::VectorXd>
    void velocity(const V& p, V& v) const {
        v = p.cwiseProduct(inverse_mass_);
    }
    // Unit masses: drifts move q by p in the kick's pass (splitting_loop.hpp).
    bool velocity_is_p() const { return unit_; }

    // Any other scalar: the dual numbers of Tao's binding and of
    // Gauss-Legendre's Newton matrix (second derivatives of H), or the long
    // double of a reference. Asked of a Python force, refused in its terms.
    template <class V>
        requires(!std::same_as<V, Eigen::VectorXd>)
    scalar_of<V> kinetic(const V&) const {
        refuse_scalar();
    }
    template <class V>
        requires(!std::same_as<V, Eigen::VectorXd>)
    scalar_of<V> potential(const V&) const {
        refuse_scalar();
    }
    [[noreturn]] static void refuse_scalar() {
        throw invalid_argument("a Python force gives F(q) in double only, not the second derivatives of H (on dual "
                               "numbers) that tao(...)'s binding and Gauss-Legendre's Newton iteration take; expected "
                               "a method that needs the force alone (a splitting table, an RKN pair, rk4, Odeint)");
    }

private:
    std::shared_ptr<const force_callables> c_;
    Eigen::VectorXd inverse_mass_;
    bool unit_ = false;
};

}  // namespace

std::vector<double> lane_potentials(const force_callables& c, const double* q, std::size_t n) {
    if (c.potential.is_none()) throw invalid_argument("no potential was given; expected potential=V(q) for energies");
    py::gil_scoped_acquire gil;
    const py::object out = c.potential(view_of(c, q, n));
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(out);
    if (!a || std::size_t(a.size()) != c.lanes)
        throw invalid_argument("potential(q) returned " + (a ? "shape " + shape_text(a) : std::string("no number")) +
                               " for q of shape " + shape_text(view_of(c, q, n)) + "; expected " +
                               (c.lanes > 1 ? "one value per row" : "one value"));
    return {a.data(), a.data() + c.lanes};
}

runnable_system callable_runnable(std::shared_ptr<const force_callables> c, std::vector<double> x0) {
    const std::size_t n = c->masses.size(), width = 2 * n * c->lanes;
    if (n == 0 || x0.size() != width)
        throw invalid_argument("a state of " + std::to_string(x0.size()) + " numbers; expected q then p, " +
                               std::to_string(width));
    for (std::size_t i = 0; i < n; ++i)
        if (!(c->masses[i] > 0 && std::isfinite(c->masses[i])))
            throw invalid_argument("masses[" + std::to_string(i) + "] = " + shortest(c->masses[i]) +
                                   "; expected finite masses > 0");
    callable_force sys(c);
    const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(x0.data(), Eigen::Index(n * c->lanes));
    Eigen::VectorXd f;
    sys.force(q, f);  // its shape and finiteness, before any run
    if (c->first_bad_lane >= 0)
        throw invalid_argument("force(q) is not finite at the initial state" +
                               (c->lanes > 1 ? " of row " + std::to_string(c->first_bad_lane) : std::string()) +
                               "; expected finite forces");
    runnable_system r;
    r.system = "python force";
    r.degrees_of_freedom = n * c->lanes;
    r.hamiltonian = !c->potential.is_none();
    if (r.hamiltonian) {
        const double v0 = sys.potential(q);
        if (!std::isfinite(v0))
            throw invalid_argument("potential(q) = " + shortest(v0) + " at the initial state; expected a finite value");
        r.energy = [sys](const std::vector<double>& x) {
            const phase_space<double> s = from_stacked<phase_space<double>>(x);
            return sys.kinetic(s.p) + sys.potential(s.q);
        };
    }
    // Splitting tables, rk4, the RKN pairs and Odeint; nothing that needs
    // the force's derivative or another scalar than double.
    r.form = {.separable_hamiltonian = true, .quadratic_kinetic = true};
    r.compiled = {.kinds = {}, .classic = {}, .extrapolated = false};  // every method on the generic path
    app::detail::generic_parts g = app::detail::generic_separable(erased_separable::of(sys), r.energy);
    r.x0 = std::move(x0);
    r.runner = std::move(g.run);
    r.section = std::move(g.section);
    r.events = std::move(g.events);
    return r;
}

std::vector<ensemble_row> callable_ensemble(const force_callables& one, const std::vector<std::vector<double>>& starts,
                                            const ensemble_request& request) {
    method_spec method;
    method.kind = method_kind::table;
    method.name = request.method->name();
    method.coefficients = request.method;
    const double t0 = request.t0, dt = request.dt;
    const std::size_t steps = request.steps, sample_every = request.sample_every;
    auto c = std::make_shared<force_callables>(one);
    c->lanes = starts.size();
    c->first_bad_lane = -1;
    const std::size_t n = c->masses.size(), lanes = c->lanes, half = n * lanes;
    std::vector<double> x(2 * half);
    for (std::size_t lane = 0; lane < lanes; ++lane)
        for (std::size_t i = 0; i < n; ++i) {
            x[lane * n + i] = starts[lane][i];
            x[half + lane * n + i] = starts[lane][n + i];
        }
    const runnable_system r = callable_runnable(c, x);
    const bool energy = !c->potential.is_none();
    // Each row's H: sum p^2 / (2 m) from the state, V from one call for all rows.
    const auto energies = [&](const std::vector<double>& y) {
        std::vector<double> e = energy ? lane_potentials(*c, y.data(), n) : std::vector<double>(lanes, 0.0);
        for (std::size_t lane = 0; lane < lanes; ++lane)
            for (std::size_t i = 0; i < n; ++i) e[lane] += 0.5 * y[half + lane * n + i] * y[half + lane * n + i] / c->masses[i];
        return e;
    };
    std::vector<ensemble_row> rows(lanes);
    for (ensemble_row& row : rows) row.max_energy_error = energy ? 0.0 : std::nan(""), row.megno = std::nan("");
    const std::vector<double> e0 = energies(x);
    run_request rq;
    rq.dt = dt;
    rq.observed = false;
    rq.timing_repeats = 0;  // one run, its final state kept (runnable.hpp)
    double t = t0;
    for (std::size_t done = 0; done < steps;) {
        const std::size_t chunk = std::min(sample_every, steps - done);
        const run_result step = r.run(method, rq, t, t + double(chunk) * dt, x);
        if (!step.stable)
            throw invalid_argument("the ensemble stopped at t = " + shortest(t) + ": " + step.failure +
                                   (c->first_bad_lane >= 0 ? " (row " + std::to_string(c->first_bad_lane) +
                                                                 "'s force was not finite)"
                                                           : std::string()));
        x = step.final_state;
        done += chunk;
        t = t0 + double(done) * dt;
        if (!energy) continue;
        const std::vector<double> e = energies(x);
        for (std::size_t lane = 0; lane < lanes; ++lane) {
            const double err = std::fabs(e[lane] - e0[lane]) / (e0[lane] != 0 ? std::fabs(e0[lane]) : 1.0);
            if (!(err <= divergence_limit)) rows[lane].stable = false;
            rows[lane].max_energy_error = std::max(rows[lane].max_energy_error, err);
        }
    }
    for (std::size_t lane = 0; lane < lanes; ++lane) {
        auto& s = rows[lane].final_state;
        s.assign(x.begin() + long(lane * n), x.begin() + long(lane * n + n));
        s.insert(s.end(), x.begin() + long(half + lane * n), x.begin() + long(half + lane * n + n));
    }
    return rows;
}

}  // namespace sympl::app::python
