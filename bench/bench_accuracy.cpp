// Time to a given energy accuracy: the largest relative energy error seen over
// a run, |H(x(t_k)) - H0| / |H0|, must stay at or below the target (1e-10
// unless --target). The energy is looked at about 100 times a run, never
// constraining a step: fixed-step methods look every max(1, n/100) steps,
// dense-output steppers interpolate to 101 even times, controlled steppers look
// at the end of the first step past each of those times. For every contender the cheapest
// step (or loosest tolerance) that meets it is found by a scan from loose to
// tight and bisection on its logarithm; that run is then timed (median of
// several). Contenders, side by side in one process on the same force code:
// sympl's catalog tables, force-gradient methods (J_F u analytic: fpu_beta's
// and henon_heiles's force_derivative) and processed methods (processing.hpp;
// the processor applied at each look), sympl's embedded RKN pairs dprkn6,
// dprkn8, dprkn12 (rkn_pairs.hpp; not symplectic), each with fixed steps
// (step() per step, searched over dt) and controlled (integrate_controlled
// with absolute = relative tolerance, searched over it, looked at as Odeint's
// controlled steppers), and Boost.Odeint's runge_kutta4,
// cash_karp54, dopri5 (dense output), fehlberg78, bulirsch_stoer (controlled and
// dense output), adams_bashforth_moulton<8> and its two symplectic RKN steppers.
// Prints times and each one's ratio to the best Odeint method, then the best of
// each kind: "sympl" (symplectic: tables, force-gradient, processed), "sympl-ns"
// (sympl, not symplectic: the RKN pairs) and "odeint".
//   bench_accuracy [--quick] [--target 1e-10] [--large]
// Problems: Henon-Heiles at E = 1/8 (x0 from henon_heiles::initial_state) over
// t = 1000; FPU-beta chains (beta = 1, fixed ends) of N = 1000 over t = 100
// and, with --large, N = 100000 over t = 10, from rest with pseudo-random
// momenta uniform in [-1, 1] (a fixed linear congruential sequence), which
// strains the springs far into the quartic range.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include "cheapest_run.hpp"

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>

namespace odeint = boost::numeric::odeint;

