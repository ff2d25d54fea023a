// The stability map: largest stable step of every table on the oscillator and the stiff FPU problem.
#include "study.hpp"

#include <algorithm>
#include <cmath>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/stiff_fpu.hpp>

#include "output/format.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

using S1 = phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;

// Largest step for which the run stays bounded (energy error below 1e8 over n
// steps): bounded motion near a stability limit has a large but finite energy
// error, while past it the error grows exponentially.
namespace {

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

}  // namespace

void stability_study(const study_context& c) {
    const hamiltonians::harmonic_oscillator ho{};
    const hamiltonians::stiff_fpu fpu{};
    const S1 x0(V1(1.0), V1(0.0));
    using SF = phase_space<double, 6>;
    const SF y0 = fpu.initial_state();
    const std::size_t n = c.quick ? 2000 : 20000;
    atomic_file csv(c.dir / "stability.csv");
    csv.stream() << "method,interval_theory,ho_largest_stable_h,stiff_fpu_largest_stable_omega_dt,just_past\n";
    c.summary << "## Stability map\n\nLargest stable h = omega*dt on the harmonic oscillator (energy error < 1e8 over " << n
       << " steps, first unstable step by a scan in 0.05 and bisection) against the interval computed from the one-step propagator (|trace| < 2), and the "
          "largest stable omega*dt on the stiff FPU runnable_system (omega = 50, the stiff springs' frequency). "
          "`just past`: the oscillator at 1.02 times the measured limit.\n\n"
       << "| method | interval (theory) | oscillator | stiff FPU | just past |\n|---|---|---|---|---|\n";
    const auto study = [&](const std::string& name, double theory, auto make_ho, auto make_fpu) {
        c.bar.show("stability map: " + name);
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
                       format_number(std::fabs(energy(ho, x) - 0.5) / 0.5, 2) + ")";
            } catch (const integration_error& e) {
                past = "blows up at step " + std::to_string(e.step) + " (t = " + format_number(e.time, 4) + ")";
            }
        }
        csv.stream() << name << "," << theory << "," << h_ho << "," << dt_fpu * fpu.omega << ",\"" << past << "\"\n";
        c.summary << "| " << name << " | " << format_number(theory) << " | " << format_number(h_ho) << " | " << format_number(dt_fpu * fpu.omega) << " | "
           << past << " |\n";
    };
    for (const auto& t : catalog())
        study(t.name(), double(t.stability_interval()),
              [&] { return make_stepper<S1>(ho, t); }, [&] { return make_stepper<SF>(fpu, t); });
    study("rk4 (classic)", 2 * std::sqrt(2.0), [&] { return make_classic<rk4, S1>(ho); },
          [&] { return make_classic<rk4, SF>(fpu); });
    study("euler (classic)", 0.0, [&] { return make_classic<euler, S1>(ho); }, [&] { return make_classic<euler, SF>(fpu); });
    c.summary << "\nEuler has no stability interval (|det| = 1 + h^2 per step): its 'limit' is where the growth over "
       << n << " steps reaches 1e8, and shrinks as n grows. The scan steps h by 0.05 from 0 and bisects at the first "
          "unstable point; a measured limit a little above the interval means the growth just past it is too slow to "
          "show in " << n << " steps.\n\n";
    csv.commit();
}

}  // namespace sympl::app
