// The energy error over a long span: the symplectic leapfrog against the
// classic fourth-order Runge-Kutta at equal cost in force evaluations, on the
// Kepler problem at e = 0.5, sampled at logarithmically spaced times.
#include "study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/kepler.hpp>

#include "output/format.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {

struct sample {
    std::size_t rk_steps;
    int k;  // 10^(k/10) periods nominally
    double leapfrog, rk4;
};

struct long_span {
    std::size_t per_period, rk_per_period, periods;
    double h;
    std::vector<sample> samples{};
    std::uint64_t lf_forces = 0, rk_forces = 0;
};

long_span measure(const study_context& c) {
    using K = phase_space<double, 2>;
    const hamiltonians::kepler kep{};
    const double ecc = 0.5, period = 2 * std::numbers::pi;
    // The leapfrog takes 4 steps of h for each step of 4h of RK4: one force
    // per step against four, so both spend the same forces per unit time.
    const std::size_t per_period = 400;
    const double h = period / double(per_period);
    const std::size_t periods = c.quick ? 100 : 10000;
    const std::size_t rk_per_period = per_period / 4;
    const K x0 = hamiltonians::kepler::initial_state(ecc);
    const double e0 = energy(kep, x0);
    const auto relative = [&](const K& y) { return std::fabs(energy(kep, y) - e0) / std::fabs(e0); };

    auto lf = make_stepper<K>(kep, method("leapfrog_kdk"));
    auto rk = make_classic<rk4, K>(kep);
    K a = x0, b = x0;

    // Samples at about 10 per decade from one period on, each on a whole
    // number of RK4 steps so that both methods stop at the same time; each
    // holds the largest error since the previous sample (every step counts).
    long_span r{.per_period = per_period, .rk_per_period = rk_per_period, .periods = periods, .h = h};
    std::vector<sample>& samples = r.samples;
    std::size_t done = 0;  // RK4 steps so far (the leapfrog has done 4 times as many)
    for (int k = 0;; ++k) {
        const double nominal = std::pow(10.0, k / 10.0);
        if (nominal > double(periods) * (1 + 1e-12)) break;
        const std::size_t target = std::min<std::size_t>(std::llround(nominal * double(rk_per_period)),
                                                         periods * rk_per_period);
        if (target <= done) continue;
        c.bar.show("energy over a long span: " + format_number(double(target) / double(rk_per_period), 3) + " of " +
                   std::to_string(periods) + " periods");
        double worst_lf = 0, worst_rk = 0;
        integrate_steps(lf, a, 4 * h * double(done), h, 4 * (target - done),
                        [&](const K& y, double) { worst_lf = std::max(worst_lf, relative(y)); });
        integrate_steps(rk, b, 4 * h * double(done), 4 * h, target - done,
                        [&](const K& y, double) { worst_rk = std::max(worst_rk, relative(y)); });
        done = target;
        samples.push_back({target, k, worst_lf, worst_rk});
    }
    r.lf_forces = lf.force_evaluations();
    r.rk_forces = rk.force_evaluations();
    return r;

}

// energy_long_span.csv and, with gnuplot, its PNG.
bool write_files(const study_context& c, const long_span& r) {
    const auto& [per_period, rk_per_period, periods, h, samples, lf_forces, rk_forces] = r;
    atomic_file csv(c.dir / "energy_long_span.csv");
    csv.stream().precision(10);
    csv.stream() << "t,periods,leapfrog_energy_error,rk4_energy_error\n";
    for (const sample& s : samples)
        csv.stream() << 4 * h * double(s.rk_steps) << "," << double(s.rk_steps) / double(rk_per_period) << ","
                     << s.leapfrog << "," << s.rk4 << "\n";
    csv.commit();

    const std::string lf_label = "leapfrog_kdk, h = 2 pi/" + std::to_string(per_period) + " = " + format_number(h) +
                                 ", " + std::to_string(lf_forces) + " forces";
    const std::string rk_label =
        "rk4, 4h = " + format_number(4 * h) + ", " + std::to_string(rk_forces) + " forces";
    const bool plots = have_gnuplot();
    if (plots) {
        atomic_file gp(c.dir / "energy_long_span.gp");
        gp.stream() << "set terminal pngcairo size 900,600\nset output " << gnuplot_string("energy_long_span.png")
                    << "\nset datafile separator ','\nset logscale xy\nset format x '10^{%L}'\nset format y '10^{%L}'\n"
                    << "set xlabel 'time (periods)'\nset ylabel 'max relative energy error |H - H_0|/|H_0|'\n"
                    << "set title " << gnuplot_string("Kepler e = 0.5: energy error at equal cost in force evaluations")
                    << " noenhanced\nset key bottom right noenhanced\nset grid\nplot "
                    << gnuplot_string("energy_long_span.csv") << " using 2:($3 > 0 ? $3 : NaN) with lines lw 2 dt 1 title "
                    << gnuplot_string(lf_label) << ", " << gnuplot_string("energy_long_span.csv")
                    << " using 2:($4 > 0 ? $4 : NaN) with lines lw 2 dt 2 title " << gnuplot_string(rk_label) << "\n";
        gp.commit();
        run_gnuplot(c.dir / "energy_long_span.gp", c.dir / "energy_long_span.png");
    }

    return plots;
}

