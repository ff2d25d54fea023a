#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include <boost/numeric/odeint.hpp>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

namespace test_core_test_table {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
std::string message_of(auto&& build) {
    try {
        build();
    } catch (const error& e) {
        return e.what();
    }
    return "no exception";
}
bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
}  // namespace

TEST_CASE("table: invalid tables are refused with the table, the bad value and what was expected") {
    const auto lengths = message_of([] { table("mine", {0.5, 0.5}, {1}); });
    CHECK(contains(lengths, "table 'mine'"));
    CHECK(contains(lengths, "kick has 2 coefficients and drift has 1"));
    CHECK(contains(message_of([] { table("e", {}, {}); }), "expected equal lengths of at least 1"));
    const auto nan = message_of([] { table("n", {std::numeric_limits<coefficient>::quiet_NaN(), 1}, {1, 0}); });
    CHECK(contains(nan, "kick[0] = nan"));
    CHECK(contains(nan, "expected a finite coefficient"));
    const auto sum = message_of([] { table("s", {0.5, 0.4}, {1, 0}); });
    CHECK(contains(sum, "sum(kick) = 0.9"));
    CHECK(contains(sum, "expected 1 within 1e-14"));
    CHECK(contains(message_of([] { table("d", {1}, {1 + 1e-13L}); }), "sum(drift)"));
    CHECK(contains(message_of([] { from_seed("v", {1, 1}, {1, 0}); }), "expected M = 2"));
}

TEST_CASE("table: canonical form merges neighbours and drops zero sub-steps") {
    // K(1/4) K(1/4) D(1/2) D(0) D(1/2) K(1/2) -> K(1/2) D(1) K(1/2)
    const table t("merged", {0.25L, 0.25L, 0, 0.5L}, {0, 0.5L, 0.5L, 0});
    CHECK(t == method("leapfrog_kdk"));
    CHECK(t.stages() == 2);
    CHECK(t.force_evaluations() == 1);
}

TEST_CASE("table: force evaluations count the reuse of the last force") {
    CHECK(method("leapfrog_kdk").force_evaluations() == 1);
    CHECK(method("leapfrog_dkd").force_evaluations() == 1);
    CHECK(method("euler_cromer").force_evaluations() == 1);
    CHECK(method("forest_ruth_4").force_evaluations() == 3);
    CHECK(method("pefrl_4").force_evaluations() == 4);
    CHECK(method("yoshida_6").force_evaluations() == 7);
    CHECK(method("sofroniou_spaletta_10").force_evaluations() == 35);
    CHECK(method("blanes_moan_srkn11b").force_evaluations() == 11);
}

TEST_CASE("table: linear stability interval (|trace| < 2 on the harmonic oscillator)") {
    // Leapfrog: trace = 2 - h^2, stable for h < 2.
    CHECK(method("leapfrog_kdk").stability_interval() == doctest::Approx(2.0).epsilon(1e-12));
    CHECK(method("euler_cromer").stability_interval() == doctest::Approx(2.0).epsilon(1e-12));
    // Forest-Ruth / triple jump of leapfrog: known limit 1.5734 (McLachlan 1995 reports ~1.57).
    CHECK(method("forest_ruth_4").stability_interval() == doctest::Approx(1.5734).epsilon(1e-3));
    // Composing leapfrog s times with weights 1/s is leapfrog at dt/s: stable up to 2s.
    const table four = compose(method("leapfrog_kdk"), {0.25L, 0.25L, 0.25L, 0.25L});
    CHECK(four.stability_interval() == doctest::Approx(8.0).epsilon(1e-9));
}

TEST_CASE("table: symmetry and the adjoint") {
    CHECK(method("leapfrog_kdk").is_symmetric());
    CHECK_FALSE(method("euler_cromer").is_symmetric());
    CHECK(adjoint(method("euler_cromer")) == method("euler_cromer_dk"));
    const table& ma4 = method("mclachlan_atela_4");
    CHECK_FALSE(ma4.is_symmetric());
    CHECK(adjoint(adjoint(ma4)) == ma4);
    // A method followed by its adjoint (half a step each) is symmetric.
    CHECK(concatenate(method("euler_cromer"), method("euler_cromer_dk")) == method("leapfrog_kdk"));
    CHECK(concatenate(ma4, adjoint(ma4)).is_symmetric());
}

