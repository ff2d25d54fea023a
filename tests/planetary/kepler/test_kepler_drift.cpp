// The exact Kepler drift (universal variables, Danby 1988 ch. 6.9) against the
// closed-form orbit from orbital elements in long double; its invariants,
// time reversal, the batched drift (kepler_lanes.hpp) against the scalar
// one, a solve that Newton alone cannot finish.
//
// The bound on the drift's error. Rounding the inputs (position, velocity,
// GM, h) by a relative eps/2 each moves the exact result by up to
// eps/2 * kappa * |r(h)|, where
//     kappa = sum_u |u| |d r(h) / d u| / |r(h)|,  u over x, y, z, vx, vy, vz, GM, h,
// is the componentwise relative condition number of the flow (measured here
// by finite differences of a long-double reference). kappa contains what makes
// a Kepler drift hard: the phase error growing with the number of periods
// (d r / d h ~ |v| h), the pericentre passage of an eccentric orbit, the
// cancellation in beta = 2GM/r - v^2 near a parabola. The drift adds the
// rounding of its own representation r(h) = f r0 + g v0: f and g (from
// Stumpff functions good to a few eps, and s solved to rounding) carry a few
// eps relative error (f = 1 - GM G2 / r0 an absolute error of eps), so the
// sum r0 + (f - 1) r0 + g v0 an error of a few eps times
//     c_fg = ((2 + |f|) |r0| + |g| |v0|) / |r(h)|,
// large where a hyperbolic body comes in from far and leaves again (f ~ -cosh
// of the anomaly change) or an eccentric one falls from apocentre to
// pericentre (|r(h)| << |r0|), although kappa may be small there. The bound:
//     |r - r_exact| / |r_exact| <= C eps (kappa + c_fg),   C = 32
// (a few tens of roundings along the way). Measured worst: see the messages.
#include <doctest/doctest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <Eigen/Geometry>

#include <sympl/planetary/kepler/kepler_drift.hpp>
#include <sympl/planetary/kepler/kepler_lanes.hpp>

