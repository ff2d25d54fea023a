// Test particles of the Wisdom-Holman stepper (test_particles.hpp) on the
// outer solar system of Hairer, Lubich & Wanner:
//   (a) the planets' run is bit-identical with and without test particles, in
//       democratic heliocentric and Jacobi coordinates, with correctors and kernels;
//   (b) a test particle follows the orbit of a planet of mass 1e-30 placed where
//       it is (the same splitting, to rounding), in both coordinates;
//   (c) against an independent accurate run (the whole system with the particle
//       as a body of mass 1e-30, T + V split by Blanes & Moan's S6 at a small
//       step) its error is of the planets' size and falls as h^2 (the leapfrog);
//   (d) MEGNO per particle: about 2 on a quasi-periodic orbit at 2.2 AU,
//       growing for a particle near Jupiter's orbit (Wisdom 1980's chaotic zone);
//   (e) bad input names the particle.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <sympl/core/splitting_stepper.hpp>
#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/methods/catalog.hpp>
#include <sympl/planetary/test_particles/test_particles.hpp>
#include <sympl/planetary/wisdom_holman_stepper.hpp>

namespace test_planetary_test_test_particles {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using State = phase_space<double>;
const hamiltonians::outer_solar_system sys{};

State solar_system() {
    const auto x = sys.initial_state();
    return State(x.q, x.p);
}
std::vector<double> masses() { return std::vector<double>(sys.mass.begin(), sys.mass.end()); }

// A particle on a circular orbit of radius a about the Sun's position in x,
// at angle `phase` in the plane z = 0, inclined by `tilt`, moving with the barycentre.
std::pair<std::array<double, 3>, std::array<double, 3>> circular(const State& x, double a, double phase,
                                                                   double tilt = 0) {
    const double v = std::sqrt(sys.G * sys.mass[0] / a);
    double total = 0;
    std::array<double, 3> vcm{};
    for (int j = 0; j < sys.bodies; ++j) {
        total += sys.mass[std::size_t(j)];
        for (int c = 0; c < 3; ++c) vcm[std::size_t(c)] += x.p[3 * j + c];
    }
    const double c = std::cos(phase), s = std::sin(phase), ct = std::cos(tilt), st = std::sin(tilt);
    return {{x.q[0] + a * c, x.q[1] + a * s * ct, x.q[2] + a * s * st},
            {vcm[0] / total - v * s, vcm[1] / total + v * c * ct, vcm[2] / total + v * c * st}};
}

test_particle_set<double> belt(const State& x, std::size_t n, double a0, double a1) {
    test_particle_set<double> p;
    for (std::size_t i = 0; i < n; ++i) {
        const double a = a0 + (a1 - a0) * double(i) / double(std::max<std::size_t>(1, n - 1));
        const auto rv = circular(x, a, 2.4 * double(i), 0.01 * double(i % 7));
        p.add(rv.first, rv.second);
    }
    return p;
}

// The system with one more body of mass 1e-30 at the particle's place.
State with_body(const State& x, const std::array<double, 3>& r, const std::array<double, 3>& v, double m) {
    State y(x.size() + 3);
    y.q.head(x.size()) = x.q, y.p.head(x.size()) = x.p;
    for (int c = 0; c < 3; ++c) y.q[x.size() + c] = r[std::size_t(c)], y.p[x.size() + c] = m * v[std::size_t(c)];
    return y;
}

// The Newtonian N-body problem of any masses, T + V (for the reference runs).
struct nbody {
    std::vector<double> mass;
    double G;
    template <class V> auto kinetic(const V& p) const {
        typename V::Scalar t(0);
        for (std::size_t i = 0; i < mass.size(); ++i) t += p.template segment<3>(Eigen::Index(3 * i)).squaredNorm() / (2 * mass[i]);
        return t;
    }
    template <class V> auto potential(const V& q) const {
        using std::sqrt;
        typename V::Scalar u(0);
        for (std::size_t i = 0; i < mass.size(); ++i)
            for (std::size_t j = i + 1; j < mass.size(); ++j)
                u -= G * mass[i] * mass[j] /
                     sqrt((q.template segment<3>(Eigen::Index(3 * i)) - q.template segment<3>(Eigen::Index(3 * j))).squaredNorm());
        return u;
    }
    template <class V> void velocity(const V& p, V& v) const {
        for (std::size_t i = 0; i < mass.size(); ++i)
            v.template segment<3>(Eigen::Index(3 * i)) = p.template segment<3>(Eigen::Index(3 * i)) / mass[i];
    }
    template <class V> void force(const V& q, V& f) const {
        using S = typename V::Scalar;
        f.setZero();
        for (std::size_t i = 0; i < mass.size(); ++i)
            for (std::size_t j = i + 1; j < mass.size(); ++j) {
                const Eigen::Matrix<S, 3, 1> d = q.template segment<3>(Eigen::Index(3 * i)) - q.template segment<3>(Eigen::Index(3 * j));
                const S r2 = d.squaredNorm();
                const Eigen::Matrix<S, 3, 1> g = d * (S(G * mass[i] * mass[j]) / (r2 * std::sqrt(r2)));
                f.template segment<3>(Eigen::Index(3 * i)) -= g;
                f.template segment<3>(Eigen::Index(3 * j)) += g;
            }
    }
};

// A table and the stepper's options.
struct variant {
    const char* table;
    wisdom_holman_options options;
};
}  // namespace

