// Cost per step of the Wisdom-Holman stepper (planetary/wisdom_holman_stepper.hpp; democratic
// heliocentric coordinates, Duncan, Levison & Lee 1998, Astron. J. 116, 2067)
// on the outer solar system of Hairer, Lubich & Wanner, against a tight
// hand-written loop of the same method: the state in plain arrays, the scalar
// kepler_drift per planet, the pairwise interaction and the jump, with the
// same sub-steps joined across steps. Two methods: the leapfrog (kick-drift-kick)
// and SABA_2 (Laskar & Robutel 2001). Side by side in one process, in
// interleaved rounds (median of the rounds); prints ns per step, ns per planet
// per step and the ratio, and the largest difference of the two final states.
// Then the composition kernel (Wisdom, Holman & Touma 1996; Rein, Tamayo &
// Brown 2019) against the plain drift-kick-drift leapfrog, both with
// corrector 17, at h = 200 days, in democratic heliocentric and in Jacobi
// coordinates, and the lazy implementer's kernel (Jacobi only): ns per step and
// the final relative energy error. Last, 10^6 years (10^5 with --quick) at
// 1/20 of Jupiter's period: the largest relative energy error and the time.
//   bench_wisdom_holman [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>
#include <vector>

#include <sympl/core/hamiltonian.hpp>
#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/methods/catalog.hpp>
#include <sympl/planetary/kepler/kepler_lanes.hpp>
#include <sympl/planetary/coordinates.hpp>
#include <sympl/planetary/wisdom_holman_stepper.hpp>

namespace {
using State = sympl::phase_space<double, 18>;
constexpr int planets = 5;

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// The hand-written method: heliocentric positions Q, velocities P / m (DLL 1998).
struct plain {
    double m[planets + 1], G, gm, total;
    Eigen::Vector3d r[planets], v[planets], a[planets], centre, momentum;