namespace test_planetary_test_kepler_drift {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using ld = long double;
using V3 = Eigen::Matrix<ld, 3, 1>;
using V3d = Eigen::Vector3d;
constexpr double eps = std::numeric_limits<double>::epsilon();
constexpr ld pi = 3.14159265358979323846264338327950288L;

struct ld_state {
    V3 r, v;
};

// ---- The closed-form orbit from elements (long double) ----------------------

// E - e sin E = M (e < 1) or e sinh F - F = M (e > 1), Newton kept inside a
// bracket of the root.
ld solve_kepler(ld e, ld M) {
    ld lo, hi, E;
    if (e < 1) {
        lo = M - 2, hi = M + 2;
        E = M + 0.85L * e * (std::sin(M) >= 0 ? 1 : -1);
    } else {
        lo = M >= 0 ? 0 : -std::log(2 * std::fabs(M) / e + 2) - 1;
        hi = M >= 0 ? std::log(2 * std::fabs(M) / e + 2) + 1 : 0;
        E = (M >= 0 ? 1 : -1) * std::log(2 * std::fabs(M) / e + 1.8L);
    }
    for (int i = 0; i < 200; ++i) {
        const ld f = e < 1 ? E - e * std::sin(E) - M : e * std::sinh(E) - E - M;
        const ld d = e < 1 ? 1 - e * std::cos(E) : e * std::cosh(E) - 1;
        (f < 0 ? lo : hi) = E;
        ld next = E - f / d;
        if (!(next > lo && next < hi)) next = (lo + hi) / 2;
        if (std::fabs(next - E) <= 2 * std::numeric_limits<ld>::epsilon() * (1 + std::fabs(E)) || next == E)
            return next;
        E = next;
    }
    return E;
}

struct elements {
    ld gm, a, e, inclination, node, periapsis;  // a < 0: hyperbolic
    ld mean_motion() const { return std::sqrt(gm / std::fabs(a * a * a)); }
};

// Position and velocity at mean anomaly M (Danby 1988, sec. 6.3 and 6.5).
ld_state state_at(const elements& o, ld M) {
    ld x, y, vx, vy;
    if (o.e < 1) {
        const ld E = solve_kepler(o.e, std::remainder(M, 2 * pi));
        const ld b = std::sqrt((1 - o.e) * (1 + o.e)), r = o.a * (1 - o.e * std::cos(E)), k = std::sqrt(o.gm * o.a) / r;
        x = o.a * (std::cos(E) - o.e), y = o.a * b * std::sin(E);
        vx = -k * std::sin(E), vy = k * b * std::cos(E);
    } else {
        const ld A = -o.a, F = solve_kepler(o.e, M);
        const ld b = std::sqrt((o.e - 1) * (o.e + 1)), r = A * (o.e * std::cosh(F) - 1), k = std::sqrt(o.gm * A) / r;
        x = A * (o.e - std::cosh(F)), y = A * b * std::sinh(F);
        vx = -k * std::sinh(F), vy = k * b * std::cosh(F);
    }
    const Eigen::Matrix<ld, 3, 3> R = (Eigen::AngleAxis<ld>(o.node, V3::UnitZ()) *
                                       Eigen::AngleAxis<ld>(o.inclination, V3::UnitX()) *
                                       Eigen::AngleAxis<ld>(o.periapsis, V3::UnitZ()))
                                          .toRotationMatrix();
    return {R * V3(x, y, 0), R * V3(vx, vy, 0)};
}

// ---- The same flow from a state: f and g with the eccentric (hyperbolic)
// anomaly difference X (Danby 1988, sec. 6.8), for the condition number -----
//   elliptic:   n h = X - ec sin X + es (1 - cos X),  f = 1 - a (1 - cos X) / r0,   g = h - (X - sin X) / n
//   hyperbolic: n h = ec sinh X + es (cosh X - 1) - X, f = 1 - |a| (cosh X - 1) / r0, g = h - (sinh X - X) / n
V3 flow_position(const ld_state& x, ld gm, ld h) {
    const ld r0 = x.r.norm(), eta = x.r.dot(x.v), a = 1 / (2 / r0 - x.v.squaredNorm() / gm);
    const ld A = std::fabs(a), n = std::sqrt(gm / (A * A * A));
    const ld ec = 1 - r0 / a, es = eta / std::sqrt(gm * A);
    const bool ell = a > 0;
    const ld M = ell ? std::remainder(n * h, 2 * pi) : n * h;
    const auto kepler = [&](ld X) {
        return ell ? X - ec * std::sin(X) + es * (1 - std::cos(X)) - M : ec * std::sinh(X) + es * (std::cosh(X) - 1) - X - M;
    };
    const auto slope = [&](ld X) {
        return ell ? 1 - ec * std::cos(X) + es * std::sin(X) : ec * std::cosh(X) + es * std::sinh(X) - 1;
    };
    ld lo = M - 2, hi = M + 2;  // elliptic: |X - M| <= 2e
    if (!ell) {
        lo = M >= 0 ? 0 : -1, hi = M >= 0 ? 1 : 0;
        while (kepler(hi) < 0) hi *= 2;
        while (kepler(lo) > 0) lo *= 2;
    }
    ld X = (lo + hi) / 2;
    for (int i = 0; i < 400; ++i) {
        const ld f = kepler(X);
        (f < 0 ? lo : hi) = X;
        ld next = X - f / slope(X);
        if (!(next > lo && next < hi)) next = (lo + hi) / 2;
        if (next == X || std::fabs(next - X) <= 2 * std::numeric_limits<ld>::epsilon() * (1 + std::fabs(X))) break;
        X = next;
    }
    const ld t = M / n;  // the reduced time
    const ld f = ell ? 1 - a * (1 - std::cos(X)) / r0 : 1 - A * (std::cosh(X) - 1) / r0;
    const ld g = ell ? t - (X - std::sin(X)) / n : t - (std::sinh(X) - X) / n;
    return f * x.r + g * x.v;
}

// kappa of the comment at the top, by forward differences of relative size 1e-8
// (long double: the differences are good to ~1e-10 relative).
ld condition_number(const ld_state& x, ld gm, ld h) {
    const ld d = 1e-8L;
    const V3 base = flow_position(x, gm, h);
    ld k = 0;
    for (int j = 0; j < 6; ++j) {
        ld_state y = x;
        ld& u = j < 3 ? y.r[j] : y.v[j - 3];
        u *= 1 + d;
        k += (flow_position(y, gm, h) - base).norm() / d;
    }
    k += (flow_position(x, gm * (1 + d), h) - base).norm() / d;
    k += (flow_position(x, gm, h * (1 + d)) - base).norm() / d;
    return k / base.norm();
}

struct sample {
    elements el;
    ld M0, h;
};

// Random elements: 95% elliptic with e in [0, 0.999], 5% hyperbolic with e in
// (1, 5]; random orientation and mean anomaly; h up to 5 periods (5 x 2 pi / n
// when hyperbolic), a third of them short (up to a hundredth of a period, the
// Wisdom-Holman case); GM = 1 or the Sun's in AU and days.
sample random_sample(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(0, 1);
    sample s;
    const bool hyperbolic = u(rng) < 0.05;
    s.el.gm = u(rng) < 0.5 ? 1.0L : 2.95912208286e-4L;
    s.el.e = hyperbolic ? 1 + 4 * (1 - u(rng)) : 0.999 * u(rng);
    const ld size = std::pow(10.0L, ld(-1 + 3 * u(rng)));
    s.el.a = hyperbolic ? -size : size;
    s.el.inclination = pi * u(rng);
    s.el.node = 2 * pi * u(rng);
    s.el.periapsis = 2 * pi * u(rng);
    s.M0 = hyperbolic ? 10 * (2 * u(rng) - 1) : pi * (2 * u(rng) - 1);
    const ld span = (u(rng) < 1.0 / 3 ? 0.01L : 5.0L) * 2 * pi / s.el.mean_motion();
    s.h = span * (2 * u(rng) - 1);
    return s;
}

ld_state rounded(const ld_state& x) {
    return {x.r.cast<double>().cast<ld>(), x.v.cast<double>().cast<ld>()};
}

// The cancellation factors of r1 = f r0 + g v0 and v1 = fdot r0 + gdot v0,
// with f, g, fdot, gdot read off r1 and v1 by cross products with r0 x v0.
struct cancellation {
    ld position, velocity;
};
cancellation cancellation_of(const ld_state& x0, const ld_state& x1) {
    const ld L = x0.r.cross(x0.v).norm(), r0 = x0.r.norm(), v0 = x0.v.norm();
    const ld f = x1.r.cross(x0.v).norm() / L, g = x1.r.cross(x0.r).norm() / L;
    const ld fdot = x1.v.cross(x0.v).norm() / L, gdot = x1.v.cross(x0.r).norm() / L;
    // The drift adds 1 r0 + (f - 1) r0 + g v0 (and likewise for v): terms up to
    // (2 + |f|) r0 and (2 + |gdot|) v0 whose sum is r1 (v1).
    return {((2 + f) * r0 + g * v0) / x1.r.norm(), (fdot * r0 + (2 + gdot) * v0) / x1.v.norm()};
}

ld energy(const ld_state& x, ld gm) { return x.v.squaredNorm() / 2 - gm / x.r.norm(); }

void drift(ld_state& x, double gm, double h) {
    V3d r = x.r.cast<double>(), v = x.v.cast<double>();
    kepler_drift(r, v, gm, h);
    x = {r.cast<ld>(), v.cast<ld>()};
}
}  // namespace

