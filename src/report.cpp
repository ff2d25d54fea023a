// The work-precision report and the single-scene run.
#include "report.hpp"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/hamiltonians/stiff_fpu.hpp>

#include "problems.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

std::string fmt(double v, int digits = 4) {
    std::ostringstream s;
    s << std::setprecision(digits) << v;
    return s.str();
}

// A file written to a temporary name and renamed when complete: a failed run
// leaves no half-written output.
class atomic_file {
public:
    explicit atomic_file(fs::path path) : path_(std::move(path)), tmp_(path_.string() + ".part"), out_(tmp_) {
        if (!out_) throw error("cannot write " + tmp_.string());
    }
    ~atomic_file() {
        if (!committed_) {
            out_.close();
            std::error_code ec;
            fs::remove(tmp_, ec);
        }
    }
    std::ofstream& stream() { return out_; }
    void commit() {
        out_.close();
        fs::rename(tmp_, path_);
        committed_ = true;
    }

private:
    fs::path path_, tmp_;
    std::ofstream out_;
    bool committed_ = false;
};

struct progress {
    bool tty = isatty(STDERR_FILENO);
    void show(const std::string& what) const {
        if (tty) std::cerr << "\r\033[K" << what << std::flush;
    }
    void done() const {
        if (tty) std::cerr << "\r\033[K" << std::flush;
    }
};

// The reference state at t_end: exact, or Sofroniou-Spaletta 10 in long double
// at two steps (the difference estimates the reference's own error).
struct reference_state {
    std::vector<double> x;
    double error = 0;  // relative; 0 for an exact solution
    std::string kind;
};

reference_state make_reference(const scene& s, const problem& p, const fs::path& cache = {}) {
    if (p.exact) return {p.exact(s.t_end - s.t0), 0.0, "exact"};
    const double dt = *std::min_element(s.dt.begin(), s.dt.end()) / 4;
    const std::string kind =
        p.hamiltonian ? "sofroniou_spaletta_10, long double, dt = " + fmt(dt) : "rk4, dt = " + fmt(dt);
    // Cached on disk under a key of everything the reference depends on.
    std::ostringstream key;
    key << std::setprecision(17) << s.system << ';' << s.t0 << ';' << s.t_end << ';' << dt;
    for (const auto& [k, v] : s.parameters) key << ';' << k << '=' << v;
    for (double v : p.x0) key << ';' << v;
    const fs::path file =
        cache.empty() ? fs::path() : cache / ("reference_" + std::to_string(std::hash<std::string>{}(key.str())) + ".txt");
    if (!file.empty() && fs::exists(file)) {
        std::ifstream in(file);
        std::string stored;
        std::getline(in, stored);
        reference_state r{{}, 0, kind + " (cached)"};
        double v;
        if (stored == key.str() && in >> r.error) {
            while (in >> v) r.x.push_back(v);
            if (r.x.size() == p.x0.size()) return r;
        }
    }
    const auto coarse = p.reference(s.t0, s.t_end, 2 * dt, p.x0);
    const auto fine = p.reference(s.t0, s.t_end, dt, p.x0);
    reference_state r{fine, relative_difference(coarse, fine), kind};
    if (!file.empty()) {
        fs::create_directories(cache);
        atomic_file out(file);
        out.stream() << key.str() << "\n" << std::setprecision(17) << r.error << "\n";
        for (double v : r.x) out.stream() << v << "\n";
        out.commit();
    }
    return r;
}

// Relative change of the area of a small loop around x0 in the (q_0, p_0)
// plane, carried by the method (-1 when the run is unstable).
double loop_area_error(const problem& p, const method_spec& m, run_request rq, double t0, double t_end) {
    rq.energy = false;
    rq.timing_repeats = 0;
    rq.trajectory = nullptr;
    rq.trajectory_every = rq.energy_series_every = 0;
    const std::size_t n = p.degrees_of_freedom;
    const double r = 0.05 * std::max(1.0, std::hypot(p.x0[0], p.x0[n])), pi = std::acos(-1.0);
    using State = phase_space<double>;
    const auto to_state = [n](const std::vector<double>& v) {
        State x(static_cast<Eigen::Index>(n));
        for (std::size_t i = 0; i < n; ++i) x.q[i] = v[i], x.p[i] = v[n + i];
        return x;
    };
    const auto circle = [&](double s) {
        std::vector<double> v = p.x0;
        v[0] += r * std::cos(2 * pi * s);
        v[n] += r * std::sin(2 * pi * s);
        return to_state(v);
    };
    bool stable = true;
    const auto flow = [&](State& x) {
        std::vector<double> v(2 * n);
        for (std::size_t i = 0; i < n; ++i) v[i] = x.q[i], v[n + i] = x.p[i];
        const run_result res = p.run(m, rq, t0, t_end, v);
        if (!res.stable) stable = false;
        else x = to_state(res.final_state);
    };
    const auto loop = carry_loop(circle, flow, {64, 4096, r / 16});  // polygon error ~ (1/16)^2/6 ~ 7e-4
    return stable ? std::fabs(loop_area(loop, 0) - pi * r * r) / (pi * r * r) : -1;
}