TEST_CASE("table: triple jump and Suzuki composition raise the order by two (measured)") {
    const table lf = method("leapfrog_kdk");
    const table tj = triple_jump(lf);
    CHECK(tj.order() == 4);
    CHECK(tj.force_evaluations() == 3);  // adjacent kicks merged
    for (auto problem : {order_problem::pendulum, order_problem::nonquadratic_kinetic}) {
        CAPTURE(to_string(problem));
        CHECK(std::fabs(measure_order(tj, problem).order - 4) <= 0.15);
        CHECK(std::fabs(measure_order(suzuki_fractal(lf), problem).order - 4) <= 0.15);
        CHECK(std::fabs(measure_order(triple_jump(method("forest_ruth_4")), problem).order - 6) <= 0.15);
        CHECK(std::fabs(measure_order(triple_jump(tj), problem).order - 6) <= 0.15);
    }
    // The triple jump of leapfrog is Forest-Ruth up to the kick/drift reading.
    CHECK(triple_jump(method("leapfrog_dkd")).stages() == method("forest_ruth_4").stages());
    CHECK_THROWS_AS(triple_jump(method("euler_cromer")), invalid_argument);
    // Euler-Cromer then its adjoint over half steps is the leapfrog: symmetric,
    // so order 2 (not the parts' 1), and the triple jump raises it to 4.
    const table ec2 = concatenate(method("euler_cromer"), method("euler_cromer_dk"));
    CHECK(ec2.is_symmetric());
    CHECK(ec2.order() == 2);
    CHECK(std::fabs(measure_order(ec2, order_problem::pendulum).order - 2) <= 0.15);
    CHECK(std::fabs(measure_order(triple_jump(ec2), order_problem::nonquadratic_kinetic).order - 4) <= 0.15);
    // An unsymmetric concatenation keeps the smaller order.
    CHECK(concatenate(method("euler_cromer"), method("euler_cromer_dk"), 0.3L).order() == 1);
    CHECK_THROWS_AS(compose(lf, {0.5L, 0.4L}), invalid_argument);
}

TEST_CASE("table: from_drift_first reproduces Boost.Odeint's symplectic_rkn_sb3a_mclachlan on the pendulum") {
    // Odeint's coefficients a (drift) and b (kick), converted by role, must give
    // Odeint's own trajectory.
    using container = std::array<double, 1>;
    boost::numeric::odeint::symplectic_rkn_sb3a_mclachlan<container> odeint_stepper;
    std::vector<coefficient> drift, kick;
    for (double a : odeint_stepper.coef_a()) drift.push_back(a);
    for (double b : odeint_stepper.coef_b()) kick.push_back(b);
    const table converted = from_drift_first("odeint", drift, kick);
    CHECK(converted.stages() == method("odeint_sb3a_mclachlan").stages());

    using State = phase_space<double, 1>;
    splitting_stepper<hamiltonians::pendulum, State> ours({}, converted);
    State x(Eigen::Matrix<double, 1, 1>(1.3), Eigen::Matrix<double, 1, 1>(0.2));
    std::pair<container, container> y{{1.3}, {0.2}};
    auto dqdt = [](const container& p, container& dq) { dq[0] = p[0]; };
    auto dpdt = [](const container& q, container& dp) { dp[0] = -std::sin(q[0]); };
    for (int i = 0; i < 1000; ++i) {
        ours.step(x, 0.05);
        odeint_stepper.do_step(std::make_pair(dqdt, dpdt), y, 0.0, 0.05);
    }
    CHECK(std::fabs(x.q[0] - y.first[0]) <= 1e-13);
    CHECK(std::fabs(x.p[0] - y.second[0]) <= 1e-13);
    // And the catalog entry (built from the published fractions) agrees too.
    splitting_stepper<hamiltonians::pendulum, State> cat({}, method("odeint_sb3a_mclachlan"));
    State z(Eigen::Matrix<double, 1, 1>(1.3), Eigen::Matrix<double, 1, 1>(0.2));
    for (int i = 0; i < 1000; ++i) cat.step(z, 0.05);
    CHECK(max_difference(x, z) <= 1e-13);
}

namespace {
// Property tests of the table algebra over random tables (doctest loops over
// a seeded generator: every failure names its case).
// A random consistent table of 1..8 stages: coefficients in [-1, 1], the last
// of each role closing its sum to 1.
table random_table(std::mt19937_64& rng, int id) {
    std::uniform_int_distribution<int> stages(1, 8);
    std::uniform_real_distribution<double> c(-1, 1);
    const int m = stages(rng);
    std::vector<coefficient> kick(m), drift(m);
    coefficient sk = 0, sd = 0;
    for (int i = 0; i + 1 < m; ++i) {
        sk += kick[i] = c(rng);
        sd += drift[i] = c(rng);
    }
    kick[m - 1] = 1 - sk;
    drift[m - 1] = 1 - sd;
    return table("random_" + std::to_string(id), kick, drift);
}

bool same_coefficients(const table& a, const table& b, long double tolerance) {
    if (a.kick().size() != b.kick().size()) return false;
    for (std::size_t i = 0; i < a.kick().size(); ++i)
        if (std::fabs(a.kick()[i] - b.kick()[i]) > tolerance || std::fabs(a.drift()[i] - b.drift()[i]) > tolerance)
            return false;
    return true;
}
}  // namespace

