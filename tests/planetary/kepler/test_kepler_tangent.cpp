// The tangent map of the Kepler drift (kepler_tangent.hpp) against the
// derivative of the drift itself: central differences of kepler_drift in long
// double at 2e-6 and 1e-6 of the tangent, Richardson-extrapolated (their
// error O(1e-24) from the step, O(1e-13) from rounding). The tangent is exact
// to rounding: its own error a few eps times the condition of the flow,
// which grows with the drift's length (the phase: |v| h) and eccentricity.
// Measured over 2000 orbits of each kind: 3.8e-13 for short drifts of nearly
// circular orbits (the Wisdom-Holman case), 6.5e-12 for elliptic ones over up
// to 3 periods (the period reduction's dependence on the orbit included),
// 3.4e-12 for hyperbolic ones; the bounds 1e-11 and 1e-10 hold condition
// numbers up to ~1e4 and ~1e5 times eps. A tangent that missed the root's
// dependence on the start (ds = 0) would be off by O(1).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include <Eigen/Core>

#include <sympl/planetary/kepler/kepler_drift.hpp>
#include <sympl/planetary/kepler/kepler_tangent.hpp>

namespace test_planetary_test_kepler_tangent {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using ld = long double;

// The largest difference of the tangent from the differences, relative to the largest component.
double tangent_error(const double (&r)[3], const double (&v)[3], const double (&dr)[3], const double (&dv)[3], double gm,
                     double h) {
    double tr[3] = {dr[0], dr[1], dr[2]}, tv[3] = {dv[0], dv[1], dv[2]};
    kepler_drift_tangent(r, v, tr, tv, gm, h);
    const auto central = [&](ld e, ld (&out)[6]) {
        Eigen::Matrix<ld, 3, 1> rp, vp, rm, vm;
        for (int i = 0; i < 3; ++i) {
            rp[i] = r[i] + e * dr[i], vp[i] = v[i] + e * dv[i];
            rm[i] = r[i] - e * dr[i], vm[i] = v[i] - e * dv[i];
        }
        kepler_drift<ld>(rp, vp, gm, h);
        kepler_drift<ld>(rm, vm, gm, h);
        for (int i = 0; i < 3; ++i) out[i] = (rp[i] - rm[i]) / (2 * e), out[i + 3] = (vp[i] - vm[i]) / (2 * e);
    };
    ld coarse[6], fine[6];
    central(2e-6L, coarse);
    central(1e-6L, fine);
    const double tangent[6] = {tr[0], tr[1], tr[2], tv[0], tv[1], tv[2]};
    double difference = 0, size = 0;
    for (int i = 0; i < 6; ++i) {
        const ld reference = (4 * fine[i] - coarse[i]) / 3;
        difference = std::max(difference, double(std::fabs(reference - tangent[i])));
        size = std::max(size, double(std::fabs(reference)));
    }
    return difference / size;
}
}  // namespace

TEST_CASE("kepler_tangent: the tangent map is the drift's derivative, to rounding") {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const char* kinds[] = {"short drifts of nearly circular orbits", "elliptic, up to 3 periods", "hyperbolic"};
    for (int kind = 0; kind < 3; ++kind) {
        double worst = 0;
        for (int trial = 0; trial < 2000; ++trial) {
            const double gm = 1, a = 1.5 + u(rng) * u(rng);
            const double r[3] = {a, 0.1 * u(rng), 0.1 * u(rng)};
            const double circular = std::sqrt(gm / a), period = 2 * 3.141592653589793 * a * std::sqrt(a / gm);
            const double speed = kind == 0 ? 1 + 0.05 * u(rng) : kind == 1 ? 1 + 0.35 * u(rng) : 1.5 + 0.5 * std::fabs(u(rng));
            const double v[3] = {0.2 * u(rng) * circular, speed * circular, 0.1 * u(rng) * circular};
            const double h = (kind == 0 ? period / 20 : kind == 1 ? 3 * period : 2 * period) * u(rng);
            const double dr[3] = {u(rng), u(rng), u(rng)}, dv[3] = {u(rng) * circular, u(rng) * circular, u(rng) * circular};
            worst = std::max(worst, tangent_error(r, v, dr, dv, gm, h));
        }
        MESSAGE(std::string(kinds[kind]) << ": largest relative difference from the drift's derivative " << worst);
        CHECK(worst < (kind == 0 ? 1e-11 : 1e-10));
    }
}

TEST_CASE("kepler_tangent: a drift of whole periods moves the body by the change of its period") {
    // Back at the start after 2 periods, but a change of the energy changes
    // the period: the tangent carries d(period) times the velocity.
    const double r[3] = {1, 0, 0}, v[3] = {0, 1.1, 0}, gm = 1;
    const double beta = 2 * gm / 1 - 1.21, period = 2 * 3.141592653589793 * gm / (beta * std::sqrt(beta));
    const double dr[3] = {0.3, -0.2, 0.1}, dv[3] = {0.05, 0.1, -0.02};
    CHECK(tangent_error(r, v, dr, dv, gm, 2 * period) < 1e-10);
    CHECK_THROWS_AS(tangent_error({0, 0, 0}, v, dr, dv, gm, 1.0), invalid_argument);
}

}  // namespace test_planetary_test_kepler_tangent
