// The lane loops compiled a second time for AVX2 (core/wide_lanes.hpp) give
// the bits the loops compiled with the build's flags give:
//   (a) Kepler drifts of 1000 bodies, circular to hyperbolic, over short and
//       long steps (the lanes, their general iterations and the scalar
//       fallback all taken);
//   (b) a Wisdom-Holman run of the outer solar system with a belt of test
//       particles that cross Jupiter's and Saturn's orbits, encounters
//       tracked and particles removed, in both coordinates: planets,
//       particles and both logs the same, bit for bit.
//   (c) the square roots in vector registers, four and two wide, against
//       std::sqrt over every class of double and every tail length.
// On a CPU without AVX2 both runs take the same loops; the test says so.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <vector>

#include <sympl/core/wide_lanes.hpp>
#include <sympl/hamiltonians/outer_solar_system.hpp>
#include <sympl/methods/catalog.hpp>
#include <sympl/planetary/test_particles/encounters.hpp>
#include <sympl/planetary/kepler/kepler_lanes.hpp>
#include <sympl/planetary/wisdom_holman_stepper.hpp>

namespace test_core_test_wide_lanes {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
// Turns the AVX2 loops off for a scope, and back on after it.
struct narrow_lanes {
    narrow_lanes() { use_wide_lanes(false); }
    ~narrow_lanes() { use_wide_lanes(true); }
};

void say_which() {
    if (!wide_lanes())
        MESSAGE("this CPU has no AVX2 (or the build is not for x86): both runs took the same loops");
}

using Arrays = std::array<std::vector<double>, 6>;

// Bodies about GM = 1 at r = 1 with speeds from 0.2 to 1.6 times the
// circular one (eccentric, near-parabolic, hyperbolic), in tilted planes.
Arrays bodies(std::size_t n) {
    Arrays b;
    for (std::size_t i = 0; i < n; ++i) {
        const double phase = 0.37 * double(i), tilt = 0.05 * double(i % 11), speed = 0.2 + 1.4 * double(i) / double(n);
        const double c = std::cos(phase), s = std::sin(phase);
        const double values[6] = {c, s * std::cos(tilt), s * std::sin(tilt), -speed * s, speed * c * std::cos(tilt),
                                  speed * c * std::sin(tilt) + 0.1 * speed};
        for (std::size_t k = 0; k < 6; ++k) b[k].push_back(values[k]);
    }
    return b;
}

void drift(Arrays& b, double h) {
    kepler_drift_all<double>({b[0], b[1], b[2], b[3], b[4], b[5]}, 1.0, h);
}
}  // namespace

TEST_CASE("wide lanes: Kepler drifts in AVX2 are the bits of the build's own loops") {
    say_which();
    for (double h : {0.01, 0.3, 5.0}) {
        CAPTURE(h);
        Arrays wide = bodies(1000), narrow = wide;
        for (int k = 0; k < 20; ++k) drift(wide, h);
        {
            narrow_lanes off;
            for (int k = 0; k < 20; ++k) drift(narrow, h);
        }
        for (std::size_t c = 0; c < 6; ++c) CHECK(wide[c] == narrow[c]);
    }
}

namespace {
// The bits, NaN's included (== would pass no NaN).
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
}  // namespace