struct row {
    std::string scene, method;
    double dt = 0, tolerance = 0;
    run_result r;
    double final_error = -1;
    double loop_area_error = -1;  // only where the scene asks for it
};

const char* kind_name(method_kind k) {
    switch (k) {
        case method_kind::table: return "table";
        case method_kind::classic: return "classic";
        case method_kind::odeint_rk4: return "odeint";
        case method_kind::odeint_dopri5: return "odeint";
    }
    return "?";
}

std::string csv_number(double v) { return v < 0 ? "" : fmt(v, 6); }

// Fastest time to reach `level` for one method (infinity when never reached).
double time_to_reach(const std::vector<row>& rows, const std::string& scene, const std::string& method, double level) {
    double best = HUGE_VAL;
    for (const row& r : rows)
        if (r.scene == scene && r.method == method && r.r.stable && r.final_error >= 0 && r.final_error <= level &&
            r.r.seconds >= 0)
            best = std::min(best, r.r.seconds);
    return best;
}

bool have_gnuplot() { return std::system("gnuplot --version > /dev/null 2>&1") == 0; }

// Runs a gnuplot script; a failure is said on stderr and leaves no empty PNG.
void run_gnuplot(const fs::path& script, const fs::path& png) {
    if (std::system(("gnuplot '" + script.string() + "' 2>/dev/null").c_str()) != 0 || !fs::exists(png) ||
        fs::file_size(png) == 0) {
        std::error_code ec;
        fs::remove(png, ec);
        std::cerr << "sympl: gnuplot could not draw " << png.string() << " (script: " << script.string() << ")\n";
    }
}

std::string safe(const std::string& s) {
    std::string out = s;
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
    return out;
}

// ---- special studies ---------------------------------------------------------

using S1 = phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;

// Largest step for which the run stays bounded (energy error below 1e8 over n
// steps): bounded motion near a stability limit has a large but finite energy
// error, while past it the error grows exponentially.
template <class Stable>
double largest_stable(Stable&& stable, double step, double limit) {
    // Scan upward to the first unstable step (bands of stability beyond it do
    // not count), then bisect between it and the last stable one.
    double lo = 0, hi = 0;
    for (double h = step; h <= limit; h += step) {
        if (!stable(h)) {
            hi = h;
            break;
        }
        lo = h;
    }
    if (hi == 0) return limit;
    for (int i = 0; i < 30; ++i) {
        const double mid = (lo + hi) / 2;
        (stable(mid) ? lo : hi) = mid;
    }
    return lo;
}

template <class Stepper, class State, class H>
double energy_growth(Stepper s, State x, const H& h, double dt, std::size_t n) {
    const double e0 = energy(h, x);
    try {
        integrate_steps(s, x, 0.0, dt, n);
    } catch (const integration_error&) {
        return HUGE_VAL;
    }
    return std::fabs(energy(h, x) - e0) / std::fabs(e0);
}