void write_summary(const study_context& c, const long_span& r, bool plots) {
    const auto& [per_period, rk_per_period, periods, h, samples, lf_forces, rk_forces] = r;
    const double cost_gap = std::fabs(double(lf_forces) - double(rk_forces)) / double(rk_forces);
    c.summary << "## Energy error over a long span\n\nKepler runnable_system at e = 0.5 (period 2 pi) for " << periods
              << " periods: the symplectic leapfrog_kdk at h = 2 pi/" << per_period << " against the classic rk4 at 4h, "
              << "the same cost per unit time (" << lf_forces << " against " << rk_forces
              << " force evaluations, within " << format_number(100 * cost_gap, 2)
              << "%; the leapfrog's extra ones start each sampled segment afresh). Largest relative energy error "
              << "since the previous sample (about 10 samples per decade):\n\n"
              << "| periods | leapfrog_kdk | rk4 |\n|---|---|---|\n";
    for (const sample& s : samples)
        if (s.k % 10 == 0)
            c.summary << "| " << double(s.rk_steps) / double(rk_per_period) << " | " << format_number(s.leapfrog, 3)
                      << " | " << format_number(s.rk4, 3) << " |\n";

    // Read the result from the numbers: the leapfrog's range over the span,
    // RK4's growth exponent from 10 periods (or the first sample) to the end,
    // and the first sample where RK4 is the worse of the two.
    double lf_low = samples.front().leapfrog, lf_high = lf_low;
    for (const sample& s : samples) lf_low = std::min(lf_low, s.leapfrog), lf_high = std::max(lf_high, s.leapfrog);
    const sample& last = samples.back();
    const sample* from = &samples.front();
    for (const sample& s : samples)
        if (s.k == 10) from = &s;
    const double exponent = std::log(last.rk4 / from->rk4) /
                            std::log(double(last.rk_steps) / double(from->rk_steps));
    const sample* crossing = nullptr;
    for (const sample& s : samples)
        if (s.rk4 > s.leapfrog) { crossing = &s; break; }
    const double lf_growth = last.leapfrog / samples.front().leapfrog;
    const bool linear = exponent > 0.8 && exponent < 1.25;
    c.summary << "\nThe leapfrog's error "
              << (lf_growth < 2 ? "stays bounded, its peak in each orbit not growing"
                                : "grows by a factor " + format_number(lf_growth, 3) + " from the first period to the end")
              << " (samples between " << format_number(lf_low, 3) << " and " << format_number(lf_high, 3)
              << "), while rk4's grows " << (linear ? "roughly linearly in t" : "") << (linear ? " (as t^" : "as t^")
              << format_number(exponent, 3) << " from " << format_number(double(from->rk_steps) / double(rk_per_period), 3)
              << " periods to the end" << (linear ? ")" : "") << ", from " << format_number(samples.front().rk4, 3)
              << " after one period to " << format_number(last.rk4, 3) << " after " << periods << " periods; ";
    if (crossing == &samples.front())
        c.summary << "at equal cost rk4 is the less accurate from the first period on.";
    else if (crossing)
        c.summary << "at equal cost rk4 is the more accurate only up to between "
                  << format_number(double((crossing - 1)->rk_steps) / double(rk_per_period), 3) << " and "
                  << format_number(double(crossing->rk_steps) / double(rk_per_period), 3) << " periods.";
    else
        c.summary << "over this span rk4 stays the more accurate of the two.";
    c.summary << " Files: energy_long_span.csv" << (plots ? ", energy_long_span.png" : " (install gnuplot for the PNG)")
              << ".\n\n";
}

}  // namespace

void energy_long_span_study(const study_context& c) {
    const long_span r = measure(c);
    write_summary(c, r, write_files(c, r));
}

}  // namespace sympl::app
