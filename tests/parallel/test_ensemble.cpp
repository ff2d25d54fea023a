// ensemble.hpp: many trajectories, in input order, the same bits for any
// thread count, a blow-up reported where it happened without touching the others.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

#include <sympl/parallel/ensemble.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>
#include <sympl/hamiltonians/pendulum.hpp>
#include <sympl/sympl.hpp>

namespace test_parallel_test_ensemble {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using hh = hamiltonians::henon_heiles;
using state = phase_space<double, 2>;

namespace {
std::vector<state> section_starts(int n, double energy) {
    std::vector<state> s;
    for (int i = 0; i < n; ++i) s.push_back(hh::initial_state(energy, -0.3 + 0.6 * i / n, 0.02 * (i % 5)));
    return s;
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const state& a, const state& b) {
    for (int k = 0; k < 2; ++k)
        if (!same_bits(a.q[k], b.q[k]) || !same_bits(a.p[k], b.p[k])) return false;
    return true;
}
// Largest distance from the origin along the orbit: a per-trajectory reduction.
struct max_radius {
    double r = 0;
    void operator()(const state& x, double) { r = std::max(r, x.q.norm()); }
    double value() const { return r; }
};
}  // namespace

TEST_CASE("ensemble: results are bitwise identical for 1 and 4 threads, and equal to each run alone") {
    const auto starts = section_starts(23, 0.125);  // 23: a partial last batch
    ensemble_options o;
    o.dt = 0.05;
    o.steps = 4000;
    o.sample_every = 4;
    o.megno = true;
    o.threads = 1;
    const auto one = run_ensemble(hh{}, method("blanes_moan_s6"), starts, o, max_radius{});
    o.threads = 4;
    const auto four = run_ensemble(hh{}, method("blanes_moan_s6"), starts, o, max_radius{});
    REQUIRE(one.size() == starts.size());
    for (std::size_t i = 0; i < starts.size(); ++i) {
        CHECK(one[i].stable);
        CHECK(same_bits(one[i].final_state, four[i].final_state));
        CHECK(same_bits(one[i].megno, four[i].megno));
        CHECK(same_bits(one[i].max_energy_error, four[i].max_energy_error));
        CHECK(same_bits(one[i].quantity, four[i].quantity));
        CHECK(one[i].quantity >= starts[i].q.norm());
        CHECK(one[i].max_energy_error < 1e-6);
    }
    // Input order: trajectory i alone, through the same lanes, gives row i.
    for (std::size_t i : {std::size_t(0), std::size_t(9), std::size_t(22)}) {
        const auto alone = run_ensemble(hh{}, method("blanes_moan_s6"), std::vector<state>{starts[i]}, o, max_radius{});
        CHECK(same_bits(alone[0].final_state, one[i].final_state));
        CHECK(same_bits(alone[0].megno, one[i].megno));
    }
}

TEST_CASE("ensemble: a trajectory that blows up is reported with its step, and the others are unaffected") {
    auto starts = section_starts(11, 0.1);
    // Far beyond the saddle (V -> -infinity along q2): escapes and overflows in finite time.
    starts[5] = state(Eigen::Vector2d(0, 3), Eigen::Vector2d(0, 1));
    ensemble_options o;
    o.dt = 0.01;
    o.steps = 3000;
    o.sample_every = 10;
    const auto r = run_ensemble(hh{}, method("leapfrog_kdk"), starts, o);
    CHECK_FALSE(r[5].stable);
    CHECK(r[5].blowup_step > 1);
    CHECK(r[5].blowup_step < 3000);
    CHECK(r[5].blowup_time == doctest::Approx(o.dt * double(r[5].blowup_step - 1)));
    CHECK(r[5].failure.find("step " + std::to_string(r[5].blowup_step)) != std::string::npos);
    CHECK(is_finite(r[5].final_state));  // the last finite state is kept
    CHECK(r[5].final_state.q[1] > 3);
    // The replay found the step: one more step from the kept state is not finite.
    auto last = r[5].final_state;
    make_stepper<state>(hh{}, method("leapfrog_kdk")).step(last, o.dt);
    CHECK_FALSE(is_finite(last));
    std::vector<state> others = starts;
    others.erase(others.begin() + 5);
    const auto without = run_ensemble(hh{}, method("leapfrog_kdk"), others, o);
    for (std::size_t i = 0, j = 0; i < starts.size(); ++i) {
        if (i == 5) continue;
        CHECK(r[i].stable);
        CHECK(same_bits(r[i].final_state, without[j].final_state));
        CHECK(same_bits(r[i].max_energy_error, without[j].max_energy_error));
        ++j;
    }
    SUBCASE("an energy error beyond the divergence limit ends the trajectory there") {
        o.divergence = 10;
        const auto d = run_ensemble(hh{}, method("leapfrog_kdk"), starts, o);
        CHECK_FALSE(d[5].stable);
        CHECK(d[5].blowup_step % o.sample_every == 0);  // found at a sample
        CHECK(d[5].blowup_step <= r[5].blowup_step);
        CHECK(d[5].failure.find("relative energy error") != std::string::npos);
        CHECK(d[4].stable);
    }
}

TEST_CASE("ensemble: bad input is refused with the value and what was expected, before any work") {
    auto starts = section_starts(4, 0.1);
    ensemble_options o;
    o.dt = 0.05;
    o.steps = 10;
    o.dt = -1;
    CHECK_THROWS_WITH_AS(run_ensemble(hh{}, method("leapfrog_kdk"), starts, o), doctest::Contains("dt = -1"), invalid_argument);
    o.dt = 0.05;
    starts[2].p[0] = std::nan("");
    CHECK_THROWS_WITH_AS(run_ensemble(hh{}, method("leapfrog_kdk"), starts, o), doctest::Contains("start 2"), invalid_argument);
    CHECK_THROWS_WITH_AS(run_ensemble_range(hh{}, method("leapfrog_kdk"), starts, 1, 3, o),
                         doctest::Contains("beginning at a multiple of"), invalid_argument);
}

TEST_CASE("ensemble: over a parameter of the Hamiltonian, each trajectory with its own") {
    using P = phase_space<double, 1>;
    const std::vector<double> gravity{0.5, 1.0, 2.0, 4.0};
    const std::vector<P> starts(4, P(Eigen::Matrix<double, 1, 1>(0.1), Eigen::Matrix<double, 1, 1>(0.0)));
    ensemble_options o;
    o.dt = 0.001;
    o.steps = 3000;
    // Small swings: q(t) ~ 0.1 cos(sqrt(g) t); the first passage through 0 is
    // at t = pi/(2 sqrt(g)), which the reduction finds.
    struct first_zero {
        double t = -1;
        double last = 1;
        void operator()(const P& x, double time) {
            if (t < 0 && last > 0 && x.q[0] <= 0) t = time;
            last = x.q[0];
        }
        double value() const { return t; }
    };
    const auto r = run_parameter_ensemble([](double g) { return hamiltonians::pendulum{1, 1, g}; }, gravity,
                                          method("leapfrog_kdk"), starts, o, first_zero{});
    for (std::size_t i = 0; i < gravity.size(); ++i)
        CHECK(r[i].quantity == doctest::Approx(M_PI / (2 * std::sqrt(gravity[i]))).epsilon(0.01));
}

}  // namespace test_parallel_test_ensemble
