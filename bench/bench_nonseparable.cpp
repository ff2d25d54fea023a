// Per-step cost of the methods for a non-separable H(q, p) against tight
// hand-written loops of the same methods, and per evaluation of the gradient
// pair (dH/dq, dH/dp), on the double pendulum (hamiltonians/double_pendulum.hpp)
// at the step sizes of its built-in scene.
//
// Contenders, all calling the same inlined analytic gradients:
//   gradient pair   dH/dq and dH/dp at one point: the floor every method pays
//                   per evaluation;
//   gauss_2/4/6     sympl::gauss_collocation_stepper, one step() per step;
//   hand gauss      the same iteration written out on std::array: starting
//                   values from the last step's collocation polynomial, fixed
//                   point, the same componentwise stopping rule;
//   tao(yoshida_6)  sympl::tao_stepper (binding from tao_options_for), and a
//                   hand loop of its composed map on std::array;
//   semiexplicit(yoshida_6)  sympl::semiexplicit_stepper (no hand loop: its
//                   cost is the same gradient pairs, counted).
// Per-step cost: a run of n steps timed (processor time), median over rounds that run every
// contender once (interleaved, so a slow spell of a shared machine falls on all).
// --energy instead: the scene's span t = 2000, each method's max relative
// energy error and time (median of 5) over the scene's step sizes, and
// Odeint's Bulirsch-Stoer and Fehlberg 7(8) through integrate_adaptive with
// absolute = relative tolerance (as the program runs them), in one process.
//   bench_nonseparable [--quick | --energy]
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

#include <boost/numeric/odeint.hpp>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/double_pendulum.hpp>

namespace {

using State = sympl::phase_space<double, 2>;
using V = Eigen::Vector2d;
const sympl::hamiltonians::double_pendulum pendulum{};
const State start(V(1.0, 0.5), V(0.2, -0.1));
volatile double sink = 0;

// Processor time of the run: on a shared machine the wall time also counts
// the slices other processes took, and unevenly between short and long runs.
double seconds(const std::function<void()>& run) {
    const std::clock_t t0 = std::clock();
    run();
    return double(std::clock() - t0) / CLOCKS_PER_SEC;
}

// f = (dH/dp, -dH/dq) at y = (q, p) through the system's own gradients.
inline void vector_field(const std::array<double, 4>& y, std::array<double, 4>& f) {
    V q(y[0], y[1]), p(y[2], y[3]), gq, gp;
    pendulum.dH_dq(q, p, gq);
    pendulum.dH_dp(q, p, gp);
    f = {gp[0], gp[1], -gq[0], -gq[1]};
}

// The Gauss-Legendre iteration of gauss_collocation.hpp written out for this
// problem: extrapolated start, fixed point, componentwise scale, rtol = eps,
// the leftover rule and the plateau.
template <int S>
struct hand_gauss {
    std::array<std::array<double, S>, S> a{}, beta{};
    std::array<double, S> c{}, d{};
    std::array<std::array<double, 4>, S> z{}, f{};
    bool started = false;
    long evaluations = 0;