void stability_study(bool quick, std::ostream& md, const fs::path& dir, const progress& bar) {
    const hamiltonians::harmonic_oscillator ho{};
    const hamiltonians::stiff_fpu fpu{};
    const S1 x0(V1(1.0), V1(0.0));
    using SF = phase_space<double, 6>;
    const SF y0 = fpu.initial_state();
    const std::size_t n = quick ? 2000 : 20000;
    atomic_file csv(dir / "stability.csv");
    csv.stream() << "method,interval_theory,ho_largest_stable_h,stiff_fpu_largest_stable_omega_dt,just_past\n";
    md << "## Stability map\n\nLargest stable h = omega*dt on the harmonic oscillator (energy error < 1e8 over " << n
       << " steps, first unstable step by a scan in 0.05 and bisection) against the interval computed from the one-step propagator (|trace| < 2), and the "
          "largest stable omega*dt on the stiff FPU problem (omega = 50, the stiff springs' frequency). "
          "`just past`: the oscillator at 1.02 times the measured limit.\n\n"
       << "| method | interval (theory) | oscillator | stiff FPU | just past |\n|---|---|---|---|---|\n";
    const auto study = [&](const std::string& name, double theory, auto make_ho, auto make_fpu) {
        bar.show("stability map: " + name);
        const double h_ho = largest_stable([&](double h) { return energy_growth(make_ho(), x0, ho, h, n) < 1e8; }, 0.05, 12);
        const double dt_fpu = largest_stable(
            [&](double dt) { return energy_growth(make_fpu(), y0, fpu, dt, n) < 1e8; }, 0.05 / fpu.omega, 12 / fpu.omega);
        std::string past;
        {
            S1 x = x0;
            auto s = make_ho();
            try {
                integrate_steps(s, x, 0.0, 1.02 * h_ho, 100 * n);
                past = "bounded over " + std::to_string(100 * n) + " steps (energy error " +
                       fmt(std::fabs(energy(ho, x) - 0.5) / 0.5, 2) + ")";
            } catch (const integration_error& e) {
                past = "blows up at step " + std::to_string(e.step) + " (t = " + fmt(e.time, 4) + ")";
            }
        }
        csv.stream() << name << "," << theory << "," << h_ho << "," << dt_fpu * fpu.omega << ",\"" << past << "\"\n";
        md << "| " << name << " | " << fmt(theory) << " | " << fmt(h_ho) << " | " << fmt(dt_fpu * fpu.omega) << " | "
           << past << " |\n";
    };
    for (const auto& t : catalog())
        study(t.name(), double(t.stability_interval()),
              [&] { return make_stepper<S1>(ho, t); }, [&] { return make_stepper<SF>(fpu, t); });
    study("rk4 (classic)", 2 * std::sqrt(2.0), [&] { return make_classic<rk4, S1>(ho); },
          [&] { return make_classic<rk4, SF>(fpu); });
    study("euler (classic)", 0.0, [&] { return make_classic<euler, S1>(ho); }, [&] { return make_classic<euler, SF>(fpu); });
    md << "\nEuler has no stability interval (|det| = 1 + h^2 per step): its 'limit' is where the growth over "
       << n << " steps reaches 1e8, and shrinks as n grows. The scan steps h by 0.05 from 0 and bisects at the first "
          "unstable point; a measured limit a little above the interval means the growth just past it is too slow to "
          "show in " << n << " steps.\n\n";
    csv.commit();
}