namespace {

constexpr std::size_t looks = 100;  // about this many energy looks a run

enum class kind { symplectic, pair, odeint };  // sympl symplectic, sympl non-symplectic (RKN pairs), Odeint
const char* kind_name(kind k) { return k == kind::symplectic ? "sympl" : k == kind::pair ? "sympl-ns" : "odeint"; }

struct contender {
    std::string name;
    kind of;
    double loose, tight;                // the range searched (a step or a tolerance)
    std::function<double(double)> run;  // max relative energy error for a parameter
};

// |e - e0| / |e0|; a non-finite energy counts as a failure (std::max would skip a NaN).
double relative_error(double e, double e0) { return std::isfinite(e) ? std::fabs(e - e0) / std::fabs(e0) : 1e300; }

// A problem as both libraries see it: sympl's Hamiltonian and state, and
// Odeint's first-order state y = (q, p) with its right-hand side and energy.
template <class H, class X, class Y>
struct runnable_system {
    std::string name;
    H h;
    X x0;
    double t_end;
    std::function<Y(const X&)> to_y;
    std::function<void(const Y&, Y&)> rhs;  // dy/dt
    std::function<double(const Y&)> energy_of;
};

template <class H, class X, class Y>
std::vector<contender> contenders(const runnable_system<H, X, Y>& pr) {
    std::vector<contender> all;
    const double e0 = sympl::energy(pr.h, pr.x0), t_end = pr.t_end;
    const auto relative = [e0](double e) { return relative_error(e, e0); };
    // sympl: n steps of t_end/n, observed every n/100 steps (the driver's observer).
    const auto sympl_run = [&pr, relative, t_end](auto make_stepper) {
        return [&pr, relative, t_end, make_stepper](double dt) {
            const std::size_t n = static_cast<std::size_t>(std::ceil(t_end / dt));
            auto s = make_stepper();
            X x = pr.x0;
            double worst = 0;
            try {
                sympl::integrate_steps(
                    s, x, 0.0, t_end / double(n), n,
                    [&](const X& y, double) { worst = std::max(worst, relative(sympl::energy(pr.h, y))); },
                    sympl::run_options{std::max<std::size_t>(1, n / looks)});
            } catch (const std::exception&) {  // blew up: refused by the driver
                return 1e300;
            }
            return worst;
        };
    };
    for (const char* t : {"blanes_moan_s6", "blanes_moan_s10", "blanes_moan_srkn11b", "blanes_moan_srkn14a",
                          "okunbor_skeel_6", "blanes_casas_escorihuela_a18", "blanes_casas_escorihuela_b17",
                          "blanes_casas_escorihuela_b19", "kahan_li_8", "suzuki_umeno_8", "sofroniou_spaletta_10"}) {
        const sympl::table m = sympl::method(t);
        all.push_back({t, kind::symplectic, 2.0, 1e-4, sympl_run([&pr, m] { return sympl::make_stepper<X>(pr.h, m); })});
    }
    for (const sympl::table& m : sympl::force_gradient_catalog())
        all.push_back({m.name(), kind::symplectic, 2.0, 1e-4, sympl_run([&pr, m] { return sympl::make_stepper<X>(pr.h, m); })});
    for (const sympl::processed_method& m : sympl::processed_catalog())
        all.push_back({m.name, kind::symplectic, 2.0, 1e-4,
                       sympl_run([&pr, m] { return sympl::processed_stepper<H, X>(pr.h, m); })});
    // The embedded RKN pairs (not symplectic): fixed steps like the tables, and
    // controlled, looked at the end of the first step past each of 101 even times.
    const auto add_pair = [&]<class P>() {
        all.push_back({std::string(P::name) + "_fixed", kind::pair, 2.0, 1e-4,
                       sympl_run([&pr] { return sympl::make_rkn_stepper<P, X>(pr.h); })});
        all.push_back({std::string(P::name) + "_controlled", kind::pair, 1e-2, 1e-16,
                       [&pr, relative, t_end](double tol) {
                           auto s = sympl::make_rkn_stepper<P, X>(pr.h);
                           X x = pr.x0;
                           double worst = 0, next = 0;
                           sympl::control_options control;
                           control.absolute_tolerance = control.relative_tolerance = tol;
                           control.dt_initial = t_end / 1e4;  // as Odeint's
                           try {
                               sympl::integrate_controlled(s, x, 0.0, t_end, control, [&](const X& y, double t) {
                                   if (t < next && t < t_end) return;
                                   worst = std::max(worst, relative(sympl::energy(pr.h, y)));
                                   while (next <= t) next += t_end / looks;
                               });
                           } catch (const std::exception&) {  // step size underflow at too tight a tolerance
                               return 1e300;
                           }
                           return worst;
                       }});
    };
    add_pair.template operator()<sympl::dprkn6>();
    add_pair.template operator()<sympl::dprkn8>();
    add_pair.template operator()<sympl::dprkn12>();

    const Y y0 = pr.to_y(pr.x0);
    const auto system = [&pr](const Y& y, Y& dy, double) { pr.rhs(y, dy); };
    const auto times = [t_end] {
        std::vector<double> t;
        for (std::size_t k = 0; k <= looks; ++k) t.push_back(t_end * double(k) / double(looks));
        return t;
    }();
    const auto observe = [&pr, relative](double& worst) {
        return [&pr, relative, &worst](const Y& y, double) { worst = std::max(worst, relative(pr.energy_of(y))); };
    };
    // Fixed steps: n steps of t_end/n, the energy looked at every max(1, n/100).
    const auto fixed = [=](auto make) {
        return [=](double dt) {
            const std::size_t n = static_cast<std::size_t>(std::ceil(t_end / dt)), every = std::max<std::size_t>(1, n / looks);
            const double h = t_end / double(n);
            auto s = make();
            Y y = y0;
            double worst = 0;
            auto look = observe(worst);
            look(y, 0.0);
            for (std::size_t done = 0; done < n && worst < 1e300;) {
                const std::size_t m = std::min(every, n - done);
                odeint::integrate_n_steps(s, system, y, h * double(done), h, m);
                done += m;
                look(y, h * double(done));
            }
            return worst;
        };
    };
    const auto controlled = [=](auto make) {  // look at the first step end past each of 101 even times
        return [=](double tol) {
            auto s = make(tol);
            Y y = y0;
            double worst = 0, next = 0;
            auto look = observe(worst);
            try {
                odeint::integrate_adaptive(s, system, y, 0.0, t_end, t_end / 1e4, [&](const Y& x, double t) {
                    if (t < next && t < t_end) return;
                    look(x, t);
                    while (next <= t) next += t_end / looks;
                });
            } catch (const std::exception&) {  // Odeint gives up (step size underflow at too tight a tolerance)
                return 1e300;
            }
            return worst;
        };
    };
    const auto at_times = [=](auto make) {  // dense output: interpolated to the look times
        return [=](double tol) {
            auto s = make(tol);
            Y y = y0;
            double worst = 0;
            try {
                odeint::integrate_times(s, system, y, times.begin(), times.end(), t_end / 1e4, observe(worst));
            } catch (const std::exception&) {  // Odeint gives up (step size underflow at too tight a tolerance)
                return 1e300;
            }
            return worst;
        };
    };
    all.push_back({"odeint_rk4", kind::odeint, 1.0, 1e-5, fixed([] { return odeint::runge_kutta4<Y>(); })});
    all.push_back({"odeint_abm8", kind::odeint, 1.0, 1e-5, fixed([] { return odeint::adams_bashforth_moulton<8, Y>(); })});
    all.push_back({"odeint_cash_karp54", kind::odeint, 1e-2, 1e-16, controlled([](double tol) {
                       return odeint::make_controlled(tol, tol, odeint::runge_kutta_cash_karp54<Y>());
                   })});
    all.push_back({"odeint_dopri5_dense", kind::odeint, 1e-2, 1e-16, at_times([](double tol) {
                       return odeint::make_dense_output(tol, tol, odeint::runge_kutta_dopri5<Y>());
                   })});
    all.push_back({"odeint_fehlberg78", kind::odeint, 1e-2, 1e-16, controlled([](double tol) {
                       return odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<Y>());
                   })});
    all.push_back({"odeint_bulirsch_stoer", kind::odeint, 1e-2, 1e-16,
                   controlled([](double tol) { return odeint::bulirsch_stoer<Y>(tol, tol); })});
    all.push_back({"odeint_bulirsch_stoer_dense", kind::odeint, 1e-2, 1e-16,
                   at_times([](double tol) { return odeint::bulirsch_stoer_dense_out<Y>(tol, tol); })});
    return all;
}

