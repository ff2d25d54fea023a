// sympl's generic stepper against the same schemes hand-written over raw
// arrays and against Boost.Odeint, side by side in one process, on Kepler and
// on an FPU-beta chain with N = 1e5 (analytic forces everywhere).
// Prints ns/step, force evaluations/step and ratios (best of several runs).
//   bench_splitting [--quick]
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/kepler.hpp>

namespace odeint = boost::numeric::odeint;

namespace {

double best_ns_per_step(int repeats, long steps, const std::function<void()>& setup, const std::function<double()>& run) {
    double best = 1e300;
    volatile double sink = 0;
    for (int r = 0; r < repeats; ++r) {
        setup();
        const auto t0 = std::chrono::steady_clock::now();
        sink = sink + run();
        const auto t1 = std::chrono::steady_clock::now();
        best = std::min(best, std::chrono::duration<double, std::nano>(t1 - t0).count() / steps);
    }
    return best;
}

struct row {
    std::string name;
    double ns;
    double forces;
};

void report(const char* problem, const std::vector<row>& rows, const char* baseline_hand, const char* baseline_odeint,
            const char* scheme) {
    double hand = 0, ode = 0, ours = 0;
    for (const row& r : rows) {
        if (r.name == baseline_hand) hand = r.ns;
        if (r.name == baseline_odeint) ode = r.ns;
        if (r.name.rfind("sympl", 0) == 0) ours = r.ns;
    }
    std::printf("  %-44s %12s %14s\n", scheme, "ns/step", "forces/step");
    for (const row& r : rows) std::printf("  %-44s %12.1f %14.2f\n", r.name.c_str(), r.ns, r.forces);
    std::printf("  ratio sympl / hand-written = %.3f   sympl / odeint = %.3f   (%s)\n\n", ours / hand, ours / ode, problem);
}

// ---- hand-written reference loops -------------------------------------------
void kepler_force(const double* q, double* f) {
    const double r2 = q[0] * q[0] + q[1] * q[1];
    const double k = -1.0 / (r2 * std::sqrt(r2));
    f[0] = k * q[0];
    f[1] = k * q[1];
}

void fpu_force(const double* q, double* f, long n, double beta) {
    double left = q[0] + beta * q[0] * q[0] * q[0];
    for (long i = 0; i + 1 < n; ++i) {
        const double r = q[i + 1] - q[i];
        const double right = r + beta * r * r * r;
        f[i] = right - left;
        left = right;
    }
    const double r = -q[n - 1];
    f[n - 1] = (r + beta * r * r * r) - left;
}

// Leapfrog KDK with the last force reused.
template <class Force>
void hand_leapfrog(double* q, double* p, double* f, long n, double dt, long steps, Force force) {
    force(q, f);
    for (long s = 0; s < steps; ++s) {
        for (long i = 0; i < n; ++i) p[i] += 0.5 * dt * f[i];
        for (long i = 0; i < n; ++i) q[i] += dt * p[i];
        force(q, f);
        for (long i = 0; i < n; ++i) p[i] += 0.5 * dt * f[i];
    }
}

// Drift-first 6-stage SB3A (McLachlan 1995), Odeint's coefficients: 6 drifts, 5 kicks.
template <class Force>
void hand_sb3a(double* q, double* p, double* f, long n, double dt, long steps, Force force) {
    const double a0 = 0.40518861839525227722, a1 = -0.28714404081652408900, a2 = 0.5 - (a0 + a1);
    const double b0 = -3.0 / 73, b1 = 17.0 / 59, b2 = 1 - 2 * (b0 + b1);
    const double a[6] = {a0, a1, a2, a2, a1, a0}, b[5] = {b0, b1, b2, b1, b0};
    for (long s = 0; s < steps; ++s)
        for (int k = 0; k < 6; ++k) {
            const double ha = a[k] * dt;
            for (long i = 0; i < n; ++i) q[i] += ha * p[i];
            if (k == 5) break;
            force(q, f);
            const double hb = b[k] * dt;
            for (long i = 0; i < n; ++i) p[i] += hb * f[i];
        }
}

// ---- the benchmark -----------------------------------------------------------------
void kepler_bench(bool quick) {
    const long steps = quick ? 200000 : 2000000;
    const int repeats = quick ? 3 : 7;
    const double dt = 1e-3;
    using State = sympl::phase_space<double, 2>;
    const State x0 = sympl::hamiltonians::kepler::initial_state(0.5);
    std::printf("Kepler e = 0.5, fixed-size 2D state, %ld steps of dt = %g\n", steps, dt);
    for (int scheme = 0; scheme < 2; ++scheme) {
        std::vector<row> rows;
        const char* table = scheme == 0 ? "leapfrog_kdk" : "odeint_sb3a_mclachlan";
        {
            auto s = sympl::make_stepper<State>(sympl::hamiltonians::kepler{}, sympl::method(table));
            State x = x0;
            const double ns = best_ns_per_step(repeats, steps, [&] { x = x0; s.reset_counters(); },
                                               [&] { s.steps(x, dt, steps); return x.q[0]; });
            rows.push_back({std::string("sympl ") + table, ns, double(s.force_evaluations()) / steps});
        }
        {
            std::array<double, 2> q, p, f;
            long forces = 0;
            auto force = [&](const double* qq, double* ff) { ++forces; kepler_force(qq, ff); };
            const double ns = best_ns_per_step(repeats, steps, [&] { q = {x0.q[0], x0.q[1]}; p = {x0.p[0], x0.p[1]}; forces = 0; },
                [&] {
                    if (scheme == 0) hand_leapfrog(q.data(), p.data(), f.data(), 2, dt, steps, force);
                    else hand_sb3a(q.data(), p.data(), f.data(), 2, dt, steps, force);
                    return q[0];
                });
            rows.push_back({scheme == 0 ? "hand-written leapfrog" : "hand-written sb3a", ns, double(forces) / steps});
        }
        {
            using C = std::array<double, 2>;
            C q, p;
            long forces = 0;
            if (scheme == 0) {
                odeint::velocity_verlet<C> vv;
                auto accel = [&](const C& x, const C&, C& a, double) { ++forces; kepler_force(x.data(), a.data()); };
                const double ns = best_ns_per_step(repeats, steps, [&] { q = {x0.q[0], x0.q[1]}; p = {x0.p[0], x0.p[1]}; forces = 0; vv.reset(); },
                    [&] { for (long s = 0; s < steps; ++s) vv.do_step(accel, std::make_pair(std::ref(q), std::ref(p)), 0.0, dt); return q[0]; });
                rows.push_back({"odeint velocity_verlet", ns, double(forces) / steps});
            } else {
                odeint::symplectic_rkn_sb3a_mclachlan<C> sb;
                auto dq = [](const C& pp, C& d) { d = pp; };
                auto dp = [&](const C& x, C& d) { ++forces; kepler_force(x.data(), d.data()); };
                const double ns = best_ns_per_step(repeats, steps, [&] { q = {x0.q[0], x0.q[1]}; p = {x0.p[0], x0.p[1]}; forces = 0; },
                    [&] { for (long s = 0; s < steps; ++s) sb.do_step(std::make_pair(dq, dp), std::make_pair(std::ref(q), std::ref(p)), 0.0, dt); return q[0]; });
                rows.push_back({"odeint symplectic_rkn_sb3a_mclachlan", ns, double(forces) / steps});
            }
        }
        report("Kepler", rows, scheme == 0 ? "hand-written leapfrog" : "hand-written sb3a",
               scheme == 0 ? "odeint velocity_verlet" : "odeint symplectic_rkn_sb3a_mclachlan",
               scheme == 0 ? "leapfrog (velocity Verlet)" : "4th order: McLachlan SB3A, 6 stages");
    }
}

void fpu_bench(bool quick) {
    const long n = 100000;
    const long steps = quick ? 20 : 200;
    const int repeats = quick ? 3 : 5;
    const double dt = 0.01, beta = 1.0;
    std::vector<double> q0(n), p0(n, 0.0);
    for (long i = 0; i < n; ++i) q0[i] = 0.1 * std::sin(3.141592653589793 * (i + 1) / (n + 1)) + 1e-3 * std::sin(0.37 * i);
    std::printf("FPU-beta chain, N = %ld, dynamic state, %ld steps of dt = %g\n", n, steps, dt);
    using State = sympl::phase_space<double>;
    const Eigen::Map<const Eigen::VectorXd> q0m(q0.data(), n), p0m(p0.data(), n);
    for (int scheme = 0; scheme < 2; ++scheme) {
        std::vector<row> rows;
        const char* table = scheme == 0 ? "leapfrog_kdk" : "odeint_sb3a_mclachlan";
        {
            auto s = sympl::make_stepper<State>(sympl::hamiltonians::fpu_beta{beta}, sympl::method(table));
            State x(q0m, p0m);
            const double ns = best_ns_per_step(repeats, steps, [&] { x.q = q0m; x.p = p0m; s.reset_counters(); },
                                               [&] { s.steps(x, dt, steps); return x.q[7]; });
            rows.push_back({std::string("sympl ") + table, ns, double(s.force_evaluations()) / steps});
        }
        {
            std::vector<double> q, p, f(n);
            long forces = 0;
            auto force = [&](const double* qq, double* ff) { ++forces; fpu_force(qq, ff, n, beta); };
            const double ns = best_ns_per_step(repeats, steps, [&] { q = q0; p = p0; forces = 0; },
                [&] {
                    if (scheme == 0) hand_leapfrog(q.data(), p.data(), f.data(), n, dt, steps, force);
                    else hand_sb3a(q.data(), p.data(), f.data(), n, dt, steps, force);
                    return q[7];
                });
            rows.push_back({scheme == 0 ? "hand-written leapfrog" : "hand-written sb3a", ns, double(forces) / steps});
        }
        {
            using C = std::vector<double>;
            C q, p;
            long forces = 0;
            if (scheme == 0) {
                odeint::velocity_verlet<C> vv;
                auto accel = [&](const C& x, const C&, C& a, double) { ++forces; fpu_force(x.data(), a.data(), n, beta); };
                const double ns = best_ns_per_step(repeats, steps, [&] { q = q0; p = p0; forces = 0; vv.reset(); },
                    [&] { for (long s = 0; s < steps; ++s) vv.do_step(accel, std::make_pair(std::ref(q), std::ref(p)), 0.0, dt); return q[7]; });
                rows.push_back({"odeint velocity_verlet", ns, double(forces) / steps});
            } else {
                odeint::symplectic_rkn_sb3a_mclachlan<C> sb;
                auto dq = [](const C& pp, C& d) { d = pp; };
                auto dp = [&](const C& x, C& d) { ++forces; fpu_force(x.data(), d.data(), n, beta); };
                const double ns = best_ns_per_step(repeats, steps, [&] { q = q0; p = p0; forces = 0; },
                    [&] { for (long s = 0; s < steps; ++s) sb.do_step(std::make_pair(dq, dp), std::make_pair(std::ref(q), std::ref(p)), 0.0, dt); return q[7]; });
                rows.push_back({"odeint symplectic_rkn_sb3a_mclachlan", ns, double(forces) / steps});
            }
        }
        report("FPU-beta", rows, scheme == 0 ? "hand-written leapfrog" : "hand-written sb3a",
               scheme == 0 ? "odeint velocity_verlet" : "odeint symplectic_rkn_sb3a_mclachlan",
               scheme == 0 ? "leapfrog (velocity Verlet)" : "4th order: McLachlan SB3A, 6 stages");
    }
}

}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    std::printf("bench_splitting (-O3 -march=native); best of several runs, one process\n\n");
    kepler_bench(quick);
    fpu_bench(quick);
}
