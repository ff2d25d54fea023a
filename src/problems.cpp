// Systems by name, and one runner that takes any method to any of them.
#include "problems.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <ostream>
#include <type_traits>
#include <utility>

#include <sympl/sympl.hpp>
#include <sympl/odeint.hpp>
#include <sympl/hamiltonians/damped_driven_oscillator.hpp>
#include <sympl/hamiltonians/double_well.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/morse.hpp>
#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/relativistic_pendulum.hpp>
#include <sympl/hamiltonians/stiff_fpu.hpp>
#include <sympl/hamiltonians/toda.hpp>
#include <sympl/hamiltonians/two_particle_spring.hpp>

namespace sympl::app {

namespace {

using State = phase_space<double>;
using Vec = State::vector;
namespace odeint = boost::numeric::odeint;

State to_state(const std::vector<double>& x) {
    const auto n = static_cast<Eigen::Index>(x.size() / 2);
    State s(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        s.q[i] = x[i];
        s.p[i] = x[n + i];
    }
    return s;
}

template <class S>
std::vector<double> to_vector(const phase_space<S>& s) {
    std::vector<double> x(2 * s.size());
    for (Eigen::Index i = 0; i < s.size(); ++i) {
        x[i] = double(s.q[i]);
        x[s.size() + i] = double(s.p[i]);
    }
    return x;
}

template <class X>
std::vector<double> stacked(const X& x) {
    return to_vector(State(x.q.template cast<double>(), x.p.template cast<double>()));
}

double clock_seconds() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The first-order form dx/dt of any system, for Odeint, on stacked vectors.
// Odeint copies the system at every step, so the workspace lives outside it:
// no allocation per evaluation.
struct workspace {
    Vec q, p, a, b;
    std::uint64_t evaluations = 0;
};

template <class Sys>
struct first_order {
    const Sys* sys;
    workspace* w;
    void operator()(const std::vector<double>& x, std::vector<double>& dxdt, double t) const {
        const auto n = static_cast<Eigen::Index>(x.size() / 2);
        w->q = Eigen::Map<const Vec>(x.data(), n);
        w->p = Eigen::Map<const Vec>(x.data() + n, n);
        if constexpr (separable_hamiltonian<Sys, Vec>) {
            velocity(*sys, w->p, w->a);
            force(*sys, w->q, w->b);
        } else {
            sys->dq_dt(w->q, w->p, t, w->a);
            sys->dp_dt(w->q, w->p, t, w->b);
        }
        Eigen::Map<Vec>(dxdt.data(), n) = w->a;
        Eigen::Map<Vec>(dxdt.data() + n, n) = w->b;
        ++w->evaluations;
    }
};

[[noreturn]] void unsupported(const std::string& method, const std::string& why) {
    throw invalid_argument("method '" + method + "' " + why);
}

template <class Sys>
class runner {
public:
    runner(Sys sys, std::function<double(const std::vector<double>&)> energy) : sys_(std::move(sys)), energy_(std::move(energy)) {}