TEST_CASE("kepler_drift: 10^5 random orbits against the closed form, error <= 32 eps (kappa + c_fg)") {
    // 10^5 here (each sample also costs ten long-double Kepler solves for kappa);
    // bench/bench_kepler_drift.cpp drifts 10^6.
    std::mt19937_64 rng(20240530);
    const int n = 100000;
    double worst = 0, worst_error = 0, worst_kappa = 0, largest_kappa = 0, reference_worst = 0;
    for (int i = 0; i < n; ++i) {
        const sample s = random_sample(rng);
        const ld_state exact0 = state_at(s.el, s.M0);
        const ld_state x0 = rounded(exact0);
        const double gm = double(s.el.gm), h = double(s.h);
        const ld_state exact1 = state_at(s.el, s.M0 + s.el.mean_motion() * s.h);
        ld_state x = x0;
        drift(x, gm, h);
        const ld kappa = condition_number(x0, gm, h) + cancellation_of(x0, exact1).position;
        const ld error = (x.r - exact1.r).norm() / exact1.r.norm();
        largest_kappa = std::max(largest_kappa, double(kappa));
        if (double(error / (eps * kappa)) > worst) {
            worst = double(error / (eps * kappa));
            worst_error = double(error);
            worst_kappa = double(kappa);
        }
        // The two references agree (the elements and the f and g forms).
        reference_worst = std::max(reference_worst, double((flow_position(exact0, s.el.gm, s.h) - exact1.r).norm() /
                                                             exact1.r.norm() / kappa));
    }
    MESSAGE("max error / (eps (kappa + c_fg)) = " << worst << " (error " << worst_error << " at kappa + c_fg = "
                                                 << worst_kappa << "); largest kappa + c_fg " << largest_kappa);
    CHECK(worst <= 32);
    CHECK(reference_worst <= 1e-15);  // long-double references: ~100 long-double eps times kappa
}

TEST_CASE("kepler_drift: 10^6 drifts keep energy and angular momentum to a few eps of their scale") {
    // Energy relative to its scale |v|^2/2 + GM/r (E itself cancels near a
    // parabola), angular momentum relative to |r||v|. r(h) and v(h) carry a
    // few eps relative error times their cancellation factors (the comment at
    // the top), so the bound is 16 eps (1 + max(c_r, c_v)).
    // States are made cheaply in double (random direction, distance
    // 10^[-1, 2], speed 0.05..1.9 times the circular one: elliptic, near-parabolic
    // and hyperbolic), h up to 5 x 2 pi sqrt(r^3 / GM): the time is the drift's.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    std::normal_distribution<double> normal(0, 1);
    const int n = 1000000;
    double worst_energy = 0, worst_momentum = 0, drift_seconds = 0;
    for (int i = 0; i < n; ++i) {
        const double gm = u(rng) < 0.5 ? 1.0 : 2.95912208286e-4;
        const V3d dr = V3d(normal(rng), normal(rng), normal(rng)).normalized(), dv = V3d(normal(rng), normal(rng), normal(rng)).normalized();
        const double r = std::pow(10.0, -1 + 3 * u(rng)), speed = std::sqrt(gm / r) * (0.05 + 1.85 * u(rng));
        V3d q = r * dr, p = speed * dv;
        const double h = 5 * 2 * 3.141592653589793 * std::sqrt(r * r * r / gm) * (2 * u(rng) - 1) * (u(rng) < 0.3 ? 0.002 : 1);
        const ld_state x0{q.cast<ld>(), p.cast<ld>()};
        const auto start = std::chrono::steady_clock::now();
        kepler_drift(q, p, gm, h);
        drift_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const ld_state x{q.cast<ld>(), p.cast<ld>()};
        const cancellation c = cancellation_of(x0, x);
        const ld factor = 1 + std::max(c.position, c.velocity);
        const ld scale = std::max(x0.v.squaredNorm() / 2 + gm / x0.r.norm(), x.v.squaredNorm() / 2 + gm / x.r.norm());
        worst_energy = std::max(worst_energy, double(std::fabs(energy(x, gm) - energy(x0, gm)) / (scale * factor * eps)));
        const ld lscale = std::max(x0.r.norm() * x0.v.norm(), x.r.norm() * x.v.norm());
        worst_momentum = std::max(worst_momentum, double((x.r.cross(x.v) - x0.r.cross(x0.v)).norm() / (lscale * factor * eps)));
    }
    MESSAGE("energy error <= " << worst_energy << " eps (1 + c) scale, angular momentum <= " << worst_momentum
                               << " eps (1 + c) |r||v|; " << n << " drifts took " << drift_seconds << " s");
    CHECK(worst_energy <= 16);
    CHECK(worst_momentum <= 16);
}

TEST_CASE("kepler_drift: drift(h) then drift(-h) returns to the start to rounding") {
    // The return error: the forward error (<= C eps kappa_f |r1|, kappa_f =
    // kappa + c_fg of the forward drift) carried back by the backward flow
    // (x kappa_b), plus the backward drift's own C eps kappa_b: C = 32.
    std::mt19937_64 rng(11);
    double worst = 0;
    for (int i = 0; i < 20000; ++i) {
        const sample s = random_sample(rng);
        const ld_state x0 = rounded(state_at(s.el, s.M0));
        const double gm = double(s.el.gm), h = double(s.h);
        ld_state x = x0;
        drift(x, gm, h);
        const ld kappa_f = condition_number(x0, gm, h) + cancellation_of(x0, x).position;
        const ld kappa_b = condition_number(x, gm, -h) + cancellation_of(x, x0).position;
        drift(x, gm, -h);
        const ld error = (x.r - x0.r).norm() / x0.r.norm();
        worst = std::max(worst, double(error / (eps * kappa_b * (1 + kappa_f))));
    }
    MESSAGE("return error <= " << worst << " eps kappa_b (1 + kappa_f)");
    CHECK(worst <= 32);
}

