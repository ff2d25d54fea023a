// The Wisdom-Holman stepper in democratic heliocentric coordinates
// (Wisdom & Holman 1991, Astron. J. 102, 1528; Duncan, Levison & Lee 1998,
// Astron. J. 116, 2067) on the outer solar system of Hairer, Lubich & Wanner
// and on a star with two planets of masses eps and 0.6 eps:
//   (a) planet masses -> 0: every planet follows its exact Kepler orbit, to rounding;
//   (b) the relative energy error stays bounded over 2 10^4 steps and scales as
//       eps h^2 for the leapfrog and as eps h^4 (+ eps^2 h^2) for SABA_2
//       (Laskar & Robutel 2001, Celest. Mech. Dyn. Astron. 80, 39);
//   (c) on the outer solar system it is far below the T + V leapfrog's at the same step;
//   (d) bad input names the body;
//   (e) the symplectic corrector (Wisdom, Holman & Touma 1996): its weights
//       solve their conditions; the leapfrog's energy error goes from eps h^2
//       to eps h^(2K+2) + eps^2 h^2 (slopes in h and in the planet masses);
//       chunks, a new dt, its cost; the weights solved for any symmetric
//       table (SABA_2, SBAB_2: their eps h^4 terms removed); tables
//       that are not symmetric refused;
//   (f) the composition kernel (Wisdom, Holman & Touma 1996; Rein, Tamayo &
//       Brown 2019): with corrector 17 the eps^2 h^2 term becomes eps^2 h^4
//       (slopes in h and in the planet masses); its sub-steps, its cost,
//       tables refused;
//   (g) Jacobi coordinates (Wisdom & Holman 1991): (a) again, the leapfrog's
//       eps h^2, the composition and lazy kernels' eps^2 h^4, the lazy one's cost;
//   (h) MEGNO: the tangent against differences of two runs; <Y> -> 2 on
//       quasi-periodic orbits, growing on a chaotic one.
// Also: steps(n) against n calls of step(), the counters, and the drivers.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include <sympl/drivers/fixed_step.hpp>
#include <sympl/core/splitting_stepper.hpp>
#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/methods/catalog.hpp>
#include <sympl/planetary/kepler/kepler_drift.hpp>
#include <sympl/planetary/wisdom_holman_stepper.hpp>

namespace test_planetary_test_wisdom_holman_stepper {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
constexpr double eps = std::numeric_limits<double>::epsilon();
constexpr double two_pi = 6.283185307179586;
using State = phase_space<double>;
using V3 = Eigen::Vector3d;

// H = sum |p_i|^2 / 2m_i - sum_{i<j} G m_i m_j / |q_i - q_j| in long double.
long double energy_ld(const std::vector<double>& m, double G, const State& x) {
    long double t = 0, v = 0;
    const std::size_t n = m.size();
    for (std::size_t i = 0; i < n; ++i) {
        const Eigen::Matrix<long double, 3, 1> p = x.p.segment<3>(Eigen::Index(3 * i)).cast<long double>();
        t += p.squaredNorm() / (2 * (long double)m[i]);
        for (std::size_t j = i + 1; j < n; ++j) {
            const Eigen::Matrix<long double, 3, 1> d =
                (x.q.segment<3>(Eigen::Index(3 * i)) .cast<long double>() - x.q.segment<3>(Eigen::Index(3 * j)).cast<long double>());
            v -= (long double)G * m[i] * m[j] / std::sqrt(d.squaredNorm());
        }
    }
    return t + v;
}

struct planetary_system {
    std::vector<double> mass;
    double G = 1;
    State start;
};

// A planet on the orbit (a, e) about G (m_0 + m), at pericentre (apocentre if
// `apo`), its orbit turned by `node` about z and tilted by `tilt` about x.
void place(planetary_system& s, std::size_t i, double a, double e, bool apo, double node, double tilt) {
    const double gm = s.G * (s.mass[0] + s.mass[i]);
    const double r = apo ? a * (1 + e) : a * (1 - e);
    const double v = std::sqrt(gm * (2 / r - 1 / a));
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(node, V3::UnitZ()) * Eigen::AngleAxisd(tilt, V3::UnitX())).toRotationMatrix();
    s.start.q.segment<3>(Eigen::Index(3 * i)) = R * V3(r, 0, 0);
    s.start.p.segment<3>(Eigen::Index(3 * i)) = s.mass[i] * (R * V3(0, v, 0));
}

// A star of mass 1 (G = 1) and planets of eps and 0.6 eps on orbits a = 1 (e = 0.05)
// and a = 1.8 (e = 0.08, tilted by 0.05): inner period 2 pi. Total momentum zero.
planetary_system two_planets(double epsilon) {
    planetary_system s{{1.0, epsilon, 0.6 * epsilon}, 1.0, State(9)};
    place(s, 1, 1.0, 0.05, false, 0.0, 0.0);
    place(s, 2, 1.8, 0.08, true, 2.0, 0.05);
    s.start.p.segment<3>(0) = -(s.start.p.segment<3>(3) + s.start.p.segment<3>(6));
    return s;
}

// The outer solar system with every planet's mass times `scale` (velocities kept).
planetary_system outer_solar_system(double scale = 1) {
    hamiltonians::outer_solar_system sys{};
    for (int i = 1; i < sys.bodies; ++i) sys.mass[std::size_t(i)] *= scale;
    const auto x = sys.initial_state();
    return {std::vector<double>(sys.mass.begin(), sys.mass.end()), sys.G, State(x.q, x.p)};
}

// The largest relative energy error over n steps of h, checked every step
// (with a corrector, every step's output is corrected, the run going on uncorrected).
struct energy_run {
    double worst = 0, first_half = 0, second_half = 0;
};
energy_run energy_errors(const planetary_system& s, const table& t, double h, std::size_t n,
                         wisdom_holman_options options = {}) {
    wisdom_holman_stepper<State> wh(s.mass, s.G, t, options);
    State x = s.start;
    const long double e0 = energy_ld(s.mass, s.G, x);
    energy_run r;
    for (std::size_t k = 1; k <= n; ++k) {
        wh.step(x, h);
        const double e = double(std::fabs((energy_ld(s.mass, s.G, x) - e0) / e0));
        r.worst = std::max(r.worst, e);
        (2 * k <= n ? r.first_half : r.second_half) = std::max(2 * k <= n ? r.first_half : r.second_half, e);
    }
    return r;
}