// The Odeint symplectic RKN steppers take (q, p) separately: their own runner.
template <class H, class X, class Y, class Q>
void add_odeint_rkn(std::vector<contender>& all, const runnable_system<H, X, Y>& pr, std::function<void(const Q&, Q&)> force,
                    std::function<Q(const Eigen::Matrix<double, X::dimension, 1>&)> to_q,
                    std::function<double(const Q&, const Q&)> energy_qp) {
    const double e0 = sympl::energy(pr.h, pr.x0), t_end = pr.t_end;
    const auto make_run = [=](auto make) {
        return [=](double dt) {
            const std::size_t n = static_cast<std::size_t>(std::ceil(t_end / dt)), every = std::max<std::size_t>(1, n / looks);
            const double h = t_end / double(n);
            auto s = make();
            Q q = to_q(pr.x0.q), p = to_q(pr.x0.p);
            const auto rhs = [&](const Q& qq, Q& f) { force(qq, f); };
            const auto relative = [e0](double e) { return relative_error(e, e0); };
            double worst = relative(energy_qp(q, p));
            for (std::size_t i = 1; i <= n && worst < 1e300; ++i) {
                s.do_step(rhs, std::make_pair(std::ref(q), std::ref(p)), 0.0, h);
                if (i % every == 0 || i == n) worst = std::max(worst, relative(energy_qp(q, p)));
            }
            return worst;
        };
    };
    all.push_back({"odeint_rkn_sb3a_mclachlan", kind::odeint, 1.0, 1e-5,
                   make_run([] { return odeint::symplectic_rkn_sb3a_mclachlan<Q>(); })});
}