TEST_CASE("test particles: the planets' run is bit-identical with and without them") {
    const variant variants[] = {
        {"leapfrog_kdk", {}},
        {"saba_2", {5, wh_kernel::kick, wh_coordinates::democratic_heliocentric}},
        {"leapfrog_dkd", {17, wh_kernel::composition, wh_coordinates::democratic_heliocentric}},
        {"leapfrog_kdk", {0, wh_kernel::kick, wh_coordinates::jacobi}},
        {"leapfrog_dkd", {17, wh_kernel::lazy, wh_coordinates::jacobi}},
        {"saba_2", {0, wh_kernel::kick, wh_coordinates::jacobi}},
    };
    for (const variant& v : variants) {
        const std::string name = v.table;
        CAPTURE(name);
        CAPTURE(coordinates_name(v.options.coordinates));
        CAPTURE(v.options.corrector_order);
        wisdom_holman_stepper<State> plain(masses(), sys.G, method(v.table), v.options);
        wisdom_holman_stepper<State> with(masses(), sys.G, method(v.table), v.options);
        State a = solar_system(), b = a;
        with.set_test_particles(belt(b, 37, 6.0, 9.0));
        for (int chunk = 0; chunk < 40; ++chunk) {
            plain.steps(a, 200, 25);
            with.steps(b, 200, 25);
        }
        CHECK((a.q.array() == b.q.array()).all());
        CHECK((a.p.array() == b.p.array()).all());
        CHECK(with.test_particles().size() == 37);
    }
}

TEST_CASE("test particles: a particle follows a planet of mass 1e-30 placed where it is, to rounding") {
    const variant variants[] = {
        {"leapfrog_kdk", {}},
        {"saba_2", {}},
        {"leapfrog_dkd", {17, wh_kernel::composition, wh_coordinates::democratic_heliocentric}},
        {"leapfrog_kdk", {0, wh_kernel::kick, wh_coordinates::jacobi}},
        {"saba_2", {5, wh_kernel::kick, wh_coordinates::jacobi}},
        {"leapfrog_dkd", {17, wh_kernel::lazy, wh_coordinates::jacobi}},
    };
    for (const variant& va : variants) {
        const std::string t = va.table, coordinates = coordinates_name(va.options.coordinates);
        const int corrector = va.options.corrector_order;
        CAPTURE(t);
        CAPTURE(coordinates);
        CAPTURE(corrector);
        {
            const State x = solar_system();
            const auto rv = circular(x, 7.3, 1.0, 0.05);
            std::vector<double> m = masses();
            m.push_back(1e-30);
            const wisdom_holman_options o = va.options;
            wisdom_holman_stepper<State> tp(masses(), sys.G, method(t), o), planet(m, sys.G, method(t), o);
            State a = x, b = with_body(x, rv.first, rv.second, 1e-30);
            test_particle_set<double> one;
            one.add(rv.first, rv.second);
            tp.set_test_particles(one);
            const std::size_t n = 2000;  // 1100 years of 200 days
            tp.steps(a, 200, n);
            planet.steps(b, 200, n);
            const auto& p = tp.test_particles();
            double worst = 0;
            for (int c = 0; c < 3; ++c) {
                const double r = (c == 0 ? p.x : c == 1 ? p.y : p.z)[0];
                const double v = (c == 0 ? p.vx : c == 1 ? p.vy : p.vz)[0];
                worst = std::max(worst, std::fabs(r - b.q[18 + c]) / 7.3);
                worst = std::max(worst, std::fabs(v - b.p[18 + c] / 1e-30) / std::sqrt(sys.G / 7.3));
            }
            MESSAGE(coordinates << ", " << t << ", corrector " << corrector
                                 << ": particle against planet of mass 1e-30 after " << n << " steps: " << worst
                                 << " relative");
            // Rounding only: a random walk of the phase, n^1.5 eps with room (as
            // the stepper's own Kepler test), and the 1e-30 mass itself.
            CHECK(worst < 1e-9);
        }
    }
}