    run_result operator()(const method_spec& m, const run_request& rq, double t0, double t_end,
                          const std::vector<double>& x0) const {
        run_result r;
        // The measured run: observed every step for energy, trajectory and blow-up.
        const bool energy = rq.energy && energy_;
        const double e0 = energy ? energy_(x0) : 0;
        const double scale = e0 != 0 ? std::fabs(e0) : 1;
        std::size_t step = 0;  // the observer sees t0 (step 0), then every step
        std::vector<double> buffer;
        constexpr double divergence = 1e3;
        double size0 = 1;
        for (double v : x0) size0 = std::max(size0, std::fabs(v));
        const auto observe = [&](const auto& x, double t) {
            if (energy || rq.energy_series_every || rq.trajectory_every) buffer = stacked(x);
            if (energy) {
                const double err = std::fabs(energy_(buffer) - e0) / scale;
                // A finite but exploding run is unstable too: report where, not a huge number.
                if (err > divergence)
                    throw integration_error("the run diverged: relative energy error " + std::to_string(err) +
                                                " > 1e3 after step " + std::to_string(step) + " (t = " +
                                                std::to_string(t) + ")",
                                            step, t);
                r.max_energy_error = std::max(r.max_energy_error, err);
                if (rq.energy_series_every && step % rq.energy_series_every == 0) r.energy_series.emplace_back(t, err);
            }
            if (!energy) {  // no energy to watch (damped systems): watch the size of the state
                double size = 0;
                for (Eigen::Index i = 0; i < x.q.size(); ++i) size = std::max({size, std::fabs(double(x.q[i])), std::fabs(double(x.p[i]))});
                if (size > 1e12 * size0)
                    throw integration_error("the run diverged: |x| grew by more than 1e12 after step " +
                                                std::to_string(step) + " (t = " + std::to_string(t) + ")",
                                            step, t);
            }
            if (rq.trajectory && rq.trajectory_every && step % rq.trajectory_every == 0) {
                *rq.trajectory << t;
                for (double v : buffer) *rq.trajectory << ',' << v;
                *rq.trajectory << '\n';
            }
            ++step;
        };
        if (energy) r.max_energy_error = 0;
        State x = to_state(x0);
        try {
            const auto [steps, forces] = drive(m, rq, t0, t_end, x, observe, true);
            r.steps = steps;
            r.force_evaluations = forces;
            r.final_state = to_vector(x);
        } catch (const integration_error& e) {
            r.stable = false;
            r.blowup_step = e.step;
            r.blowup_time = e.time;
            r.failure = e.what();
            r.max_energy_error = -1;
            return r;
        }
        // Timing: the same run with nothing observed, best of several.
        for (int k = 0; k < rq.timing_repeats; ++k) {
            State y = to_state(x0);
            const double start = clock_seconds();
            drive(m, rq, t0, t_end, y, no_observer{}, false);
            const double s = clock_seconds() - start;
            r.seconds = r.seconds < 0 ? s : std::min(r.seconds, s);
        }
        return r;
    }

    // Runs the span, calling obs(x, t) after every step when observed.
    // Returns (steps, force evaluations).
    template <class Observer>
    std::pair<std::size_t, std::uint64_t> drive(const method_spec& m, const run_request& rq, double t0, double t_end,
                                                State& x, Observer&& obs, bool observed) const {
        const auto with_driver = [&](auto stepper) -> std::pair<std::size_t, std::uint64_t> {
            run_summary s;
            if (observed)
                s = integrate_until(stepper, x, t0, t_end, rq.dt, obs);
            else
                s = integrate_until(stepper, x, t0, t_end, rq.dt);
            return {s.steps, s.force_evaluations};
        };
        switch (m.kind) {
            case method_kind::table:
                if constexpr (separable_hamiltonian<Sys, Vec>)
                    return with_driver(splitting_stepper<Sys, State>(sys_, *m.coefficients));
                else
                    unsupported(m.name, "is a splitting table; this system is not Hamiltonian (use a classic method)");
            case method_kind::classic:
                return classic(m.name, with_driver);
            case method_kind::odeint_rk4:
                return odeint_fixed(rq.dt, t0, t_end, x, obs, observed);
            case method_kind::odeint_dopri5:
                return odeint_adaptive(rq.tolerance, t0, t_end, x, obs, observed);
        }
        unsupported(m.name, "is of an unknown kind");
    }

private:
    template <class Drive>
    std::pair<std::size_t, std::uint64_t> classic(const std::string& name, Drive&& go) const {
        using E = decltype(equations_of<State>(sys_));
        if (name == "euler") return go(make_classic<euler, State>(sys_));
        if (name == "euler_cromer") return go(make_classic<euler_cromer, State>(sys_));
        if (name == "half_step") return go(make_classic<half_step, State>(sys_));
        if (name == "euler_richardson" || name == "rk2") return go(make_classic<euler_richardson, State>(sys_));
        if (name == "rk4") return go(make_classic<rk4, State>(sys_));
        if (name == "velocity_verlet") return go(make_classic<velocity_verlet, State>(sys_));
        if (name == "predictor_corrector") return go(make_classic<predictor_corrector, State>(sys_));
        if (name == "leapfrog_two_step") {
            if constexpr (newtonian_form<E>)
                return go(make_classic<leapfrog_two_step, State>(sys_));
            else
                unsupported(name, "needs Newton's form x'' = a(x, v, t); this system is Hamiltonian (use velocity_verlet)");
        }
        if (name == "damped_leapfrog") {
            if constexpr (damped_newtonian_form<E, State>)
                return go(make_classic<damped_leapfrog, State>(sys_));
            else
                unsupported(name, "needs a force split as F(x, t) - G(v); only damped_oscillator has one");
        }
        unsupported(name, "is not a classic method");
    }