// Least-squares slope of log y against log x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double n = double(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
        const double a = std::log(x[i]), b = std::log(y[i]);
        sx += a, sy += b, sxx += a * a, sxy += a * b;
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

V3 heliocentric_position(const State& x, std::size_t i) {
    return x.q.segment<3>(Eigen::Index(3 * i)) - x.q.segment<3>(0);
}
}  // namespace

// Rounding: each drift moves a planet's energy (its semi-major axis) by a few
// eps, a random walk of size sqrt(k) eps after k drifts; the phase error that
// drives grows as n^(3/2) eps (omega h) after n steps, omega h < 1 here. The
// bound n^1.5 eps is that, with room; a wrong weight or GM is off by far more.
// In both coordinates (in Jacobi ones each planet is then about G m_0 (1 + 1e-20)).
TEST_CASE("wisdom_holman: with planet masses -> 0 every planet follows its exact Kepler orbit, to rounding") {
    for (const char* name : {"leapfrog_kdk", "saba_3", "sbab_2"}) {
        for (int which = 0; which < 4; ++which) {
            const planetary_system s = which % 2 == 0 ? outer_solar_system(1e-20) : two_planets(1e-20);
            const double h = which % 2 == 0 ? 50.0 : two_pi / 40;
            const std::size_t n = 2000;
            const wh_coordinates coordinates = which < 2 ? wh_coordinates::democratic_heliocentric : wh_coordinates::jacobi;
            wisdom_holman_stepper<State> wh(s.mass, s.G, method(name), {.coordinates = coordinates});
            State x = s.start;
            wh.steps(x, h, n);
            double worst = 0;
            for (std::size_t i = 1; i < s.mass.size(); ++i) {
                // The exact orbit: one drift of n h about G m_0 (the planets' pull is 1e-20 of it).
                Eigen::Vector3d r = heliocentric_position(s.start, i);
                Eigen::Vector3d v = s.start.p.segment<3>(Eigen::Index(3 * i)) / s.mass[i] - s.start.p.segment<3>(0) / s.mass[0];
                kepler_drift(r, v, s.G * s.mass[0], double(n) * h);
                worst = std::max(worst, (heliocentric_position(x, i) - r).norm() / r.norm());
            }
            const std::string label = std::string(name) + (which % 2 == 0 ? " outer solar system" : " two planets") + ", " +
                                      coordinates_name(coordinates);
            MESSAGE(label << ": largest relative position error after "
                         << n << " steps = " << worst / eps << " eps, bound n^1.5 eps = " << std::pow(double(n), 1.5) << " eps");
            CHECK(worst < std::pow(double(n), 1.5) * eps);
        }
    }
}

TEST_CASE("wisdom_holman: the leapfrog's energy error is bounded and scales as eps h^2") {
    const table& lf = method("leapfrog_kdk");
    SUBCASE("bounded over 2 10^4 steps") {
        const energy_run r = energy_errors(two_planets(1e-3), lf, two_pi / 50, 20000);
        MESSAGE("eps = 1e-3, h = 2 pi / 50: largest relative energy error " << r.first_half << " (first half), "
                                                                            << r.second_half << " (second half)");
        CHECK(r.second_half < 1.5 * r.first_half);
    }
    SUBCASE("slope in h and in eps") {
        const double span = 40 * two_pi;  // 40 inner periods
        std::vector<double> hs, errors;
        for (double k : {25.0, 50.0, 100.0}) {
            const double h = two_pi / k;
            hs.push_back(h);
            errors.push_back(energy_errors(two_planets(1e-4), lf, h, std::size_t(std::lround(span / h))).worst);
        }
        const double in_h = slope(hs, errors);
        std::vector<double> epsilons, errors_eps;
        for (double e : {1e-5, 1e-4, 1e-3}) {
            epsilons.push_back(e);
            errors_eps.push_back(energy_errors(two_planets(e), lf, two_pi / 50, 2000).worst);
        }
        const double in_eps = slope(epsilons, errors_eps);
        MESSAGE("leapfrog: errors " << errors[0] << ", " << errors[1] << ", " << errors[2] << " at h = 2 pi / 25, 50, 100 (eps = 1e-4): slope "
                                    << in_h << "; " << errors_eps[0] << ", " << errors_eps[1] << ", " << errors_eps[2]
                                    << " at eps = 1e-5, 1e-4, 1e-3 (h = 2 pi / 50): slope " << in_eps);
        CHECK(std::fabs(in_h - 2) < 0.15);
        CHECK(std::fabs(in_eps - 1) < 0.15);
    }
}

TEST_CASE("wisdom_holman: SABA_2's energy error scales as eps h^4 where eps^2 h^2 is small") {
    const table& saba = method("saba_2");
    const double span = 40 * two_pi;
    std::vector<double> hs, errors;
    for (double k : {25.0, 35.0, 50.0}) {
        const double h = two_pi / k;
        hs.push_back(h);
        errors.push_back(energy_errors(two_planets(1e-6), saba, h, std::size_t(std::lround(span / h))).worst);
    }
    const double in_h = slope(hs, errors);
    std::vector<double> epsilons, errors_eps;
    for (double e : {1e-6, 1e-5, 1e-4}) {
        epsilons.push_back(e);
        errors_eps.push_back(energy_errors(two_planets(e), saba, two_pi / 25, 1000).worst);
    }
    const double in_eps = slope(epsilons, errors_eps);
    MESSAGE("saba_2: errors " << errors[0] << ", " << errors[1] << ", " << errors[2] << " at h = 2 pi / 25, 35, 50 (eps = 1e-6): slope "
                              << in_h << "; " << errors_eps[0] << ", " << errors_eps[1] << ", " << errors_eps[2]
                              << " at eps = 1e-6, 1e-5, 1e-4 (h = 2 pi / 25): slope " << in_eps);
    CHECK(std::fabs(in_h - 4) < 0.15);
    CHECK(std::fabs(in_eps - 1) < 0.15);
    // Where eps^2 h^2 dominates (eps = 1e-3, small steps: h^2 < eps), the error
    // falls as h^2 only.
    const planetary_system heavy = two_planets(1e-3);
    const double coarse = energy_errors(heavy, saba, two_pi / 100, 2000).worst;
    const double fine = energy_errors(heavy, saba, two_pi / 200, 4000).worst;
    MESSAGE("saba_2 at eps = 1e-3: " << coarse << " at h = 2 pi / 100, " << fine << " at 2 pi / 200: slope "
                                      << std::log2(coarse / fine));
    CHECK(std::fabs(std::log2(coarse / fine) - 2) < 0.15);
}

