// Time to a max relative energy error on the built-in charged_particle system
// over t = 2000 (the scene's t_end x 40), by the report's recipe, in one
// process: sympl's cylindrical_split (blanes_moan_srkn11b, srkn14a, srkn6b)
// and cartesian_split(kahan_li_8) over dt = 0.8 .. 0.005 (9 steps), Boost.
// Odeint's controlled fehlberg78 (abs = rel tolerance 1e-3 .. 1e-14, first
// step t/1000, an observer every step). Max energy error from an observed
// run; time the median of 5 interleaved rounds, each run repeated to 5 ms.
// Prints CSV (method, dt or tolerance, max_energy_error, seconds), then for
// 1e-8 and 1e-10 the fastest of each side, read off by log-log interpolation
// between the bracketing runs, and their ratio.
// What `sympl report` on the scene with t_end = 2000 measures, without the
// program (docs/charged-particles.md).
//   bench_charged_accuracy > runs.csv
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include <sympl/hamiltonians/charged_particle.hpp>
#include <sympl/interop/odeint.hpp>
#include <sympl/sympl.hpp>

#include "running/general_system.hpp"

using namespace sympl;
namespace odeint = boost::numeric::odeint;
const hamiltonians::charged_particle H{};
const double T = 2000;
using St = phase_space<double, 2>;
St x0() {
    return St(Eigen::Vector2d(1, 0), Eigen::Vector2d(0.4, 1));
}
double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
struct run {
    run(std::string m, double p, std::function<double(bool)> g) : method(std::move(m)), param(p), go(std::move(g)) {}
    std::string method;
    double param;
    std::function<double(bool)> go;
    double err = 0;
    std::vector<double> times;
};
double rel(const St& x, double e0) {
    return std::abs(H.energy(x.q, x.p) / e0 - 1);
}

template <class Stepper>
double sympl_run(Stepper s, double dt, bool observe) {
    St x = x0();
    const double e0 = H.energy(x.q, x.p);
    double worst = 0;
    if (observe)
        integrate_until(s, x, 0.0, T, dt, [&](const St& y, double) {
            worst = std::max(worst, rel(y, e0));
        });
    else
        integrate_until(s, x, 0.0, T, dt);
    return observe ? worst : x.q[0];
}
double fehlberg(double tol, bool observe) {
    using OS = std::array<double, 4>;
    odeint_workspace<double, 2> w;
    auto f = make_odeint_system<2>(app::general_system<hamiltonians::charged_particle>{H}, &w);
    OS y{1, 0, 0.4, 1};
    const double e0 = H.energy(x0().q, x0().p);
    double worst = 0;
    odeint::integrate_adaptive(odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<OS>()), f, y, 0.0, T,
                               T / 1000, [&](const OS& z, double) {
                                   if (observe) {
                                       St s(Eigen::Vector2d(z[0], z[1]), Eigen::Vector2d(z[2], z[3]));
                                       worst = std::max(worst, rel(s, e0));
                                   }
                               });
    return observe ? worst : y[0];
}
int main() {
    std::vector<run> runs;
    std::vector<double> dts;
    for (int i = 0; i < 9; ++i)
        dts.push_back(0.8 * std::pow(0.005 / 0.8, i / 8.0));
    const charged::particle a = H.particle();
    const auto f = H.electromagnetic_field();
    for (const char* t : {"blanes_moan_srkn11b", "blanes_moan_srkn14a", "blanes_moan_srkn6b"})
        for (double dt : dts)
            runs.push_back(
                {std::string("cylindrical_split(") + t + ")", dt, [=](bool o) {
                     return sympl_run(
                         charged::axisymmetric_splitting_stepper<charged::radial_mirror_field, 2>(a, f, method(t)), dt,
                         o);
                 }});
    for (double dt : dts)
        runs.push_back({"cartesian_split(kahan_li_8)", dt, [=](bool o) {
                            return sympl_run(charged::canonical_splitting_stepper<charged::radial_mirror_field, 2>(
                                                 a, f, method("kahan_li_8")),
                                             dt, o);
                        }});
    for (int i = 0; i < 12; ++i) {
        double tol = 1e-3 * std::pow(1e-14 / 1e-3, i / 11.0);
        runs.push_back({"odeint_fehlberg78", tol, [=](bool o) {
                            return fehlberg(tol, o);
                        }});
    }
    for (auto& r : runs) {
        try {
            r.err = r.go(true);
        } catch (...) {
            r.err = INFINITY;
        }
        if (!std::isfinite(r.err))
            r.err = INFINITY;
    }
    volatile double sink = 0;
    for (int round = 0; round < 5; ++round)
        for (auto& r : runs) {
            if (!std::isfinite(r.err))
                continue;
            int reps = 0;
            double t0 = now(), t1;
            do {
                sink = sink + r.go(false);
                ++reps;
                t1 = now();
            } while (t1 - t0 < 0.005);
            r.times.push_back((t1 - t0) / reps);
        }
    std::printf("method,param,max_energy_error,seconds\n");
    for (auto& r : runs) {
        std::sort(r.times.begin(), r.times.end());
        std::printf("%s,%.4g,%.3e,%.4g\n", r.method.c_str(), r.param, r.err,
                    r.times.empty() ? NAN : r.times[r.times.size() / 2]);
    }
    // Time to each level per method: log-log interpolation between the two
    // runs of its sweep (coarse to fine) that bracket it, as the report reads it.
    for (const double level : {1e-8, 1e-10}) {
        std::string best_sympl, best_odeint;
        double t_sympl = INFINITY, t_odeint = INFINITY;
        for (std::size_t i = 0; i < runs.size(); ++i) {
            const run& a = runs[i];
            const bool first = i == 0 || runs[i - 1].method != a.method;
            double t = INFINITY;
            if (first && a.err <= level && !a.times.empty()) t = a.times[a.times.size() / 2];
            if (i + 1 < runs.size() && runs[i + 1].method == a.method) {
                const run& b = runs[i + 1];
                if (a.err > level && level >= b.err && !a.times.empty() && !b.times.empty()) {
                    const double f = std::log(a.err / level) / std::log(a.err / b.err);
                    const double ta = a.times[a.times.size() / 2], tb = b.times[b.times.size() / 2];
                    t = std::exp(std::log(ta) + f * (std::log(tb) - std::log(ta)));
                }
            }
            const bool odeint_run = a.method.rfind("odeint", 0) == 0;
            if (odeint_run && t < t_odeint) t_odeint = t, best_odeint = a.method;
            if (!odeint_run && t < t_sympl) t_sympl = t, best_sympl = a.method;
        }
        std::printf("# max energy error %.0e: sympl %s %.3g ms, Odeint %s %.3g ms, Odeint / sympl = %.2fx\n", level,
                    best_sympl.c_str(), 1e3 * t_sympl, best_odeint.c_str(), 1e3 * t_odeint, t_odeint / t_sympl);
    }
}
