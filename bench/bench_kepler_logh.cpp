// Time to a final-state error on eccentric Kepler orbits: sympl's tables in
// LogH fictitious time (plain and extrapolated) and at fixed steps against
// Boost.Odeint's runge_kutta4, runge_kutta_dopri5, runge_kutta_fehlberg78 and
// bulirsch_stoer, side by side in one process. For each method the cheapest
// step (or loosest tolerance) that reaches the target is found by a scan from
// loose to tight and bisection on its logarithm; that run is then timed
// (median of several). Prints times and the ratio of each to the best sympl
// method.
//   bench_kepler_logh [--quick] [--target 1e-8] [--orbits 10] [--e 0.9]
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "cheapest_run.hpp"

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/kepler.hpp>

namespace odeint = boost::numeric::odeint;
using K = sympl::phase_space<double, 2>;
using KX = sympl::phase_space<double, 3>;
using Y = std::array<double, 4>;

namespace {

struct contender {
    std::string name;
    bool tolerance;                       // swept parameter: a tolerance (else a step)
    double loose, tight;                  // the range searched
    std::function<K(double)> run;         // final state for a parameter
};

}  // namespace

int main(int argc, char** argv) {
    double target = 1e-8, e = 0.9;
    int orbits = 10, repeats = 7;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--quick")) repeats = 3, orbits = 2;
        else if (!std::strcmp(argv[i], "--target") && i + 1 < argc) target = std::atof(argv[++i]);
        else if (!std::strcmp(argv[i], "--orbits") && i + 1 < argc) orbits = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--e") && i + 1 < argc) e = std::atof(argv[++i]);
    }
    const double pi = std::numbers::pi, t_end = 2 * pi * orbits;
    const sympl::hamiltonians::kepler h{};
    const K x0 = sympl::hamiltonians::kepler::initial_state(e);
    const K exact = sympl::hamiltonians::kepler::exact_state(e, t_end);
    const double scale = std::max(exact.q.cwiseAbs().maxCoeff(), exact.p.cwiseAbs().maxCoeff());

    std::vector<contender> all;
    for (const char* t : {"blanes_moan_s6", "blanes_moan_s10", "kahan_li_8", "sofroniou_spaletta_10"}) {
        const sympl::table method = sympl::method(t);
        all.push_back({std::string("logh(") + t + ")", false, 1.0, 1e-4, [=](double ds) {
                           KX X = sympl::to_extended(h, x0);
                           sympl::splitting_stepper<sympl::logh<sympl::hamiltonians::kepler>, KX> s({h}, method);
                           sympl::integrate_to_time(s, X, t_end, ds);
                           return sympl::physical_state(X);
                       }});
    }
    // The LogH leapfrog extrapolated (extrapolation.hpp), as Mikkola & Tanikawa 1999 use it.
    for (int columns : {4, 5, 6, 7, 8}) {
        const sympl::table method = sympl::method("leapfrog_dkd");
        all.push_back({"extrapolated(logh(leapfrog_dkd), " + std::to_string(columns) + ")", false, 3.0, 0.01, [=](double ds) {
                           KX X = sympl::to_extended(h, x0);
                           sympl::extrapolation_stepper s(
                               sympl::splitting_stepper<sympl::logh<sympl::hamiltonians::kepler>, KX>({h}, method), columns);
                           sympl::integrate_to_time(s, X, t_end, ds);
                           return sympl::physical_state(X);
                       }});
    }
    for (const char* t : {"blanes_moan_s6", "sofroniou_spaletta_10"}) {
        const sympl::table method = sympl::method(t);
        all.push_back({t, false, 0.05, 1e-6, [=](double dt) {
                           K x = x0;
                           auto s = sympl::make_stepper<K>(h, method);
                           sympl::integrate_until(s, x, 0.0, t_end, dt);
                           return x;
                       }});
    }
    const auto rhs = [&](const Y& y, Y& dy, double) {
        const double r2 = y[0] * y[0] + y[1] * y[1], inv_r3 = 1 / (r2 * std::sqrt(r2));
        dy = {y[2], y[3], -y[0] * inv_r3, -y[1] * inv_r3};
    };
    const Y y0 = {x0.q[0], x0.q[1], x0.p[0], x0.p[1]};
    const auto to_k = [](const Y& y) { return K(Eigen::Vector2d(y[0], y[1]), Eigen::Vector2d(y[2], y[3])); };
    all.push_back({"odeint_rk4", false, 0.05, 1e-6, [=](double dt) {
                       Y y = y0;
                       odeint::runge_kutta4<Y> s;
                       const auto n = static_cast<long>(std::ceil(t_end / dt));
                       odeint::integrate_n_steps(s, rhs, y, 0.0, t_end / double(n), n);
                       return to_k(y);
                   }});
    const auto adaptive = [&](auto make) {
        return [=](double tol) {
            Y y = y0;
            auto s = make(tol);
            odeint::integrate_adaptive(s, rhs, y, 0.0, t_end, 1e-3);
            return to_k(y);
        };
    };
    all.push_back({"odeint_dopri5", true, 1e-3, 1e-15, adaptive([](double tol) {
                       return odeint::make_controlled(tol, tol, odeint::runge_kutta_dopri5<Y>());
                   })});
    all.push_back({"odeint_fehlberg78", true, 1e-3, 1e-15, adaptive([](double tol) {
                       return odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<Y>());
                   })});
    all.push_back({"odeint_bulirsch_stoer", true, 1e-3, 1e-15,
                   adaptive([](double tol) { return odeint::bulirsch_stoer<Y>(tol, tol); })});

    std::printf("Kepler e = %g, %d orbits, final error %g (relative, max norm); Release -O3 -march=native\n", e, orbits,
                target);
    std::printf("%-40s %14s %12s %12s %10s\n", "method", "step/tolerance", "error", "time [s]", "vs best sympl");
    struct result {
        std::string name;
        double parameter, error, seconds;
        bool sympl;
    };
    std::vector<result> results;
    for (const contender& c : all) {
        const auto error = [&](double p) {
            const K x = c.run(p);
            const double d = sympl::max_difference(x, exact) / scale;
            return std::isfinite(d) ? d : 1e300;
        };
        const std::optional<double> found = sympl::bench::loosest_meeting(error, c.loose, c.tight, target, 24);
        if (!found) {
            std::printf("%-40s %14s\n", c.name.c_str(), "not reached");
            continue;
        }
        const double p = *found;
        const double seconds = sympl::bench::seconds_of([&] { (void)c.run(p); }, repeats);
        results.push_back({c.name, p, error(p), seconds, c.name.rfind("odeint", 0) != 0});
    }
    double best = 1e300;
    for (const result& r : results)
        if (r.sympl) best = std::min(best, r.seconds);
    for (const result& r : results)
        std::printf("%-40s %14.4g %12.3g %12.4g %9.2fx\n", r.name.c_str(), r.parameter, r.error, r.seconds, r.seconds / best);
    return 0;
}