TEST_CASE("wisdom_holman: on the outer solar system, far below the T + V leapfrog at the same step") {
    const hamiltonians::outer_solar_system sys{};
    using Fixed = phase_space<double, 18>;
    const planetary_system s = outer_solar_system();
    const double h = 50;  // days; Jupiter's period is 4332 days
    const std::size_t n = 10000, every = 10;
    const long double e0 = energy_ld(s.mass, s.G, s.start);
    auto wh = make_wisdom_holman<Fixed>(sys, method("leapfrog_kdk"));
    auto tv = make_stepper<Fixed>(sys, method("leapfrog_kdk"));
    Fixed a = sys.initial_state(), b = a;
    double worst_wh = 0, worst_tv = 0;
    for (std::size_t k = 0; k < n; k += every) {
        wh.steps(a, h, every);
        tv.steps(b, h, every);
        worst_wh = std::max(worst_wh, double(std::fabs(energy_ld(s.mass, s.G, State(a.q, a.p)) / e0 - 1)));
        worst_tv = std::max(worst_tv, double(std::fabs(energy_ld(s.mass, s.G, State(b.q, b.p)) / e0 - 1)));
    }
    MESSAGE("h = 50 days, 10^4 steps: largest relative energy error " << worst_wh << " (Wisdom-Holman), " << worst_tv
                                                                       << " (T + V leapfrog): ratio " << worst_tv / worst_wh);
    CHECK(worst_tv > 100 * worst_wh);
    CHECK(wh.kepler_drifts() == n);
    // The forces are carried over between calls handed back the state returned.
    CHECK(wh.interaction_evaluations() == n + 1);
}

TEST_CASE("wisdom_holman: the outer solar system's energy error stays bounded over 10^5 steps (13700 years)") {
    const hamiltonians::outer_solar_system sys{};
    using Fixed = phase_space<double, 18>;
    const planetary_system s = outer_solar_system();
    const long double e0 = energy_ld(s.mass, s.G, s.start);
    auto wh = make_wisdom_holman<Fixed>(sys, method("leapfrog_kdk"));
    Fixed x = sys.initial_state();
    const std::size_t n = 100000, every = 10;
    double halves[2] = {0, 0};
    for (std::size_t k = 0; k < n; k += every) {
        wh.steps(x, 50.0, every);
        double& worst = halves[2 * k < n ? 0 : 1];
        worst = std::max(worst, double(std::fabs(energy_ld(s.mass, s.G, State(x.q, x.p)) / e0 - 1)));
    }
    MESSAGE("h = 50 days: largest relative energy error " << halves[0] << " (first 5 10^4 steps), " << halves[1]
                                                          << " (last 5 10^4)");
    CHECK(halves[1] < 1.5 * halves[0]);
}

TEST_CASE("wisdom_holman: steps(n) equals n calls of step() to rounding, counters and the drivers") {
    const planetary_system s = two_planets(1e-3);
    const double h = two_pi / 50;
    for (const char* name : {"leapfrog_kdk", "leapfrog_dkd", "saba_2", "blanes_2013_aba_8_6_4"}) {
        const table& t = method(name);
        wisdom_holman_stepper<State> one(s.mass, s.G, t), many(s.mass, s.G, t);
        State x = s.start, y = s.start;
        for (int k = 0; k < 100; ++k) one.step(x, h);
        many.steps(y, h, 100);
        const double scale = std::max(x.q.cwiseAbs().maxCoeff(), 1.0);
        CHECK(max_difference(x, y) < 1e3 * eps * scale);
        // Joined sub-steps: one fewer kick or drift per step than the table has.
        const auto ops = t.substeps();
        const std::size_t kicks = std::size_t(std::count_if(ops.begin(), ops.end(), [](const substep& o) { return o.kind == substep::kick; }));
        const std::size_t drifts = ops.size() - kicks;
        const bool kick_ends = ops.front().kind == substep::kick && ops.back().kind == substep::kick;
        const bool drift_ends = ops.front().kind == substep::drift && ops.back().kind == substep::drift;
        CHECK(many.interaction_evaluations() == (kick_ends ? 100 * (kicks - 1) + 1 : 100 * kicks));
        CHECK(many.kepler_drifts() == (drift_ends ? 100 * (drifts - 1) + 1 : 100 * drifts));
        // A state changed between calls is converted afresh.
        State z = s.start;
        one.step(z, h);
        wisdom_holman_stepper<State> fresh(s.mass, s.G, t);
        State w = s.start;
        fresh.step(w, h);
        CHECK(max_difference(z, w) == 0);
    }
    // The driver of fixed_step.hpp, backwards and forwards.
    wisdom_holman_stepper<State> wh(s.mass, s.G, method("saba_2"));
    State x = s.start;
    const run_summary r = integrate_until(wh, x, 0.0, 10 * two_pi, h);
    CHECK(r.steps == 500);
    wh.steps(x, -h, 500);
    CHECK(max_difference(x, s.start) < 1e-12);
}

TEST_CASE("wisdom_holman: a corrector on SABA_2 and SBAB_2 removes their eps h^4 terms") {
    const double span = 20 * two_pi;
    for (const std::string name : {"saba_2", "sbab_2"})
        for (int order : {0, 5}) {
            std::vector<double> hs, errors;
            // Corrected, the steps are longer: at 2 pi / 40 it is down to 1.4e-14, near rounding.
            const std::vector<double> per_period = order == 0 ? std::vector<double>{20, 28, 40} : std::vector<double>{14, 20, 28};
            for (double k : per_period) {
                hs.push_back(two_pi / k);
                errors.push_back(
                    energy_errors(two_planets(1e-7), method(name), hs.back(), std::size_t(std::lround(span / hs.back())), {order})
                        .worst);
            }
            const double in_h = slope(hs, errors);
            MESSAGE(name << ", corrector " << order << ", eps = 1e-7: errors " << errors[0] << ", " << errors[1] << ", "
                         << errors[2] << " at h = 2 pi / " << per_period[0] << ", " << per_period[1] << ", " << per_period[2] << ": slope " << in_h);
            CHECK(std::fabs(in_h - (order == 0 ? 4 : 6)) < 0.15);
        }
}