TEST_CASE("test particles: against an accurate run, the leapfrog's error of the planets' size, falling as h^2") {
    const State x = solar_system();
    const auto rv = circular(x, 7.3, 1.0, 0.05);
    std::vector<double> m = masses();
    m.push_back(1e-30);
    // The reference: T + V by S6 at 2 days (its error below 1e-10 here).
    const double span = 7200;  // days, 20 years
    State ref = with_body(x, rv.first, rv.second, 1e-30);
    auto accurate = make_stepper<State>(nbody{m, sys.G}, method("blanes_moan_s6"));
    accurate.steps(ref, 2, std::size_t(span / 2));
    for (wh_coordinates coordinates : {wh_coordinates::democratic_heliocentric, wh_coordinates::jacobi}) {
        CAPTURE(coordinates_name(coordinates));
        std::vector<double> tp_error, planet_error;
        for (double h : {40.0, 20.0}) {
            wisdom_holman_options o;
            o.coordinates = coordinates;
            wisdom_holman_stepper<State> wh(masses(), sys.G, method("leapfrog_kdk"), o);
            State a = x;
            test_particle_set<double> one;
            one.add(rv.first, rv.second);
            wh.set_test_particles(one);
            wh.steps(a, h, std::size_t(span / h));
            const auto& p = wh.test_particles();
            const double e = std::hypot(p.x[0] - ref.q[18], p.y[0] - ref.q[19], p.z[0] - ref.q[20]);
            double worst_planet = 0;
            for (int j = 1; j < 6; ++j)
                worst_planet = std::max(worst_planet, (a.q.segment<3>(3 * j) - ref.q.segment<3>(3 * j)).norm());
            tp_error.push_back(e), planet_error.push_back(worst_planet);
            MESSAGE(coordinates_name(coordinates) << ", h = " << h << " days: particle off by " << e
                                                  << " AU, the planets by at most " << worst_planet << " AU");
        }
        // The same splitting error for the particle as for the planets
        // (O(eps h^2), eps ~ 1e-3), and second order in h.
        CHECK(tp_error[1] < 10 * planet_error[1]);
        CHECK(tp_error[1] < 1e-4);
        CHECK(tp_error[0] / tp_error[1] > 3);
        CHECK(tp_error[0] / tp_error[1] < 5.5);
    }
}