void kepler_099_study(bool quick, std::ostream& md, const fs::path& dir, const progress& bar) {
    using K = phase_space<double, 2>;
    const hamiltonians::kepler h{};
    const double e = 0.99, period = 2 * std::acos(-1.0);
    const K x0 = hamiltonians::kepler::initial_state(e);
    const K exact = hamiltonians::kepler::exact_state(e, period);
    const double e0 = energy(h, x0);
    atomic_file csv(dir / "kepler_e0.99.csv");
    csv.stream() << "method,dt_or_tolerance,steps,force_evaluations,max_energy_error,final_error\n";
    md << "## Kepler, e = 0.99\n\nOne period from pericentre (r = 0.01, speed 14.1): the largest relative energy error, "
          "reached at the pericentre passage, and the final error.\n\n"
       << "| method | dt / tolerance | force evaluations | max energy error | final error |\n|---|---|---|---|---|\n";
    const auto line = [&](const std::string& name, double p, std::uint64_t steps, std::uint64_t forces, double err,
                          const K& x) {
        const double fin = max_difference(x, exact) / exact.p.cwiseAbs().maxCoeff();
        csv.stream() << name << "," << p << "," << steps << "," << forces << "," << err << "," << fin << "\n";
        md << "| " << name << " | " << fmt(p) << " | " << forces << " | " << fmt(err, 3) << " | " << fmt(fin, 3) << " |\n";
    };
    const std::vector<double> dts = quick ? std::vector<double>{1e-4} : std::vector<double>{1e-4, 2e-5};
    for (const std::string name : {"leapfrog_kdk", "blanes_moan_s6", "sofroniou_spaletta_10"})
        for (double dt : dts) {
            bar.show("Kepler e = 0.99: " + name);
            K x = x0;
            double worst = 0;
            auto s = make_stepper<K>(h, method(name));
            const auto r = integrate_until(s, x, 0.0, period, dt, [&](const K& y, double) {
                worst = std::max(worst, std::fabs(energy(h, y) - e0) / std::fabs(e0));
            });
            line(name, dt, r.steps, r.force_evaluations, worst, x);
        }
    for (double dt : dts) {
        K x = x0;
        double worst = 0;
        auto s = make_classic<rk4, K>(h);
        const auto r = integrate_until(s, x, 0.0, period, dt, [&](const K& y, double) {
            worst = std::max(worst, std::fabs(energy(h, y) - e0) / std::fabs(e0));
        });
        line("rk4 (classic)", dt, r.steps, r.force_evaluations, worst, x);
    }
    for (double tol : quick ? std::vector<double>{1e-8} : std::vector<double>{1e-8, 1e-10}) {
        bar.show("Kepler e = 0.99: adaptive Euler-Richardson");
        K x = x0;
        double worst = 0;
        auto s = make_classic<euler_richardson, K>(h);
        adaptive_options o;
        o.tolerance = tol;
        o.dt_initial = 1e-4;
        const auto r = integrate_adaptive(s, x, 0.0, period, o, [&](const K& y, double) {
            worst = std::max(worst, std::fabs(energy(h, y) - e0) / std::fabs(e0));
        });
        line("adaptive euler_richardson", tol, r.accepted + r.rejected, r.force_evaluations, worst, x);
    }
    md << "\nThe fixed-step methods spend their steps uniformly while all the error is made at pericentre; the "
          "adaptive Euler-Richardson shrinks its step there (it is second order and not symplectic, so its energy "
          "error drifts).\n\n";
    csv.commit();
}

void long_run_study(bool quick, std::ostream& md, const fs::path& dir, const progress& bar) {
    const hamiltonians::pendulum h{};
    const S1 x0(V1(1.2), V1(0.3));
    const double e0 = energy(h, x0), dt = 0.001;
    const std::size_t last = quick ? 1000000 : 100000000;
    atomic_file csv(dir / "long_run.csv");
    csv.stream() << "steps,energy_error_plain,energy_error_compensated\n";
    md << "## Long run: compensated summation\n\nPendulum, forest_ruth_4 at dt = 0.001 (truncation error ~1e-14), "
       << last << " steps. Relative energy error at each decade:\n\n| steps | plain | compensated |\n|---|---|---|\n";
    auto plain = make_stepper<S1>(h, method("forest_ruth_4"));
    auto kahan = make_stepper<S1>(h, method("forest_ruth_4"), stepper_options{true});
    S1 a = x0, b = x0;
    std::size_t done = 0;
    for (std::size_t target = 1000; target <= last; target *= 10) {
        bar.show("long run: " + std::to_string(target) + " steps");
        integrate_steps(plain, a, dt * double(done), dt, target - done);
        integrate_steps(kahan, b, dt * double(done), dt, target - done);
        done = target;
        const double ea = std::fabs(energy(h, a) - e0) / e0, eb = std::fabs(energy(h, b) - e0) / e0;
        csv.stream() << target << "," << ea << "," << eb << "\n";
        md << "| " << target << " | " << fmt(ea, 3) << " | " << fmt(eb, 3) << " |\n";
    }
    md << "\n";
    csv.commit();
}

template <class S>
double kepler_precision_error() {
    using K = phase_space<S, 2>;
    K x = hamiltonians::kepler::initial_state<S>(0.5);
    auto s = make_stepper<K>(hamiltonians::kepler{}, method("sofroniou_spaletta_10"));
    const S period = S(2) * S(3.14159265358979323846264338327950288L);
    integrate_until(s, x, S(0), period, S(period / S(200)));
    const K exact = hamiltonians::kepler::exact_state<S>(0.5, period);
    return double(max_difference(x, exact));
}

