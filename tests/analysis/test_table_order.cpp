// table_order.hpp: the order and the error at equal cost of a table, on the
// library's own problems.
#include <doctest/doctest.h>

#include <cmath>

#include <sympl/methods/catalog.hpp>
#include <sympl/analysis/table_order.hpp>

namespace test_analysis_test_table_order {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

TEST_CASE("table_order: the error at equal cost falls as cost^-p, p the order") {
    // Doubling the force evaluations halves dt, so an order-p method's error
    // falls by 2^p in the asymptotic range.
    for (const char* name : {"leapfrog_kdk", "forest_ruth_4", "blanes_moan_s6", "yoshida_6"}) {
        const table& t = method(name);
        const double e1 = error_at_equal_cost(t, 1200), e2 = error_at_equal_cost(t, 2400);
        CAPTURE(name);
        CAPTURE(std::log2(e1 / e2));
        CHECK(std::fabs(std::log2(e1 / e2) - t.order()) <= 0.15);
    }
}

TEST_CASE("table_order: at equal cost, the optimised methods beat the plain compositions of their order") {
    // Blanes & Moan 2002 designed S6 for a small error constant: at the same
    // cost it is more accurate than the triple jump of the same order, which
    // is what the column in `sympl tables` is for.
    CHECK(error_at_equal_cost(method("blanes_moan_s6")) < 0.1 * error_at_equal_cost(method("yoshida_4")));
    CHECK(error_at_equal_cost(method("blanes_moan_s10")) < error_at_equal_cost(method("yoshida_6")));
}

}  // namespace test_analysis_test_table_order
