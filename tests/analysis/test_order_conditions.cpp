// order_conditions.hpp: the modified vector field of a table and its order
// conditions, checked against known algebra and every catalog entry.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include <sympl/methods/catalog.hpp>
#include <sympl/analysis/order_conditions.hpp>

namespace test_analysis_test_order_conditions {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

TEST_CASE("order_conditions: the free Lie algebra and the Nystrom ideal have the known dimensions") {
    // Witt's formula gives 2, 1, 2, 3, 6, 9, 18 for the free Lie algebra on two
    // letters; the RKN conditions number 2, 1, 2, 2, 4, 5, 10 (Blanes & Moan
    // 2002, table 1), so the ideal of [V,[V,[V,T]]] has 0, 0, 0, 1, 2, 4, 8.
    const std::size_t lie[] = {2, 1, 2, 3, 6, 9, 18}, nystrom[] = {2, 1, 2, 2, 4, 5, 10};
    for (int k = 1; k <= 7; ++k) {
        CAPTURE(k);
        const std::size_t l = detail::lie_basis(k).size(), ideal = detail::nystrom_ideal(k).size();
        CHECK(l == lie[k - 1]);
        CHECK(l - ideal == nystrom[k - 1]);
    }
}

TEST_CASE("order_conditions: log of exp(x) exp(y) is the Baker-Campbell-Hausdorff series") {
    // log(e^T e^V) = T + V + [T,V]/2 + ([T,[T,V]] - [V,[T,V]])/12 + ...
    const word_series field = modified_field({{substep::drift, 1}, {substep::kick, 1}}, 3);
    const auto t = detail::letter(false), v = detail::letter(true);
    const auto tv = detail::bracket(t, 1, v, 1), ttv = detail::bracket(t, 1, tv, 2), vtv = detail::bracket(v, 1, tv, 2);
    for (std::size_t w = 0; w < 4; ++w) CHECK(std::fabs(field.part[2][w] - tv[w] / 2) < 1e-18L);
    for (std::size_t w = 0; w < 8; ++w) CHECK(std::fabs(field.part[3][w] - (ttv[w] - vtv[w]) / 12) < 1e-18L);
}

TEST_CASE("order_conditions: every catalog table has exactly its declared order, and RKN tables only for quadratic T") {
    // The conditions of degrees 1..p hold to rounding (1e-13: some tables are
    // published with 16 digits) and those of degree p+1 fail by far more.
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        const int p = t.order(), top = std::min(p + 1, 11);
        const word_series field = modified_field(t.substeps(), top);
        for (int k = 1; k <= p; ++k) CHECK(condition_residual(field, k, t.requirement()) < 1e-13L);
        if (p + 1 <= top) CHECK(condition_residual(field, p + 1, t.requirement()) > 1e-9L);
        if (t.needs_quadratic_kinetic()) CHECK(algebraic_order(t, top, kinetic_requirement::any) < p);
    }
    for (const table& t : force_gradient_catalog()) {
        CAPTURE(t.name());
        CHECK(algebraic_order(t, t.order() + 1) == t.order());
    }
}

TEST_CASE("order_conditions: a kick/drift swap is seen") {
    // Swapping the roles of an RKN table's weights keeps the general
    // conditions (symmetric in T and V; order 4 for SRKN14a) but not the
    // Nystrom ones, which are not.
    const table& t = method("blanes_moan_srkn14a");
    const table swapped = table::from_substeps("swapped", [&] {
        std::vector<substep> ops = t.substeps();
        for (substep& s : ops) s.kind = s.kind == substep::kick ? substep::drift : substep::kick;
        return ops;
    }(), 0, {}, kinetic_requirement::quadratic);
    CHECK(algebraic_order(t, 7) == 6);
    CHECK(algebraic_order(swapped, 7) == 4);
}

TEST_CASE("order_conditions: a reading gives both orders and the first unmet condition") {
    // McLachlan-Atela 4 (RKN): order 3 in general, 4 for T = p^2/2, and its
    // leading error is the size of E_4 (nonzero, below that of leapfrog's E_3).
    const order_conditions_reading rkn = read_order_conditions(method("mclachlan_atela_4"), 8);
    CHECK(rkn.representable);
    CHECK(rkn.general == 3);
    CHECK(rkn.quadratic == 4);
    const word_series field = modified_field(method("mclachlan_atela_4").substeps(), 8);
    CHECK(rkn.leading_error == doctest::Approx(double(condition_residual(field, 4, kinetic_requirement::any))));
    CHECK(rkn.leading_error > 1e-6);
    CHECK(rkn.leading_error < read_order_conditions(method("leapfrog_kdk"), 8).leading_error);
    // Sofroniou-Spaletta 10 meets every condition up to degree 10: "at least 10".
    const order_conditions_reading ss10 = read_order_conditions(method("sofroniou_spaletta_10"), 10);
    CHECK(ss10.general == 10);
    CHECK(ss10.leading_error == 0);
    // Weights near the double range overflow the series: said, not a wrong order.
    const table huge("huge", {1e300, -1e300, 1}, {0.5, 0.5, 0});
    const order_conditions_reading h = read_order_conditions(huge, 6);
    CHECK_FALSE(h.representable);
    CHECK(h.general == 0);
}

TEST_CASE("order_conditions: bad degrees are refused with the value") {
    CHECK_THROWS_WITH_AS(word_series(0), doctest::Contains("degree 0"), invalid_argument);
    const word_series field = modified_field({{substep::drift, 1}}, 3);
    CHECK_THROWS_WITH_AS(condition_residual(field, 4, kinetic_requirement::any), doctest::Contains("degree 4"),
                         invalid_argument);
}

TEST_CASE("order_conditions: a processed method's kernel has exactly its effective order, its plain order 4") {
    // The effective conditions know nothing of the processor: they must find,
    // from the kernel alone, the order the catalog claims for kernel + processor
    // (measured with the processor in test_processing.cpp), and no more.
    for (const processed_method& m : processed_catalog()) {
        CAPTURE(m.name);
        const std::vector<substep> ops = m.kernel.substeps();
        const int top = m.order + 1;
        CHECK(effective_order(ops, top, kinetic_requirement::any) == m.order);
        CHECK(effective_order(ops, top, kinetic_requirement::quadratic) == m.order);
        CHECK(algebraic_order(m.kernel, top, kinetic_requirement::any) == 4);
        // The first unmet effective condition is at an odd degree (the kernel is
        // symmetric) and is not rounding: far above the 1e-13 tolerance.
        const auto defects = effective_condition_defects(ops, top, kinetic_requirement::any);
        coefficient leading = 0;
        for (coefficient c : defects[std::size_t(top - 1)]) leading += c * c;
        CHECK(std::sqrt(leading) > 1e-8L);
    }
    // A plain table is its own kernel: symmetric order 4 tables have effective
    // order 4 or more, never less, and leapfrog (order 2) stays at 2: no
    // processor removes the degree-3 error [T,[T,V]] - [V,[V,T]]/2 it leaves.
    CHECK(effective_order(method("yoshida_4").substeps(), 5, kinetic_requirement::any) >= 4);
    CHECK(effective_order(method("leapfrog_kdk").substeps(), 5, kinetic_requirement::any) == 2);
}

}  // namespace test_analysis_test_order_conditions