void extreme_study(std::ostream& md, const fs::path& dir) {
    atomic_file csv(dir / "extreme_scales.csv");
    csv.stream() << "case,max_energy_error,final_error\n";
    md << "## Extreme scales and precisions\n\nKepler e = 0.5, blanes_moan_s6, dt = period/2000, one period, in units "
          "where lengths are scaled by L (mu -> mu L^3): relative errors are the same at every scale.\n\n"
       << "| L | max energy error | final error |\n|---|---|---|\n";
    for (double L : {1e-20, 1.0, 1e20}) {
        scene s;
        s.system = "kepler";
        s.parameters["scale"] = L;
        s.t_end = 2 * std::acos(-1.0);
        const problem p = make_problem(s);
        run_request rq;
        rq.dt = s.t_end / 2000;
        rq.energy = true;
        rq.timing_repeats = 0;
        const run_result r = p.run({"blanes_moan_s6", method_kind::table, method("blanes_moan_s6")}, rq, 0, s.t_end, p.x0);
        const double fin = relative_difference(r.final_state, p.exact(s.t_end));
        csv.stream() << "L=" << L << "," << r.max_energy_error << "," << fin << "\n";
        md << "| " << fmt(L) << " | " << fmt(r.max_energy_error, 6) << " | " << fmt(fin, 6) << " |\n";
    }
    md << "\nThe same orbit with Sofroniou-Spaletta 10 at dt = period/200 in three precisions (final error in q, p):\n\n"
       << "| scalar | final error |\n|---|---|\n";
    const double ef = kepler_precision_error<float>(), ed = kepler_precision_error<double>(),
                 el = kepler_precision_error<long double>();
    md << "| float | " << fmt(ef, 3) << " |\n| double | " << fmt(ed, 3) << " |\n| long double | " << fmt(el, 3) << " |\n\n";
    csv.stream() << "float," << "," << ef << "\ndouble,," << ed << "\nlong double,," << el << "\n";
    csv.commit();
}

void energy_series_study(const std::vector<scene>& scenes, const fs::path& dir, bool plots) {
    // The energy error along the run for a few methods on the first Kepler scene (or the first Hamiltonian one).
    const scene* chosen = nullptr;
    for (const scene& s : scenes)
        if (s.system == "kepler") { chosen = &s; break; }
    if (!chosen) return;
    const problem p = make_problem(*chosen);
    const double dt = chosen->dt[chosen->dt.size() / 2];
    atomic_file csv(dir / "energy_vs_time.csv");
    csv.stream() << "method,t,energy_error\n";
    std::vector<std::string> names;
    for (const std::string name : {"leapfrog_kdk", "blanes_moan_s6", "odeint_rk4", "odeint_dopri5"}) {
        method_spec m{name, name == "odeint_rk4"      ? method_kind::odeint_rk4
                            : name == "odeint_dopri5" ? method_kind::odeint_dopri5
                                                      : method_kind::table,
                      std::nullopt};
        if (m.kind == method_kind::table) m.coefficients = method(name);
        run_request rq;
        rq.dt = dt;
        rq.tolerance = 1e-8;
        rq.energy = true;
        rq.energy_series_every = std::max<std::size_t>(1, std::size_t((chosen->t_end - chosen->t0) / dt / 400));
        rq.timing_repeats = 0;
        const run_result r = p.run(m, rq, chosen->t0, chosen->t_end, p.x0);
        for (const auto& [t, e] : r.energy_series) csv.stream() << name << "," << t << "," << e << "\n";
        names.push_back(name);
    }
    csv.commit();
    if (!plots) return;
    std::ofstream gp(dir / "energy_vs_time.gp");
    gp << "set terminal pngcairo size 900,600\nset output '" << (dir / "energy_vs_time.png").string() << "'\n"
       << "set datafile separator ','\nset logscale y\nset format y '10^{%L}'\nset xlabel 't'\n"
       << "set ylabel 'relative energy error'\nset title '" << chosen->name << ": dt = " << fmt(dt)
       << " (dopri5: tolerance 1e-8)' noenhanced\nset key outside noenhanced\n";
    gp << "plot ";
    for (std::size_t i = 0; i < names.size(); ++i)
        gp << (i ? ", " : "") << "'" << (dir / "energy_vs_time.csv").string() << "' using (strcol(1) eq '" << names[i]
           << "' ? $2 : NaN):($3 > 0 ? $3 : NaN) with lines title '" << names[i] << "' noenhanced";
    gp << "\n";
    gp.close();
    run_gnuplot(dir / "energy_vs_time.gp", dir / "energy_vs_time.png");
}

