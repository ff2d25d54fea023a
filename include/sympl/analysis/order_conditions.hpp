#pragma once
// A table's order read off its modified vector field, exactly, with no test
// problem. One step of a splitting method is the product of the sub-steps'
// flows, exp(b_1 dt T) exp(a_1 dt V) ..., each T (drift) and V (kick) a
// vector field. Its logarithm (Baker-Campbell-Hausdorff) is
//     dt (T + V) + dt^2 E_2 + dt^3 E_3 + ...
// with E_k a Lie polynomial of degree k in T and V; the method has order p
// when E_2 .. E_p vanish (Hairer, Lubich & Wanner, Geometric Numerical
// Integration, 2nd ed. 2006, sect. III.5; McLachlan & Quispel 2002, Acta
// Numerica 11, 341). For quadratic kinetic energy the bracket [V,[V,[V,T]]]
// is zero, so only the part of E_k outside the Lie ideal it generates must
// vanish: the Runge-Kutta-Nystrom conditions (2, 1, 2, 2, 4, 5, 10 of them at
// degrees 1..7; Blanes & Moan 2002, J. Comput. Appl. Math. 142, 313).
//
// The series are computed numerically in the free associative algebra on the
// two letters, truncated at a degree, in long double: the words of length k
// are indexed by k bits (1 = kick, the first letter most significant). That
// is 2^(D+1) coefficients, cheap up to D ~ 12. A force-gradient kick carries
// g dt^3 [V,[T,V]] in its exponent (table.hpp).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/table.hpp"

namespace sympl {

// A series truncated at a degree: part[k][w] is the coefficient of word w of
// length k (part[0] is the constant term).
struct word_series {
    std::vector<std::vector<coefficient>> part;

    explicit word_series(int max_degree) {
        if (max_degree < 1 || max_degree > 16)
            throw invalid_argument("word_series: degree " + std::to_string(max_degree) + "; expected 1 .. 16");
        for (int k = 0; k <= max_degree; ++k) part.emplace_back(std::size_t(1) << k, coefficient(0));
    }
    int max_degree() const { return int(part.size()) - 1; }

