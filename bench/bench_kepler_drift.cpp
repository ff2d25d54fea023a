// Cost of the exact Kepler drift per body: the batched kepler_drift_all
// (lanes of up to kepler_lanes bodies: the short-drift path, then quartic
// iterations with a convergence mask for the lanes it leaves) against a loop
// of the single-body kepler_drift on the same inputs, side by side in one
// process, in interleaved rounds (median of the rounds). Two input
// sets of 10^6 bodies: outer-solar-system-like orbits (e < 0.25, a = 5..40 AU,
// GM of the Sun in AU and days, h = 1/10 of Jupiter's period down to ~180
// days, the Wisdom-Holman case) and random elements (e in [0, 0.999], 5%
// hyperbolic, h up to 5 periods). Prints ns per body per drift and the ratio.
// Then the Wisdom-Holman case itself: a batch of 5 bodies on the orbits of the
// outer planets (a and e of Jupiter, Saturn, Uranus, Neptune and Pluto, random
// orientation and anomaly) drifted again and again by h = 1/20 and 1/5 of
// Jupiter's period, one kepler_drift_all call per drift, against 5 calls of
// kepler_drift: ns per planet per drift.
//   bench_kepler_drift [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include <sympl/planetary/kepler/kepler_lanes.hpp>

namespace {
double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

struct bodies {
    std::vector<double> x, y, z, vx, vy, vz;
    double gm = 2.95912208286e-4, h = 0;
    sympl::kepler_bodies<double> view() { return {x, y, z, vx, vy, vz}; }
};

// A body on the orbit of semi-major axis a (a < 0: hyperbolic) and
// eccentricity e, at eccentric (hyperbolic) anomaly E, turned by random angles.
void add(bodies& b, std::mt19937_64& rng, double a, double e, double E) {
    std::uniform_real_distribution<double> u(0, 1);
    double x, y, vx, vy;
    if (e < 1) {
        const double r = a * (1 - e * std::cos(E)), k = std::sqrt(b.gm * a) / r, s = std::sqrt(1 - e * e);
        x = a * (std::cos(E) - e), y = a * s * std::sin(E), vx = -k * std::sin(E), vy = k * s * std::cos(E);
    } else {
        const double A = -a, r = A * (e * std::cosh(E) - 1), k = std::sqrt(b.gm * A) / r, s = std::sqrt(e * e - 1);
        x = A * (e - std::cosh(E)), y = A * s * std::sinh(E), vx = -k * std::sinh(E), vy = k * s * std::cosh(E);
    }
    const double i = 3.141592653589793 * u(rng), w = 6.283185307179586 * u(rng), node = 6.283185307179586 * u(rng);
    // R = Rz(node) Rx(i) Rz(w) applied to (x, y, 0).
    const auto turn = [&](double px, double py, double& ox, double& oy, double& oz) {
        const double x1 = px * std::cos(w) - py * std::sin(w), y1 = px * std::sin(w) + py * std::cos(w);
        const double y2 = y1 * std::cos(i), z2 = y1 * std::sin(i);
        ox = x1 * std::cos(node) - y2 * std::sin(node), oy = x1 * std::sin(node) + y2 * std::cos(node), oz = z2;
    };
    double ox, oy, oz;
    turn(x, y, ox, oy, oz);
    b.x.push_back(ox), b.y.push_back(oy), b.z.push_back(oz);
    turn(vx, vy, ox, oy, oz);
    b.vx.push_back(ox), b.vy.push_back(oy), b.vz.push_back(oz);
}

bodies solar_like(std::size_t n, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    bodies b;
    for (std::size_t k = 0; k < n; ++k) add(b, rng, 5 + 35 * u(rng), 0.25 * u(rng), 6.283185307179586 * u(rng));
    b.h = 433.0;  // ~ Jupiter's period / 10 in days
    return b;
}

bodies random_elements(std::size_t n, std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    bodies b;
    b.gm = 1;
    for (std::size_t k = 0; k < n; ++k) {
        if (u(rng) < 0.05) add(b, rng, -(0.1 + 10 * u(rng)), 1 + 4 * u(rng), 4 * (2 * u(rng) - 1));
        else add(b, rng, 0.1 + 10 * u(rng), 0.999 * u(rng), 6.283185307179586 * u(rng));
    }
    b.h = 31.4;  // 5 periods at a = 1, a fraction to many periods for the others
    return b;
}
}  // namespace

