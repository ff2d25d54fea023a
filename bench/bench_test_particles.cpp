// Cost per test particle per step of the Wisdom-Holman stepper
// (planetary/test_particles/test_particles.hpp) on the outer solar system of Hairer, Lubich
// & Wanner with test particles on near-circular orbits at 6-9 AU, h = 200
// days, the leapfrog (kick-drift-kick), in democratic heliocentric and Jacobi
// coordinates: (stepper with N particles - stepper without) / N, against a
// planet's cost (the stepper without particles / 5) and against a tight hand
// loop of the same method in democratic heliocentric coordinates (particles
// as arrays of 3-vectors, sympl::kepler_drift per particle, the kick and jump
// written out). Then N = 1e2 ... 1e6 (ns per particle per step: flat when
// the work is arithmetic, rising when it waits on memory), and the particles
// split over two threads (two steppers, the planets run in each). Median of
// interleaved rounds, timed in thread CPU time; one process on a shared
// machine: the ratios hold best.
// With --long instead: 10^4 particles over 10^5 years (182625 steps of 200
// days) in both coordinates, beside the same run without them, particles
// removed as `sympl run` removes them; prints whether the planets' final
// states are bit-identical, the particles left and the cost per particle-step.
//   bench_test_particles [--quick | --long]
// Built with CMake's default Release flags (-O3 -DNDEBUG, no -march=native).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <thread>
#include <vector>

#include <Eigen/Core>

#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/methods/catalog.hpp>
#include <sympl/planetary/coordinates.hpp>
#include <sympl/planetary/test_particles/encounters.hpp>
#include <sympl/planetary/kepler/kepler_drift.hpp>
#include <sympl/planetary/wisdom_holman_stepper.hpp>

namespace {
using State = sympl::phase_space<double, 18>;
using V3 = Eigen::Vector3d;
const sympl::hamiltonians::outer_solar_system sys{};
constexpr double h = 200;  // days

// The calling thread's CPU time: the machine is shared, and wall time counts
// the other processes' turns on the cores; CPU time does not (their effect on
// caches and memory stays).
double now() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}
double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// N particles on circular orbits about the Sun, a from 6 to 9 AU, spread in
// longitude and slightly inclined; inertial positions and velocities.
sympl::test_particle_set<double> belt(const State& x, std::size_t n) {
    sympl::test_particle_set<double> p;
    double total = 0;
    V3 momentum = V3::Zero();
    for (int j = 0; j < sys.bodies; ++j) total += sys.mass[std::size_t(j)], momentum += x.p.segment<3>(3 * j);
    for (std::size_t i = 0; i < n; ++i) {
        const double a = 6 + 3 * double(i) / double(std::max<std::size_t>(1, n - 1)), phase = 2.39996 * double(i);
        const double incl = 0.02 * std::sin(double(i)), v = std::sqrt(sys.G * sys.mass[0] / a);
        const V3 r(a * std::cos(phase), a * std::sin(phase) * std::cos(incl), a * std::sin(phase) * std::sin(incl));
        const V3 u(-v * std::sin(phase), v * std::cos(phase) * std::cos(incl), v * std::cos(phase) * std::sin(incl));
        const V3 pos = r + x.q.segment<3>(0), vel = u + momentum / total;
        p.add({pos[0], pos[1], pos[2]}, {vel[0], vel[1], vel[2]});
    }
    return p;
}

// Seconds per step of the stepper with these particles.
double stepper_time(const sympl::test_particle_set<double>& p, sympl::wh_coordinates c, std::size_t steps) {
    sympl::wisdom_holman_options o;
    o.coordinates = c;
    auto wh = sympl::make_wisdom_holman<State>(sys, sympl::method("leapfrog_kdk"), o);
    State x = sys.initial_state();
    if (p.size()) wh.set_test_particles(p);
    wh.steps(x, h, 2);  // loaded, warm
    const double t0 = now();
    wh.steps(x, h, steps);
    return (now() - t0) / double(steps);
}

// The hand loop: democratic heliocentric leapfrog, K(h/2) D(h) K(h/2), kicks
// of adjacent steps joined; planets and particles as 3-vectors.
struct hand_loop {
    static constexpr int planets = 5;
    double m[planets + 1], gm;
    V3 r[planets], v[planets], a[planets];
    std::vector<V3> pr, pv;