void report(const std::string& title, const std::vector<contender>& all, double target, int repeats) {
    std::printf("\n%s: time to max relative energy error <= %g (~100 looks); -O3 -march=native\n", title.c_str(),
                target);
    std::printf("%-30s %-9s %12s %10s %12s %14s\n", "method", "kind", "dt/tol", "error", "time [ms]", "best Odeint /");
    struct result {
        std::string name;
        double parameter, error, seconds;
        kind of;
    };
    std::vector<result> results;
    for (const contender& c : all) {
        const std::optional<double> found = sympl::bench::loosest_meeting(c.run, c.loose, c.tight, target, 28);
        if (!found) {
            std::printf("%-30s %-9s %12s\n", c.name.c_str(), kind_name(c.of), "not reached");
            continue;
        }
        const double p = *found;
        double error = 0;
        const double seconds = sympl::bench::seconds_of([&] { error = c.run(p); }, repeats, 0.05);
        results.push_back({c.name, p, error, seconds, c.of});
    }
    std::array<double, 3> best{1e300, 1e300, 1e300};
    std::array<std::string, 3> best_name{"none", "none", "none"};
    for (const result& r : results) {
        const auto k = static_cast<std::size_t>(r.of);
        if (r.seconds < best[k]) best[k] = r.seconds, best_name[k] = r.name;
    }
    const double best_odeint = best[static_cast<std::size_t>(kind::odeint)];
    for (const result& r : results)
        std::printf("%-30s %-9s %12.4g %10.3g %12.4g %13.2fx\n", r.name.c_str(), kind_name(r.of), r.parameter, r.error,
                    r.seconds * 1e3, best_odeint / r.seconds);
    for (const kind k : {kind::symplectic, kind::pair, kind::odeint}) {
        const auto i = static_cast<std::size_t>(k);
        std::printf("best %-8s %-30s %10.4g ms  (best Odeint / it = %.2fx)\n", kind_name(k), best_name[i].c_str(),
                    best[i] * 1e3, best_odeint / best[i]);
    }
}

using HH = sympl::hamiltonians::henon_heiles;
using HX = sympl::phase_space<double, 2>;
using HY = std::array<double, 4>;
using HQ = std::array<double, 2>;

void henon_heiles(double target, int repeats) {
    const runnable_system<HH, HX, HY> pr{
        "Henon-Heiles E = 1/8, t = 1000", HH{}, HH::initial_state(1.0 / 8), 1000.0,
        [](const HX& x) { return HY{x.q[0], x.q[1], x.p[0], x.p[1]}; },
        [](const HY& y, HY& d) { d = {y[2], y[3], -y[0] - 2 * y[0] * y[1], -y[1] - y[0] * y[0] + y[1] * y[1]}; },
        [](const HY& y) {
            return (y[2] * y[2] + y[3] * y[3]) / 2 + (y[0] * y[0] + y[1] * y[1]) / 2 + y[0] * y[0] * y[1] -
                   y[1] * y[1] * y[1] / 3;
        }};
    auto all = contenders(pr);
    add_odeint_rkn<HH, HX, HY, HQ>(
        all, pr, [](const HQ& q, HQ& f) { f = {-q[0] - 2 * q[0] * q[1], -q[1] - q[0] * q[0] + q[1] * q[1]}; },
        [](const Eigen::Vector2d& v) { return HQ{v[0], v[1]}; },
        [](const HQ& q, const HQ& p) {
            return (p[0] * p[0] + p[1] * p[1]) / 2 + (q[0] * q[0] + q[1] * q[1]) / 2 + q[0] * q[0] * q[1] -
                   q[1] * q[1] * q[1] / 3;
        });
    report(pr.name, all, target, repeats);
}

