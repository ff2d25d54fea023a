// The published tables, entry by entry: an entry that fails here does not ship.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>

namespace test_methods_test_catalog_tables {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
// Measured order within 0.15 of the claim (the house threshold).
void check_order(const table& t, order_problem problem, int expected) {
    const order_measurement m = measure_order(t, problem);
    CAPTURE(to_string(problem));
    CAPTURE(m.order);
    CHECK(std::fabs(m.order - expected) <= 0.15);
}
}  // namespace

TEST_CASE("catalog_tables: coefficient sums are 1 and every entry has a citation") {
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        const coefficient ks = std::accumulate(t.kick().begin(), t.kick().end(), coefficient(0));
        const coefficient ds = std::accumulate(t.drift().begin(), t.drift().end(), coefficient(0));
        CHECK(std::fabs(static_cast<double>(ks - 1)) <= 1e-14);
        CHECK(std::fabs(static_cast<double>(ds - 1)) <= 1e-14);
        CHECK(t.order() >= 1);
        CHECK(t.citation().size() > 10);
    }
}

TEST_CASE("catalog_tables: measured order on the pendulum and Kepler (quadratic T)") {
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        check_order(t, order_problem::pendulum, t.order());
        check_order(t, order_problem::kepler, t.order());
    }
}

TEST_CASE("catalog_tables: measured order with non-quadratic kinetic energy") {
    // Methods not flagged RKN-only keep their order for T = sqrt(1 + p^2);
    // the flagged ones must really lose it (else the flag is wrong).
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        if (!t.needs_quadratic_kinetic()) {
            check_order(t, order_problem::nonquadratic_kinetic, t.order());
        } else {
            const double o = measure_order(t, order_problem::nonquadratic_kinetic).order;
            CAPTURE(o);
            CHECK(o < t.order() - 0.5);
        }
    }
}

TEST_CASE("catalog_tables: Blanes, Casas & Escorihuela's order-8 tables read with kick and drift swapped measure 4") {
    // Some public copies of these tables put the paper's a (drift) weights on
    // the kicks; read that way each is an order-4 method.
    for (const char* name : {"blanes_casas_escorihuela_a18", "blanes_casas_escorihuela_b17",
                             "blanes_casas_escorihuela_b19"}) {
        CAPTURE(name);
        const table& t = method(name);
        std::vector<substep> ops = t.substeps();  // the same sequence, each weight given the other role
        for (substep& o : ops) o.kind = o.kind == substep::kick ? substep::drift : substep::kick;
        const table swapped = table::from_substeps("swapped", ops, 4, "", kinetic_requirement::quadratic);
        const double right = measure_order(t, order_problem::pendulum).order;
        const double wrong = measure_order(swapped, order_problem::pendulum).order;
        CAPTURE(right);
        CAPTURE(wrong);
        CHECK(std::fabs(right - 8) <= 0.15);
        CHECK(std::fabs(wrong - 4) <= 0.15);
    }
}

TEST_CASE("catalog_tables: force-gradient methods, order measured, and they need quadratic T") {
    for (const table& t : force_gradient_catalog()) {
        CAPTURE(t.name());
        CHECK(t.has_force_gradient());
        CHECK(t.needs_quadratic_kinetic());
        CHECK(t.family() == "force-gradient");
        CHECK(t.citation().size() > 10);
        check_order(t, order_problem::pendulum, t.order());
        check_order(t, order_problem::kepler, t.order());
        // With T = sqrt(1 + p^2), [V,[T,V]] depends on p and is no kick: the order must drop.
        const double o = measure_order(t, order_problem::nonquadratic_kinetic).order;
        CAPTURE(o);
        CHECK(o < t.order() - 0.5);
    }
    // The sign of the gradient term matters: Chin's 4A with its gradient negated is a second-order method.
    const table& chin = force_gradient_method("chin_4a");
    std::vector<coefficient> flipped = chin.gradient();
    for (coefficient& g : flipped) g = -g;
    const table wrong("chin_4a_flipped", chin.kick(), chin.drift(), flipped, 4, "test");
    CHECK(std::fabs(measure_order(wrong, order_problem::kepler).order - 2) <= 0.15);
    CHECK_THROWS_WITH_AS(force_gradient_method("chin_4b"), doctest::Contains("chin_4a, chin_4a_triple_jump"),
                         invalid_argument);
}


}  // namespace test_methods_test_catalog_tables