    static word_series identity(int max_degree) {
        word_series s(max_degree);
        s.part[0][0] = 1;
        return s;
    }
};

namespace detail {
// Words are concatenated by shifting the first one's bits left.
inline std::vector<coefficient> concatenate_words(const std::vector<coefficient>& u, const std::vector<coefficient>& v,
                                                  int degree_v) {
    std::vector<coefficient> out(u.size() * v.size(), 0);
    for (std::size_t i = 0; i < u.size(); ++i) {
        if (u[i] == 0) continue;
        for (std::size_t j = 0; j < v.size(); ++j) out[(i << degree_v) | j] += u[i] * v[j];
    }
    return out;
}

// [u, v] = uv - vu for homogeneous u (degree du) and v (degree dv).
inline std::vector<coefficient> bracket(const std::vector<coefficient>& u, int du, const std::vector<coefficient>& v,
                                        int dv) {
    std::vector<coefficient> uv = concatenate_words(u, v, dv);
    const std::vector<coefficient> vu = concatenate_words(v, u, du);
    for (std::size_t i = 0; i < uv.size(); ++i) uv[i] -= vu[i];
    return uv;
}

inline std::vector<coefficient> letter(bool kick) { return kick ? std::vector<coefficient>{0, 1} : std::vector<coefficient>{1, 0}; }

// An orthonormal basis (modified Gram-Schmidt, twice) of the span of `vectors`.
// With `carried` (one vector per input, empty meaning zero), the same linear
// combinations are applied to it, and on return it holds, for each basis
// vector, the combination of the carried vectors that goes with it.
inline std::vector<std::vector<coefficient>> orthonormal_basis(const std::vector<std::vector<coefficient>>& vectors,
                                                               std::vector<std::vector<coefficient>>* carried = nullptr) {
    std::vector<std::vector<coefficient>> basis, basis_carried;
    for (std::size_t j = 0; j < vectors.size(); ++j) {
        std::vector<coefficient> v = vectors[j], with = carried ? (*carried)[j] : std::vector<coefficient>{};
        coefficient before = 0;
        for (coefficient x : v) before += x * x;
        if (before == 0) continue;
        for (int pass = 0; pass < 2; ++pass)
            for (std::size_t b = 0; b < basis.size(); ++b) {
                const auto& e = basis[b];
                coefficient dot = 0;
                for (std::size_t i = 0; i < v.size(); ++i) dot += e[i] * v[i];
                for (std::size_t i = 0; i < v.size(); ++i) v[i] -= dot * e[i];
                if (carried && !basis_carried[b].empty()) {
                    if (with.empty()) with.assign(basis_carried[b].size(), 0);
                    for (std::size_t i = 0; i < with.size(); ++i) with[i] -= dot * basis_carried[b][i];
                }
            }
        coefficient after = 0;
        for (coefficient x : v) after += x * x;
        if (after <= 1e-24L * before) continue;  // dependent on the earlier ones
        const coefficient norm = std::sqrt(after);
        for (coefficient& x : v) x /= norm;
        for (coefficient& x : with) x /= norm;
        basis.push_back(std::move(v));
        basis_carried.push_back(std::move(with));
    }
    if (carried) *carried = std::move(basis_carried);
    return basis;
}

// The degree-k part of the Lie ideal generated by [V,[V,[V,T]]]: spanned by
// its iterated brackets with single letters. Cached per degree.
inline const std::vector<std::vector<coefficient>>& nystrom_ideal(int degree) {
    static std::mutex guard;
    static std::map<int, std::vector<std::vector<coefficient>>> cache;
    const std::lock_guard<std::mutex> lock(guard);
    auto found = cache.find(degree);
    if (found != cache.end()) return found->second;
    std::vector<std::vector<coefficient>> spanning;
    if (degree >= 4) {
        std::vector<coefficient> u = letter(false);
        for (int i = 0; i < 3; ++i) u = bracket(letter(true), 1, u, i + 1);  // [V,[V,[V,T]]]
        std::vector<std::vector<coefficient>> level{u};
        for (int d = 4; d < degree; ++d) {
            std::vector<std::vector<coefficient>> next;
            for (const auto& w : level)
                for (bool kick : {false, true}) next.push_back(bracket(letter(kick), 1, w, d));
            level = orthonormal_basis(next);  // keeps the spanning set at the ideal's dimension
        }
        spanning = std::move(level);
    }
    return cache.emplace(degree, orthonormal_basis(spanning)).first->second;
}

// An orthonormal basis of the degree-k part of the free Lie algebra on the two
// letters, from the right-nested brackets [x1,[x2,..,xk]] of every word (they
// span it). Cached per degree.
inline const std::vector<std::vector<coefficient>>& lie_basis(int degree) {
    static std::mutex guard;
    static std::map<int, std::vector<std::vector<coefficient>>> cache;
    const std::lock_guard<std::mutex> lock(guard);
    auto found = cache.find(degree);
    if (found != cache.end()) return found->second;
    std::vector<std::vector<coefficient>> brackets;
    for (std::size_t bits = 0; bits < (std::size_t(1) << degree); ++bits) {
        std::vector<coefficient> w = letter(bits & 1);
        for (int i = 1; i < degree; ++i) w = bracket(letter((bits >> i) & 1), 1, w, i);
        brackets.push_back(std::move(w));
    }
    return cache.emplace(degree, orthonormal_basis(brackets)).first->second;
}

// What conjugation can cancel at degree k (effective_condition_defects): the
// ideal (quadratic T), then [e, T + V] for e in a basis of degree k - 1 >= 2,
// orthonormalized with the Lie element each image comes from carried along
// (empty for the ideal's), so that a projection onto an image also says how
// much to add to the processor's exponent. Cached per degree and kinetic energy.
inline const std::pair<std::vector<std::vector<coefficient>>, std::vector<std::vector<coefficient>>>& cancellable(
    int degree, kinetic_requirement kinetic) {
    static std::mutex guard;
    static std::map<std::pair<int, kinetic_requirement>,
                    std::pair<std::vector<std::vector<coefficient>>, std::vector<std::vector<coefficient>>>>
        cache;
    {
        const std::lock_guard<std::mutex> lock(guard);
        auto found = cache.find({degree, kinetic});
        if (found != cache.end()) return found->second;
    }
    std::vector<std::vector<coefficient>> image, source;
    if (kinetic == kinetic_requirement::quadratic)
        for (const auto& e : nystrom_ideal(degree)) image.push_back(e), source.emplace_back();
    if (degree >= 3)
        for (const auto& e : lie_basis(degree - 1))
            image.push_back(bracket(e, degree - 1, {1, 1}, 1)), source.push_back(e);
    auto basis = orthonormal_basis(image, &source);
    const std::lock_guard<std::mutex> lock(guard);
    return cache.emplace(std::make_pair(degree, kinetic), std::make_pair(std::move(basis), std::move(source)))
        .first->second;
}
}  // namespace detail

// Truncated product: (x y) up to the smaller of the two degrees.
inline word_series operator*(const word_series& x, const word_series& y) {
    const int d = std::min(x.max_degree(), y.max_degree());
    word_series out(d);
    std::vector<std::size_t> nonzero;  // y's words with a coefficient, per degree: y is often sparse
    for (int j = 0; j <= d; ++j) {
        const auto& v = y.part[std::size_t(j)];
        nonzero.clear();
        for (std::size_t b = 0; b < v.size(); ++b)
            if (v[b] != 0) nonzero.push_back(b);
        if (nonzero.empty()) continue;
        for (int i = 0; i + j <= d; ++i) {
            const auto& u = x.part[std::size_t(i)];
            auto& w = out.part[std::size_t(i + j)];
            for (std::size_t a = 0; a < u.size(); ++a) {
                if (u[a] == 0) continue;
                for (std::size_t b : nonzero) w[(a << j) | b] += u[a] * v[b];
            }
        }
    }
    return out;
}

// exp(s) for a series without constant term.
inline word_series exp_of(const word_series& s) {
    word_series out = word_series::identity(s.max_degree()), power = out;
    coefficient factorial = 1;
    for (int n = 1; n <= s.max_degree(); ++n) {
        power = power * s;
        factorial *= n;
        for (int k = 0; k <= s.max_degree(); ++k)
            for (std::size_t w = 0; w < power.part[std::size_t(k)].size(); ++w)
                out.part[std::size_t(k)][w] += power.part[std::size_t(k)][w] / factorial;
    }
    return out;
}

// log(m) for a series with constant term 1.
inline word_series log_of(const word_series& m) {
    word_series x = m;
    x.part[0][0] = 0;
    word_series out(m.max_degree()), power = word_series::identity(m.max_degree());
    for (int n = 1; n <= m.max_degree(); ++n) {
        power = power * x;
        const coefficient c = (n % 2 ? 1.0L : -1.0L) / n;
        for (int k = 0; k <= m.max_degree(); ++k)
            for (std::size_t w = 0; w < power.part[std::size_t(k)].size(); ++w)
                out.part[std::size_t(k)][w] += c * power.part[std::size_t(k)][w];
    }
    return out;
}

// The exponent of one sub-step: weight times its letter, and for a
// force-gradient kick gradient * [V,[T,V]] at degree 3.
inline word_series exponent_of(const substep& s, int max_degree) {
    word_series e(max_degree);
    e.part[1][s.kind == substep::kick ? 1 : 0] = s.weight;
    if (s.kind == substep::kick && s.gradient != 0 && max_degree >= 3) {
        const auto v = detail::letter(true), t = detail::letter(false);
        const auto vtv = detail::bracket(v, 1, detail::bracket(t, 1, v, 1), 2);
        for (std::size_t w = 0; w < vtv.size(); ++w) e.part[3][w] = s.gradient * vtv[w];
    }
    return e;
}

// x * exp(w L) for a single letter L: exp(w L) has one word per degree, L^j
// with weight w^j / j!, so the product costs one pass per degree pair.
inline word_series times_flow(const word_series& x, bool kick, coefficient w) {
    const int d = x.max_degree();
    word_series out = x;
    coefficient c = 1;
    for (int j = 1; j <= d; ++j) {
        c *= w / coefficient(j);
        const std::size_t word = kick ? (std::size_t(1) << j) - 1 : 0;
        for (int i = 0; i + j <= d; ++i) {
            const auto& u = x.part[std::size_t(i)];
            auto& v = out.part[std::size_t(i + j)];
            for (std::size_t a = 0; a < u.size(); ++a) v[(a << j) | word] += c * u[a];
        }
    }
    return out;
}

// log of the product of the sub-steps' flows, in order of application: the
// method's modified vector field, dt = 1, up to max_degree.
inline word_series modified_field(const std::vector<substep>& ops, int max_degree) {
    word_series product = word_series::identity(max_degree);
    for (const substep& s : ops)
        product = s.gradient == 0 ? times_flow(product, s.kind == substep::kick, s.weight)
                                  : product * exp_of(exponent_of(s, max_degree));
    return log_of(product);
}

// What a table leaves of the conditions of degree k, as coefficients of the
// words of length k: E_k itself, or, for quadratic kinetic energy, the part of
// E_k orthogonal to the ideal of [V,[V,[V,T]]]. At degree 1: E_1 - (T + V).
// All zero (to rounding) for k = 1 .. p when the order is p.
inline std::vector<coefficient> condition_defect(const word_series& field, int degree, kinetic_requirement kinetic) {
    if (degree < 1 || degree > field.max_degree())
        throw invalid_argument("condition_defect: degree " + std::to_string(degree) + "; expected 1 .. " +
                               std::to_string(field.max_degree()));
    std::vector<coefficient> e = field.part[std::size_t(degree)];
    if (degree == 1) e[0] -= 1, e[1] -= 1;
    if (kinetic == kinetic_requirement::quadratic)
        for (const auto& basis : detail::nystrom_ideal(degree)) {
            coefficient dot = 0;
            for (std::size_t i = 0; i < e.size(); ++i) dot += basis[i] * e[i];
            for (std::size_t i = 0; i < e.size(); ++i) e[i] -= dot * basis[i];
        }
    return e;
}

// Its Euclidean norm in the word basis: how far the table misses degree k
// (at degree p + 1 of an order-p table: the size of its leading error).
inline coefficient condition_residual(const word_series& field, int degree, kinetic_requirement kinetic) {
    coefficient sum = 0;
    for (coefficient x : condition_defect(field, degree, kinetic)) sum += x * x;
    return std::sqrt(sum);
}

// The order read off a modified field: the largest p <= its degree such that
// the residuals of degrees 1 .. p are below `tolerance`, for the given kinetic
// energy (for a table, by default its own requirement). p = max_degree means
// "at least max_degree".
inline int algebraic_order(const word_series& field, kinetic_requirement kinetic, coefficient tolerance = 1e-13L) {
    int p = 0;
    while (p < field.max_degree() && condition_residual(field, p + 1, kinetic) < tolerance) ++p;
    return p;
}
inline int algebraic_order(const table& t, int max_degree, kinetic_requirement kinetic, coefficient tolerance = 1e-13L) {
    return algebraic_order(modified_field(t.substeps(), max_degree), kinetic, tolerance);
}
inline int algebraic_order(const table& t, int max_degree) { return algebraic_order(t, max_degree, t.requirement()); }

// The effective order of a kernel K: the order of P K P^-1 for the best
// near-identity processor P = exp(Z), Z = Z_2 + Z_3 + ... (Blanes, Casas & Ros
// 1999, SIAM J. Sci. Comput. 21, 711). Conjugation turns the modified field X
// into e^(ad Z) X, and Z_(k-1) first enters degree k as [Z_(k-1), T + V]; so,
// degree by degree, Z_(k-1) is chosen to cancel what it can of e^(ad Z) X at
// degree k (least squares), and what is left is that degree's effective
// defect (for quadratic T, also modulo the ideal of [V,[V,[V,T]]]). Returns
// the defects of degrees 1 .. max_degree as word coefficients (index 0 for
// degree 1). All vanish to rounding through degree p when P K^n P^-1 has
// order p for some processor; which processor is another question (one with
// log P = Z through degree p - 1 will do).
inline std::vector<std::vector<coefficient>> effective_condition_defects(const std::vector<substep>& kernel,
                                                                         int max_degree, kinetic_requirement kinetic) {
    const word_series x = modified_field(kernel, max_degree);
    word_series z(max_degree);  // the processor's exponent, built degree by degree
    std::vector<std::vector<coefficient>> defects;
    for (int k = 1; k <= max_degree; ++k) {
        // e^(ad Z) X at degree k: Z starts at degree 2, so ad_Z^n X starts at 2n + 1.
        std::vector<coefficient> r = x.part[std::size_t(k)];
        if (k == 1) r[0] -= 1, r[1] -= 1;
        word_series zk(k), term(k);
        for (int d = 0; d <= k; ++d) zk.part[std::size_t(d)] = z.part[std::size_t(d)], term.part[std::size_t(d)] = x.part[std::size_t(d)];
        for (int n = 1; 2 * n + 1 <= k; ++n) {
            const word_series zt = zk * term, tz = term * zk;
            for (int d = 0; d <= k; ++d)
                for (std::size_t i = 0; i < term.part[std::size_t(d)].size(); ++i)
                    term.part[std::size_t(d)][i] = (zt.part[std::size_t(d)][i] - tz.part[std::size_t(d)][i]) / coefficient(n);
            for (std::size_t i = 0; i < r.size(); ++i) r[i] += term.part[std::size_t(k)][i];
        }
        const auto& [basis, basis_source] = detail::cancellable(k, kinetic);
        for (std::size_t b = 0; b < basis.size(); ++b) {
            coefficient dot = 0;
            for (std::size_t i = 0; i < r.size(); ++i) dot += basis[b][i] * r[i];
            for (std::size_t i = 0; i < r.size(); ++i) r[i] -= dot * basis[b][i];
            for (std::size_t i = 0; i < basis_source[b].size(); ++i) z.part[std::size_t(k - 1)][i] -= dot * basis_source[b][i];
        }
        defects.push_back(std::move(r));
    }
    return defects;
}

// The largest p <= max_degree whose effective defects of degrees 1 .. p are
// all below `tolerance` in norm.
inline int effective_order(const std::vector<substep>& kernel, int max_degree, kinetic_requirement kinetic,
                           coefficient tolerance = 1e-13L) {
    const auto defects = effective_condition_defects(kernel, max_degree, kinetic);
    int p = 0;
    for (const auto& d : defects) {
        coefficient sum = 0;
        for (coefficient c : d) sum += c * c;
        if (!(std::sqrt(sum) < tolerance)) break;
        ++p;
    }
    return p;
}

// Everything the conditions say about a table, from one series: its order in
// general and for quadratic kinetic energy, and the size of the first
// condition it misses (a table typed with few digits misses its conditions by
// about their rounding). Coefficients near the double range overflow the
// series; `representable` is then false and the rest is left at zero.
struct order_conditions_reading {
    int max_degree = 0;
    int general = 0, quadratic = 0;  // max_degree: "at least max_degree"
    double leading_error = 0;        // |E_(general + 1)|; 0 when general = max_degree
    bool representable = true;
};

inline order_conditions_reading read_order_conditions(const table& t, int max_degree) {
    const word_series field = modified_field(t.substeps(), max_degree);
    order_conditions_reading r;
    r.max_degree = max_degree;
    const coefficient largest = coefficient(std::numeric_limits<double>::max());
    for (const auto& part : field.part)
        for (coefficient c : part) r.representable = r.representable && std::fabs(c) <= largest;
    if (!r.representable) return r;
    r.general = algebraic_order(field, kinetic_requirement::any);
    r.quadratic = algebraic_order(field, kinetic_requirement::quadratic);
    if (r.general < max_degree) {
        const coefficient leading = condition_residual(field, r.general + 1, kinetic_requirement::any);
        if (!(leading <= largest)) return order_conditions_reading{max_degree, 0, 0, 0, false};
        r.leading_error = double(leading);
    }
    return r;
}

}  // namespace sympl