namespace {
// Bodies for the batched drift: random elements, and the hard lanes —
// near-parabolic orbits either side of e = 1 and huge drifts.
struct body_set {
    std::vector<double> x, y, z, vx, vy, vz;
    std::vector<ld_state> start;
    void add(const ld_state& s) {
        const ld_state r = rounded(s);
        start.push_back(r);
        x.push_back(double(r.r[0])), y.push_back(double(r.r[1])), z.push_back(double(r.r[2]));
        vx.push_back(double(r.v[0])), vy.push_back(double(r.v[1])), vz.push_back(double(r.v[2]));
    }
    kepler_bodies<double> view() { return {x, y, z, vx, vy, vz}; }
};
}  // namespace

TEST_CASE("kepler_drift_all: the batched drift equals the scalar drift to rounding, fallback lanes included") {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    const double gm = 1;
    std::size_t total_fallbacks = 0;
    for (const double h : {0.05, -3.0, 700.0, 1e7}) {
        body_set b;
        for (int i = 0; i < 2003; ++i) {  // not a multiple of the lane count: the tail too
            sample s = random_sample(rng);
            s.el.gm = gm;
            if (i % 5 == 1) s.el.e = 1 + (u(rng) < 0.5 ? -1 : 1) * std::pow(10.0L, ld(-10 + 8 * u(rng)));  // near-parabolic
            if (s.el.e > 1 && s.el.a > 0) s.el.a = -s.el.a;
            if (s.el.e < 1 && s.el.a < 0) s.el.a = -s.el.a;
            if (s.el.e > 1) s.M0 = std::min<ld>(s.M0, 5);
            b.add(state_at(s.el, s.M0));
        }
        const std::size_t fallbacks = kepler_drift_all(b.view(), gm, h);
        double worst = 0;
        for (std::size_t i = 0; i < b.start.size(); ++i) {
            ld_state x = b.start[i];
            drift(x, gm, h);
            const V3 rb(b.x[i], b.y[i], b.z[i]), vb(b.vx[i], b.vy[i], b.vz[i]);
            const cancellation c = cancellation_of(b.start[i], x);
            const ld kappa = condition_number(b.start[i], gm, h) + std::max(c.position, c.velocity);
            worst = std::max(worst, double((rb - x.r).norm() / x.r.norm() / (eps * kappa)));
            // Velocities: to rounding of their own size, times the same kappa.
            worst = std::max(worst, double((vb - x.v).norm() / x.v.norm() / (eps * kappa)));
        }
        MESSAGE("h = " << h << ": " << fallbacks << " of " << b.start.size()
                       << " bodies fell back to the scalar solve; max |batched - scalar| = " << worst << " eps (kappa + c)");
        CHECK(worst <= 64);  // two drifts, each within 32 eps (kappa + c)
        total_fallbacks += fallbacks;
    }
    CHECK(total_fallbacks > 0);  // the fallback lanes ran
}

TEST_CASE("kepler_drift: a solve Newton cannot finish alone still ends, and is accurate") {
    // Danby's quartic iteration started 10^12 times too far out on a
    // hyperbolic orbit with e ~ 1e4 and a drift of 1e9 dynamical times: the
    // bracket and bisection must take over.
    const ld_state x0 = rounded(state_at(elements{1, -1e-4L, 1e4L, 0.3L, 1.1L, 2.0L}, 0.5L));
    const double gm = 1, h = 1e9 * 1e-6;  // n = 1e6
    const double r0 = double(x0.r.norm()), v2 = double(x0.v.squaredNorm()), eta0 = double(x0.r.dot(x0.v));
    const auto orbit = detail::make_orbit(r0, eta0, v2, gm, h);
    for (const double guess : {1e12 * h / r0, -5.0, 1e-300, std::numeric_limits<double>::quiet_NaN()}) {
        const auto k = detail::solve_universal(orbit, guess);
        CHECK(std::fabs(k.f) <= k.noise + 4 * eps * std::fabs(h));
    }
    // The whole drift, and two more that the starter serves badly: a radial
    // plunge nearly through the centre, and a near-parabola for 1e12 times its
    // pericentre time.
    struct hard {
        ld_state x;
        double gm, h;
    };
    const std::vector<hard> cases = {
        {x0, gm, h},
        {{V3(1, 0, 0), V3(-1.4142, 1e-9L, 0)}, 1.0, 1.2},
        {rounded(state_at(elements{1, -1e8L, 1 + 1e-8L, 0.2L, 0.1L, 0.4L}, 0)), 1.0, 1e12},
    };
    for (const hard& c : cases) {
        ld_state x = rounded(c.x);
        const auto start = std::chrono::steady_clock::now();
        drift(x, c.gm, c.h);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const V3 exact = flow_position(rounded(c.x), c.gm, c.h);
        const ld kappa = condition_number(rounded(c.x), c.gm, c.h) + cancellation_of(rounded(c.x), {exact, x.v}).position;
        const ld error = (x.r - exact).norm() / exact.norm();
        MESSAGE("hard case: error " << double(error) << " = " << double(error / (eps * kappa)) << " eps (kappa + c_fg) ("
                                    << double(kappa) << "), " << seconds << " s");
        CHECK(error <= 32 * eps * kappa);
        CHECK(seconds < 0.01);
    }
}