    static void check_step(const std::vector<double>& y, std::size_t step, double t, double h) {
        for (double v : y)
            if (!std::isfinite(v))
                throw integration_error("integration blew up: step " + std::to_string(step) + " (from t = " +
                                            std::to_string(t) + " with dt = " + std::to_string(h) +
                                            ") produced a non-finite state",
                                        step, t);
    }

    template <class Observer>
    std::pair<std::size_t, std::uint64_t> odeint_fixed(double dt, double t0, double t_end, State& x, Observer& obs,
                                                       bool observed) const {
        workspace w;
        first_order<Sys> f{&sys_, &w};
        std::vector<double> y = to_vector(x);
        odeint::runge_kutta4<std::vector<double>> rk4;
        const auto n = static_cast<std::size_t>(std::floor((t_end - t0) / dt));
        double rest = (t_end - t0) - double(n) * dt;
        if (rest <= 8 * std::numeric_limits<double>::epsilon() * (t_end - t0)) rest = 0;
        State view = x;
        if (observed) obs(view, t0);  // like sympl's driver: the observer sees t0 first
        const std::size_t total = n + (rest > 0 ? 1 : 0);
        for (std::size_t i = 0; i < total; ++i) {
            const double t = t0 + double(i) * dt, h = i < n ? dt : rest;
            rk4.do_step(f, y, t, h);
            if (observed) {
                check_step(y, i + 1, t, h);
                view = to_state(y);
                obs(view, t + h);
            }
        }
        if (!observed) check_step(y, total, t_end, dt);
        x = to_state(y);
        return {total, w.evaluations};
    }

    template <class Observer>
    std::pair<std::size_t, std::uint64_t> odeint_adaptive(double tolerance, double t0, double t_end, State& x,
                                                          Observer& obs, bool observed) const {
        workspace w;
        first_order<Sys> f{&sys_, &w};
        std::vector<double> y = to_vector(x);
        auto stepper = odeint::make_controlled(tolerance, tolerance, odeint::runge_kutta_dopri5<std::vector<double>>());
        double t = t0, h = (t_end - t0) / 1000;
        std::size_t steps = 0, failed = 0;
        State view = x;
        if (observed) obs(view, t0);
        while (t < t_end) {
            if (t + h > t_end) h = t_end - t;
            if (stepper.try_step(f, y, t, h) == odeint::success) {
                ++steps;
                failed = 0;
                check_step(y, steps, t, h);
                if (observed) {
                    view = to_state(y);
                    obs(view, t);
                }
            } else if (++failed > 500 || h < 1e-14 * (t_end - t0)) {
                throw integration_error("odeint_dopri5: step size underflow at t = " + std::to_string(t), steps + 1, t);
            }
        }
        x = to_state(y);
        return {steps, w.evaluations};
    }

