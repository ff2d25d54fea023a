// Cost of a charged particle's step: sympl's boris_stepper (drift-kick-drift,
// fields through the radial_mirror_field callables) against a hand-written
// loop of the same arithmetic on plain doubles, side by side in one process,
// in interleaved rounds (median of the rounds), on the non-uniform field of
// the built-in charged_particle system in 3D. Also the relativistic pusher,
// and the two splittings per step and per exact sub-flow (cylindrical_split:
// blanes_moan_srkn11b, 11 kicks a step; cartesian_split: kahan_li_8, 17
// leapfrog steps of 4 flows, merged at the ends). Prints ns per step; the two
// Boris columns must agree to rounding in their final states (checked).
//   bench_charged [--quick]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include <sympl/charged/axisymmetric_splitting.hpp>
#include <sympl/charged/boris.hpp>
#include <sympl/charged/canonical_splitting.hpp>
#include <sympl/charged/relativistic_pusher.hpp>
#include <sympl/methods/catalog.hpp>

namespace {
double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

// The hand loop: Boris's drift-kick-drift for B = (0, 0, B0 (1 + r^2/L^2)),
// E = -k (x, y, 0), unit mass and charge, with B0 = L = 1.
void hand_boris(double* x, double* v, double dt, long n, double k) {
    const double h = dt / 2;
    for (long i = 0; i < n; ++i) {
        const double xh = x[0] + h * v[0], yh = x[1] + h * v[1], zh = x[2] + h * v[2];
        const double ex = -k * xh * h, ey = -k * yh * h;  // (e dt / 2m) E
        const double tz = h * (1 + xh * xh + yh * yh);   // (e dt / 2m) B_z
        const double mx = v[0] + ex, my = v[1] + ey, mz = v[2];
        const double px = mx + my * tz, py = my - mx * tz;  // v- + v- x tau
        const double s = 2 * tz / (1 + tz * tz);
        v[0] = mx + py * s + ex;
        v[1] = my - px * s + ey;
        v[2] = mz;
        x[0] = xh + h * v[0];
        x[1] = yh + h * v[1];
        x[2] = zh + h * v[2];
    }
}
}  // namespace

int main(int argc, char** argv) {
    using namespace sympl;
    using namespace sympl::charged;
    const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
    const long n = quick ? 200000 : 2000000;
    const int rounds = quick ? 5 : 15;
    const double dt = 0.05, k = 0.2;
    const particle a{.mass = 1, .charge = 1, .speed_of_light = 10};
    const radial_mirror_field f{.field = 1, .field_length = 1, .confinement = k};
    const kinetic_state<> start(vec3<>(1, 0, 0), vec3<>(0.4, 1, 0.3));

    std::vector<double> t_hand, t_boris, t_hc, t_cyl, t_cart;
    double difference = 0;
    volatile double sink = 0;
    for (int r = 0; r < rounds; ++r) {
        double x[3] = {1, 0, 0}, v[3] = {0.4, 1, 0.3};
        double t0 = now();
        hand_boris(x, v, dt, n, k);
        t_hand.push_back((now() - t0) / double(n));

        boris_stepper<radial_mirror_field> boris(a, f);
        kinetic_state<> s = start;
        t0 = now();
        for (long i = 0; i < n; ++i) boris.step(s, dt);
        t_boris.push_back((now() - t0) / double(n));
        difference = std::max({std::abs(s.q[0] - x[0]), std::abs(s.q[1] - x[1]), std::abs(s.p[0] - v[0])});

        relativistic_pusher<radial_mirror_field> hc(a, f);
        kinetic_state<> u = start;
        t0 = now();
        for (long i = 0; i < n; ++i) hc.step(u, dt);
        t_hc.push_back((now() - t0) / double(n));

        const long m = n / 16;
        axisymmetric_splitting_stepper<radial_mirror_field, 3> cyl(a, f, method("blanes_moan_srkn11b"));
        phase_space<double, 3> c = to_canonical(a, f, start);
        t0 = now();
        cyl.steps(c, dt * 16, std::size_t(m));
        t_cyl.push_back((now() - t0) / double(m));

        canonical_splitting_stepper<radial_mirror_field, 3> cart(a, f, method("kahan_li_8"));
        phase_space<double, 3> d = to_canonical(a, f, start);
        t0 = now();
        for (long i = 0; i < m; ++i) cart.step(d, dt * 16);
        t_cart.push_back((now() - t0) / double(m));
        sink = sink + u.q[0] + c.q[0] + d.q[0];
    }
    std::printf("charged particle, radial mirror field in 3D, %ld steps, median of %d interleaved rounds (shared "
                "machine: repeat)\n",
                n, rounds);
    std::printf("  hand-written Boris loop        %7.2f ns/step\n", 1e9 * median(t_hand));
    std::printf("  boris_stepper                  %7.2f ns/step   (%.2fx the hand loop; final states differ by %.1e)\n",
                1e9 * median(t_boris), median(t_boris) / median(t_hand), difference);
    std::printf("  relativistic_pusher            %7.2f ns/step\n", 1e9 * median(t_hc));
    std::printf("  cylindrical_split(srkn11b)     %7.2f ns/step   (%.2f ns per kick, 11 a step)\n", 1e9 * median(t_cyl),
                1e9 * median(t_cyl) / 11);
    std::printf("  cartesian_split(kahan_li_8)    %7.2f ns/step   (%.2f ns per exact flow, 17 x 4 + 1 a step)\n",
                1e9 * median(t_cart), 1e9 * median(t_cart) / 69);
    return difference < 1e-8 ? 0 : 1;
}