    plain(const sympl::hamiltonians::outer_solar_system& sys, const State& x) : G(sys.G) {
        total = 0;
        for (int i = 0; i <= planets; ++i) m[i] = sys.mass[std::size_t(i)], total += m[i];
        gm = G * m[0];
        const State y = sympl::to_democratic_heliocentric(x, std::span<const double>(sys.mass));
        centre = y.q.segment<3>(0), momentum = y.p.segment<3>(0);
        for (int i = 0; i < planets; ++i) r[i] = y.q.segment<3>(3 * i + 3), v[i] = y.p.segment<3>(3 * i + 3) / m[i + 1];
    }
    void forces() {
        for (int i = 0; i < planets; ++i) a[i].setZero();
        for (int i = 0; i < planets; ++i)
            for (int j = i + 1; j < planets; ++j) {
                const Eigen::Vector3d d = r[j] - r[i];
                const double r2 = d.squaredNorm(), k = G / (r2 * std::sqrt(r2));
                a[i] += (k * m[j + 1]) * d;
                a[j] -= (k * m[i + 1]) * d;
            }
    }
    void kick(double t) {  // interaction, then the jump (they commute)
        Eigen::Vector3d p = Eigen::Vector3d::Zero();
        for (int i = 0; i < planets; ++i) v[i] += t * a[i], p += m[i + 1] * v[i];
        for (int i = 0; i < planets; ++i) r[i] += (t / m[0]) * p;
    }
    void drift(double t) {
        for (int i = 0; i < planets; ++i) sympl::kepler_drift(r[i], v[i], gm, t);
        centre += (t / total) * momentum;
    }
    State state(const sympl::hamiltonians::outer_solar_system& sys) const {
        State y;
        y.q.segment<3>(0) = centre, y.p.segment<3>(0) = momentum;
        for (int i = 0; i < planets; ++i) y.q.segment<3>(3 * i + 3) = r[i], y.p.segment<3>(3 * i + 3) = m[i + 1] * v[i];
        return sympl::from_democratic_heliocentric(y, std::span<const double>(sys.mass));
    }
};

// Leapfrog: K(h/2) D(h) K(h/2), the kicks of adjacent steps joined.
State plain_leapfrog(const sympl::hamiltonians::outer_solar_system& sys, const State& x, double h, std::size_t n) {
    plain s(sys, x);
    s.forces();
    s.kick(h / 2);
    for (std::size_t k = 0; k < n; ++k) {
        s.drift(h);
        s.forces();
        s.kick(k + 1 < n ? h : h / 2);
    }
    return s.state(sys);
}

// SABA_2: D(c1 h) K(h/2) D(c2 h) K(h/2) D(c1 h), c1 = 1/2 - sqrt(3)/6, c2 = sqrt(3)/3;
// the drifts of adjacent steps joined.
State plain_saba2(const sympl::hamiltonians::outer_solar_system& sys, const State& x, double h, std::size_t n) {
    const double c1 = 0.5 - std::sqrt(3.0) / 6, c2 = 1 - 2 * c1;
    plain s(sys, x);
    s.drift(c1 * h);
    for (std::size_t k = 0; k < n; ++k) {
        s.forces();
        s.kick(h / 2);
        s.drift(c2 * h);
        s.forces();
        s.kick(h / 2);
        s.drift(k + 1 < n ? 2 * c1 * h : c1 * h);
    }
    return s.state(sys);
}
}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    const std::size_t n = quick ? 20000 : 200000;
    const int rounds = quick ? 3 : 7;
    const double h = 50;  // days
    const sympl::hamiltonians::outer_solar_system sys{};
    const State start = sys.initial_state();
    std::printf("Wisdom-Holman on the outer solar system (%d planets), h = %g days, %zu steps per run; "
                "median of %d interleaved rounds, one thread\n\n",
                planets, h, n, rounds);
    std::printf("%-10s %16s %16s %16s %10s %12s %14s\n", "method", "sympl ns/step", "plain ns/step", "sympl ns/planet",
                "sympl/plain", "step() ns", "max |diff|");
    double sink = 0;
    for (const char* name : {"leapfrog_kdk", "saba_2"}) {
        const bool lf = std::strcmp(name, "leapfrog_kdk") == 0;
        std::vector<double> ours, theirs, single;
        double diff = 0;
        for (int round = 0; round < rounds; ++round) {
            auto wh = sympl::make_wisdom_holman<State>(sys, sympl::method(name));
            State a = start;
            double t0 = now();
            wh.steps(a, h, n);
            ours.push_back((now() - t0) / double(n));
            t0 = now();
            const State b = lf ? plain_leapfrog(sys, start, h, n) : plain_saba2(sys, start, h, n);
            theirs.push_back((now() - t0) / double(n));
            // One call per step, the state handed back each time (converted out every step).
            auto one = sympl::make_wisdom_holman<State>(sys, sympl::method(name));
            State c = start;
            const std::size_t m = n / 10;
            t0 = now();
            for (std::size_t k = 0; k < m; ++k) one.step(c, h);
            single.push_back((now() - t0) / double(m));
            diff = std::max(diff, sympl::max_difference(a, b));
            sink += a.q[3] + b.q[4] + c.q[5];
        }
        const double s = median(ours) * 1e9, p = median(theirs) * 1e9;
        std::printf("%-10s %16.1f %16.1f %16.1f %10.2f %12.1f %14.2g\n", lf ? "leapfrog" : "saba_2", s, p, s / planets,
                    s / p, median(single) * 1e9, diff);
    }
    const double hk = 200;  // days: 1/22 of Jupiter's period, where eps^2 h^2 shows
    std::printf("\nleapfrog_dkd with corrector 17, h = %g days, %zu steps (one steps() call)\n", hk, n);
    std::printf("%-20s %-24s %12s %26s\n", "kernel", "coordinates", "ns/step", "final relative energy err");
    const double e0 = sympl::energy(sys, start);
    using C = sympl::wh_coordinates;
    using K = sympl::wh_kernel;
    const std::pair<K, C> kinds[] = {{K::kick, C::democratic_heliocentric}, {K::composition, C::democratic_heliocentric},
                                     {K::kick, C::jacobi}, {K::composition, C::jacobi}, {K::lazy, C::jacobi}};
    for (const auto& [k, c] : kinds) {
        std::vector<double> times;
        double error = 0;
        for (int round = 0; round < rounds; ++round) {
            auto wh = sympl::make_wisdom_holman<State>(sys, sympl::method("leapfrog_dkd"),
                                                       {.corrector_order = 17, .kernel = k, .coordinates = c});
            State x = start;
            const double t0 = now();
            wh.steps(x, hk, n);
            times.push_back((now() - t0) / double(n));
            error = std::fabs(sympl::energy(sys, x) / e0 - 1);
            sink += x.q[3];
        }
        std::printf("%-20s %-24s %12.1f %26.1e\n", sympl::kernel_name(k).c_str(), sympl::coordinates_name(c).c_str(),
                    median(times) * 1e9, error);
    }
    // The long run users make: 10^6 years at 1/20 of Jupiter's period, the
    // energy looked at every 1000 steps (its largest relative error), with the
    // whole run's time.
    const double years = quick ? 1e5 : 1e6, hj = 4332.59 / 20, span = years * 365.25;
    const std::size_t chunk = 1000, steps = std::size_t(span / hj) / chunk * chunk;
    std::printf("\n%g years at h = %.1f days (1/20 of Jupiter's period), %zu steps, energy every %zu steps\n", years, hj,
                steps, chunk);
    std::printf("%-72s %12s %10s %24s\n", "method", "ns/step", "run [s]", "max relative energy err");
    struct long_run {
        const char* label;
        const char* table;
        sympl::wisdom_holman_options options;
    };
    const long_run runs[] = {
        {"wh(leapfrog_kdk)", "leapfrog_kdk", {}},
        {"wh(leapfrog_kdk, corrector = 17)", "leapfrog_kdk", {.corrector_order = 17}},
        {"wh(leapfrog_dkd, corrector = 17, kernel = lazy, coordinates = jacobi)", "leapfrog_dkd",
         {.corrector_order = 17, .kernel = K::lazy, .coordinates = C::jacobi}},
        {"wh(blanes_2013_aba_10_6_4)", "blanes_2013_aba_10_6_4", {}},
    };
    for (const long_run& r : runs) {
        auto wh = sympl::make_wisdom_holman<State>(sys, sympl::method(r.table), r.options);
        State x = start;
        double worst = 0;
        const double t0 = now();
        for (std::size_t done = 0; done < steps; done += chunk) {
            wh.steps(x, hj, chunk);
            worst = std::max(worst, std::fabs(sympl::energy(sys, x) / e0 - 1));
        }
        const double seconds = now() - t0;
        std::printf("%-72s %12.1f %10.2f %24.2e\n", r.label, seconds / double(steps) * 1e9, seconds, worst);
        sink += x.q[3];
    }
    std::printf("\n(checksum %g)\n", sink);
}