    Sys sys_;
    std::function<double(const std::vector<double>&)> energy_;
};

double parameter(const scene& s, const std::string& name, double fallback) {
    auto it = s.parameters.find(name);
    return it == s.parameters.end() ? fallback : it->second;
}

// Assembles the problem for a Hamiltonian (or equations of motion) `sys`.
template <class Sys>
problem assemble(const scene& s, Sys sys, std::vector<double> x0, std::function<std::vector<double>(double)> exact,
                 bool hamiltonian) {
    problem p;
    p.system = s.system;
    p.hamiltonian = hamiltonian;
    if (!s.q0.empty()) {  // the scene's own initial state: the exact solution no longer applies
        if (2 * s.q0.size() != x0.size())
            throw invalid_argument(s.source + ": initial q has " + std::to_string(s.q0.size()) + " values; " + s.system +
                                   " expects " + std::to_string(x0.size() / 2));
        x0.assign(s.q0.begin(), s.q0.end());
        x0.insert(x0.end(), s.p0.begin(), s.p0.end());
        exact = nullptr;
    }
    p.degrees_of_freedom = x0.size() / 2;
    p.x0 = x0;
    p.exact = exact;
    if constexpr (separable_hamiltonian<Sys, Vec>) {
        p.energy = [sys](const std::vector<double>& x) { return energy(sys, to_state(x)); };
        p.reference = [sys](double t0, double t_end, double dt, const std::vector<double>& x) {
            using L = phase_space<long double>;
            const State d = to_state(x);
            L y(d.q.cast<long double>(), d.p.cast<long double>());
            splitting_stepper<Sys, L> ss(sys, method("sofroniou_spaletta_10"));
            integrate_until(ss, y, (long double)t0, (long double)t_end, (long double)dt);
            return to_vector(y);
        };
    } else {
        p.reference = [sys](double t0, double t_end, double dt, const std::vector<double>& x) {
            State y = to_state(x);
            auto s4 = make_classic<rk4, State>(sys);
            integrate_until(s4, y, t0, t_end, dt);
            return to_vector(y);
        };
    }
    p.run = runner<Sys>(sys, p.energy);
    p.unsupported = [](const method_spec& m) -> std::string {
        using E = decltype(equations_of<State>(std::declval<Sys>()));
        if (m.kind == method_kind::table && !separable_hamiltonian<Sys, Vec>)
            return "is a splitting table; this system is not Hamiltonian (use a classic method)";
        if (m.kind != method_kind::classic) return "";
        if (m.name == "leapfrog_two_step" && !newtonian_form<E>)
            return "needs Newton's form x'' = a(x, v, t); this system is Hamiltonian (use velocity_verlet)";
        if (m.name == "damped_leapfrog" && !damped_newtonian_form<E, State>)
            return "needs a force split as F(x, t) - G(v); only damped_oscillator has one";
        return "";
    };
    return p;
}

}  // namespace

double relative_difference(const std::vector<double>& a, const std::vector<double>& b) {
    double diff = 0, scale = 0;
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        diff = std::max(diff, std::fabs(a[i] - b[i]));
        scale = std::max(scale, std::fabs(b[i]));
    }
    return scale > 0 ? diff / scale : diff;
}

