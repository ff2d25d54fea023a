// Per-step cost of sympl's generic stepper against tight hand-written loops
// and Boost.Odeint running the same table, side by side in one process.
//
// Problems: Kepler and Henon-Heiles (2-D, fixed-size states), FPU-beta chains
// of N = 1e3 and 1e5 (and 1e6 with --large, SB3A only). Tables: leapfrog KDK
// (velocity Verlet), McLachlan's SB3A (Odeint's symplectic_rkn_sb3a_mclachlan)
// and Blanes & Moan's S10 (a 10-stage table, run in Odeint through its
// symplectic_nystroem_stepper_base with the same coefficients).
//
// Contenders, all calling the same inlined force kernel:
//   hand          a tight loop over std::array (2-D) or std::vector (FPU), the
//                 stage count and the drift-first / kick-first pattern known at
//                 compile time, the last force reused (leapfrog) and the last
//                 drift joined with the next step's first (drift-first tables);
//   sympl raw     sympl::splitting_stepper::steps(x, dt, n) on a user-style
//                 Hamiltonian whose force(q, f) calls the kernel through
//                 q.data() and f.data(), velocity(p) returning p;
//   hand Eigen    (2-D problems) the same loops with q, p, f in fixed-size
//                 Eigen vectors and the force written as Eigen expressions;
//   sympl eigen   the same with the force written as Eigen expressions
//                 (measured against hand Eigen where there is one);
//   sympl step()  the raw-pointer Hamiltonian, one step() call per step: each
//                 call checks q against the q its kept force belongs to and
//                 reuses that force (printed: step() loop / steps(n));
//   hand per call (leapfrog) one hand-written step per call, the state and
//                 the kept force in memory between calls, no checks: its ratio
//                 to the hand loop is the floor of step()'s to steps(n);
//   odeint        do_step per step, the momentum derivative calling the kernel.
// Per-step cost with set-up cancelled: (time of 2n steps - time of n steps) / n,
// in rounds that run every contender once (interleaved, so a slow spell of a
// shared machine falls on all), median over the rounds.
//   bench_splitting [--quick] [--large] [--leapfrog]   (--leapfrog: that table only)
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
#include <sympl/hamiltonians/kepler.hpp>

namespace odeint = boost::numeric::odeint;