namespace {
// Outer-planet-like orbits (e < 0.25, a = 5..40 AU, GM of the Sun in AU and
// days) at a random mean anomaly and orientation, drifted by up to `fraction`
// of Jupiter's period (4333 days) either way: the Wisdom-Holman drift.
struct short_drift {
    ld_state x;
    double gm, h;
};
short_drift outer_planet_drift(std::mt19937_64& rng, double fraction) {
    std::uniform_real_distribution<double> u(0, 1);
    const elements el{2.95912208286e-4L, 5 + 35 * ld(u(rng)), 0.25L * ld(u(rng)), pi * ld(u(rng)),
                      2 * pi * ld(u(rng)), 2 * pi * ld(u(rng))};
    return {rounded(state_at(el, pi * (2 * ld(u(rng)) - 1))), double(el.gm), fraction * 4333 * (2 * u(rng) - 1)};
}

// What the solve sees of a drift, in S.
template <class S>
detail::kepler_orbit<S> orbit_of(const short_drift& c) {
    return detail::make_orbit<S>(S(c.x.r.norm()), S(c.x.r.dot(c.x.v)), S(c.x.v.squaredNorm()), S(c.gm), S(c.h));
}

// The root s of Kepler's equation in long double: Newton (t' = r > 0) on the
// library's residual in long double.
ld root_of(const detail::kepler_orbit<ld>& o) {
    ld s = detail::starting_value(o);
    for (int i = 0; i < 100; ++i) {
        const auto k = detail::residual_at(o, s);
        const ld next = s - k.f / k.r;
        if (next == s) break;
        s = next;
    }
    return s;
}
}  // namespace

TEST_CASE("kepler_drift: the series starter puts short drifts of near-circular orbits close to the root") {
    // What lets one quartic step finish a Wisdom-Holman drift of the outer
    // planets (kepler_drift.hpp, starting_value): from a relative error
    // delta the quartic step leaves ~delta^4. Measured: 1.3e-8, 1.9e-5 and
    // 4.5e-4 (e up to 0.25 here; the outer planets' own orbits, e < 0.05
    // but Pluto's, start within 1e-6 at h = 1/20 of Jupiter's period).
    std::mt19937_64 rng(17);
    const std::pair<double, double> fraction_bound[] = {{1.0 / 80, 1e-7}, {1.0 / 20, 1e-4}, {1.0 / 10, 2e-3}};
    for (const auto& [fraction, bound] : fraction_bound) {
        double worst = 0;
        for (int i = 0; i < 20000; ++i) {
            const short_drift c = outer_planet_drift(rng, fraction);
            const ld root = root_of(orbit_of<ld>(c));
            worst = std::max(worst, double(std::fabs((detail::starting_value(orbit_of<double>(c)) - root) / root)));
        }
        MESSAGE("h up to " << fraction << " of Jupiter's period: starting value within " << worst << " of the root");
        CHECK(worst <= bound);
    }
}

TEST_CASE("kepler_drift: Kepler's equation carried a small step agrees with the series summed there") {
    // residual_shifted (the addition theorems of the G's) against
    // residual_at at s + d, |d| up to 1e-4 |s|, around the root of
    // outer-planet-like drifts and of random ones (elliptic and hyperbolic,
    // |beta s^2| <= 27).
    std::mt19937_64 rng(19);
    std::uniform_real_distribution<double> u(-1, 1);
    double worst = 0, worst_f = 0;
    int shifted = 0;
    for (int i = 0; i < 20000; ++i) {
        short_drift c = outer_planet_drift(rng, 1.0 / 10);
        if (i % 2) {
            const sample r = random_sample(rng);
            c = {rounded(state_at(r.el, r.M0)), double(r.el.gm), double(r.h)};
        }
        const auto o = orbit_of<double>(c);
        if (o.h == 0) continue;
        const double s = double(root_of(orbit_of<ld>(c))), d = s * 1e-4 * u(rng);
        if (!(std::fabs(o.beta) * d * d <= 0x1p-16)) continue;  // outside residual_shifted's range
        // Past (pi + 2)^2 (hyperbolic drifts only, after the period reduction)
        // the series' own rounding grows with the quarterings: not compared.
        if (std::fabs(o.beta) * s * s > 27) continue;
        const auto k = detail::residual_at(o, s), direct = detail::residual_at(o, s + d);
        const auto carried = detail::residual_shifted(o, k, (s + d) - s);
        if (!std::isfinite(direct.f) || !std::isfinite(direct.r)) continue;
        ++shifted;
        // The G's and r against their scale (their values and the terms they sum).
        const double g1 = std::fabs(carried.g1 - direct.g1) / (std::fabs(direct.g1) + std::fabs(s) * std::fabs(direct.c0));
        const double g2 = std::fabs(carried.g2 - direct.g2) / (std::fabs(direct.g2) + std::fabs(s * direct.g1));
        const double r = std::fabs(carried.r - direct.r) /
                         (std::fabs(o.r0 * direct.c0) + std::fabs(o.eta0 * direct.g1) + std::fabs(o.gm * direct.g2));
        worst = std::max({worst, g1 / eps, g2 / eps, r / eps});
        worst_f = std::max(worst_f, std::fabs(carried.f - direct.f) / (k.noise + direct.noise));
    }
    MESSAGE(shifted << " shifts: G1, G2, r within " << worst << " eps of their scale; t within " << worst_f
                    << " of the noise of the two evaluations");
    CHECK(shifted > 10000);
    CHECK(worst <= 16);
    CHECK(worst_f <= 1);
}