void plot_work_precision(const std::vector<row>& rows, const std::vector<scene>& scenes, const fs::path& dir) {
    const int cols = scenes.size() > 1 ? 2 : 1, rows_n = int((scenes.size() + 1) / 2);
    std::ofstream gp(dir / "work_precision.gp");
    gp << "set terminal pngcairo size " << 700 * cols << "," << 450 * rows_n << "\nset output '"
       << (dir / "work_precision.png").string() << "'\nset logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
       << "set xlabel 'wall time [s]'\nset ylabel 'final error (relative)'\nset key outside right font ',8'\n"
       << "set multiplot layout " << rows_n << "," << cols << "\n";
    for (const scene& s : scenes) {
        const fs::path data = dir / ("wp_" + safe(s.name) + ".dat");
        std::ofstream d(data);
        std::vector<std::string> methods;
        for (const method_spec& m : s.methods) {
            d << "# " << m.name << "\n";
            int points = 0;
            for (const row& r : rows)
                if (r.scene == s.name && r.method == m.name && r.r.stable && r.final_error > 0 && r.r.seconds > 0) {
                    d << r.r.seconds << " " << r.final_error << "\n";
                    ++points;
                }
            if (points == 0) d << "NaN NaN\n";
            d << "\n\n";
            methods.push_back(m.name);
        }
        gp << "set title '" << s.name << "' noenhanced\nplot ";
        for (std::size_t i = 0; i < methods.size(); ++i)
            gp << (i ? ", " : "") << "'" << data.string() << "' index " << i << " with linespoints title '" << methods[i]
               << "' noenhanced";
        gp << "\n";
    }
    gp << "unset multiplot\n";
    gp.close();
    run_gnuplot(dir / "work_precision.gp", dir / "work_precision.png");
}

}  // namespace

namespace {
// Every method must run on the system before anything runs or is written.
void check_methods(const scene& s, const problem& p) {
    for (const method_spec& m : s.methods)
        if (const std::string why = p.unsupported(m); !why.empty())
            throw scene_error(s.source + ": method '" + m.name + "' " + why);
}
}  // namespace

void run_scene(const scene& s, bool json, std::ostream& out) {
    const problem p = make_problem(s);
    check_methods(s, p);
    const reference_state ref = make_reference(s, p);
    const fs::path dir = s.output.directory;
    fs::create_directories(dir);
    std::vector<std::string> lines;
    std::vector<std::unique_ptr<atomic_file>> files;  // committed together at the end
    for (const method_spec& m : s.methods) {
        run_request rq;
        rq.dt = s.dt.front();
        rq.tolerance = s.tolerances.front();
        rq.energy = s.output.energy_error && p.hamiltonian;
        rq.timing_repeats = 1;
        std::unique_ptr<atomic_file> trajectory;
        if (s.output.trajectory_every) {
            trajectory = std::make_unique<atomic_file>(dir / (safe(s.name) + "_" + m.name + "_trajectory.csv"));
            trajectory->stream() << "t";
            for (std::size_t i = 0; i < p.degrees_of_freedom; ++i) trajectory->stream() << ",q" << i;
            for (std::size_t i = 0; i < p.degrees_of_freedom; ++i) trajectory->stream() << ",p" << i;
            trajectory->stream() << "\n" << std::setprecision(17);
            rq.trajectory = &trajectory->stream();
            rq.trajectory_every = s.output.trajectory_every;
        }
        const run_result r = p.run(m, rq, s.t0, s.t_end, p.x0);
        if (trajectory) files.push_back(std::move(trajectory));
        const double fin = r.stable ? relative_difference(r.final_state, ref.x) : -1;
        const double area = r.stable && s.output.loop_area ? loop_area_error(p, m, rq, s.t0, s.t_end) : -1;
        std::ostringstream l;
        if (json) {
            l << "{\"scene\": \"" << s.name << "\", \"method\": \"" << m.name << "\", \"status\": \""
              << (r.stable ? "stable" : "unstable") << "\"";
            if (!r.stable) l << ", \"blowup_step\": " << r.blowup_step << ", \"blowup_time\": " << r.blowup_time;
            l << ", \"steps\": " << r.steps << ", \"force_evaluations\": " << r.force_evaluations;
            if (r.max_energy_error >= 0) l << ", \"max_energy_error\": " << r.max_energy_error;
            if (fin >= 0) l << ", \"final_error\": " << fin;
            if (area >= 0) l << ", \"loop_area_error\": " << area;
            l << ", \"reference\": \"" << ref.kind << "\", \"seconds\": " << std::max(r.seconds, 0.0);
            if (s.output.final_state && r.stable) {
                l << ", \"final_state\": [";
                for (std::size_t i = 0; i < r.final_state.size(); ++i) l << (i ? ", " : "") << std::setprecision(17) << r.final_state[i];
                l << "]";
            }
            l << "}";
        } else {
            l << std::left << std::setw(24) << m.name;
            if (!r.stable) {
                l << "UNSTABLE: blew up at step " << r.blowup_step << " (t = " << r.blowup_time << ")";
            } else {
                l << std::right << std::setw(10) << r.steps << " steps" << std::setw(12) << r.force_evaluations
                  << " forces   energy error " << std::setw(10) << (r.max_energy_error >= 0 ? fmt(r.max_energy_error, 3) : "-")
                  << "   final error " << std::setw(10) << fmt(fin, 3) << "   " << fmt(r.seconds * 1e3, 3) << " ms";
                if (area >= 0) l << "   loop area error " << fmt(area, 3);
                if (s.output.final_state) {
                    l << "\n    final state:";
                    for (double v : r.final_state) l << " " << std::setprecision(17) << v;
                }
            }
        }
        lines.push_back(l.str());
    }
    for (auto& f : files) f->commit();
    if (json) {
        out << "[\n";
        for (std::size_t i = 0; i < lines.size(); ++i) out << "  " << lines[i] << (i + 1 < lines.size() ? ",\n" : "\n");
        out << "]\n";
    } else {
        out << s.name << ": " << s.system << ", t = " << s.t0 << " .. " << s.t_end << ", dt = " << s.dt.front()
            << " (dopri5 tolerance " << s.tolerances.front() << "), reference: " << ref.kind;
        if (ref.error > 0) out << " (its own error ~" << fmt(ref.error, 2) << ")";
        out << "\n";
        for (const auto& l : lines) out << "  " << l << "\n";
    }
}