namespace {

// ---- the force kernels (raw pointers) and their Eigen-expression twins ------
struct kepler_kernel {
    static constexpr int dimension = 2;
    void operator()(const double* q, double* f) const {
        const double r2 = q[0] * q[0] + q[1] * q[1];
        const double k = -1.0 / (r2 * std::sqrt(r2));
        f[0] = k * q[0];
        f[1] = k * q[1];
    }
    template <class V> void eigen_force(const V& q, V& f) const {
        const double r2 = q.squaredNorm();
        f = q * (-1.0 / (r2 * std::sqrt(r2)));
    }
    template <class V> auto potential(const V& q) const { using std::sqrt; return -1 / sqrt(q.squaredNorm()); }
};

struct henon_heiles_kernel {
    static constexpr int dimension = 2;
    void operator()(const double* q, double* f) const {
        f[0] = -q[0] - 2 * q[0] * q[1];
        f[1] = -q[1] - q[0] * q[0] + q[1] * q[1];
    }
    template <class V> void eigen_force(const V& q, V& f) const {
        f = -q - Eigen::Vector2d(2 * q[0] * q[1], q[0] * q[0] - q[1] * q[1]);
    }
    template <class V> auto potential(const V& q) const {
        return (q[0] * q[0] + q[1] * q[1]) / 2 + q[0] * q[0] * q[1] - q[1] * q[1] * q[1] / 3;
    }
};

// FPU-beta with fixed ends: f_i = phi'(q_{i+1} - q_i) - phi'(q_i - q_{i-1}), phi'(r) = r + beta r^3.
struct fpu_kernel {
    long n;
    double beta = 1.0;
    void operator()(const double* q, double* f) const {
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
    // One pass, phi' evaluated twice per bond: what Eigen expressions give.
    template <class V> void eigen_force(const V& q, V& f) const {
        const auto phi = [this](const auto& r) { return r + beta * r.cube(); };
        const auto a = q.array();
        f.segment(1, n - 2) = phi(a.segment(2, n - 2) - a.segment(1, n - 2)) - phi(a.segment(1, n - 2) - a.head(n - 2));
        const double r0 = q[1] - q[0], rn = -q[n - 1], q0 = q[0], d = q[n - 1] - q[n - 2];
        f[0] = (r0 + beta * r0 * r0 * r0) - (q0 + beta * q0 * q0 * q0);
        f[n - 1] = (rn + beta * rn * rn * rn) - (d + beta * d * d * d);
    }
    template <class V> auto potential(const V& q) const {
        typename V::Scalar v(0);
        for (long i = 0; i <= n; ++i) {
            const auto r = (i < n ? q[i] : 0.0) - (i > 0 ? q[i - 1] : 0.0);
            v += r * r / 2 + beta * r * r * r * r / 4;
        }
        return v;
    }
};

// The user-style Hamiltonians sympl runs: T = |p|^2 / 2, velocity(p) = p,
// the force through raw pointers or as Eigen expressions.
enum class force_style { raw_pointers, eigen_expressions };
template <class Kernel, force_style Style>
struct user_hamiltonian {
    Kernel kernel;
    template <class V> auto kinetic(const V& p) const { return p.squaredNorm() / 2; }
    template <class V> auto potential(const V& q) const { return kernel.potential(q); }
    template <class V> const V& velocity(const V& p) const { return p; }
    template <class V> void force(const V& q, V& f) const {
        if constexpr (Style == force_style::raw_pointers) kernel(q.data(), f.data());
        else kernel.eigen_force(q, f);
    }
};

// ---- tight hand-written loops ---------------------------------------------
// What a performance-minded user writes: the state in locals (a fixed-size
// state lives in registers; a large one behind restrict pointers, so the
// compiler knows the force does not write into q or p), the stages unrolled,
// the half kicks of consecutive leapfrog steps joined and the last drift of a
// drift-first step joined with the next step's first.
template <int N, class Body>
void with_local_state(double* q_io, double* p_io, long n_runtime, const Body& body) {
    if constexpr (N > 0) {
        std::array<double, N> q, p, f;
        std::copy(q_io, q_io + N, q.begin());
        std::copy(p_io, p_io + N, p.begin());
        body(q.data(), p.data(), f.data(), long(N));
        std::copy(q.begin(), q.end(), q_io);
        std::copy(p.begin(), p.end(), p_io);
    } else {
        std::vector<double> f(static_cast<std::size_t>(n_runtime));
        body(q_io, p_io, f.data(), n_runtime);
    }
}

// Leapfrog KDK: half kick, then (drift, force, full kick) per step, less a half kick at the end.
template <int N, class Force>
void hand_leapfrog(double* q_io, double* p_io, long n_runtime, double dt, long steps, const Force& force) {
    with_local_state<N>(q_io, p_io, n_runtime, [&](double* __restrict q, double* __restrict p, double* __restrict f, long n) {
        force(q, f);
        for (long i = 0; i < n; ++i) p[i] += 0.5 * dt * f[i];
        for (long s = 0; s < steps; ++s) {
            for (long i = 0; i < n; ++i) q[i] += dt * p[i];
            force(q, f);
            const double h = s + 1 < steps ? dt : 0.5 * dt;
            for (long i = 0; i < n; ++i) p[i] += h * f[i];
        }
    });
}

// One leapfrog step per call, q, p and the last force in memory between
// calls, as a loop of stepper.step() has them: the half kick and the drift
// in one pass, the force, the second half kick; no checks. Its cost over
// hand_leapfrog's is the floor for sympl's step() loop over steps(n).
template <int N, class Force>
[[gnu::noinline]] void hand_leapfrog_one_step(double* __restrict q, double* __restrict p, double* __restrict f,
                                              long n_runtime, double dt, const Force& force) {
    const long n = N > 0 ? N : n_runtime;
    for (long i = 0; i < n; ++i) {
        p[i] += 0.5 * dt * f[i];
        q[i] += dt * p[i];
    }
    force(q, f);
    for (long i = 0; i < n; ++i) p[i] += 0.5 * dt * f[i];
}

// Drift-first D d0 K k0 D d1 ... K k(K-1) D dK, K known at compile time.
template <int N, int K, class Force>
void hand_drift_first(double* q_io, double* p_io, long n_runtime, double dt, long steps,
                      const std::array<double, K + 1>& drift, const std::array<double, K>& kick, const Force& force) {
    std::array<double, K + 1> hd;
    std::array<double, K> hk;
    for (int k = 0; k <= K; ++k) hd[k] = drift[k] * dt;
    for (int k = 0; k < K; ++k) hk[k] = kick[k] * dt;
    with_local_state<N>(q_io, p_io, n_runtime, [&](double* __restrict q, double* __restrict p, double* __restrict f, long n) {
        for (long i = 0; i < n; ++i) q[i] += hd[0] * p[i];
        for (long s = 0; s < steps; ++s) {
#pragma GCC unroll 16
            for (int k = 0; k < K - 1; ++k) {
                force(q, f);
                for (long i = 0; i < n; ++i) p[i] += hk[k] * f[i];
                for (long i = 0; i < n; ++i) q[i] += hd[k + 1] * p[i];
            }
            force(q, f);
            for (long i = 0; i < n; ++i) p[i] += hk[K - 1] * f[i];
            const double d = s + 1 < steps ? hd[K] + hd[0] : hd[K];
            for (long i = 0; i < n; ++i) q[i] += d * p[i];
        }
    });
}

// The same two loops for a user who keeps a small state in Eigen vectors and
// writes the force as Eigen expressions: q, p, f fixed-size locals, updated by
// Eigen expressions. The stepper's cost for that force is measured against this.
template <int N, class Force>
void hand_leapfrog_eigen(double* q_io, double* p_io, double dt, long steps, const Force& force) {
    using Vec = Eigen::Matrix<double, N, 1>;
    Vec q = Eigen::Map<Vec>(q_io), p = Eigen::Map<Vec>(p_io), f;
    force(q, f);
    p += 0.5 * dt * f;
    for (long s = 0; s < steps; ++s) {
        q += dt * p;
        force(q, f);
        p += (s + 1 < steps ? dt : 0.5 * dt) * f;
    }
    std::copy(q.data(), q.data() + N, q_io);
    std::copy(p.data(), p.data() + N, p_io);
}

template <int N, int K, class Force>
void hand_drift_first_eigen(double* q_io, double* p_io, double dt, long steps, const std::array<double, K + 1>& drift,
                            const std::array<double, K>& kick, const Force& force) {
    using Vec = Eigen::Matrix<double, N, 1>;
    std::array<double, K + 1> hd;
    std::array<double, K> hk;
    for (int k = 0; k <= K; ++k) hd[k] = drift[k] * dt;
    for (int k = 0; k < K; ++k) hk[k] = kick[k] * dt;
    Vec q = Eigen::Map<Vec>(q_io), p = Eigen::Map<Vec>(p_io), f;
    q += hd[0] * p;
    for (long s = 0; s < steps; ++s) {
#pragma GCC unroll 16
        for (int k = 0; k < K - 1; ++k) {
            force(q, f);
            p += hk[k] * f;
            q += hd[k + 1] * p;
        }
        force(q, f);
        p += hk[K - 1] * f;
        q += (s + 1 < steps ? hd[K] + hd[0] : hd[K]) * p;
    }
    std::copy(q.data(), q.data() + N, q_io);
    std::copy(p.data(), p.data() + N, p_io);
}

// ---- Odeint: the same table through its Nystrom base (drift, then kick, per stage) ----
template <std::size_t Stages, class C>
using odeint_nystrom =
    odeint::symplectic_nystroem_stepper_base<Stages, 4, C, C, double, C, C, double,
                                             typename odeint::algebra_dispatcher<C>::algebra_type,
                                             typename odeint::operations_dispatcher<C>::operations_type,
                                             odeint::initially_resizer>;
template <std::size_t Stages, class C>
struct odeint_table_stepper : odeint_nystrom<Stages, C> {
    using typename odeint_nystrom<Stages, C>::coef_type;
    odeint_table_stepper(const coef_type& drift, const coef_type& kick) : odeint_nystrom<Stages, C>(drift, kick) {}
};

// ---- timing ------------------------------------------------------------------
double seconds(const std::function<void()>& f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A contender: reset to the initial state, run n steps, return a number of the state (kept live).
struct contender {
    std::string name;
    std::function<void()> reset;
    std::function<double(long)> run;
    std::vector<double> per_step = {};  // ns, one per round
    double median() {
        std::sort(per_step.begin(), per_step.end());
        return per_step[per_step.size() / 2];
    }
};

volatile double sink = 0;

void measure(std::vector<contender>& cs, long n, int rounds) {
    for (int r = 0; r < rounds; ++r)
        for (contender& c : cs) {
            c.reset();
            const double t1 = seconds([&] { sink = sink + c.run(n); });
            c.reset();
            const double t2 = seconds([&] { sink = sink + c.run(2 * n); });
            c.per_step.push_back(std::max(t2 - t1, 0.0) / double(n) * 1e9);
        }
}

void print(const char* runnable_system, const char* scheme, std::vector<contender>& cs) {
    std::printf("%s, %s\n", runnable_system, scheme);
    // "/ hand": over the hand loop of the same force style where there is one
    // (the 2-D problems), else over the raw-pointer hand loop.
    const auto eigen_style = [](const contender& c) { return c.name.find("Eigen") != std::string::npos; };
    const auto per_call = [](const contender& c) { return c.name.find("per step") != std::string::npos; };
    double hand = 0, hand_eigen = 0, odeint_ns = 0;
    for (contender& c : cs) {
        if (c.name.rfind("hand", 0) == 0 && !per_call(c)) (eigen_style(c) ? hand_eigen : hand) = c.median();
        if (c.name.rfind("odeint", 0) == 0) odeint_ns = c.median();
    }
    std::printf("  %-52s %11s %9s %9s\n", "", "ns/step", "/ hand", "/ odeint");
    for (contender& c : cs) {
        const double reference = eigen_style(c) && hand_eigen > 0 ? hand_eigen : hand;
        std::printf("  %-52s %11.2f %9.3f %9.3f\n", c.name.c_str(), c.median(), c.median() / reference,
                    c.median() / odeint_ns);
    }
    // The conventional loop against the library's own, raw-pointer force both (issue 37: within 1.15).
    // The hand loop's own ratio, one call per step against one loop, is that
    // ratio's floor: the state crossing each call in memory.
    double steps_ns = 0, step_ns = 0, hand_call_ns = 0;
    for (contender& c : cs) {
        if (c.name == "sympl raw-pointer force, steps(n)") steps_ns = c.median();
        if (c.name == "sympl raw-pointer force, step() per step") step_ns = c.median();
        if (c.name == "hand leapfrog, one call per step") hand_call_ns = c.median();
    }
    if (steps_ns > 0) std::printf("  step() loop / steps(n): %.3f\n", step_ns / steps_ns);
    if (hand_call_ns > 0 && hand > 0)
        std::printf("  hand: one call per step / one loop: %.3f\n", hand_call_ns / hand);
    std::printf("\n");
}

struct scheme {
    const char* label;
    const char* table;
};

// One problem: every scheme, every contender. State: q0, p0 of dimension N (0: dynamic, n).
template <int N, class Kernel>
void run_problem(const char* runnable_system, const Kernel& kernel, const std::vector<double>& q0, const std::vector<double>& p0,
                 double dt, long n_steps, int rounds, const std::vector<scheme>& schemes) {
    const long n = long(q0.size());
    using State = sympl::phase_space<double, N == 0 ? Eigen::Dynamic : N>;
    using C = std::conditional_t<N == 0, std::vector<double>, std::array<double, std::size_t(N > 0 ? N : 1)>>;
    const auto to_state = [&] {
        State x(n);
        for (long i = 0; i < n; ++i) x.q[i] = q0[i], x.p[i] = p0[i];
        return x;
    };
    const auto to_container = [&](const std::vector<double>& v) {
        C c{};
        if constexpr (N == 0) c = v;
        else std::copy(v.begin(), v.end(), c.begin());
        return c;
    };
    for (const scheme& sc : schemes) {
        const sympl::table t = sympl::method(sc.table);
        std::vector<contender> cs;
        State x = to_state();
        C q = to_container(q0), p = to_container(p0);
        auto raw = sympl::make_stepper<State>(user_hamiltonian<Kernel, force_style::raw_pointers>{kernel}, t);
        auto eig = sympl::make_stepper<State>(user_hamiltonian<Kernel, force_style::eigen_expressions>{kernel}, t);
        const auto reset_state = [&, x0 = x] { x = x0; };
        const auto reset_arrays = [&] { q = to_container(q0); p = to_container(p0); };
        const auto subs = t.substeps();
        const bool leapfrog = std::string(sc.table) == "leapfrog_kdk";
        // hand
        if (leapfrog) {
            cs.push_back({"hand leapfrog", reset_arrays, [&](long k) {
                              hand_leapfrog<N>(q.data(), p.data(), n, dt, k, kernel);
                              return q[0];
                          }});
        }
        // The drift-first tables here: SB3A (5 kicks) and S10 (10 kicks).
        std::array<double, 6> d5{};
        std::array<double, 5> k5{};
        std::array<double, 11> d10{};
        std::array<double, 10> k10{};
        if (!leapfrog) {
            const std::size_t kicks = subs.size() / 2;
            for (std::size_t i = 0; i < subs.size(); ++i) {
                const double w = double(subs[i].weight);
                if (kicks == 5) (i % 2 ? k5[i / 2] : d5[i / 2]) = w;
                else (i % 2 ? k10[i / 2] : d10[i / 2]) = w;
            }
            if (kicks == 5)
                cs.push_back({"hand drift-first, 5 kicks", reset_arrays, [&](long k) {
                                  hand_drift_first<N, 5>(q.data(), p.data(), n, dt, k, d5, k5, kernel);
                                  return q[0];
                              }});
            else
                cs.push_back({"hand drift-first, 10 kicks", reset_arrays, [&](long k) {
                                  hand_drift_first<N, 10>(q.data(), p.data(), n, dt, k, d10, k10, kernel);
                                  return q[0];
                              }});
        }
        // The hand loops of an Eigen user (2-D problems).
        const auto eigen_force = [&kernel](const auto& qq, auto& ff) { kernel.eigen_force(qq, ff); };
        if constexpr (N > 0) {
            if (leapfrog)
                cs.push_back({"hand leapfrog, Eigen-expression force", reset_arrays, [&](long k) {
                                  hand_leapfrog_eigen<N>(q.data(), p.data(), dt, k, eigen_force);
                                  return q[0];
                              }});
            else if (subs.size() / 2 == 5)
                cs.push_back({"hand drift-first, 5 kicks, Eigen-expression force", reset_arrays, [&](long k) {
                                  hand_drift_first_eigen<N, 5>(q.data(), p.data(), dt, k, d5, k5, eigen_force);
                                  return q[0];
                              }});
            else
                cs.push_back({"hand drift-first, 10 kicks, Eigen-expression force", reset_arrays, [&](long k) {
                                  hand_drift_first_eigen<N, 10>(q.data(), p.data(), dt, k, d10, k10, eigen_force);
                                  return q[0];
                              }});
        }
        cs.push_back({"sympl raw-pointer force, steps(n)", [&] { reset_state(); raw.reset_counters(); }, [&](long k) {
                          raw.steps(x, dt, std::size_t(k));
                          return x.q[0];
                      }});
        cs.push_back({"sympl Eigen-expression force, steps(n)", [&] { reset_state(); }, [&](long k) {
                          eig.steps(x, dt, std::size_t(k));
                          return x.q[0];
                      }});
        cs.push_back({"sympl raw-pointer force, step() per step", reset_state, [&](long k) {
                          for (long i = 0; i < k; ++i) raw.step(x, dt);
                          return x.q[0];
                      }});
        C f_kept = to_container(q0);  // the hand loop's force kept between calls
        if (leapfrog)
            cs.push_back({"hand leapfrog, one call per step", [&] { reset_arrays(); kernel(q.data(), f_kept.data()); },
                          [&](long k) {
                              for (long i = 0; i < k; ++i)
                                  hand_leapfrog_one_step<N>(q.data(), p.data(), f_kept.data(), n, dt, kernel);
                              return q[0];
                          }});
        // odeint
        const auto dq = [](const C& pp, C& d) { d = pp; };
        const auto dp = [&](const C& qq, C& d) { kernel(qq.data(), d.data()); };
        odeint::velocity_verlet<C> vv;
        odeint::symplectic_rkn_sb3a_mclachlan<C> sb3a;
        typename odeint_table_stepper<11, C>::coef_type od{}, ok{};
        for (int i = 0; i < 11; ++i) od[i] = d10[i], ok[i] = i < 10 ? k10[i] : 0.0;
        odeint_table_stepper<11, C> s10(od, ok);
        if (leapfrog)
            cs.push_back({"odeint velocity_verlet", [&] { reset_arrays(); vv.reset(); }, [&](long k) {
                              auto accel = [&](const C& qq, const C&, C& a, double) { kernel(qq.data(), a.data()); };
                              for (long i = 0; i < k; ++i) vv.do_step(accel, std::make_pair(std::ref(q), std::ref(p)), 0.0, dt);
                              return q[0];
                          }});
        else if (subs.size() / 2 == 5)
            cs.push_back({"odeint symplectic_rkn_sb3a_mclachlan", reset_arrays, [&](long k) {
                              for (long i = 0; i < k; ++i)
                                  sb3a.do_step(std::make_pair(dq, dp), std::make_pair(std::ref(q), std::ref(p)), 0.0, dt);
                              return q[0];
                          }});
        else
            cs.push_back({"odeint nystrom base, the same 10-kick table", reset_arrays, [&](long k) {
                              for (long i = 0; i < k; ++i)
                                  s10.do_step(std::make_pair(dq, dp), std::make_pair(std::ref(q), std::ref(p)), 0.0, dt);
                              return q[0];
                          }});
        measure(cs, n_steps, rounds);
        print(runnable_system, sc.label, cs);
    }
}

}  // namespace

int main(int argc, char** argv) {
    bool quick = false, large = false, leapfrog_only = false;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) quick = true;
        else if (std::strcmp(argv[i], "--large") == 0) large = true;
        else if (std::strcmp(argv[i], "--leapfrog") == 0) leapfrog_only = true;
        else {
            std::fprintf(stderr, "bench_splitting: unknown argument '%s'; expected --quick, --large or --leapfrog\n",
                         argv[i]);
            return 2;
        }
    }
    const int rounds = quick ? 7 : 21;
    std::printf("bench_splitting: per-step cost, set-up cancelled ((t(2n) - t(n)) / n), median of %d interleaved rounds\n\n",
                rounds);
    const scheme sb3a = {"SB3A (McLachlan 1995), 5 forces", "odeint_sb3a_mclachlan"};
    std::vector<scheme> all = {{"leapfrog (velocity Verlet)", "leapfrog_kdk"}, sb3a,
                               {"S10 (Blanes & Moan 2002), 10 forces", "blanes_moan_s10"}};
    if (leapfrog_only) all.resize(1);
    const auto kepler0 = sympl::hamiltonians::kepler::initial_state(0.5);
    run_problem<2>("Kepler e = 0.5", kepler_kernel{}, {kepler0.q[0], kepler0.q[1]}, {kepler0.p[0], kepler0.p[1]}, 1e-3,
                   quick ? 20000 : 100000, rounds, all);
    run_problem<2>("Henon-Heiles E = 1/8", henon_heiles_kernel{}, {0.0, 0.1}, {std::sqrt(0.25 - 0.01 + 2e-3 / 3), 0.0},
                   1e-2, quick ? 20000 : 100000, rounds, all);
    for (long n : {1000L, 100000L}) {
        std::vector<double> q0(n), p0(n, 0.0);
        for (long i = 0; i < n; ++i)
            q0[i] = 0.1 * std::sin(3.141592653589793 * double(i + 1) / double(n + 1)) + 1e-3 * std::sin(0.37 * double(i));
        const std::string name = "FPU-beta N = " + std::to_string(n);
        run_problem<0>(name.c_str(), fpu_kernel{n}, q0, p0, 0.01, (quick ? 2e6 : 1e7) / double(n), rounds, all);
    }
    if (large) {
        const long n = 1000000;
        std::vector<double> q0(n), p0(n, 0.0);
        for (long i = 0; i < n; ++i) q0[i] = 0.1 * std::sin(3.141592653589793 * double(i + 1) / double(n + 1));
        run_problem<0>("FPU-beta N = 1e6", fpu_kernel{n}, q0, p0, 0.01, quick ? 3 : 6, rounds, {sb3a});
    }
}