TEST_CASE("wisdom_holman: the corrector takes the leapfrog's energy error from eps h^2 to eps^2 h^2") {
    const double span = 20 * two_pi;
    for (const std::string name : {"leapfrog_kdk", "leapfrog_dkd"}) {
        const table& lf = method(name);
        const auto corrected = [&](const planetary_system& s, int order, double h) {
            return energy_errors(s, lf, h, std::size_t(std::lround(span / h)), {order}).worst;
        };
        SUBCASE("order in h") {
            for (int order : {3, 5}) {
                std::vector<double> hs, errors;
                for (double k : {10.0, 14.0, 20.0}) {
                    hs.push_back(two_pi / k);
                    errors.push_back(corrected(two_planets(1e-7), order, hs.back()));
                }
                const double in_h = slope(hs, errors);
                MESSAGE(name << ", corrector " << order << ", eps = 1e-7: errors " << errors[0] << ", " << errors[1] << ", "
                             << errors[2] << " at h = 2 pi / 10, 14, 20: slope " << in_h << " (theory " << order + 1 << ")");
                CHECK(std::fabs(in_h - (order + 1)) < 0.3);
            }
        }
        SUBCASE("eps^2 in place of eps, at h = 1/20 of the inner period") {
            const double h = two_pi / 20;
            const double plain[2] = {corrected(two_planets(1e-3), 0, h), corrected(two_planets(1e-4), 0, h)};
            const double fixed[2] = {corrected(two_planets(1e-3), 17, h), corrected(two_planets(1e-4), 17, h)};
            MESSAGE(name << ", h = 2 pi / 20: eps = 1e-3, 1e-4: " << plain[0] << ", " << plain[1] << " (ratio "
                         << plain[0] / plain[1] << ") without, " << fixed[0] << ", " << fixed[1] << " (ratio "
                         << fixed[0] / fixed[1] << ") with corrector 17; cut by " << plain[0] / fixed[0] << " at eps = 1e-3");
            CHECK(std::fabs(std::log10(plain[0] / plain[1]) - 1) < 0.15);
            CHECK(std::fabs(std::log10(fixed[0] / fixed[1]) - 2) < 0.15);
            // The cut is c / eps with c the ratio of the two error constants,
            // O(1) by the theory: at least 0.05 / eps.
            CHECK(plain[0] / fixed[0] > 0.05 / 1e-3);
        }
    }
}

TEST_CASE("wisdom_holman: on the outer solar system the corrector's error scales as the planets' masses squared") {
    const double h = 200;  // days: 1/22 of Jupiter's period
    const std::size_t n = 2000, every = 10;
    double errors[2][2] = {};  // [scale 1, 0.1][without, with corrector 11]
    for (int m = 0; m < 2; ++m) {
        const planetary_system s = outer_solar_system(m == 0 ? 1.0 : 0.1);
        const long double e0 = energy_ld(s.mass, s.G, s.start);
        for (int c = 0; c < 2; ++c) {
            wisdom_holman_stepper<State> wh(s.mass, s.G, method("leapfrog_kdk"), {c == 0 ? 0 : 11});
            State x = s.start;
            for (std::size_t k = 0; k < n; k += every) {
                wh.steps(x, h, every);
                errors[m][c] = std::max(errors[m][c], double(std::fabs(energy_ld(s.mass, s.G, x) / e0 - 1)));
            }
        }
    }
    MESSAGE("h = 200 days, 2000 steps: largest relative energy error " << errors[0][0] << " without, " << errors[0][1]
            << " with corrector 11 (cut by " << errors[0][0] / errors[0][1] << "); planet masses / 10: ratios "
            << errors[0][0] / errors[1][0] << " without, " << errors[0][1] / errors[1][1] << " with");
    CHECK(std::fabs(std::log10(errors[0][0] / errors[1][0]) - 1) < 0.15);
    CHECK(std::fabs(std::log10(errors[0][1] / errors[1][1]) - 2) < 0.15);
    CHECK(errors[0][0] / errors[0][1] > 0.05 / 1e-3);  // c / eps as above, Jupiter's eps ~ 1e-3
}