    hand_loop(const State& x, const sympl::test_particle_set<double>& p) {
        for (int i = 0; i <= planets; ++i) m[i] = sys.mass[std::size_t(i)];
        gm = sys.G * m[0];
        const State y = sympl::to_democratic_heliocentric(x, std::span<const double>(sys.mass));
        double total = 0;
        for (double mi : m) total += mi;
        for (int i = 0; i < planets; ++i) r[i] = y.q.segment<3>(3 * i + 3), v[i] = y.p.segment<3>(3 * i + 3) / m[i + 1];
        for (std::size_t i = 0; i < p.size(); ++i) {
            pr.push_back(V3(p.x[i], p.y[i], p.z[i]) - x.q.segment<3>(0));
            pv.push_back(V3(p.vx[i], p.vy[i], p.vz[i]) - y.p.segment<3>(0) / total);
        }
    }
    void kick(double t) {
        for (int i = 0; i < planets; ++i) a[i].setZero();
        for (int i = 0; i < planets; ++i)
            for (int j = i + 1; j < planets; ++j) {
                const V3 d = r[j] - r[i];
                const double r2 = d.squaredNorm(), k = sys.G / (r2 * std::sqrt(r2));
                a[i] += (k * m[j + 1]) * d, a[j] -= (k * m[i + 1]) * d;
            }
        V3 p = V3::Zero();
        for (int i = 0; i < planets; ++i) v[i] += t * a[i], p += m[i + 1] * v[i];
        const V3 shift = (t / m[0]) * p;
        for (int i = 0; i < planets; ++i) r[i] += shift;
        for (std::size_t k = 0; k < pr.size(); ++k) {
            pr[k] += shift;
            V3 acc = V3::Zero();
            for (int i = 0; i < planets; ++i) {
                const V3 d = r[i] - pr[k];
                const double r2 = d.squaredNorm();
                acc += (sys.G * m[i + 1] / (r2 * std::sqrt(r2))) * d;
            }
            pv[k] += t * acc;
        }
    }
    void drift(double t) {
        for (int i = 0; i < planets; ++i) sympl::kepler_drift(r[i], v[i], gm, t);
        for (std::size_t k = 0; k < pr.size(); ++k) sympl::kepler_drift(pr[k], pv[k], gm, t);
    }
};

double hand_time(const sympl::test_particle_set<double>& p, std::size_t steps) {
    hand_loop s(sys.initial_state(), p);
    s.kick(h / 2);
    const double t0 = now();
    for (std::size_t k = 0; k < steps; ++k) s.drift(h), s.kick(h);
    return (now() - t0) / double(steps);
}

// The planets with and without 10^4 particles over 10^5 years, the
// particles removed as `sympl run` removes them (src/commands/run_test_particles.cpp):
// within a planet's Hill radius (where a Kepler orbit about the star
// perturbed no longer describes them), within the Sun's radius, or past
// 100 AU. The cost per particle-step counts the particles alive at the end
// of each 100-step chunk, so it errs high. Both runs take the same calls (a
// call joins the kicks of its steps).
int long_run() {
    const State x0 = sys.initial_state();
    const sympl::test_particle_set<double> p = belt(x0, 10000);
    const std::size_t steps = 182625, chunk = 100;
    sympl::encounter_options lost;
    lost.radius.push_back(0.005);  // AU, the Sun
    for (int k = 1; k < sys.bodies; ++k)
        lost.radius.push_back((x0.q.segment<3>(3 * k) - x0.q.segment<3>(0)).norm() *
                              std::cbrt(sys.mass[std::size_t(k)] / (3 * sys.mass[0])));
    lost.escape_distance = 100;
    int failures = 0;
    for (auto c : {sympl::wh_coordinates::democratic_heliocentric, sympl::wh_coordinates::jacobi}) {
        sympl::wisdom_holman_options o;
        o.coordinates = c;
        auto with = sympl::make_wisdom_holman<State>(sys, sympl::method("leapfrog_kdk"), o);
        auto without = with;
        with.set_test_particles(p);
        with.track_encounters(lost, 0);
        State a = x0, b = x0;
        double t_with = 0, t_without = 0, particle_steps = 0;
        for (std::size_t k = 0; k < steps; k += chunk) {
            const std::size_t n = std::min(chunk, steps - k);
            double t0 = now();
            with.steps(a, h, n);
            t_with += now() - t0;
            t0 = now();
            without.steps(b, h, n);
            t_without += now() - t0;
            particle_steps += double(n) * double(with.test_particles().size());
        }
        const bool same = (a.q.array() == b.q.array()).all() && (a.p.array() == b.p.array()).all();
        failures += same ? 0 : 1;
        std::size_t by_reason[4] = {};
        for (const auto& l : with.encounters().losses()) ++by_reason[std::size_t(l.reason)];
        std::printf("%-24s 10^5 years: planets %s; %zu of 10^4 particles left (removed: %zu in a Hill sphere or "
                    "the Sun, %zu past 100 AU, %zu non-finite); %.1f CPU s with, %.1f without: %.1f ns per "
                    "particle-step\n",
                    sympl::coordinates_name(c).c_str(), same ? "bit-identical" : "DIFFERENT",
                    with.test_particles().size(), by_reason[0], by_reason[1],
                    by_reason[3], t_with, t_without, (t_with - t_without) / particle_steps * 1e9);
    }
    return failures;
}
}  // namespace

