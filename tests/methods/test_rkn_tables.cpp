// The published tables of the Dormand-Prince RKN pairs (rkn_tables.hpp): the
// classical order conditions hold for the main and embedded weights to
// rounding, the embedded ones fail one order up, and the FSAL property.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <sympl/methods/rkn_tables.hpp>

namespace test_methods_test_rkn_tables {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
// The classical order conditions of RKN methods for q'' = f(q) that involve
// at most one level of a (Hairer, Norsett & Wanner I, sect. II.14), from the
// exact integrals int_0^c (c - s) s^k ds = c^(k+2) / ((k+1)(k+2)):
//   velocity weights, order m + 1:     sum bp_i c_i^m = 1 / (m + 1)
//   velocity weights, order m + k + 3: sum bp_i c_i^m a_ij c_j^k = 1 / ((k+1)(k+2)(m+k+3))
//   position weights, order m + 2:     sum b_i c_i^m = 1 / ((m+1)(m+2))
//   position weights, order m + k + 4: sum b_i c_i^m a_ij c_j^k = 1 / ((k+1)(k+2)(m+k+3)(m+k+4))
// and the chain sum w_i a_ij a_jl c_l^k of order k + 5 (velocity) and k + 6 (position).
// Returns the largest defect, relative to the sum of the magnitudes of its terms,
// over the conditions of orders lo..hi.
struct condition_defect {
    long double worst = 0;
    std::string where;
};
template <class P>
condition_defect order_defect(bool embedded, int lo, int hi) {
    using L = long double;
    const rkn_coefficients<P, L> t;
    const int s = P::stages;
    const auto& b = embedded ? t.b_hat : t.b;
    const auto& bp = embedded ? t.bp_hat : t.bp;
    condition_defect d;
    const auto check = [&](L value, L scale, L exact, int order, const std::string& what) {
        if (order < lo || order > hi) return;
        const L defect = std::fabs(value - exact) / std::max(scale, std::fabs(exact));
        if (defect > d.worst) d = {defect, what + " (order " + std::to_string(order) + ")"};
    };
    std::vector<L> ac(s);  // sum_j a_ij c_j^k
    std::vector<L> aac(s);  // sum_j a_ij sum_l a_jl c_l^k
    for (int m = 0; m <= 12; ++m) {
        L v = 0, sv = 0, q = 0, sq = 0;
        for (int i = 0; i < s; ++i) {
            const L w = std::pow(t.c[i], L(m));
            v += bp[i] * w, sv += std::fabs(bp[i] * w), q += b[i] * w, sq += std::fabs(b[i] * w);
        }
        check(v, sv, L(1) / (m + 1), m + 1, "sum bp c^" + std::to_string(m));
        check(q, sq, L(1) / ((m + 1) * (m + 2)), m + 2, "sum b c^" + std::to_string(m));
    }
    for (int k = 0; k <= 10; ++k) {
        for (int i = 0; i < s; ++i) {
            ac[i] = 0;
            for (int j = 0; j < i; ++j) ac[i] += t.a[i][j] * std::pow(t.c[j], L(k));
        }
        for (int i = 0; i < s; ++i) {
            aac[i] = 0;
            for (int j = 0; j < i; ++j) aac[i] += t.a[i][j] * ac[j];
        }
        const L g = L(1) / ((k + 1) * (k + 2));
        for (int m = 0; m + k <= 10; ++m) {
            L v = 0, sv = 0, q = 0, sq = 0;
            for (int i = 0; i < s; ++i) {
                const L w = std::pow(t.c[i], L(m)) * ac[i];
                v += bp[i] * w, sv += std::fabs(bp[i] * w), q += b[i] * w, sq += std::fabs(b[i] * w);
            }
            const std::string what = "c^" + std::to_string(m) + " a c^" + std::to_string(k);
            check(v, sv, g / (m + k + 3), m + k + 3, "sum bp " + what);
            check(q, sq, g / ((m + k + 3) * (m + k + 4)), m + k + 4, "sum b " + what);
        }
        L v = 0, sv = 0, q = 0, sq = 0;
        for (int i = 0; i < s; ++i)
            v += bp[i] * aac[i], sv += std::fabs(bp[i] * aac[i]), q += b[i] * aac[i], sq += std::fabs(b[i] * aac[i]);
        const L gg = g / ((k + 3) * (k + 4));
        check(v, sv, gg / (k + 5), k + 5, "sum bp a a c^" + std::to_string(k));
        check(q, sq, gg / ((k + 5) * (k + 6)), k + 6, "sum b a a c^" + std::to_string(k));
    }
    return d;
}

// Coefficients rounded to long double and summed: defects of a few hundred ulps
// of the terms (the 17-stage pair's entries reach 50 and cancel).
constexpr long double conditions_hold = 1e-15L;
// A condition one order above the formula's fails by far more than rounding.
constexpr long double conditions_fail = 1e-6L;

template <class P>
void check_order_conditions() {
    const std::string pair = P::name;
    CAPTURE(pair);
    // Main and embedded, up to order 6 or their order if lower, must hold ...
    const condition_defect main = order_defect<P>(false, 1, std::min(P::order, 12));
    const condition_defect emb = order_defect<P>(true, 1, P::embedded_order);
    CAPTURE(main.where);
    CAPTURE(emb.where);
    CHECK(main.worst < conditions_hold);
    CHECK(emb.worst < conditions_hold);
    // ... and the embedded formula must not reach its main formula's order
    // (else the difference would estimate nothing).
    CHECK(order_defect<P>(true, P::embedded_order + 1, P::embedded_order + 1).worst > conditions_fail);
}
}  // namespace

TEST_CASE("rkn tables: the tables satisfy their order conditions, the embedded formulae not one more") {
    check_order_conditions<dprkn6>();
    check_order_conditions<dprkn8>();
    check_order_conditions<dprkn12>();
    // First same as last: stage s is q_new, for the 6- and 8-stage pairs only.
    CHECK(rkn_coefficients<dprkn6, double>().fsal);
    CHECK(rkn_coefficients<dprkn8, double>().fsal);
    CHECK_FALSE(rkn_coefficients<dprkn12, double>().fsal);
}

}  // namespace test_methods_test_rkn_tables