TEST_CASE("wisdom_holman: the corrector in and out: chunks, a new dt, the cost, refused tables") {
    const planetary_system s = two_planets(1e-3);
    const double h = two_pi / 20;
    for (const std::string name : {"leapfrog_kdk", "leapfrog_dkd"}) {
        const table& lf = method(name);
        const int order = 11, K = 5;
        // In and out with no step between: C(C^-1(x)) = x to rounding.
        wisdom_holman_stepper<State> wh(s.mass, s.G, lf, {order});
        State x = s.start;
        wh.steps(x, h, 0);
        CHECK(max_difference(x, s.start) < 100 * eps * 2);
        // One run against ten chunks: the chunks go on from the uncorrected
        // state, so they differ by rounding only (a kick of h against two of
        // h/2 where the chunks meet), grown as n^1.5 eps (see the first test).
        wisdom_holman_stepper<State> one(s.mass, s.G, lf, {order}), chunks(s.mass, s.G, lf, {order});
        State a = s.start, b = s.start;
        const std::size_t n = 1000;
        one.steps(a, h, n);
        for (int k = 0; k < 10; ++k) chunks.steps(b, h, n / 10);
        INFO(name);
        CHECK(max_difference(a, b) < std::pow(double(n), 1.5) * eps * 2);
        // C^-1 and C cost 4K Kepler drifts and 4K - 1 interaction evaluations
        // each (the middle two kicks of C are at one position).
        const bool kick_first = lf.substeps().front().kind == substep::kick;
        CHECK(one.kepler_drifts() == (kick_first ? n : n + 1) + 2 * 4 * K);
        CHECK(one.interaction_evaluations() == (kick_first ? n + 1 : n) + 2 * (4 * K - 1));
        // A new dt re-loads from the state handed in, as a fresh stepper would.
        State c = a;
        one.step(c, h / 2);
        wisdom_holman_stepper<State> fresh(s.mass, s.G, lf, {order});
        State d = a;
        fresh.step(d, h / 2);
        CHECK(max_difference(c, d) == 0);
    }
    // The drivers take chunks of at least steps_per_check() steps, so C, at
    // every return, costs under 1/32 of a run: here one C^-1, 5 C's of 4K = 32
    // drifts each, against 5000 steps.
    wisdom_holman_stepper<State> driven(s.mass, s.G, method("leapfrog_kdk"), {17});
    State y = s.start;
    const std::size_t n = 5000;
    integrate_steps(driven, y, 0.0, h, n);
    MESSAGE("corrector 17, " << n << " steps by integrate_steps: " << driven.kepler_drifts() << " Kepler drifts, chunks of "
                             << driven.steps_per_check());
    CHECK(driven.steps_per_check() > 64);
    CHECK(double(driven.kepler_drifts() - n) < double(n) / 32 + 2 * 4 * 8);
    // The same tables under other names are leapfrogs too.
    CHECK_NOTHROW(wisdom_holman_stepper<State>(s.mass, s.G, method("sbab_1"), {3}));
    CHECK_NOTHROW(wisdom_holman_stepper<State>(s.mass, s.G, method("saba_1"), {3}));
    CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>(s.mass, s.G, method("ruth_3"), {5}),
                         doctest::Contains("symplectic corrector of order 5 with table 'ruth_3' (not symmetric); "
                                           "expected a symmetric table"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>(s.mass, s.G, method("leapfrog_kdk"), {4}),
                         doctest::Contains("order 4; expected 3, 5, 7, 9, 11 or 17"), invalid_argument);
}

// slopes are those of the eps^2 terms.
TEST_CASE("wisdom_holman: the composition kernel takes the corrected error from eps^2 h^2 to eps^2 h^4") {
    const double span = 20 * two_pi;
    const table& dkd = method("leapfrog_dkd");
    const auto worst = [&](const planetary_system& s, wisdom_holman_options o, double h) {
        return energy_errors(s, dkd, h, std::size_t(std::lround(span / h)), o).worst;
    };
    const wisdom_holman_options plain{.corrector_order = 17}, kernel{.corrector_order = 17, .kernel = wh_kernel::composition};
    std::vector<double> hs, with, without;
    for (double k : {20.0, 28.0, 40.0}) {
        hs.push_back(two_pi / k);
        with.push_back(worst(two_planets(1e-3), kernel, hs.back()));
        without.push_back(worst(two_planets(1e-3), plain, hs.back()));
    }
    const double in_h = slope(hs, with), in_h_without = slope(hs, without);
    std::vector<double> epsilons, errors_eps;
    for (double e : {1e-4, 3.16e-4, 1e-3}) {
        epsilons.push_back(e);
        errors_eps.push_back(worst(two_planets(e), kernel, two_pi / 40));
    }
    const double in_eps = slope(epsilons, errors_eps);
    MESSAGE("corrector 17, eps = 1e-3, h = 2 pi / 20, 28, 40: with the composition kernel " << with[0] << ", " << with[1]
            << ", " << with[2] << ": slope " << in_h << " (theory 4); without " << without[0] << ", " << without[1]
            << ", " << without[2] << ": slope " << in_h_without << " (theory 2); cut by " << without[2] / with[2]
            << " at h = 2 pi / 40");
    MESSAGE("corrector 17 and kernel, h = 2 pi / 40: " << errors_eps[0] << ", " << errors_eps[1] << ", " << errors_eps[2]
            << " at eps = 1e-4, 3.16e-4, 1e-3: slope " << in_eps << " (theory 2)");
    CHECK(std::fabs(in_h - 4) < 0.15);
    CHECK(std::fabs(in_h_without - 2) < 0.15);
    CHECK(std::fabs(in_eps - 2) < 0.15);
    // The cut is c / h^2 with c the ratio of the two error constants, O(1):
    // at h^2 = 0.025, at least 10.
    CHECK(without[2] / with[2] > 10);
}