namespace {
// The outer planets' semi-major axes (AU) and eccentricities (Jupiter to
// Pluto), at a random orientation and mean anomaly: the batch of a
// Wisdom-Holman step.
constexpr ld planet_a[5] = {5.2026L, 9.5549L, 19.2184L, 30.1104L, 39.5447L};
constexpr ld planet_e[5] = {0.0484L, 0.0555L, 0.0464L, 0.0095L, 0.2490L};
constexpr ld jupiter_period = 4332.6L;  // days

elements random_orientation(std::mt19937_64& rng, ld gm, ld a, ld e) {
    std::uniform_real_distribution<double> u(0, 1);
    return {gm, a, e, pi * ld(u(rng)), 2 * pi * ld(u(rng)), 2 * pi * ld(u(rng))};
}

// |batched - exact| / |exact| for body i of b after drifting by h, in units
// of eps (kappa + c), kappa + c as in the first test.
double error_in_kappa(const body_set& b, std::size_t i, const V3& exact, ld gm, ld h) {
    const V3 rb(b.x[i], b.y[i], b.z[i]);
    const ld kappa = condition_number(b.start[i], double(gm), double(h)) + cancellation_of(b.start[i], {exact, V3::Zero()}).position;
    return double((rb - exact).norm() / exact.norm() / (eps * kappa));
}

// The short-drift lanes run on b as kepler_drift_all runs them for 5 or 6
// bodies (one group of 6, a 5th body's lane padded with body 0).
detail::lane_bodies<double, 6> short_lanes(const body_set& b, double gm, double h, bool (&done)[6]) {
    detail::lane_bodies<double, 6> lanes;
    for (int l = 0; l < 6; ++l) {
        const std::size_t i = std::size_t(l) < b.x.size() ? std::size_t(l) : 0;
        lanes.x[l] = b.x[i], lanes.y[l] = b.y[i], lanes.z[l] = b.z[i];
        lanes.vx[l] = b.vx[i], lanes.vy[l] = b.vy[i], lanes.vz[l] = b.vz[i], lanes.gm[l] = gm;
    }
    detail::short_drift_lanes<double, 6>(lanes, h, done);
    return lanes;
}
}  // namespace

TEST_CASE("kepler_drift_all: the 5 outer planets in one batch take the short-drift lanes and equal the scalar drift") {
    // Both solves stop within 4 eps |s| of the root (solve_universal's test,
    // which the lanes apply too) and form f and g with a few roundings each
    // (the lanes multiply by 1/r0 and 1/r where the scalar solve divides): the
    // two drifts differ by a few eps (kappa + c), bound 8. The lanes are
    // checked directly too: at h up to a tenth of Jupiter's period every
    // planet takes the short-drift path (its starter is then within 2e-3 of
    // the root, which one quartic step brings to rounding).
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u(0, 1);
    const ld gm = 2.95912208286e-4L;
    for (const ld fraction : {1.0L / 20, 1.0L / 10, 1.0L / 5}) {
        double worst = 0;
        int short_path = 0, total = 0;
        for (int trial = 0; trial < 2000; ++trial) {
            body_set b;
            for (int k = 0; k < 5; ++k)
                b.add(state_at(random_orientation(rng, gm, planet_a[k], planet_e[k]), pi * (2 * ld(u(rng)) - 1)));
            const double h = double(fraction * jupiter_period * (u(rng) < 0.5 ? -1 : 1));
            bool done[6];
            const auto lanes = short_lanes(b, double(gm), h, done);
            for (int l = 0; l < 5; ++l) short_path += done[l] ? 1 : 0;
            total += 5;
            kepler_drift_all(b.view(), double(gm), h);
            for (std::size_t i = 0; i < 5; ++i) {
                ld_state x = b.start[i];
                drift(x, double(gm), h);
                if (done[i]) {  // the lanes' own result is what kepler_drift_all kept
                    CHECK(lanes.x[i] == b.x[i]);
                    CHECK(lanes.vz[i] == b.vz[i]);
                }
                worst = std::max(worst, error_in_kappa(b, i, x.r, gm, h));
            }
        }
        MESSAGE("h = P_Jupiter * " << double(fraction) << ": " << short_path << " of " << total
                                   << " drifts took the short-drift lanes; max |batched - scalar| = " << worst
                                   << " eps (kappa + c)");
        CHECK(worst <= 8);
        if (fraction <= 1.0L / 10) CHECK(short_path == total);
    }
}

TEST_CASE("kepler_drift_all: lanes the short-drift path cannot take, beside ones it takes, are still exact") {
    // A batch of 6 (one lane group) and one of 5 with a single hard body
    // (which goes to the scalar solve directly): outer planets, and a
    // hyperbolic body, a nearly radial e = 0.999 orbit, and one of 11-day
    // period drifted for 20 periods (the period reduction). Every body against
    // the closed form, with the first test's bound 32 eps (kappa + c_fg).
    std::mt19937_64 rng(29);
    std::uniform_real_distribution<double> u(0, 1);
    const ld gm = 2.95912208286e-4L, h = jupiter_period / 20;
    struct body {
        elements el;
        ld M0;
        bool hard;
    };
    double worst = 0;
    int hard_left = 0, hard_total = 0, easy_taken = 0, easy_total = 0;
    for (int trial = 0; trial < 300; ++trial) {
        std::vector<body> six = {
            {random_orientation(rng, gm, planet_a[0], planet_e[0]), pi * (2 * ld(u(rng)) - 1), false},
            {random_orientation(rng, gm, -2, 3), 4 * (2 * ld(u(rng)) - 1), true},
            {random_orientation(rng, gm, planet_a[1], planet_e[1]), pi * (2 * ld(u(rng)) - 1), false},
            {random_orientation(rng, gm, 10, 0.999L), 0.05L * (2 * ld(u(rng)) - 1), true},
            {random_orientation(rng, gm, 0.1L, 0.2L), pi * (2 * ld(u(rng)) - 1), true},
            {random_orientation(rng, gm, planet_a[3], planet_e[3]), pi * (2 * ld(u(rng)) - 1), false},
        };
        std::vector<body> five = {six[0], six[2], six[5], six[1 + 2 * (trial % 2)], six[0]};
        five[4] = {random_orientation(rng, gm, planet_a[2], planet_e[2]), pi * (2 * ld(u(rng)) - 1), false};
        for (const std::vector<body>* batch : {&six, &five}) {
            body_set b;
            for (const body& x : *batch) b.add(state_at(x.el, x.M0));
            bool done[6];
            short_lanes(b, double(gm), double(h), done);  // which lanes the short-drift path takes
            kepler_drift_all(b.view(), double(gm), double(h));
            for (std::size_t i = 0; i < batch->size(); ++i) {
                const body& x = (*batch)[i];
                (x.hard ? hard_total : easy_total) += 1;
                if (x.hard) hard_left += done[i] ? 0 : 1;
                else easy_taken += done[i] ? 1 : 0;
                const V3 exact = state_at(x.el, x.M0 + x.el.mean_motion() * h).r;
                worst = std::max(worst, error_in_kappa(b, i, exact, gm, h));
            }
        }
    }
    MESSAGE("short-drift lanes left " << hard_left << " of " << hard_total << " hard bodies and took " << easy_taken
                                      << " of " << easy_total << " planets; max error " << worst << " eps (kappa + c_fg)");
    CHECK(hard_left == hard_total);  // the hard lanes really were left to the other solves
    CHECK(easy_taken == easy_total);
    CHECK(worst <= 32);
}