problem make_problem(const scene& s) {
    const auto P = [&](const char* name, double fallback) { return parameter(s, name, fallback); };
    const auto vec = [](const auto& x) { return stacked(x); };
    const std::string& n = s.system;
    if (n == "harmonic_oscillator") {
        const hamiltonians::harmonic_oscillator h{P("mass", 1), P("omega", 1)};
        const phase_space<double, 1> x0(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.0));
        return assemble(s, h, vec(x0), [h, x0](double t) { return stacked(h.exact(x0, t)); }, true);
    }
    if (n == "pendulum") {
        const hamiltonians::pendulum h{P("mass", 1), P("length", 1), P("gravity", 1)};
        return assemble(s, h, {1.2, 0.3}, nullptr, true);
    }
    if (n == "kepler") {
        const double e = P("eccentricity", 0.5), L = P("scale", 1), mu = P("mu", 1);
        if (mu != 1 && L != 1) throw invalid_argument(s.source + ": give kepler either mu or scale, not both");
        // Units scaled by L (lengths) at fixed time unit: mu -> mu L^3, q -> L q, p -> L p.
        const hamiltonians::kepler h{mu * L * L * L};
        const auto x0 = hamiltonians::kepler::initial_state(e);
        const auto scaled = [L](std::vector<double> v) {
            for (double& c : v) c *= L;
            return v;
        };
        std::function<std::vector<double>(double)> exact;
        if (mu == 1) exact = [e, scaled](double t) { return scaled(stacked(hamiltonians::kepler::exact_state(e, t))); };
        return assemble(s, h, scaled(vec(x0)), exact, true);
    }
    if (n == "kepler_3d") {
        const double e = P("eccentricity", 0.5), i = P("inclination", 0.3), o = P("node", 0.5), w = P("periapsis", 0.7);
        return assemble(s, hamiltonians::kepler{}, vec(hamiltonians::kepler::initial_state_3d(e, i, o, w)),
                        [=](double t) { return stacked(hamiltonians::kepler::exact_state_3d(e, i, o, w, t)); }, true);
    }
    if (n == "relativistic_pendulum")
        return assemble(s, hamiltonians::relativistic_pendulum{P("mass", 1), P("c", 1), P("k", 1)}, {1.2, 0.9}, nullptr,
                        true);
    if (n == "henon_heiles")
        return assemble(s, hamiltonians::henon_heiles{},
                        vec(hamiltonians::henon_heiles::initial_state(P("energy", 1.0 / 6), P("q2", 0.1), P("p2", 0))),
                        nullptr, true);
    if (n == "fpu_beta") {
        const int N = int(P("n", 32));
        if (N < 1) throw invalid_argument(s.source + ": fpu_beta n = " + std::to_string(N) + "; expected >= 1");
        std::vector<double> x0(2 * N, 0.0);
        const double pi = std::acos(-1.0);
        for (int k = 0; k < N; ++k) x0[k] = std::sin(pi * (k + 1) / (N + 1));  // lowest mode, amplitude 1
        return assemble(s, hamiltonians::fpu_beta{P("beta", 1)}, x0, nullptr, true);
    }
    if (n == "stiff_fpu") {
        const hamiltonians::stiff_fpu h{P("omega", 50)};
        const int m = int(P("pairs", 3));
        if (m < 1) throw invalid_argument(s.source + ": stiff_fpu pairs = " + std::to_string(m) + "; expected >= 1");
        return assemble(s, h, stacked(h.initial_state<double, Eigen::Dynamic>(m)), nullptr, true);
    }
    if (n == "outer_solar_system") {
        const hamiltonians::outer_solar_system h{};
        return assemble(s, h, vec(h.initial_state()), nullptr, true);
    }
    if (n == "two_particle_spring") {
        const hamiltonians::two_particle_spring h{P("mass", 1), P("stiffness", 1)};
        const auto x0 = hamiltonians::two_particle_spring::initial_state();
        return assemble(s, h, vec(x0), [h, x0](double t) { return stacked(h.exact(x0, t)); }, true);
    }
    if (n == "morse") {
        const hamiltonians::morse h{P("mass", 1), P("depth", 1), P("width", 1), P("position", 0)};
        const phase_space<double, 1> x0(Eigen::Matrix<double, 1, 1>(0.5), Eigen::Matrix<double, 1, 1>(0.4));
        return assemble(s, h, vec(x0), [h, x0](double t) { return stacked(h.exact(x0, t)); }, true);
    }
    if (n == "double_well") return assemble(s, hamiltonians::double_well{P("barrier", 1)}, {0.5, 0.3}, nullptr, true);
    if (n == "toda") {
        const int N = int(P("n", 8));
        if (N < 2) throw invalid_argument(s.source + ": toda n = " + std::to_string(N) + "; expected >= 2");
        std::vector<double> x0(2 * N, 0.0);
        for (int k = 0; k < N; ++k) x0[N + k] = std::cos(2 * std::acos(-1.0) * k / N);
        return assemble(s, hamiltonians::toda{}, x0, nullptr, true);
    }
    if (n == "damped_oscillator") {
        const hamiltonians::damped_driven_oscillator o{P("mass", 1), P("stiffness", 1), P("damping", 0.3),
                                                       P("drive_amplitude", 0), P("drive_frequency", 0)};
        const phase_space<double, 1> x0(Eigen::Matrix<double, 1, 1>(1.0), Eigen::Matrix<double, 1, 1>(0.0));
        return assemble(s, o, vec(x0), [o, x0](double t) { return stacked(o.exact(x0, t)); }, false);
    }
    throw invalid_argument(s.source + ": unknown system '" + n + "'");
}

}  // namespace sympl::app