    explicit hand_gauss(double h) {
        const sympl::gauss_tableau t = sympl::gauss_legendre_tableau(S);
        const auto b = sympl::gauss_extrapolation(t, 1.0L);
        for (int i = 0; i < S; ++i) {
            c[i] = double(t.c[i]);
            d[i] = double(t.d[i]);
            for (int j = 0; j < S; ++j) {
                a[i][j] = double(t.a[i][j]) * h;
                beta[i][j] = double(b[i][j]);
            }
        }
    }
    void step(std::array<double, 4>& y, double h) {
        if (started) {
            std::array<std::array<double, 4>, S> n{};
            for (int i = 0; i < S; ++i)
                for (int j = 0; j < S; ++j)
                    for (int k = 0; k < 4; ++k) n[i][k] += beta[i][j] * z[j][k];
            z = n;
        } else {
            std::array<double, 4> f0;
            vector_field(y, f0);
            ++evaluations;
            for (int i = 0; i < S; ++i)
                for (int k = 0; k < 4; ++k) z[i][k] = c[i] * h * f0[k];
            started = true;
        }
        const double eps = std::numeric_limits<double>::epsilon();
        double previous = 0, best = INFINITY;
        int since_best = 0;
        for (int it = 1; it <= 50; ++it) {
            for (int i = 0; i < S; ++i) {
                std::array<double, 4> yi;
                for (int k = 0; k < 4; ++k) yi[k] = y[k] + z[i][k];
                vector_field(yi, f[i]);
            }
            evaluations += S;
            std::array<double, 4> dz{}, ymax{};
            double bq = 0, bp = 0;
            for (int k = 0; k < 4; ++k) {
                ymax[k] = std::fabs(y[k]);
                for (int i = 0; i < S; ++i) {
                    double zn = 0;
                    for (int j = 0; j < S; ++j) zn += a[i][j] * f[j][k];
                    dz[k] = std::max(dz[k], std::fabs(zn - z[i][k]));
                    z[i][k] = zn;
                    ymax[k] = std::max(ymax[k], std::fabs(y[k] + zn));
                }
                (k < 2 ? bq : bp) = std::max(k < 2 ? bq : bp, ymax[k]);
            }
            double e = 0;
            for (int k = 0; k < 4; ++k) e = std::max(e, dz[k] / (eps * (ymax[k] + (k < 2 ? bq : bp))));
            const double theta = it > 1 ? e / previous : 0;
            if (e < best) {
                best = e;
                since_best = 0;
            } else {
                ++since_best;
            }
            if ((e <= 1 && (it == 1 || (theta < 1 && theta / (1 - theta) * e <= 0.125))) ||
                (since_best >= 2 && best <= 0x1p-36 / eps))
                break;
            previous = e;
        }
        for (int i = 0; i < S; ++i)
            for (int k = 0; k < 4; ++k) y[k] += d[i] * z[i][k];
    }
};

// Tao's composed map (extended_phase_space.hpp) written out on std::array:
// per weight g, A(g/2) B(g/2) C(g) B(g/2) A(g/2), neighbouring A's merged, the
// binding in each component's units.
struct hand_tao {
    std::vector<double> gamma;
    double omega;
    std::array<double, 2> root{};
    std::array<double, 2> q{}, p{}, x{}, y{};
    long evaluations = 0;

    hand_tao(const sympl::tao_options& o, const std::vector<long double>& weights)
        : gamma(weights.begin(), weights.end()), omega(o.omega) {
        for (int k = 0; k < 2; ++k) root[k] = std::sqrt(o.momentum_scales.empty() ? o.momentum_scale : o.momentum_scales[k]);
    }
    void gradients(const std::array<double, 2>& a, const std::array<double, 2>& b, V& gq, V& gp) {
        const V qa(a[0], a[1]), pb(b[0], b[1]);
        pendulum.dH_dq(qa, pb, gq);
        pendulum.dH_dp(qa, pb, gp);
        ++evaluations;
    }
    V aq, ap;  // the gradients of the last A, at (q, y): still valid at the next step's first A
    bool cached = false;
    void flow_A(double t) {
        if (!cached) gradients(q, y, aq, ap);
        cached = true;
        const V& gq = aq;
        const V& gp = ap;
        for (int k = 0; k < 2; ++k) {
            p[k] -= t * gq[k];
            x[k] += t * gp[k];
        }
    }
    void flow_B(double t) {
        V gq, gp;
        gradients(x, p, gq, gp);
        cached = false;
        for (int k = 0; k < 2; ++k) {
            q[k] += t * gp[k];
            y[k] -= t * gq[k];
        }
    }
    void flow_C(double t) {
        const double c = std::cos(2 * omega * t), s = std::sin(2 * omega * t);
        for (int k = 0; k < 2; ++k) {
            const double sq = q[k] + x[k], sp = p[k] + y[k];
            const double dq = root[k] * (q[k] - x[k]), dp = (p[k] - y[k]) / root[k];
            const double rq = (c * dq + s * dp) / root[k], rp = root[k] * (c * dp - s * dq);
            q[k] = (sq + rq) / 2;
            x[k] = (sq - rq) / 2;
            p[k] = (sp + rp) / 2;
            y[k] = (sp - rp) / 2;
        }
    }
    void step(double dt) {
        double pending = gamma.front() / 2 * dt;
        for (std::size_t i = 0; i < gamma.size(); ++i) {
            const double h = gamma[i] * dt;
            flow_A(pending);
            flow_B(h / 2);
            flow_C(h);
            flow_B(h / 2);
            pending = h / 2 + (i + 1 < gamma.size() ? gamma[i + 1] / 2 * dt : 0.0);
        }
        flow_A(pending);
    }
};

// The median of the rounds' times.
double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
}

struct row {
    std::string name;
    std::vector<double> per_step;  // seconds per step, one per round
    double evaluations_per_step = 0;
};


// --energy: time to a max relative energy error over the scene's span. Every
// run is one job; the rounds time every job once (interleaved), median of 5.
struct energy_job {
    std::string name;
    double parameter;                       // dt, or Odeint's tolerance
    std::function<double(bool)> run;        // observe: returns max |H/H0 - 1|
    double worst = 0;
    std::vector<double> times{};
};