TEST_CASE("kepler_drift: a hyperbolic flyby from far out to far out in one drift is exact to 32 eps n kappa") {
    // Near-radial hyperbolas (pericentre q, r0 from 30 to 300 q / (e - 1))
    // drifted through pericentre out to about three times as far, in one
    // drift, scalar and batched. In one f and g update the terms of r(h)
    // grow as cosh of the anomaly change (F of 10 to 12 here) and their sum
    // lost up to 7 digits (q = 1e-3, e = 1.5, r from 44.7 to 134: 1.4e-7
    // relative, h off by 0.8%; here 5430 eps kappa, h to 2.7e5 eps |r||v|).
    // In n pieces of anomaly change <= 2 (drift_in_pieces) each piece adds
    // the rounding of one drift with no large c_fg, carried on by the flow:
    // the bound is C eps n kappa, C = 32, and r x v keeps h to 16 eps |r||v|
    // (its rounding as a state).
    std::mt19937_64 rng(31);
    std::uniform_real_distribution<double> u(0, 1);
    double worst = 0, worst_h = 0;
    int pieces = 0;
    for (int trial = 0; trial < 200; ++trial) {
        const ld e = 1 + ld(0.01 + 2.0 * u(rng)), q = std::pow(10.0L, -3 + 2 * ld(u(rng)));
        const ld r_start = q / (e - 1) * std::pow(10.0L, 1.5L + ld(u(rng)));
        elements el = random_orientation(rng, 1, -q / (e - 1), e);
        const ld F0 = -std::acosh((1 + r_start / -el.a) / e), M0 = e * std::sinh(F0) - F0, M1 = -3 * M0;
        const ld h = (M1 - M0) / el.mean_motion();
        const ld_state x0 = rounded(state_at(el, M0));
        const ld_state exact = state_at(el, M1);
        const ld F1 = solve_kepler(e, M1);  // -beta s^2 is the anomaly change squared
        pieces += (F1 - F0) * (F1 - F0) > 36 ? 1 : 0;
        const ld kappa = condition_number(x0, 1, h) * std::ceil((F1 - F0) / 2);
        body_set b;
        b.add(x0), b.add(x0);
        kepler_drift_all(b.view(), 1.0, double(h));
        ld_state x = x0;
        drift(x, 1, double(h));
        for (const ld_state& y : {x, ld_state{V3(b.x[1], b.y[1], b.z[1]), V3(b.vx[1], b.vy[1], b.vz[1])}}) {
            worst = std::max(worst, double((y.r - exact.r).norm() / exact.r.norm() / (eps * kappa)));
            worst_h = std::max(worst_h, double((y.r.cross(y.v) - x0.r.cross(x0.v)).norm() /
                                               (eps * y.r.norm() * y.v.norm())));
        }
    }
    MESSAGE("flybys: error <= " << worst << " eps n kappa; |h1 - h0| <= " << worst_h << " eps |r||v| (" << pieces
                                << " long drifts)");
    CHECK(pieces == 200);  // every anomaly change is past 6: long drifts
    CHECK(worst <= 32);
    CHECK(worst_h <= 16);
}

