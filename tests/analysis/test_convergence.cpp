#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>

namespace test_analysis_test_convergence {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

TEST_CASE("measure_order sees a kick/drift swap that the harmonic oscillator cannot") {
    // McLachlan-Atela order 4 read with its letters swapped (drifts taken as
    // kicks): the measured order drops to 3 on the pendulum.
    const table& ma4 = method("mclachlan_atela_4");
    const table swapped("swapped", ma4.drift(), ma4.kick());
    CHECK(std::fabs(measure_order(ma4, order_problem::pendulum).order - 4) <= 0.15);
    CHECK(measure_order(swapped, order_problem::pendulum).order < 3.5);
    CHECK(measure_order(swapped, order_problem::kepler).order < 3.5);
}

TEST_CASE("measure_order reports the slopes it read and where it read the order") {
    const order_measurement m = measure_order(method("leapfrog_kdk"), order_problem::kepler);
    CHECK(m.converged);
    CHECK(m.agreeing == 3);
    REQUIRE(m.slopes.size() >= 3);
    for (std::size_t k = 1; k < m.slopes.size(); ++k) {
        CHECK(m.slopes[k].dt == doctest::Approx(m.slopes[k - 1].dt / 2));
        CHECK(m.slopes[k].difference < m.slopes[k - 1].difference);
    }
    CHECK(m.largest_difference >= m.smallest_difference);
    CHECK(m.largest_dt == doctest::Approx(4 * m.smallest_dt));
}

namespace {
// The table as a user types it from a printout: every coefficient to 17 significant digits.
table typed_with_17_digits(const table& t) {
    const auto round = [](const std::vector<coefficient>& c) {
        std::vector<coefficient> out;
        for (coefficient x : c) {
            char text[64];
            std::snprintf(text, sizeof text, "%.17Lg", x);
            out.push_back(std::strtold(text, nullptr));
        }
        return out;
    };
    return table(t.name() + " (17 digits)", round(t.kick()), round(t.drift()), t.order());
}
}  // namespace

TEST_CASE("measure_order reads a 17-digit table's order above the rounding of its coefficients") {
    // Typed with 17 digits, a table meets its order conditions to ~1e-17 only:
    // below ~1e-21 the slope falls to 2. Read naively there, Sofroniou-Spaletta
    // 10 measures 2; the reading must stop above that tail.
    for (const char* name : {"sofroniou_spaletta_10", "kahan_li_10", "mclachlan_ss17", "yoshida_8"}) {
        const table t = typed_with_17_digits(method(name));
        for (auto runnable_system : {order_problem::pendulum, order_problem::kepler}) {
            CAPTURE(name);
            CAPTURE(to_string(runnable_system));
            const order_measurement m = measure_order(t, runnable_system);
            CAPTURE(m.order);
            CHECK(std::fabs(m.order - t.order()) <= 0.15);
            CHECK(m.smallest_difference > 1e-21);
        }
    }
    // The tail itself is there: read all the way down, the last slopes are 2.
    order_options deep;
    deep.floor = 1e-26;
    deep.max_steps = std::size_t(1) << 16;
    const order_measurement raw = measure_order(typed_with_17_digits(method("sofroniou_spaletta_10")),
                                                order_problem::pendulum, deep);
    CHECK(raw.rounding_level > 0);
    CHECK(std::fabs(raw.slopes.back().slope - 2) <= 0.15);
}

}  // namespace test_analysis_test_convergence