using FPU = sympl::hamiltonians::fpu_beta;
using FX = sympl::phase_space<double>;
using FY = std::vector<double>;

// phi'(r) = r + r^3 (beta = 1) between neighbours, fixed ends.
void fpu_force(const double* q, double* f, std::size_t n) {
    double left = q[0] + q[0] * q[0] * q[0];
    for (std::size_t i = 0; i + 1 < n; ++i) {
        const double r = q[i + 1] - q[i], right = r + r * r * r;
        f[i] = right - left;
        left = right;
    }
    const double r = -q[n - 1];
    f[n - 1] = (r + r * r * r) - left;
}
double fpu_energy(const double* q, const double* p, std::size_t n) {
    double e = 0;
    for (std::size_t i = 0; i < n; ++i) e += p[i] * p[i] / 2;
    for (std::size_t i = 0; i <= n; ++i) {
        const double r = (i < n ? q[i] : 0) - (i > 0 ? q[i - 1] : 0), r2 = r * r;
        e += r2 / 2 + r2 * r2 / 4;
    }
    return e;
}

void fpu(std::size_t n, double t_end, double target, int repeats) {
    FX x0(Eigen::VectorXd::Zero(Eigen::Index(n)), Eigen::VectorXd::Zero(Eigen::Index(n)));
    std::uint64_t state = 12345;
    for (std::size_t i = 0; i < n; ++i) {
        state = state * 6364136223846793005ULL + 1442695040888963407ULL;  // Knuth's MMIX LCG
        x0.p[Eigen::Index(i)] = double(state >> 11) / double(1ULL << 53) * 2 - 1;
    }
    const runnable_system<FPU, FX, FY> pr{
        "FPU-beta N = " + std::to_string(n) + ", t = " + std::to_string(int(t_end)), FPU{1.0}, x0, t_end,
        [n](const FX& x) {
            FY y(2 * n);
            for (std::size_t i = 0; i < n; ++i) y[i] = x.q[Eigen::Index(i)], y[n + i] = x.p[Eigen::Index(i)];
            return y;
        },
        [n](const FY& y, FY& d) {
            std::copy(y.begin() + long(n), y.end(), d.begin());
            fpu_force(y.data(), d.data() + n, n);
        },
        [n](const FY& y) { return fpu_energy(y.data(), y.data() + n, n); }};
    auto all = contenders(pr);
    add_odeint_rkn<FPU, FX, FY, FY>(
        all, pr, [n](const FY& q, FY& f) { fpu_force(q.data(), f.data(), n); },
        [](const Eigen::VectorXd& v) { return FY(v.data(), v.data() + v.size()); },
        [n](const FY& q, const FY& p) { return fpu_energy(q.data(), p.data(), n); });
    report(pr.name, all, target, repeats);
}

}  // namespace

int main(int argc, char** argv) {
    double target = 1e-10;
    int repeats = 5;
    bool large = false;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--quick")) repeats = 3;
        else if (!std::strcmp(argv[i], "--large")) large = true;
        else if (!std::strcmp(argv[i], "--target") && i + 1 < argc) target = std::atof(argv[++i]);
        else {
            std::fprintf(stderr, "usage: bench_accuracy [--quick] [--large] [--target 1e-10]\n");
            return 2;
        }
    }
    if (!(target > 0 && target < 1)) {
        std::fprintf(stderr, "bench_accuracy: --target %g; expected a relative error in (0, 1)\n", target);
        return 2;
    }
    henon_heiles(target, repeats);
    fpu(1000, 100, target, repeats);
    if (large) fpu(100000, 10, target, repeats);
    return 0;
}