TEST_CASE("kepler_drift: flybys from very far out, in double and float, keep E and h to rounding per piece") {
    // Started at |F0| = 12..25 (float: 6..10), Kepler's equation of the
    // whole drift itself cancels by about e^(2 |F0|), so its root is no guide
    // to the pieces (it put a body at |r| = 2e55 instead of 4.4e5, found by
    // review): the pieces stop on time. Each of the n pieces adds a few
    // roundings (C = 16) of |r||v| to h and of |v|^2 / 2 + GM / r to E, the
    // latter at a piece boundary, at least one unit of anomaly from the
    // pericentre, up to 2 / (e cosh 1 - 1) < 4 times the ends' scale; the
    // impact parameter b = |r0 x v0| / |v0| is held to a relative eps r0 / b
    // (r0 / b from 1e4 to 1e11), and the distance reached with it: |r(h)| to
    // C n eps r0 / b.
    std::mt19937_64 rng(37);
    std::uniform_real_distribution<double> u(0, 1);
    const auto trial = [&](auto zero, double f_low, double f_high, double& worst_e, double& worst_h, double& worst_r) {
        using S = decltype(zero);
        using V = Eigen::Matrix<S, 3, 1>;
        const ld e = 1 + ld(0.01 + 2.0 * u(rng)), q = std::pow(10.0L, -3 + 2 * ld(u(rng)));
        const elements el = random_orientation(rng, 1, -q / (e - 1), e);
        const ld F0 = -ld(f_low + (f_high - f_low) * u(rng)), M0 = e * std::sinh(F0) - F0, M1 = -1.2L * M0;
        const ld_state x0 = state_at(el, M0), exact = state_at(el, M1);
        V r = x0.r.cast<S>(), v = x0.v.cast<S>();
        const ld_state start{r.template cast<ld>(), v.template cast<ld>()};
        kepler_drift(r, v, S(1), S((M1 - M0) / el.mean_motion()));
        const ld_state end{r.template cast<ld>(), v.template cast<ld>()};
        const ld n = std::ceil((solve_kepler(e, M1) - F0) / 2), eps_s = std::numeric_limits<S>::epsilon();
        const auto energy_scale = [](const ld_state& x) { return x.v.squaredNorm() / 2 + 1 / x.r.norm(); };
        worst_e = std::max(worst_e, double(std::fabs(energy(end, 1) - energy(start, 1)) /
                                           (n * eps_s * std::max(energy_scale(start), energy_scale(end)))));
        worst_h = std::max(worst_h, double((end.r.cross(end.v) - start.r.cross(start.v)).norm() /
                                           (n * eps_s * std::max(end.r.norm() * end.v.norm(), start.r.norm() * start.v.norm()))));
        const ld sensitivity = start.r.norm() * start.v.norm() / start.r.cross(start.v).norm();
        worst_r = std::max(worst_r, double(std::fabs(end.r.norm() / exact.r.norm() - 1) / (n * eps_s * sensitivity)));
    };
    double e_double = 0, h_double = 0, r_double = 0, e_float = 0, h_float = 0, r_float = 0;
    for (int i = 0; i < 100; ++i) trial(0.0, 12, 25, e_double, h_double, r_double);
    for (int i = 0; i < 100; ++i) trial(0.0f, 6, 10, e_float, h_float, r_float);
    MESSAGE("double: |E1 - E0| <= " << e_double << " n eps scale, |h1 - h0| <= " << h_double << " n eps |r||v|, |r| to "
                                    << r_double << " n eps r0 / b; float: " << e_float << ", " << h_float << ", " << r_float);
    CHECK(e_double <= 64);
    CHECK(h_double <= 16);
    CHECK(r_double <= 16);
    CHECK(e_float <= 64);
    CHECK(h_float <= 16);
    CHECK(r_float <= 16);
    // A drift that ends beyond sqrt(max), where |r| no longer squares (a = -1,
    // e = 2, F from -5 to 356 and 700; float to 45): the pieces stop short of
    // it and one solve goes on (the review found these refused as overflowing).
    for (const ld f1 : {356.0L, 400.0L, 700.0L}) {
        const elements el{1, -1, 2, 0.3L, 1.1L, 2.0L};
        const ld M0 = 2 * std::sinh(-5.0L) + 5, M1 = 2 * std::sinh(f1) - f1;
        const ld_state x0 = rounded(state_at(el, M0));
        const ld exact = std::fabs(el.a) * (el.e * std::cosh(f1) - 1);
        ld_state x = x0;
        drift(x, 1, double((M1 - M0) / el.mean_motion()));
        CAPTURE(double(f1));
        CHECK(double(std::fabs(x.r.norm() / exact - 1)) <= 1e-9);
    }
    const ld_state start = state_at({1, -1, 2, 0, 0, 0}, 2 * std::sinh(-5.0L) + 5);
    Eigen::Vector3f rf = start.r.cast<float>(), vf = start.v.cast<float>();
    kepler_drift(rf, vf, 1.0f, float((2 * std::sinh(45.0L) - 45) - (2 * std::sinh(-5.0L) + 5)));
    CHECK(double(std::fabs(rf.cast<ld>().norm() / (2 * std::cosh(45.0L) - 1) - 1)) <= 1e-3);
}

TEST_CASE("kepler_drift: bad input names the value and the body") {
    V3d r(1, 0, 0), v(0, 1, 0), zero = V3d::Zero();
    CHECK_THROWS_WITH_AS(kepler_drift(zero, v, 1.0, 0.1), doctest::Contains("|r| = 0"), invalid_argument);
    CHECK_THROWS_WITH_AS(kepler_drift(r, v, -1.0, 0.1), doctest::Contains("GM = -1"), invalid_argument);
    CHECK_THROWS_WITH_AS(kepler_drift(r, v, 0.0, 0.1), doctest::Contains("GM = 0"), invalid_argument);
    CHECK_THROWS_WITH_AS(kepler_drift(r, v, 1.0, std::numeric_limits<double>::infinity()), doctest::Contains("h = inf"),
                         invalid_argument);
    V3d bad_v(0, std::nan(""), 0);
    CHECK_THROWS_WITH_AS(kepler_drift(r, bad_v, 1.0, 0.1), doctest::Contains("velocity y = nan"), invalid_argument);

    body_set b;
    for (int i = 0; i < 12; ++i) b.add({V3(1 + i, 0, 0), V3(0, 1, 0)});
    b.x[9] = 0;  // body 9 at the central mass
    CHECK_THROWS_WITH_AS(kepler_drift_all(b.view(), 1.0, 0.1), doctest::Contains("|r| of body 9 = 0"), invalid_argument);
    b.x[9] = 10;
    b.vz[3] = std::numeric_limits<double>::infinity();
    CHECK_THROWS_WITH_AS(kepler_drift_all(b.view(), 1.0, 0.1), doctest::Contains("velocity z of body 3 = inf"),
                         invalid_argument);
    b.vz[3] = 0;
    std::vector<double> gms(12, 1.0);
    gms[5] = -2;
    CHECK_THROWS_WITH_AS(kepler_drift_all(b.view(), std::span<const double>(gms), 0.1), doctest::Contains("GM = -2"),
                         invalid_argument);
    gms.pop_back();
    CHECK_THROWS_WITH_AS(kepler_drift_all(b.view(), std::span<const double>(gms), 0.1),
                         doctest::Contains("11 values of GM for 12 bodies"), invalid_argument);
    b.y.pop_back();
    CHECK_THROWS_WITH_AS(kepler_drift_all(b.view(), 1.0, 0.1), doctest::Contains("11 values in y"), invalid_argument);
}

}  // namespace test_planetary_test_kepler_drift