int main(int argc, char** argv) {
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    const std::size_t n = quick ? 100000 : 1000000;
    const int rounds = quick ? 3 : 7;
    std::mt19937_64 rng(42);
    std::printf("Kepler drift, %zu bodies per set, kepler_lanes = %d, %d quartic iterations in the lanes; "
                "median of %d interleaved rounds, one thread\n\n",
                n, sympl::kepler_lanes, sympl::kepler_lane_iterations, rounds);
    std::printf("%-28s %14s %14s %10s %12s\n", "inputs", "scalar ns/body", "batched ns/body", "batched/scalar",
                "fallbacks");
    double sink = 0;
    for (int set = 0; set < 2; ++set) {
        const bodies start = set == 0 ? solar_like(n, rng) : random_elements(n, rng);
        std::vector<double> scalar_times, batched_times;
        std::size_t fallbacks = 0;
        double worst = 0;
        for (int round = 0; round < rounds; ++round) {
            bodies a = start, b = start;
            double t0 = now();
            for (std::size_t i = 0; i < n; ++i) {
                Eigen::Vector3d r(a.x[i], a.y[i], a.z[i]), v(a.vx[i], a.vy[i], a.vz[i]);
                sympl::kepler_drift(r, v, a.gm, a.h);
                a.x[i] = r[0], a.y[i] = r[1], a.z[i] = r[2], a.vx[i] = v[0], a.vy[i] = v[1], a.vz[i] = v[2];
            }
            scalar_times.push_back((now() - t0) / double(n));
            t0 = now();
            fallbacks = sympl::kepler_drift_all(b.view(), b.gm, b.h);
            batched_times.push_back((now() - t0) / double(n));
            for (std::size_t i = 0; i < n; ++i)
                worst = std::max(worst, std::hypot(a.x[i] - b.x[i], a.y[i] - b.y[i], a.z[i] - b.z[i]) /
                                            std::hypot(a.x[i], a.y[i], a.z[i]));
            sink += a.x[n / 2] + b.x[n / 3];
        }
        const double s = median(scalar_times) * 1e9, t = median(batched_times) * 1e9;
        std::printf("%-28s %14.1f %14.1f %10.2f %12zu\n", set == 0 ? "outer-solar-system-like" : "random elements", s, t,
                    t / s, fallbacks);
        std::printf("%-28s max relative |batched - scalar| position difference %.2g\n", "", worst);
    }
    // The batch of the outer planets, drifted `drifts` times in a row (each
    // drift starts where the last ended: the anomalies move round the orbits).
    const std::size_t drifts = quick ? 20000 : 200000;
    std::printf("\n5 outer planets in one batch, %zu drifts per round; ns per planet per drift\n", drifts);
    std::printf("%-28s %14s %14s %10s %12s\n", "h", "scalar ns", "batched ns", "batched/scalar", "fallbacks");
    const double a[5] = {5.2026, 9.5549, 19.2184, 30.1104, 39.5447}, e[5] = {0.0484, 0.0555, 0.0464, 0.0095, 0.2490};
    std::uniform_real_distribution<double> u(0, 1);
    bodies planets;
    for (int k = 0; k < 5; ++k) add(planets, rng, a[k], e[k], 6.283185307179586 * u(rng));
    for (const double fraction : {1.0 / 20, 1.0 / 5}) {
        std::vector<double> scalar_times, batched_times;
        std::size_t fallbacks = 0;
        double worst = 0;
        for (int round = 0; round < rounds; ++round) {
            bodies p = planets, q = planets;
            p.h = q.h = 4332.6 * fraction;
            double t0 = now();
            for (std::size_t k = 0; k < drifts; ++k)
                for (std::size_t i = 0; i < 5; ++i) {
                    Eigen::Vector3d r(p.x[i], p.y[i], p.z[i]), v(p.vx[i], p.vy[i], p.vz[i]);
                    sympl::kepler_drift(r, v, p.gm, p.h);
                    p.x[i] = r[0], p.y[i] = r[1], p.z[i] = r[2], p.vx[i] = v[0], p.vy[i] = v[1], p.vz[i] = v[2];
                }
            scalar_times.push_back((now() - t0) / double(5 * drifts));
            fallbacks = 0;
            t0 = now();
            for (std::size_t k = 0; k < drifts; ++k) fallbacks += sympl::kepler_drift_all(q.view(), q.gm, q.h);
            batched_times.push_back((now() - t0) / double(5 * drifts));
            // After `drifts` drifts the two differ by the rounding of each, carried along the orbit.
            for (std::size_t i = 0; i < 5; ++i)
                worst = std::max(worst, std::hypot(p.x[i] - q.x[i], p.y[i] - q.y[i], p.z[i] - q.z[i]) /
                                            std::hypot(p.x[i], p.y[i], p.z[i]));
            sink += p.x[1] + q.x[2];
        }
        const double s = median(scalar_times) * 1e9, t = median(batched_times) * 1e9;
        char label[40];
        std::snprintf(label, sizeof label, "P_Jupiter / %g (%.0f days)", 1 / fraction, 4332.6 * fraction);
        std::printf("%-28s %14.1f %14.1f %10.2f %12zu\n", label, s, t, t / s, fallbacks);
        std::printf("%-28s max relative |batched - scalar| position difference after %zu drifts %.2g\n", "", drifts,
                    worst);
    }
    std::printf("\n(checksum %g)\n", sink);
}
