// Poincare sections (upward crossings of q_k = 0, located by the event
// locator of events.hpp on the cubic Hermite interpolant): the oscillator's
// exact crossing states, Henon-Heiles crossings against a run with a 16 times
// smaller step, the step sequence left alone, bad input.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/analysis/poincare_section.hpp>
#include <sympl/hamiltonians/harmonic_oscillator.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>

namespace test_analysis_test_poincare_section {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using S1 = phase_space<double, 1>;
using S2 = phase_space<double, 2>;
using V1 = Eigen::Matrix<double, 1, 1>;
const double pi = std::numbers::pi;
const hamiltonians::harmonic_oscillator oscillator{};
const hamiltonians::henon_heiles henon_heiles{};

// The oscillator's exact flow as a stepper: the crossings then differ from
// the exact ones by the interpolation alone.
struct exact_oscillator {
    using state_type = S1;
    using scalar = double;
    void step(S1& x, double dt) const { x = oscillator.exact(x, dt); }
    const hamiltonians::harmonic_oscillator& hamiltonian() const { return oscillator; }
};
}  // namespace

TEST_CASE("poincare section: the oscillator's upward crossings are (q, p) = (0, 1) within dt^4/384") {
    // From (1, 0): q = cos t, p = -sin t, upward through q = 0 at 3 pi/2 + 2 pi k,
    // where p = 1. The cubic's error in p is <= dt^4/384 max|p''''| = dt^4/384;
    // the crossing time's error delta <= dt^4/384 (|dq/dt| = 1 there) moves p
    // by delta^2/2 only (dp/dt = -q = 0 at the crossing).
    for (const double dt : {0.3, 0.15}) {
        CAPTURE(dt);
        exact_oscillator s;
        const auto steps = static_cast<std::size_t>(20 * 2 * pi / dt);
        const auto points = section_crossings(s, S1(V1(1.0), V1(0.0)), dt, steps);
        REQUIRE(points.size() == 20);
        double worst = 0;
        for (const S1& c : points) {
            CHECK(c.q[0] == 0);
            worst = std::max(worst, std::fabs(c.p[0] - 1));
        }
        const double bound = std::pow(dt, 4) / 384;
        CHECK(worst <= bound * (1 + 1e-6) + 1e-15);
        // The interpolation is used: step ends alone would be off by up to dt^2/2 in p.
        CHECK(worst <= 1e-3 * dt * dt / 2);
        MESSAGE("oscillator, dt = " << dt << ": largest |p - 1| at the crossings " << worst << " (bound " << bound << ")");
    }
}