TEST_CASE("test particles: MEGNO about 2 well inside Jupiter, growing near its orbit") {
    for (wh_coordinates coordinates : {wh_coordinates::democratic_heliocentric, wh_coordinates::jacobi}) {
        CAPTURE(coordinates_name(coordinates));
        wisdom_holman_options o;
        o.coordinates = coordinates;
        wisdom_holman_stepper<State> wh(masses(), sys.G, method("saba_2"), o);
        State x = solar_system();
        test_particle_set<double> p;
        const auto far = circular(x, 2.2, 0.3), near = circular(x, 5.9, 2.0);
        p.add(far.first, far.second);
        p.add(near.first, near.second);
        wh.set_test_particles(p);
        wh.start_test_particle_megno();
        State y = x;
        wh.steps(y, 20, 8000);  // 440 years
        const std::vector<double> megno = wh.test_particle_megno();
        MESSAGE(coordinates_name(coordinates) << ": <Y> = " << megno[0] << " at 2.2 AU, " << megno[1] << " at 5.9 AU");
        CHECK(std::fabs(megno[0] - 2) < 0.3);
        CHECK(megno[1] > 4);
        // The planets' run is the stepper's without particles, joined sub-steps aside.
        wisdom_holman_stepper<State> plain(masses(), sys.G, method("saba_2"), o);
        State z = x;
        for (int k = 0; k < 8000; ++k) plain.step(z, 20);
        CHECK((y.q.array() == z.q.array()).all());
    }
}

TEST_CASE("test particles: a stepper restored from carried() goes on bit for bit, particles and MEGNO included") {
    const variant variants[] = {
        {"leapfrog_kdk", {}},
        {"leapfrog_dkd", {17, wh_kernel::lazy, wh_coordinates::jacobi}},
    };
    for (const variant& v : variants) {
        CAPTURE(v.table);
        wisdom_holman_stepper<State> whole(masses(), sys.G, method(v.table), v.options);
        State a = solar_system();
        whole.set_test_particles(belt(a, 13, 6.0, 9.0));
        whole.start_test_particle_megno();
        whole.steps(a, 200, 60);
        const std::vector<double> carried = whole.carried();
        State b = a;
        whole.steps(a, 200, 60);
        // A fresh stepper of the same masses, table and options, handed the list and the state.
        wisdom_holman_stepper<State> resumed(masses(), sys.G, method(v.table), v.options);
        resumed.restore_carried(carried);
        resumed.steps(b, 200, 60);
        CHECK((a.q.array() == b.q.array()).all());
        CHECK((a.p.array() == b.p.array()).all());
        const auto& pa = whole.test_particles();
        const auto& pb = resumed.test_particles();
        REQUIRE(pa.size() == 13);
        CHECK(pa.id == pb.id);
        CHECK(pa.x == pb.x);
        CHECK(pa.vz == pb.vz);
        const auto ma = whole.test_particle_megno(), mb = resumed.test_particle_megno();
        REQUIRE(ma.size() == mb.size());
        for (std::size_t i = 0; i < ma.size(); ++i) CHECK(ma[i] == mb[i]);
        // A list cut short is refused by name, and the stepper is left as it was.
        std::vector<double> cut(carried.begin(), carried.end() - 3);
        CHECK_THROWS_WITH_AS(resumed.restore_carried(cut), doctest::Contains("wisdom_holman_stepper"), invalid_argument);
        // A damaged particle count (the 13 before ids 0..12) sizes nothing: refused by name.
        std::vector<double> damaged = carried;
        const std::vector<double> count_and_ids = {13, 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12};
        const auto at = std::search(damaged.begin(), damaged.end(), count_and_ids.begin(), count_and_ids.end());
        REQUIRE(at != damaged.end());
        *at = 1e15;
        CHECK_THROWS_WITH_AS(resumed.restore_carried(damaged), doctest::Contains("holds a bad number of test particles"),
                             invalid_argument);
    }
}

TEST_CASE("test particles: bad input names the particle") {
    wisdom_holman_stepper<State> wh(masses(), sys.G, method("leapfrog_kdk"));
    test_particle_set<double> p;
    p.add({7, 0, 0}, {0, 0.006, 0});
    p.add({8, 0, std::nan("")}, {0, 0.006, 0});
    CHECK_THROWS_WITH_AS(wh.set_test_particles(p), doctest::Contains("z of test particle 1 = nan"),
                         invalid_argument);
    p.z.back() = 0;
    p.vx.pop_back();
    CHECK_THROWS_WITH_AS(wh.set_test_particles(p), doctest::Contains("1 values in vx"), invalid_argument);
}

}  // namespace test_planetary_test_test_particles