TEST_CASE("wide lanes: square roots in vector registers are std::sqrt's, bit for bit") {
    using limits = std::numeric_limits<double>;
    // Zeros, subnormals, the ends of the range, values that round either
    // way, infinities, negatives and NaN (sqrt gives the same default NaN).
    std::vector<double> x = {0.0, -0.0, limits::denorm_min(), 3 * limits::denorm_min(), limits::min(), limits::max(),
                             2.0, 3.0, 1 + limits::epsilon(), 1 - limits::epsilon() / 2, limits::infinity(),
                             -limits::infinity(), -1.0, -limits::denorm_min(), limits::quiet_NaN()};
    for (int i = 1; i <= 200; ++i) x.push_back(std::ldexp(1.0 + 0.0137 * i, (i % 41) - 20));
    for (std::size_t m = 0; m <= x.size(); m += (m < 12 ? 1 : 37)) {  // every tail after 4 and 2 at a time
        CAPTURE(m);
        std::vector<double> wide(m), narrow(m), in_place(x.begin(), x.begin() + std::ptrdiff_t(m));
        if (wide_lanes()) detail::square_roots_wide(x.data(), wide.data(), m);
        else detail::square_roots<false>(x.data(), wide.data(), m);
        detail::square_roots<false>(x.data(), narrow.data(), m);
        detail::square_roots<false>(in_place.data(), in_place.data(), m);
        for (std::size_t i = 0; i < m; ++i) {
            const double expected = std::sqrt(x[i]);
            CHECK(same_bits(wide[i], expected));
            CHECK(same_bits(narrow[i], expected));
            CHECK(same_bits(in_place[i], expected));
        }
    }
}

TEST_CASE("wide lanes: a tracked test-particle run in AVX2 is the bits of the build's own loops") {
    say_which();
    using State = phase_space<double, 18>;
    const hamiltonians::outer_solar_system sys{};
    const State x0 = sys.initial_state();
    // 300 particles on circular orbits from 4 to 12 AU about the Sun.
    test_particle_set<double> belt;
    for (std::size_t i = 0; i < 300; ++i) {
        const double a = 4 + 8 * double(i) / 299, phase = 2.4 * double(i), v = std::sqrt(sys.G * sys.mass[0] / a);
        belt.add({x0.q[0] + a * std::cos(phase), x0.q[1] + a * std::sin(phase), x0.q[2] + 0.01 * a},
                 {-v * std::sin(phase), v * std::cos(phase), 0});
    }
    encounter_options e;
    e.radius = {0.005, 0.35, 0.43, 0.47, 0.77, 0.1};  // AU: the Sun; about the Hill radii
    e.escape_distance = 100;
    e.log_within_hill = 3;
    for (wh_coordinates coordinates : {wh_coordinates::democratic_heliocentric, wh_coordinates::jacobi}) {
        CAPTURE(coordinates_name(coordinates));
        wisdom_holman_options o;
        o.coordinates = coordinates;
        const auto run = [&] {
            auto wh = make_wisdom_holman<State>(sys, method("leapfrog_kdk"), o);
            wh.set_test_particles(belt);
            wh.track_encounters(e);
            State x = x0;
            for (int k = 0; k < 10; ++k) wh.steps(x, 200.0, 200);  // 1100 years
            return std::pair{x, wh};
        };
        const auto [x_wide, wide] = run();
        narrow_lanes off;
        const auto [x_narrow, narrow] = run();
        MESSAGE(coordinates_name(coordinates) << ": " << wide.test_particles().size() << " of 300 left, "
                                              << wide.encounters().encounters().size() << " encounters logged");
        REQUIRE(wide.encounters().losses().size() > 10);  // the belt crosses the planets
        REQUIRE(wide.encounters().encounters().size() > 10);
        CHECK(x_wide.q == x_narrow.q);
        CHECK(x_wide.p == x_narrow.p);
        const auto &p = wide.test_particles(), &q = narrow.test_particles();
        CHECK(p.id == q.id);
        for (std::size_t c = 0; c < 6; ++c) CHECK(*p.parts()[c] == *q.parts()[c]);
        const auto &a = wide.encounters(), &b = narrow.encounters();
        REQUIRE(a.encounters().size() == b.encounters().size());
        for (std::size_t k = 0; k < a.encounters().size(); ++k) {
            CHECK(a.encounters()[k].time == b.encounters()[k].time);
            CHECK(a.encounters()[k].distance == b.encounters()[k].distance);
        }
        REQUIRE(a.losses().size() == b.losses().size());
        for (std::size_t k = 0; k < a.losses().size(); ++k) {
            CHECK(a.losses()[k].particle == b.losses()[k].particle);
            CHECK(a.losses()[k].time == b.losses()[k].time);
        }
    }
}

}  // namespace test_core_test_wide_lanes