TEST_CASE("poincare section: Henon-Heiles crossings against a run with a 16 times smaller step") {
    // A regular orbit at E = 1/12 (q2 = 0.1, p2 = 0 on the section), Yoshida's
    // order-8 composition. The coarse points (dt = 0.05) are off the fine ones
    // (dt/16: 16^4 times smaller interpolation error) by the cubic's error
    // e <= dt^4/384 max|x''''| per component, plus the crossing time's error
    // e / |dq1/dt| times |dx/dt|, plus the grid's error (the coarse run's
    // step ends against the fine run's: measured). max|x''''| from fourth
    // differences of the fine run's states.
    const double dt = 0.05, t_end = 100;
    const auto steps = static_cast<std::size_t>(t_end / dt);
    const std::size_t refine = 16;
    const S2 x0 = hamiltonians::henon_heiles::initial_state(1.0 / 12, 0.1, 0.0);
    const auto make = [] { return make_stepper<S2>(henon_heiles, method("yoshida_8")); };
    auto coarse_stepper = make();
    auto fine_stepper = make();
    const auto coarse = section_crossings(coarse_stepper, x0, dt, steps);
    const auto fine = section_crossings(fine_stepper, x0, dt / double(refine), steps * refine);
    REQUIRE(coarse.size() >= 10);
    REQUIRE(coarse.size() == fine.size());

    // The fine run's states every fine step: max|x''''| and the grid's error.
    std::vector<S2> states;
    auto a = make();
    S2 y = x0;
    integrate_steps(a, y, 0.0, dt / double(refine), steps * refine, [&](const S2& z, double) { states.push_back(z); });
    const double h = 4 * dt / double(refine);  // fourth differences over 4 fine steps
    double x4 = 0;
    for (std::size_t i = 0; i + 16 < states.size(); i += 4) {
        const S2 &s0 = states[i], &s1 = states[i + 4], &s2 = states[i + 8], &s3 = states[i + 12], &s4 = states[i + 16];
        x4 = std::max(x4, ((s0.q - 4 * s1.q + 6 * s2.q - 4 * s3.q + s4.q) / std::pow(h, 4)).cwiseAbs().maxCoeff());
        x4 = std::max(x4, ((s0.p - 4 * s1.p + 6 * s2.p - 4 * s3.p + s4.p) / std::pow(h, 4)).cwiseAbs().maxCoeff());
    }
    double grid = 0;
    auto b = make();
    S2 z = x0;
    integrate_steps(b, z, 0.0, dt, steps, [&](const S2& c, double t) {
        const auto i = static_cast<std::size_t>(std::lround(t / dt)) * refine;
        grid = std::max(grid, max_difference(c, states[i]));
    });
    const double e = 1.1 * std::pow(dt, 4) / 384 * x4;
    double worst = 0, worst_ratio = 0;
    for (std::size_t i = 0; i < coarse.size(); ++i) {
        const S2& f = fine[i];
        Eigen::Vector2d force;
        henon_heiles.force(f.q, force);
        const double speed = std::max(f.p.cwiseAbs().maxCoeff(), force.cwiseAbs().maxCoeff());
        const double bound = (e + 2 * grid) * (1 + speed / f.p[0]);  // dq1/dt = p1 > 0 upwards
        const double d = max_difference(coarse[i], f);
        CAPTURE(i);
        CHECK(d <= bound);
        worst = std::max(worst, d);
        worst_ratio = std::max(worst_ratio, d / bound);
    }
    MESSAGE("Henon-Heiles, " << coarse.size() << " crossings: largest difference to dt/16 " << worst
                             << " (largest fraction of its bound " << worst_ratio << "; max|x''''| " << x4
                             << ", grid error " << grid << ")");
}

TEST_CASE("poincare section: the run is integrate_steps' with an observer, and bad input is refused") {
    // The section runs the steps of integrate_steps with an observer: the same
    // forces as that run (the interpolant's are its own, not the stepper's).
    const S2 x0 = hamiltonians::henon_heiles::initial_state(1.0 / 12, 0.1, 0.0);
    auto s1 = make_stepper<S2>(henon_heiles, method("leapfrog_kdk"));
    auto s2 = make_stepper<S2>(henon_heiles, method("leapfrog_kdk"));
    S2 y = x0;
    integrate_steps(s2, y, 0.0, 0.05, 400, [](const S2&, double) {});
    const auto points = section_crossings(s1, x0, 0.05, 400);
    CHECK(!points.empty());
    CHECK(s1.force_evaluations() == s2.force_evaluations());
    CHECK(section_crossings(s1, x0, 0.05, 0).empty());
    CHECK_THROWS_WITH_AS(section_crossings(s1, x0, 0.05, 10, 2), doctest::Contains("k = 2 for a state of dimension 2"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(section_crossings(s1, x0, -0.05, 10), doctest::Contains("section_crossings: dt = -0.05"),
                         invalid_argument);
    // A blow-up is reported: from q2 = p2 = 3 the orbit escapes (dp2/dt = q2^2 - q2 > 0) in finite time.
    const S2 far(Eigen::Vector2d(0, 3), Eigen::Vector2d(0, 3));
    CHECK_THROWS_WITH_AS(section_crossings(s1, far, 0.5, 1000), doctest::Contains("produced a non-finite state"),
                         integration_error);
}

}  // namespace test_analysis_test_poincare_section