int main(int argc, char** argv) {
    if (argc > 1 && std::strcmp(argv[1], "--long") == 0) return long_run();
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    const int rounds = quick ? 3 : 7;
    const std::size_t n = 10000, steps = quick ? 100 : 500;
    const State x0 = sys.initial_state();
    const sympl::test_particle_set<double> none, particles = belt(x0, n);
    std::printf("Test particles with the outer solar system: %zu particles at 6-9 AU, h = %g days, leapfrog_kdk, "
                "%zu steps; median of %d interleaved rounds, one thread\n\n", n, h, steps, rounds);
    std::printf("%-24s %14s %14s %14s %12s\n", "coordinates", "ns/particle", "hand ns/part.", "ns/planet",
                "hand/sympl");
    for (auto c : {sympl::wh_coordinates::democratic_heliocentric, sympl::wh_coordinates::jacobi}) {
        const bool dh = c == sympl::wh_coordinates::democratic_heliocentric;
        std::vector<double> with, without, hand, hand0;
        for (int r = 0; r < rounds; ++r) {
            without.push_back(stepper_time(none, c, steps * 100));
            with.push_back(stepper_time(particles, c, steps));
            if (dh) hand.push_back(hand_time(particles, steps)), hand0.push_back(hand_time(none, steps * 100));
        }
        const double per = (median(with) - median(without)) / double(n) * 1e9;
        const double per_hand = dh ? (median(hand) - median(hand0)) / double(n) * 1e9 : 0;
        std::printf("%-24s %14.1f %14s %14.1f %12s\n", sympl::coordinates_name(c).c_str(), per,
                    dh ? std::to_string(per_hand).substr(0, 6).c_str() : "-", median(without) / 5 * 1e9,
                    dh ? std::to_string(per_hand / per).substr(0, 5).c_str() : "-");
    }
    // Two threads at once share the memory bus: CPU time per particle that
    // stays put from one thread to two, and from 1e4 particles (in cache) to
    // 1e6 (48 MB), says the work is arithmetic, not waiting on memory.
    std::printf("\nScaling (democratic heliocentric): CPU ns per particle per step, the particles in one thread, "
                "and split over two running at once\n");
    std::printf("%-10s %14s %14s %10s\n", "particles", "1 thread", "2 threads", "ratio");
    for (std::size_t N : {std::size_t(100), std::size_t(1000), std::size_t(10000), std::size_t(100000),
                          std::size_t(1000000)}) {
        if (quick && N > 100000) continue;
        const std::size_t k = std::max<std::size_t>(2, 2000000 / N / (quick ? 10 : 1));
        const sympl::test_particle_set<double> p = belt(x0, N), half = belt(x0, N / 2);
        std::vector<double> one, two;
        for (int r = 0; r < (N >= 100000 ? 3 : rounds); ++r) {
            one.push_back(stepper_time(p, sympl::wh_coordinates::democratic_heliocentric, k));
            double t2[2];
            std::thread a([&] { t2[0] = stepper_time(half, sympl::wh_coordinates::democratic_heliocentric, k); });
            t2[1] = stepper_time(half, sympl::wh_coordinates::democratic_heliocentric, k);
            a.join();
            two.push_back(t2[0] + t2[1]);  // CPU time of both halves
        }
        std::printf("%-10zu %14.1f %14.1f %10.2f\n", N, median(one) / double(N) * 1e9, median(two) / double(N) * 1e9,
                    median(one) / median(two));
    }
    return 0;
}