TEST_CASE("wisdom_holman: the composition kernel in and out: first order, steps, cost, refused tables") {
    const double h = two_pi / 20;
    const table& dkd = method("leapfrog_dkd");
    const wisdom_holman_options kernel{.kernel = wh_kernel::composition};
    // To first order in the interaction the kernel is the kick: without a
    // corrector the error is the leapfrog's eps h^2, changed at O(eps^2 h^2),
    // a part in eps of it.
    const planetary_system light = two_planets(1e-4);
    const std::size_t n = 400;
    const double leapfrog = energy_errors(light, dkd, h, n).worst;
    const double with_kernel = energy_errors(light, dkd, h, n, kernel).worst;
    MESSAGE("eps = 1e-4, h = 2 pi / 20, no corrector: " << leapfrog << " (leapfrog), " << with_kernel << " (kernel)");
    CHECK(std::fabs(with_kernel / leapfrog - 1) < 100 * 1e-4);
    // steps(n) against n calls of step(); 5 Kepler drifts and 5 interaction
    // evaluations a step (the first and last drifts joined across steps).
    const planetary_system s = two_planets(1e-3);
    wisdom_holman_stepper<State> one(s.mass, s.G, dkd, kernel), many(s.mass, s.G, dkd, kernel);
    State x = s.start, y = s.start;
    for (int k = 0; k < 100; ++k) one.step(x, h);
    many.steps(y, h, 100);
    CHECK(max_difference(x, y) < 1e3 * eps * std::max(x.q.cwiseAbs().maxCoeff(), 1.0));
    CHECK(many.kepler_drifts() == 5 * 100 + 1);
    CHECK(many.interaction_evaluations() == 5 * 100);
    // Tables other than the drift-kick-drift leapfrog.
    CHECK_NOTHROW(wisdom_holman_stepper<State>(s.mass, s.G, method("saba_1"), kernel));
    CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>(s.mass, s.G, method("leapfrog_kdk"),
                                                      {.corrector_order = 11, .kernel = wh_kernel::composition}),
                         doctest::Contains("kernel composition with table 'leapfrog_kdk'; expected the drift-kick-drift leapfrog"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>(s.mass, s.G, method("saba_2"), kernel),
                         doctest::Contains("kernel composition with table 'saba_2'; expected the drift-kick-drift leapfrog"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>(s.mass, s.G, dkd, {.kernel = wh_kernel(7)}),
                         doctest::Contains("wisdom_holman_stepper: kernel unknown (7); expected kick, composition or lazy"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>(s.mass, s.G, dkd, {.corrector_order = 17, .kernel = wh_kernel::lazy}),
                         doctest::Contains("kernel lazy in democratic_heliocentric coordinates; expected coordinates jacobi"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>(s.mass, s.G, dkd, {.coordinates = wh_coordinates(5)}),
                         doctest::Contains("coordinates unknown (5); expected democratic_heliocentric or jacobi"),
                         invalid_argument);
}

// Jacobi coordinates (Wisdom & Holman 1991): the leapfrog's energy error
// O(eps h^2) as in democratic heliocentric coordinates; with corrector 17 the
// composition kernel and the lazy implementer's kernel (Wisdom, Holman & Touma
// 1996; Rein, Tamayo & Brown 2019) both leave O(eps^2 h^4): slopes 4 in h and
// 2 in eps as in the test above (at h = 2 pi / 20 the slope in h is still
// 4.2: 1/28 to 1/56 of the inner period). With the lazy kernel's displacement of the
// wrong sign the corrected error would double instead (as for the composition
// kernel's weights) and keep slope 2 in h. The lazy kernel costs one Kepler
// drift and two interaction evaluations a step.
TEST_CASE("wisdom_holman: Jacobi coordinates, with the composition and the lazy kernels") {
    const double span = 20 * two_pi;
    const table& dkd = method("leapfrog_dkd");
    const auto worst = [&](const planetary_system& s, const table& t, wisdom_holman_options o, double h) {
        return energy_errors(s, t, h, std::size_t(std::lround(span / h)), o).worst;
    };
    const wh_coordinates jacobi = wh_coordinates::jacobi;
    {
        std::vector<double> hs, errors;
        for (double k : {25.0, 50.0, 100.0}) {
            hs.push_back(two_pi / k);
            errors.push_back(worst(two_planets(1e-4), method("leapfrog_kdk"), {.coordinates = jacobi}, hs.back()));
        }
        const double in_h = slope(hs, errors);
        MESSAGE("Jacobi leapfrog, eps = 1e-4: errors " << errors[0] << ", " << errors[1] << ", " << errors[2]
                                                       << " at h = 2 pi / 25, 50, 100: slope " << in_h << " (theory 2)");
        CHECK(std::fabs(in_h - 2) < 0.15);
    }
    for (const wh_kernel kernel : {wh_kernel::composition, wh_kernel::lazy}) {
        const wisdom_holman_options o{.corrector_order = 17, .kernel = kernel, .coordinates = jacobi};
        std::vector<double> hs, with, epsilons, errors_eps;
        for (double k : {28.0, 40.0, 56.0}) {
            hs.push_back(two_pi / k);
            with.push_back(worst(two_planets(1e-3), dkd, o, hs.back()));
        }
        for (double e : {1e-4, 3.16e-4, 1e-3}) {
            epsilons.push_back(e);
            errors_eps.push_back(worst(two_planets(e), dkd, o, two_pi / 40));
        }
        const double without = worst(two_planets(1e-3), dkd, {.corrector_order = 17, .coordinates = jacobi}, two_pi / 40);
        const double in_h = slope(hs, with), in_eps = slope(epsilons, errors_eps);
        MESSAGE("Jacobi, corrector 17, kernel " << kernel_name(kernel) << ", eps = 1e-3: " << with[0] << ", " << with[1]
                << ", " << with[2] << " at h = 2 pi / 28, 40, 56: slope " << in_h << " (theory 4); at h = 2 pi / 40, "
                << errors_eps[0] << ", " << errors_eps[1] << ", " << errors_eps[2] << " at eps = 1e-4, 3.16e-4, 1e-3: slope "
                << in_eps << " (theory 2); without the kernel " << without);
        CHECK(std::fabs(in_h - 4) < 0.15);
        CHECK(std::fabs(in_eps - 2) < 0.15);
        CHECK(without / with[1] > 10);  // c / h^2 as in the test above, h = 2 pi / 40
    }
    const planetary_system s = two_planets(1e-3);
    wisdom_holman_stepper<State> lazy(s.mass, s.G, dkd, {.kernel = wh_kernel::lazy, .coordinates = jacobi});
    State x = s.start;
    lazy.steps(x, two_pi / 20, 100);
    CHECK(lazy.kepler_drifts() == 100 + 1);
    CHECK(lazy.interaction_evaluations() == 2 * 100);
}

// MEGNO (Cincotta & Simo 2000): the tangent vector the stepper carries is the
// derivative of its own run. Against central differences of two runs from
// starts moved by +-1e-6 of the tangent in the stepper's coordinates (the
// internal state read by to_democratic_heliocentric / to_jacobi): the
// differences' error is O(1e-12) from the step and O(1e-10) from rounding, so
// the two agree to 1e-7 relative where a tangent without the kicks' Jacobian
// would be off by the interaction's share, O(eps) = 1e-3. Without a corrector
// (with one, the output is C of the state the tangent follows).
TEST_CASE("wisdom_holman: the MEGNO tangent is the derivative of the run") {
    const planetary_system s = two_planets(1e-3);
    const double h = two_pi / 20;
    const std::size_t n = 200, N = 2;
    struct variant {
        const char* table;
        wisdom_holman_options options;
    };
    const variant variants[] = {{"leapfrog_kdk", {}},
                                {"saba_2", {}},
                                {"leapfrog_dkd", {.kernel = wh_kernel::lazy, .coordinates = wh_coordinates::jacobi}},
                                {"leapfrog_kdk", {.coordinates = wh_coordinates::jacobi}}};
    for (const variant& c : variants) {
        const bool jacobi = c.options.coordinates == wh_coordinates::jacobi;
        const std::vector<double> inner_mass = jacobi ? jacobi_masses(s.mass) : s.mass;
        const auto internal = [&](const State& x) {  // (Q_i, P_i / m_i) of each planet
            const State y = jacobi ? to_jacobi(x, std::span<const double>(s.mass))
                                   : to_democratic_heliocentric(x, std::span<const double>(s.mass));
            std::vector<double> v;
            for (std::size_t i = 1; i <= N; ++i) {
                for (int k = 0; k < 3; ++k) v.push_back(y.q[Eigen::Index(3 * i) + k]);
                for (int k = 0; k < 3; ++k) v.push_back(y.p[Eigen::Index(3 * i) + k] / inner_mass[i]);
            }
            return v;
        };
        const std::vector<double> tangent{0.3, -0.2, 0.1, 0.01, 0.02, -0.015, -0.1, 0.25, 0.05, -0.02, 0.005, 0.01};
        const auto moved = [&](double e) {  // the start moved by e * tangent in internal coordinates
            State y = jacobi ? to_jacobi(s.start, std::span<const double>(s.mass))
                             : to_democratic_heliocentric(s.start, std::span<const double>(s.mass));
            for (std::size_t i = 1; i <= N; ++i)
                for (int k = 0; k < 3; ++k) {
                    y.q[Eigen::Index(3 * i) + k] += e * tangent[6 * (i - 1) + std::size_t(k)];
                    y.p[Eigen::Index(3 * i) + k] += e * inner_mass[i] * tangent[6 * (i - 1) + 3 + std::size_t(k)];
                }
            State x = jacobi ? from_jacobi(y, std::span<const double>(s.mass))
                             : from_democratic_heliocentric(y, std::span<const double>(s.mass));
            wisdom_holman_stepper<State> wh(s.mass, s.G, method(c.table), c.options);
            wh.steps(x, h, n);
            return internal(x);
        };
        const double e = 1e-6;
        const std::vector<double> plus = moved(e), minus = moved(-e);
        wisdom_holman_stepper<State> tracked(s.mass, s.G, method(c.table), c.options);
        tracked.start_megno(tangent);
        State x = s.start;
        tracked.steps(x, h, n);
        const std::vector<double> carried = tracked.tangent();
        double difference = 0, size = 0;
        for (std::size_t k = 0; k < carried.size(); ++k) {
            const double reference = (plus[k] - minus[k]) / (2 * e);
            difference = std::max(difference, std::fabs(carried[k] * std::exp(tracked.tangent_log_scale()) - reference));
            size = std::max(size, std::fabs(reference));
        }
        MESSAGE(std::string(c.table) << ", " << coordinates_name(c.options.coordinates) << ", kernel " << kernel_name(c.options.kernel)
                        << ": tangent against differences " << difference / size << " relative after " << n
                        << " steps (tangent grown to " << size << ")");
        CHECK(difference / size < 1e-7);
    }
    wisdom_holman_stepper<State> wh(s.mass, s.G, method("leapfrog_kdk"));
    CHECK_THROWS_WITH_AS(wh.start_megno(std::vector<double>(5, 1.0)),
                         doctest::Contains("5 tangent components for 2 planets; expected 6 per planet (dQ, dv), 12"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(wh.start_megno(std::vector<double>(12, 0.0)), doctest::Contains("expected a finite, non-zero"),
                         invalid_argument);
}

// MEGNO's theory (Cincotta, Giordano & Simo 2003): <Y> -> 2 on quasi-periodic
// orbits, as 2 + O(1/t); it grows like lambda t / 2 on chaotic ones. The outer
// solar system over 10^6 days (its Lyapunov time is millions of years): within
// 0.1 of 2, in both coordinates. Two planets of 1e-3 at a = 1 and 1.6 (well
// outside the overlap of first-order resonances, 1.3 eps^(2/7) ~ 0.18 wide,
// Wisdom 1980): within 0.1 of 2; at a = 1 and 1.2, inside it: chaotic, <Y>
// far above 2 (measured 40 after 500 orbits, 47 after 1000) and still growing.
TEST_CASE("wisdom_holman: MEGNO tends to 2 on quasi-periodic orbits and grows on a chaotic one") {
    {
        const planetary_system s = outer_solar_system();
        for (const wh_coordinates coordinates : {wh_coordinates::democratic_heliocentric, wh_coordinates::jacobi}) {
            wisdom_holman_stepper<State> wh(s.mass, s.G, method("leapfrog_kdk"), {.coordinates = coordinates});
            State x = s.start;
            wh.start_megno();
            wh.steps(x, 200, 5000);
            MESSAGE("outer solar system, " << coordinates_name(coordinates) << ", 10^6 days: <Y> = " << wh.megno()
                                           << ", Y = " << wh.megno_y());
            CHECK(std::fabs(wh.megno() - 2) < 0.1);
        }
    }
    const auto two = [](double a2) {
        planetary_system s{{1.0, 1e-3, 1e-3}, 1.0, State(9)};
        s.start.q.setZero(), s.start.p.setZero();
        place(s, 1, 1.0, 0.0, false, 0.0, 0.0);
        place(s, 2, a2, 0.0, false, 3.14159, 0.01);
        s.start.p.segment<3>(0) = -(s.start.p.segment<3>(3) + s.start.p.segment<3>(6));
        return s;
    };
    double megno[2][2] = {};  // [a2 = 1.6, 1.2][after 500, 1000 orbits]
    for (int k = 0; k < 2; ++k) {
        const planetary_system s = two(k == 0 ? 1.6 : 1.2);
        wisdom_holman_stepper<State> wh(s.mass, s.G, method("leapfrog_kdk"));
        State x = s.start;
        wh.start_megno();
        for (int half = 0; half < 2; ++half) {
            wh.steps(x, two_pi / 40, 40 * 500);
            megno[k][half] = wh.megno();
        }
    }
    MESSAGE("two planets of 1e-3: a2 = 1.6: <Y> = " << megno[0][0] << " after 500 orbits, " << megno[0][1]
                                                      << " after 1000; a2 = 1.2: " << megno[1][0] << ", " << megno[1][1]);
    CHECK(std::fabs(megno[0][1] - 2) < 0.1);
    CHECK(megno[1][1] > 10);
    CHECK(megno[1][1] > megno[1][0]);
}

TEST_CASE("wisdom_holman: bad input names the body") {
    const planetary_system s = two_planets(1e-3);
    const table& lf = method("leapfrog_kdk");
    SUBCASE("mass") {
        CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>({1.0, 1e-3, 0.0}, 1.0, lf),
                             doctest::Contains("mass of body 2 = 0"), invalid_argument);
        CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>({1.0, -1e-3, 1e-3}, 1.0, lf),
                             doctest::Contains("mass of body 1 = -0.001"), invalid_argument);
        CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>({1.0, std::nan(""), 1e-3}, 1.0, lf),
                             doctest::Contains("mass of body 1 = nan"), invalid_argument);
        CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>({1.0}, 1.0, lf), doctest::Contains("1 masses"),
                             invalid_argument);
        CHECK_THROWS_WITH_AS(wisdom_holman_stepper<State>({1.0, 1e-3}, 0.0, lf), doctest::Contains("G = 0"),
                             invalid_argument);
        CHECK_THROWS_WITH_AS((wisdom_holman_stepper<phase_space<double, 18>>({1.0, 1e-3}, 1.0, lf)),
                             doctest::Contains("fixed dimension 18"), invalid_argument);
    }
    SUBCASE("a planet at the star, two planets at one place") {
        wisdom_holman_stepper<State> wh(s.mass, s.G, lf);
        State x = s.start;
        x.q.segment<3>(6) = x.q.segment<3>(0);
        CHECK_THROWS_WITH_AS(wh.step(x, 0.1), doctest::Contains("body 2 is at the position of body 0 (the star)"),
                             invalid_argument);
        x = s.start;
        x.q.segment<3>(6) = x.q.segment<3>(3);
        CHECK_THROWS_WITH_AS(wh.step(x, 0.1), doctest::Contains("body 2 is at the position of body 1"),
                             invalid_argument);
    }
    SUBCASE("non-finite state, wrong size, bad step") {
        wisdom_holman_stepper<State> wh(s.mass, s.G, lf);
        State x = s.start;
        x.q[7] = std::numeric_limits<double>::infinity();
        CHECK_THROWS_WITH_AS(wh.step(x, 0.1), doctest::Contains("position y of body 2 = inf"), invalid_argument);
        x = s.start;
        x.p[2] = std::nan("");
        CHECK_THROWS_WITH_AS(wh.step(x, 0.1), doctest::Contains("momentum z of body 0 = nan"), invalid_argument);
        State small(6);
        CHECK_THROWS_WITH_AS(wh.step(small, 0.1), doctest::Contains("expected 3 per body, 9"), invalid_argument);
        x = s.start;
        CHECK_THROWS_WITH_AS(wh.step(x, 0.0), doctest::Contains("dt = 0"), invalid_argument);
        // After a refused state the stepper still works from a good one.
        wh.step(x, 0.1);
        CHECK(is_finite(x));
    }
    SUBCASE("a run that blows up hands back a non-finite state") {
        wisdom_holman_stepper<State> wh(s.mass, s.G, lf);
        State x = s.start;
        x.p.segment<3>(6) *= 1e200;  // planet 2 leaves at 1e200 times its speed
        x.p.segment<3>(0) = -(x.p.segment<3>(3) + x.p.segment<3>(6));
        wh.steps(x, 1e150, 3);
        CHECK(!is_finite(x));
        CHECK_THROWS_WITH_AS(wh.step(x, 0.1), doctest::Contains("expected a finite number"), invalid_argument);
    }
}

TEST_CASE("wisdom_holman: a stepper restored from carried() goes on bit for bit, every variant") {
    const planetary_system s = two_planets(1e-3);
    const double h = two_pi / 40;
    struct variant {
        const char* table;
        wisdom_holman_options options;
    };
    const wh_coordinates jacobi = wh_coordinates::jacobi;
    for (const variant& v : {variant{"leapfrog_kdk", {}}, variant{"saba_2", {.corrector_order = 5}},
                             variant{"leapfrog_dkd", {.corrector_order = 17, .kernel = wh_kernel::composition}},
                             variant{"leapfrog_dkd", {.corrector_order = 17, .kernel = wh_kernel::lazy, .coordinates = jacobi}},
                             variant{"sbab_3", {.coordinates = jacobi}}}) {
        CAPTURE(v.table);
        CAPTURE(v.options.corrector_order);
        const auto observe = [](const State&, double) {};
        wisdom_holman_stepper<State> whole(s.mass, s.G, method(v.table), v.options);
        State a = s.start;
        integrate_steps(whole, a, 0.0, h, 60, observe);
        // Stopped after 23 steps, as a checkpoint would stop it, and resumed by another stepper.
        wisdom_holman_stepper<State> first(s.mass, s.G, method(v.table), v.options);
        State b = s.start;
        integrate_steps(first, b, 0.0, h, 23, observe);
        const std::vector<double> carried = first.carried();
        wisdom_holman_stepper<State> second(s.mass, s.G, method(v.table), v.options);
        second.restore_carried(carried);
        run_options resume;
        resume.first_step = 23;
        integrate_steps(second, b, 0.0, h, 60, observe, resume);
        CHECK(max_difference(a, b) == 0);
        // Without what it carried, the resumed run starts from inertial coordinates: not bit for bit.
        wisdom_holman_stepper<State> third(s.mass, s.G, method(v.table), v.options);
        State c = s.start;
        integrate_steps(third, c, 0.0, h, 23, observe);
        wisdom_holman_stepper<State> forgetful(s.mass, s.G, method(v.table), v.options);
        integrate_steps(forgetful, c, 0.0, h, 60, observe, resume);
        CHECK(max_difference(a, c) > 0);
    }
    // A list that is not this stepper's is refused, the stepper left as it was.
    wisdom_holman_stepper<State> wh(s.mass, s.G, method("leapfrog_kdk"));
    State x = s.start;
    wh.step(x, h);
    std::vector<double> carried = wh.carried();
    carried.pop_back();
    CHECK_THROWS_WITH_AS(wh.restore_carried(carried), doctest::Contains("ends early"), invalid_argument);
    carried = wh.carried();
    carried.push_back(0);
    CHECK_THROWS_WITH_AS(wh.restore_carried(carried), doctest::Contains("is longer than"), invalid_argument);
    CHECK(wh.carried().size() + 1 == carried.size());
}

}  // namespace test_planetary_test_wisdom_holman_stepper
