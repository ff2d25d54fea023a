#pragma once
// The forms in which papers print splitting tables, turned into sympl::table:
// the first half of a palindrome (palindrome), the outer weights of a symmetric
// composition of the kick-drift-kick leapfrog (leapfrog_composition), and a
// processed leapfrog's kernel weights and processor fractions
// (processed_leapfrog; Blanes, Casas & Murua 2024, Acta Numerica 33, 1, sec. 8);
// and back, the weights of a table that composes leapfrog steps
// (leapfrog_composition_weights; Yoshida 1990, Suzuki 1990).
// The composition tools they rest on (compose, compose_symmetric, adjoint,
// concatenate, triple_jump, suzuki_fractal) are table.hpp's.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "../core/table.hpp"
#include "processing.hpp"

namespace sympl {

// A table read as a symmetric composition of a second-order symmetric map.
struct composition_weights {
    std::vector<coefficient> gamma;  // the weights, sum 1, palindromic
    int order = 0;                   // the table's order (0 = unknown)
    std::string name;
};

namespace detail {
using K = std::vector<coefficient>;
constexpr auto rkn = kinetic_requirement::quadratic;
constexpr auto any = kinetic_requirement::any;
constexpr auto kick_first = substep::kick;
constexpr auto drift_first = substep::drift;

// A symmetric table from the published first half of its sub-steps, which
// alternate kick/drift starting with `first`. The two sub-steps before the
// centre are computed, as the papers do: the last one of the half, of the
// kind other than the centre's, makes its role sum to 1/2 over the half, and
// the centre makes its own role sum to 1.
inline table palindrome(std::string name, substep::kind_t first, const K& half, int order, std::string citation,
                        kinetic_requirement requirement = any) {
    const auto kind_at = [first](std::size_t i) {
        return (i % 2 == 0) == (first == substep::kick) ? substep::kick : substep::drift;
    };
    std::vector<substep> ops;
    coefficient sum[2] = {0, 0};  // by kind
    for (std::size_t i = 0; i < half.size(); ++i) {
        ops.push_back({kind_at(i), half[i]});
        sum[kind_at(i)] += half[i];
    }
    const substep::kind_t closing = kind_at(half.size()), centre = kind_at(half.size() + 1);
    ops.push_back({closing, 0.5L - sum[closing]});
    const coefficient middle = 1 - 2 * sum[centre];
    std::vector<substep> all(ops);
    all.push_back({centre, middle});
    all.insert(all.end(), ops.rbegin(), ops.rend());
    return table::from_substeps(std::move(name), all, order, std::move(citation), requirement);
}

// The kick-drift-kick leapfrog, the base of the compositions below.
inline const table& leapfrog_base() {
    static const table lf = palindrome("leapfrog_kdk", kick_first, {}, 2, "");
    return lf;
}

// A symmetric composition of the kick-drift-kick leapfrog with the published
// outer weights (outermost first); the centre weight is 1 - 2 sum(outer).
inline table leapfrog_composition(std::string name, const K& outer, int order, std::string citation) {
    return compose_symmetric(leapfrog_base(), outer, std::move(name), order, std::move(citation))
        .with_family("composition");
}

// Processed compositions of the kick-drift-kick leapfrog: the kernel is a
// symmetric composition (outer weights, outermost first, as leapfrog_composition),
// the processor a composition of leapfrogs with step fractions -g_k .. -g_1,
// g_k .. g_1 for the tabulated g_1 .. g_k, which sum to 0 (the source computes
// one of them from the others; it is listed as 0 here). The processor's order
// of application (last tabulated fraction first) was settled by measuring the
// effective order (tests/methods/test_processing.cpp); the other order leaves the
// kernel's order 4. Digits as tabulated in Blanes, Casas & Murua 2024, Acta
// Numerica 33, 1, Table 8.1.
inline processed_method processed_leapfrog(std::string name, const K& kernel_outer, K processor_half, int order,
                                           std::string citation) {
    const table& lf = leapfrog_base();
    coefficient rest = 0;
    std::size_t computed = 0;
    for (std::size_t i = 0; i < processor_half.size(); ++i)
        if (processor_half[i] == 0) computed = i;
        else rest += processor_half[i];
    processor_half[computed] = -rest;
    K fractions;
    for (auto g = processor_half.rbegin(); g != processor_half.rend(); ++g) fractions.push_back(-*g);
    for (auto g = processor_half.rbegin(); g != processor_half.rend(); ++g) fractions.push_back(*g);
    table kernel = compose_symmetric(lf, kernel_outer, name + "_kernel", 4, citation).with_family("processed");
    return make_processed(std::move(name), std::move(kernel), lf, fractions, order, std::move(citation));
}

// gamma_i of a table that composes leapfrog steps (in kick-drift-kick form its drifts; the
// kicks are the half sums of neighbours, and in drift-kick-drift form the roles swap);
// refuses any other table, naming it and what was expected.
inline composition_weights leapfrog_composition_weights(const table& t, const std::string& who) {
    const std::string expected =
        "; expected a symmetric composition of leapfrog steps (leapfrog_kdk, triple_jump(...), suzuki_fractal(...), "
        "yoshida_6, kahan_li_8, ...)";
    const std::string named = who + ": table '" + t.name() + "'";
    if (t.has_force_gradient()) throw invalid_argument(named + " has force-gradient terms" + expected);
    if (!t.is_symmetric(1e-13L)) throw invalid_argument(named + " is not symmetric" + expected);
    const std::vector<substep> ops = t.substeps();
    // Symmetric and canonical: outer sub-steps of one kind, alternating, odd count.
    composition_weights w{{}, t.order(), t.name()};
    for (std::size_t i = 1; i < ops.size(); i += 2) w.gamma.push_back(ops[i].weight);
    for (std::size_t i = 0; i < ops.size(); i += 2) {
        const std::size_t k = i / 2;  // outer sub-step k sits between gamma_{k-1} and gamma_k
        const coefficient left = k > 0 ? w.gamma[k - 1] : 0;
        const coefficient right = k < w.gamma.size() ? w.gamma[k] : 0;
        const coefficient want = (left + right) / 2;
        if (std::fabs(ops[i].weight - want) > 1e-12L * std::max<coefficient>(1, std::fabs(want)))
            throw invalid_argument(named + ": its " + (ops[i].kind == substep::kick ? "kick" : "drift") + " number " +
                                   std::to_string(k) + " is " + format_coefficient(ops[i].weight) +
                                   " where a composition of leapfrog steps has the half sum of its neighbours, " +
                                   format_coefficient(want) + expected);
    }
    return w;
}
}  // namespace detail

}  // namespace sympl