template <class Make>
void add_sweep(std::vector<energy_job>& jobs, const std::string& name, Make make, double span) {
    const double e0 = sympl::energy(pendulum, start);
    for (int k = 0; k < 9; ++k) {
        const double dt = 0.2 * std::pow(0.005 / 0.2, k / 8.0);
        const long n = std::lround(span / dt);
        jobs.push_back({name, dt, [=](bool observe) {
                            auto s = make();
                            State x = start;
                            double worst = 0;
                            for (long i = 0; i < n; ++i) {
                                s.step(x, dt);
                                if (observe) worst = std::max(worst, std::fabs(sympl::energy(pendulum, x) / e0 - 1));
                            }
                            sink = sink + x.q[0];
                            return worst;
                        }});
    }
}

void energy_report(double span) {
    std::printf("double pendulum over t = %g: max relative energy error and time (median of 5 interleaved rounds)\n",
                span);
    std::vector<energy_job> jobs;
    add_sweep(jobs, "gauss_6", [] { return sympl::make_gauss_collocation<State>(pendulum, 3); }, span);
    add_sweep(jobs, "gauss_4", [] { return sympl::make_gauss_collocation<State>(pendulum, 2); }, span);
    const sympl::tao_options o = sympl::tao_options_for(pendulum, start);
    add_sweep(jobs, "tao(yoshida_6)", [o] { return sympl::make_tao_stepper<State>(pendulum, sympl::method("yoshida_6"), o); },
              span);
    add_sweep(jobs, "semiexplicit(yoshida_6)",
              [] { return sympl::make_semiexplicit_stepper<State>(pendulum, sympl::method("yoshida_6")); }, span);
    namespace odeint = boost::numeric::odeint;
    using S = std::array<double, 4>;
    const double e0 = sympl::energy(pendulum, start);
    for (double tol = 1e-8; tol >= 0.99e-14; tol /= 10)
        for (int kind = 0; kind < 2; ++kind)
            jobs.push_back({kind == 0 ? "odeint_bulirsch_stoer" : "odeint_fehlberg78", tol, [=](bool observe) {
                                const auto rhs = [](const S& y, S& d, double) {
                                    const V q(y[0], y[1]), p(y[2], y[3]);
                                    V a, b;
                                    pendulum.dH_dp(q, p, a);
                                    pendulum.dH_dq(q, p, b);
                                    d = {a[0], a[1], -b[0], -b[1]};
                                };
                                double worst = 0;
                                S y{start.q[0], start.q[1], start.p[0], start.p[1]};
                                const auto seen = [&](const S& z, double) {
                                    if (!observe) return;
                                    const State x(V(z[0], z[1]), V(z[2], z[3]));
                                    worst = std::max(worst, std::fabs(sympl::energy(pendulum, x) / e0 - 1));
                                };
                                if (kind == 0)
                                    odeint::integrate_adaptive(odeint::bulirsch_stoer<S>(tol, tol), rhs, y, 0.0, span, 0.01,
                                                               seen);
                                else
                                    odeint::integrate_adaptive(
                                        odeint::make_controlled(tol, tol, odeint::runge_kutta_fehlberg78<S>()), rhs, y,
                                        0.0, span, 0.01, seen);
                                sink = sink + y[0];
                                return worst;
                            }});
    for (energy_job& j : jobs) j.worst = j.run(true);
    for (int r = 0; r < 5; ++r)
        for (energy_job& j : jobs) j.times.push_back(seconds([&] { j.run(false); }));
    for (const energy_job& j : jobs)
        std::printf("%-26s %s %-9.4g max |H/H0 - 1| %.3e  %.4f s\n", j.name.c_str(),
                    j.name.rfind("odeint", 0) == 0 ? "tol" : "dt ", j.parameter, j.worst, median(j.times));
}

}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    if (argc > 1 && std::strcmp(argv[1], "--energy") == 0) {
        energy_report(2000);
        return 0;
    }
    const int rounds = quick ? 3 : 7;
    const double t_end = quick ? 50 : 200;
    std::printf("double pendulum from (1, 0.5), (0.2, -0.1), t = %g; median of %d interleaved rounds\n", t_end, rounds);

    // The floor: one gradient pair.
    {
        std::vector<double> per;
        for (int r = 0; r < rounds; ++r) {
            const long n = 2000000;
            per.push_back(seconds([&] {
                              V q(1.0, 0.5), p(0.2, -0.1), gq, gp;
                              for (long i = 0; i < n; ++i) {
                                  q[0] += 1e-9;
                                  pendulum.dH_dq(q, p, gq);
                                  pendulum.dH_dp(q, p, gp);
                                  sink = sink + gq[0] + gp[1];
                              }
                          }) / double(n));
        }
        std::printf("gradient pair (dH/dq and dH/dp): %.1f ns\n\n", median(per) * 1e9);
    }

    const sympl::tao_options tao_o = sympl::tao_options_for(pendulum, start);
    std::printf("%-26s %8s %10s %10s %10s %9s %8s\n", "method", "dt", "us/step", "hand", "ratio", "evals", "ns/eval");
    for (const double dt : {0.2, 0.0585, 0.0171}) {
        const long n = std::lround(t_end / dt);
        std::vector<row> rows;
        const auto add = [&](const std::string& name, double evals, double sec) {
            auto it = std::find_if(rows.begin(), rows.end(), [&](const row& r) { return r.name == name; });
            if (it == rows.end()) {
                rows.push_back({name, {}, 0});
                it = rows.end() - 1;
            }
            it->per_step.push_back(sec / double(n));
            it->evaluations_per_step = evals;
        };
        for (int r = 0; r < rounds; ++r) {
            for (int s = 1; s <= 3; ++s) {
                auto g = sympl::make_gauss_collocation<State>(pendulum, s);
                State x = start;
                const double sec = seconds([&] {
                    for (long i = 0; i < n; ++i) g.step(x, dt);
                });
                sink = sink + x.q[0];
                add("gauss_" + std::to_string(2 * s), double(g.force_evaluations()) / double(n), sec);
                std::array<double, 4> y{start.q[0], start.q[1], start.p[0], start.p[1]};
                long evals = 0;
                const double hand = seconds([&] {
                    if (s == 1) { hand_gauss<1> h(dt); for (long i = 0; i < n; ++i) h.step(y, dt); evals = h.evaluations; }
                    if (s == 2) { hand_gauss<2> h(dt); for (long i = 0; i < n; ++i) h.step(y, dt); evals = h.evaluations; }
                    if (s == 3) { hand_gauss<3> h(dt); for (long i = 0; i < n; ++i) h.step(y, dt); evals = h.evaluations; }
                });
                sink = sink + y[0];
                add("hand gauss_" + std::to_string(2 * s), double(evals) / double(n), hand);
            }
            {
                const auto t = sympl::method("yoshida_6");
                auto tao = sympl::make_tao_stepper<State>(pendulum, t, tao_o);
                State x = start;
                const double sec = seconds([&] {
                    for (long i = 0; i < n; ++i) tao.step(x, dt);
                });
                sink = sink + x.q[0];
                add("tao(yoshida_6)", double(tao.force_evaluations()) / double(n), sec);
                hand_tao h(tao_o, tao.weights().gamma);
                h.q = h.x = {start.q[0], start.q[1]};
                h.p = h.y = {start.p[0], start.p[1]};
                const double hand = seconds([&] {
                    for (long i = 0; i < n; ++i) h.step(dt);
                });
                sink = sink + h.q[0];
                add("hand tao(yoshida_6)", double(h.evaluations) / double(n), hand);
            }
            {
                auto semi = sympl::make_semiexplicit_stepper<State>(pendulum, sympl::method("yoshida_6"));
                State x = start;
                const double sec = seconds([&] {
                    for (long i = 0; i < n; ++i) semi.step(x, dt);
                });
                sink = sink + x.q[0];
                add("semiexplicit(yoshida_6)", double(semi.force_evaluations()) / double(n), sec);
            }
        }
        for (const row& r : rows) {
            if (r.name.rfind("hand ", 0) == 0) continue;
            const double t = median(r.per_step);
            const auto hand = std::find_if(rows.begin(), rows.end(), [&](const row& h) { return h.name == "hand " + r.name; });
            if (hand != rows.end()) {
                const double th = median(hand->per_step);
                std::printf("%-26s %8.4f %10.3f %10.3f %10.2f %9.2f %8.1f\n", r.name.c_str(), dt, t * 1e6, th * 1e6,
                            t / th, r.evaluations_per_step, t / r.evaluations_per_step * 1e9);
            } else {
                std::printf("%-26s %8.4f %10.3f %10s %10s %9.2f %8.1f\n", r.name.c_str(), dt, t * 1e6, "-", "-",
                            r.evaluations_per_step, t / r.evaluations_per_step * 1e9);
            }
        }
        std::printf("\n");
    }
    return 0;
}