TEST_CASE("table algebra: adjoint is an involution and reverses concatenation (500 random tables)") {
    std::mt19937_64 rng(20261122);
    for (int k = 0; k < 500; ++k) {
        const table a = random_table(rng, 3 * k), b = random_table(rng, 3 * k + 1);
        CAPTURE(k);
        CHECK(adjoint(adjoint(a)) == a);
        // (a then b)* = b* then a*, over the complementary fractions.
        CHECK(same_coefficients(adjoint(concatenate(a, b, 0.3L)), concatenate(adjoint(b), adjoint(a), 0.7L), 1e-17L));
        CHECK(concatenate(a, adjoint(a)).is_symmetric());
    }
}

TEST_CASE("table algebra: concatenation is associative (500 random triples)") {
    std::mt19937_64 rng(7);
    for (int k = 0; k < 500; ++k) {
        const table a = random_table(rng, 0), b = random_table(rng, 1), c = random_table(rng, 2);
        CAPTURE(k);
        // Each part a third of the step, grouped either way.
        const table left = concatenate(concatenate(a, b, 0.5L), c, 2.0L / 3);
        const table right = concatenate(a, concatenate(b, c, 0.5L), 1.0L / 3);
        CHECK(same_coefficients(left, right, 1e-17L));
    }
}

TEST_CASE("table algebra: a step of the adjoint at -dt undoes a step of the table (200 random tables, pendulum)") {
    std::mt19937_64 rng(42);
    using State = phase_space<double, 1>;
    for (int k = 0; k < 200; ++k) {
        const table t = random_table(rng, k);
        CAPTURE(k);
        splitting_stepper<hamiltonians::pendulum, State> forward({}, t), back({}, adjoint(t));
        State x(Eigen::Matrix<double, 1, 1>(1.1), Eigen::Matrix<double, 1, 1>(-0.4));
        const State x0 = x;
        forward.step(x, 0.05);
        back.step(x, -0.05);
        // Rounding of about 2M sub-steps of size up to |c| dt ~ 0.05: a few hundred eps at most.
        CHECK(max_difference(x, x0) <= 512 * std::numeric_limits<double>::epsilon());
    }
}

TEST_CASE("table algebra: random invalid tables are refused (500 of each kind)") {
    std::mt19937_64 rng(99);
    std::uniform_real_distribution<double> off(1e-12, 1e-3);
    for (int k = 0; k < 500; ++k) {
        const table t = random_table(rng, k);
        auto kick = t.kick(), drift = t.drift();
        CAPTURE(k);
        auto bad_sum = kick;
        bad_sum.back() += off(rng);
        CHECK_THROWS_AS(table("bad", bad_sum, drift), invalid_table);
        auto bad_value = drift;
        bad_value.front() = (k % 2) ? INFINITY : NAN;
        CHECK_THROWS_AS(table("bad", kick, bad_value), invalid_table);
        auto longer = kick;
        longer.push_back(0);
        CHECK_THROWS_AS(table("bad", longer, drift), invalid_table);
    }
}

TEST_CASE("table: force-gradient coefficients merge, scale by w^3 in compositions, and are validated") {
    const table& chin = force_gradient_method("chin_4a");
    CHECK(chin.gradient().size() == chin.stages());
    CHECK(chin.force_evaluations() == 2);  // the 1/6 kicks joined across steps
    CHECK(chin.force_gradient_evaluations() == 1);
    CHECK(chin.is_symmetric());
    CHECK(adjoint(chin) == chin);
    // Two half steps: each half's gradient scales by (1/2)^3, and the joined
    // kicks add their weights and gradients.
    const table two = compose(chin, {0.5L, 0.5L}, "two_halves", 4);
    coefficient total_gradient = 0;
    for (const substep& o : two.substeps()) total_gradient += o.gradient;
    CHECK(std::fabs(static_cast<double>(total_gradient - 2 * (1.0L / 72) / 8)) <= 1e-18);
    CHECK(two.has_force_gradient());
    CHECK(two.needs_quadratic_kinetic());
    // A kick whose weight is 0 but whose gradient is not stays a sub-step.
    const table pure("pure_gradient", {0.5L, 0, 0.5L}, {0.5L, 0.5L, 0}, {0, 0.01L, 0}, 2, "test");
    CHECK(pure.stages() == 3);
    CHECK(pure.force_evaluations() == 2);
    // Bad gradients name the value.
    CHECK(message_of([] { table("bad", {0.5L, 0.5L}, {1, 0}, {0, NAN}, 2, "test"); }).find("gradient[1] = nan") !=
          std::string::npos);
    CHECK(message_of([] { table("bad", {0.5L, 0.5L}, {1, 0}, {0}, 2, "test"); })
              .find("gradient has 1 coefficients and kick has 2") != std::string::npos);
}

}  // namespace test_core_test_table