void run_report(const std::vector<scene>& scenes, const report_options& options, std::ostream& out) {
    const fs::path dir = options.out_dir;
    fs::create_directories(dir);
    const progress bar;
    std::vector<row> rows;
    std::map<std::string, reference_state> references;
    const int repeats = options.quick ? 2 : 5;
    for (const scene& s : scenes) check_methods(s, make_problem(s));  // before anything runs
    for (std::size_t k = 0; k < scenes.size(); ++k) {
        const scene& s = scenes[k];
        const std::string head = "[" + std::to_string(k + 1) + "/" + std::to_string(scenes.size()) + "] " + s.name;
        bar.show(head + ": reference");
        const problem p = make_problem(s);
        const reference_state& ref = references[s.name] = make_reference(s, p, dir / "cache");
        for (const method_spec& m : s.methods) {
            const bool adaptive = m.kind == method_kind::odeint_dopri5;
            for (double v : adaptive ? s.tolerances : s.dt) {
                bar.show(head + ": " + m.name + " " + fmt(v));
                row r{s.name, m.name, adaptive ? 0.0 : v, adaptive ? v : 0.0, {}, -1};
                run_request rq;
                rq.dt = v;
                rq.tolerance = v;
                rq.energy = p.hamiltonian;
                rq.timing_repeats = repeats;
                r.r = p.run(m, rq, s.t0, s.t_end, p.x0);
                if (r.r.stable) r.final_error = relative_difference(r.r.final_state, ref.x);
                if (r.r.stable && s.output.loop_area) r.loop_area_error = loop_area_error(p, m, rq, s.t0, s.t_end);
                rows.push_back(std::move(r));
            }
        }
    }
    {
        atomic_file csv(dir / "work_precision.csv");
        csv.stream() << "scene,method,kind,dt,tolerance,status,blowup_step,blowup_time,steps,force_evaluations,seconds,"
                        "max_energy_error,final_error,reference_error,loop_area_error\n";
        for (const row& r : rows) {
            const scene* s = nullptr;
            for (const scene& x : scenes)
                if (x.name == r.scene) s = &x;
            method_kind kind = method_kind::table;
            for (const method_spec& m : s->methods)
                if (m.name == r.method) kind = m.kind;
            csv.stream() << r.scene << "," << r.method << "," << kind_name(kind) << "," << (r.dt > 0 ? fmt(r.dt, 6) : "")
                         << "," << (r.tolerance > 0 ? fmt(r.tolerance, 3) : "") << ","
                         << (r.r.stable ? "stable" : "unstable") << ","
                         << (r.r.stable ? "" : std::to_string(r.r.blowup_step)) << ","
                         << (r.r.stable ? "" : fmt(r.r.blowup_time, 8)) << "," << (r.r.stable ? std::to_string(r.r.steps) : "")
                         << "," << (r.r.stable ? std::to_string(r.r.force_evaluations) : "") << ","
                         << (r.r.stable ? csv_number(r.r.seconds) : "") << ","
                         << (r.r.stable ? csv_number(r.r.max_energy_error) : "") << ","
                         << (r.r.stable ? csv_number(r.final_error) : "") << "," << fmt(references[r.scene].error, 3)
                         << "," << csv_number(r.loop_area_error) << "\n";
        }
        csv.commit();
    }

    std::ostringstream md;
    md << "# sympl work-precision report\n\n" << (options.quick ? "Quick run (`--quick`): short spans, few steps.\n\n" : "")
       << "Final error: max |x - x_ref| / max |x_ref| at t_end against the exact solution or a Sofroniou-Spaletta 10 "
          "reference in long double (its own error in work_precision.csv). Wall time: best of "
       << repeats << " runs with nothing observed. Speed-up: time Odeint needs for the same accuracy divided by the "
          "fastest method's time (log-linear interpolation is not used: each is the fastest measured run that reaches "
          "the level).\n\n## Fastest method per accuracy level\n\n"
       << "| scene | level | fastest | time [s] | vs odeint_rk4 | vs odeint_dopri5 |\n|---|---|---|---|---|---|\n";
    std::ostringstream table;
    table << std::left << std::setw(22) << "scene" << std::setw(8) << "level" << std::setw(26) << "fastest" << std::right
          << std::setw(12) << "time [s]" << std::setw(14) << "x odeint_rk4" << std::setw(16) << "x odeint_dopri5" << "\n";
    for (const scene& s : scenes) {
        for (double level : {1e-4, 1e-8, 1e-12}) {
            std::string best;
            double best_t = HUGE_VAL;
            for (const method_spec& m : s.methods) {
                const double t = time_to_reach(rows, s.name, m.name, level);
                if (t < best_t) best_t = t, best = m.name;
            }
            const double rk = time_to_reach(rows, s.name, "odeint_rk4", level),
                         dp = time_to_reach(rows, s.name, "odeint_dopri5", level);
            const auto ratio = [&](double base) { return std::isfinite(base) && std::isfinite(best_t) ? fmt(base / best_t, 3) + "x" : std::string("not reached"); };
            const std::string fastest = std::isfinite(best_t) ? best : "none reached it";
            md << "| " << s.name << " | " << fmt(level) << " | " << fastest << " | "
               << (std::isfinite(best_t) ? fmt(best_t, 3) : "-") << " | " << ratio(rk) << " | " << ratio(dp) << " |\n";
            table << std::left << std::setw(22) << s.name << std::setw(8) << fmt(level) << std::setw(26) << fastest
                  << std::right << std::setw(12) << (std::isfinite(best_t) ? fmt(best_t, 3) : "-") << std::setw(14)
                  << ratio(rk) << std::setw(16) << ratio(dp) << "\n";
        }
    }
    md << "\n";
    const bool plots = options.plots && have_gnuplot();
    if (plots) plot_work_precision(rows, scenes, dir);
    energy_series_study(scenes, dir, plots);
    if (options.studies) {
        stability_study(options.quick, md, dir, bar);
        kepler_099_study(options.quick, md, dir, bar);
        long_run_study(options.quick, md, dir, bar);
        extreme_study(md, dir);
    }
    md << "## Files\n\nwork_precision.csv (every run; unstable runs give the step and time of blow-up and no error "
          "numbers), energy_vs_time.csv"
       << (plots ? ", work_precision.png, energy_vs_time.png" : " (install gnuplot for the PNGs)")
       << (options.studies ? ", stability.csv, kepler_e0.99.csv, long_run.csv, extreme_scales.csv" : "") << ".\n";
    {
        atomic_file summary(dir / "summary.md");
        summary.stream() << md.str();
        summary.commit();
    }
    bar.done();
    out << table.str() << "\nwrote " << (dir / "summary.md").string() << ", " << (dir / "work_precision.csv").string()
        << (plots ? ", " + (dir / "work_precision.png").string() : std::string()) << "\n";
}

}  // namespace sympl::app
