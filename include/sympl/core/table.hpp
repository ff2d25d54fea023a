#pragma once
// A splitting method as data (Gould & Tobochnik, eq. 3.74).
//
// The convention, stated once: a table of M stages advances (q, p) by dt as
//     for k = 0 .. M-1:
//         p += kick[k]  * dt * force(q)       // force    = -dV/dq
//         q += drift[k] * dt * velocity(p)    // velocity =  dT/dp
// with sum(kick) = sum(drift) = 1. A drift-first method has kick[0] = 0; a
// method that ends on a kick has drift[M-1] = 0.
//
// Gould & Tobochnik (eq. 3.74) write the same scheme with M sub-steps delta_t = dt/M and
// coefficients a_k (kick), b_k (drift) that sum to M: from_seed() converts.
// Boost.Odeint's symplectic_rkn steppers are drift-first and call their drift
// coefficients `a` and their kick coefficients `b`: from_drift_first()
// converts. Coefficients are always given by role, never by letter.
//
// Every table is kept in canonical form: adjacent sub-steps of the same kind
// are merged and zero sub-steps removed, so no force is evaluated in vain.
//
// A force-gradient method (Chin 1997; Omelyan, Mryglod & Folk 2002) also has a
// gradient coefficient g_k per kick: its kick is exp(kick[k] dt V + g_k dt^3
// [V,[T,V]]) in the operator notation of those papers. For T = p.M^-1.p / 2
// the double commutator is again a kick, by the gradient of F.M^-1.F, so
//     p += kick[k] dt F(q) + 2 g_k dt^3 J_F(q) M^-1 F(q)     (J_F = dF/dq)
// (the sign settled by measurement: with the other one Chin's 4A, g = 1/72,
// has order 2 instead of 4; tests/methods/test_catalog_tables.cpp). The steppers take J_F u
// from force_derivative() (hamiltonian.hpp). Such a table needs quadratic T.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "error.hpp"

namespace sympl {

using coefficient = long double;  // tables keep ~19 digits; steppers round to their scalar

// Which Hamiltonians a method keeps its order on.
enum class kinetic_requirement {
    any,        // any separable H = T(p) + V(q)
    quadratic,  // Runge-Kutta-Nystrom only: T(p) = p.M^-1.p / 2; lower order otherwise
};

// One sub-step of a method: a kick (p) or a drift (q) by weight * dt; a kick
// may carry a force-gradient term gradient * dt^3 [V,[T,V]] (see above).
struct substep {
    enum kind_t { kick, drift } kind;
    coefficient weight;
    coefficient gradient = 0;  // kicks only
};

namespace detail {
inline std::string format_coefficient(coefficient c) {
    std::ostringstream s;
    s.precision(21);
    s << c;
    return s.str();
}

// Merge neighbours of the same kind and drop zero weights (repeat until stable:
// dropping a zero drift can make two kicks adjacent).
inline std::vector<substep> canonical(std::vector<substep> ops) {
    std::vector<substep> out;
    out.reserve(ops.size());
    const auto zero = [](const substep& s) { return s.weight == 0 && s.gradient == 0; };
    for (const substep& s : ops) {
        if (zero(s)) continue;
        if (!out.empty() && out.back().kind == s.kind) {
            out.back().weight += s.weight;
            out.back().gradient += s.gradient;  // both are functions of q alone: kicks commute
            if (zero(out.back())) out.pop_back();
        } else {
            out.push_back(s);
        }
    }
    return out;
}
}  // namespace detail

class table {
public:
    // Validates (lengths, finiteness, sums) and stores the canonical form.
    // Throws invalid_table with a message naming the table, the bad value and
    // what was expected.
    table(std::string name, std::vector<coefficient> kick, std::vector<coefficient> drift, int order = 0,
          std::string citation = {}, kinetic_requirement requirement = kinetic_requirement::any)
        : name_(std::move(name)), order_(order), citation_(std::move(citation)), requirement_(requirement) {
        validate(kick, drift, {});
        set_substeps(to_substeps(kick, drift, {}));
    }

    // A force-gradient table: `gradient` holds one coefficient per stage, for
    // the stage's kick (0 where the kick is a plain one). Needs quadratic T.
    table(std::string name, std::vector<coefficient> kick, std::vector<coefficient> drift,
          std::vector<coefficient> gradient, int order, std::string citation)
        : name_(std::move(name)), order_(order), citation_(std::move(citation)),
          requirement_(kinetic_requirement::quadratic) {
        validate(kick, drift, gradient);
        set_substeps(to_substeps(kick, drift, gradient));
    }

    // A table from a sequence of sub-steps (composition builds these).
    static table from_substeps(std::string name, const std::vector<substep>& ops, int order, std::string citation,
                               kinetic_requirement requirement) {
        std::vector<coefficient> kick, drift, gradient;
        split(detail::canonical(ops), kick, drift, gradient);
        if (std::any_of(gradient.begin(), gradient.end(), [](coefficient g) { return g != 0; }))
            return table(std::move(name), std::move(kick), std::move(drift), std::move(gradient), order,
                         std::move(citation));
        return table(std::move(name), std::move(kick), std::move(drift), order, std::move(citation), requirement);
    }

    const std::string& name() const { return name_; }
    const std::vector<coefficient>& kick() const { return kick_; }
    const std::vector<coefficient>& drift() const { return drift_; }
    // Force-gradient coefficients, one per stage (all 0 for a plain table).
    const std::vector<coefficient>& gradient() const { return gradient_; }
    bool has_force_gradient() const {
        return std::any_of(gradient_.begin(), gradient_.end(), [](coefficient g) { return g != 0; });
    }
    // Claimed order (0 when unknown, e.g. a user's table); measure_order() checks it.
    int order() const { return order_; }
    const std::string& citation() const { return citation_; }
    // What kind of design it is ("composition", "splitting", "RKN", ...): shown
    // by `sympl tables` so that a user can choose; empty for a user's table.
    const std::string& family() const { return family_; }
    table with_family(std::string family) const {
        table t = *this;
        t.family_ = std::move(family);
        return t;
    }
    kinetic_requirement requirement() const { return requirement_; }
    bool needs_quadratic_kinetic() const { return requirement_ == kinetic_requirement::quadratic; }

    std::size_t stages() const { return kick_.size(); }

    // Alternating kick/drift sub-steps of one step, zero ones left out.
    std::vector<substep> substeps() const { return to_substeps(kick_, drift_, gradient_); }

    // Force evaluations per step in a long run: one per non-zero kick, less
    // one when the step ends on a kick and starts with one (the last force is
    // reused by the next step, so leapfrog KDK costs one).
    std::size_t force_evaluations() const {
        std::size_t n = 0;
        for (std::size_t k = 0; k < kick_.size(); ++k) n += (kick_[k] != 0 || gradient_[k] != 0);
        if ((kick_.front() != 0 || gradient_.front() != 0) && drift_.back() == 0 && n > 1) --n;
        return n;
    }
    // Evaluations of the force's derivative J_F u per step: one per gradient term.
    std::size_t force_gradient_evaluations() const {
        return std::size_t(std::count_if(gradient_.begin(), gradient_.end(), [](coefficient g) { return g != 0; }));
    }
    // Velocity evaluations per step, counted the same way.
    std::size_t velocity_evaluations() const {
        std::size_t n = 0;
        for (coefficient d : drift_) n += (d != 0);
        if (kick_.front() == 0 && drift_.back() != 0 && n > 1) --n;
        return n;
    }

    // Symmetric (self-adjoint): the sub-steps read the same backwards.
    bool is_symmetric(coefficient tolerance = 1e-14L) const {
        const auto ops = substeps();
        for (std::size_t i = 0, j = ops.size() - 1; i < ops.size(); ++i, --j)
            if (ops[i].kind != ops[j].kind || std::fabs(ops[i].weight - ops[j].weight) > tolerance ||
                std::fabs(ops[i].gradient - ops[j].gradient) > tolerance)
                return false;
        return true;
    }

    // Linear stability interval: the largest h = omega*dt such that the
    // one-step propagator of the harmonic oscillator (T = p^2/2, V = omega^2 q^2/2)
    // is stable, |trace| < 2, for all omega*dt in (0, h). 0 if none.
    double stability_interval() const {
        auto trace = [this](long double h) {
            // Propagator of (q, p) for one step; kick: p -= (c h - 2 g h^3) q (F = -q, J_F = -1),
            // drift: q += c h p (omega = 1).
            long double a = 1, b = 0, c = 0, d = 1;  // [[a b][c d]] maps (q,p) -> (q,p)
            for (const substep& s : substeps()) {
                if (s.kind == substep::kick) {
                    const long double k = s.weight * h - 2 * s.gradient * h * h * h;
                    c -= k * a;
                    d -= k * b;
                }
                else { a += s.weight * h * c; b += s.weight * h * d; }
            }
            return a + d;
        };
        const long double step = 1e-3L;
        const long double limit = 8.0L * static_cast<long double>(stages()) + 8.0L;
        long double h = step;
        for (; h < limit; h += step)
            if (std::fabs(trace(h)) >= 2) break;
        if (h >= limit) return static_cast<double>(limit);
        long double lo = h - step, hi = h;
        for (int i = 0; i < 60; ++i) {
            const long double mid = (lo + hi) / 2;
            (std::fabs(trace(mid)) >= 2 ? hi : lo) = mid;
        }
        return static_cast<double>(lo);
    }

    bool operator==(const table& o) const { return kick_ == o.kick_ && drift_ == o.drift_ && gradient_ == o.gradient_; }

private:
    static std::vector<substep> to_substeps(const std::vector<coefficient>& kick, const std::vector<coefficient>& drift,
                                            const std::vector<coefficient>& gradient) {
        std::vector<substep> ops;
        ops.reserve(2 * kick.size());
        for (std::size_t k = 0; k < kick.size(); ++k) {
            ops.push_back({substep::kick, kick[k], gradient.empty() ? 0 : gradient[k]});
            ops.push_back({substep::drift, drift[k]});
        }
        return detail::canonical(std::move(ops));
    }

    // Canonical sub-steps -> kick-first stages (kick[0] = 0 if drift comes first).
    static void split(const std::vector<substep>& ops, std::vector<coefficient>& kick, std::vector<coefficient>& drift,
                      std::vector<coefficient>& gradient) {
        kick.clear();
        drift.clear();
        gradient.clear();
        for (const substep& s : ops) {
            if (s.kind == substep::kick) {
                kick.push_back(s.weight);
                drift.push_back(0);
                gradient.push_back(s.gradient);
            } else {
                if (kick.empty()) { kick.push_back(0); drift.push_back(0); gradient.push_back(0); }
                drift.back() = s.weight;
            }
        }
    }

    void set_substeps(const std::vector<substep>& ops) { split(ops, kick_, drift_, gradient_); }

    void validate(const std::vector<coefficient>& kick, const std::vector<coefficient>& drift,
                  const std::vector<coefficient>& gradient) const {
        const std::string who = "table '" + name_ + "': ";
        if (kick.empty() || kick.size() != drift.size())
            throw invalid_table(who + "kick has " + std::to_string(kick.size()) + " coefficients and drift has " +
                                std::to_string(drift.size()) + "; expected equal lengths of at least 1");
        auto check = [&](const std::vector<coefficient>& c, const char* role) {
            for (std::size_t i = 0; i < c.size(); ++i)
                if (!std::isfinite(c[i]))
                    throw invalid_table(who + role + "[" + std::to_string(i) + "] = " + detail::format_coefficient(c[i]) +
                                        "; expected a finite coefficient");
            const coefficient sum = std::accumulate(c.begin(), c.end(), coefficient(0));
            if (std::fabs(sum - 1) > 1e-14L)
                throw invalid_table(who + "sum(" + role + ") = " + detail::format_coefficient(sum) +
                                    "; expected 1 within 1e-14");
        };
        check(kick, "kick");
        check(drift, "drift");
        if (!gradient.empty() && gradient.size() != kick.size())
            throw invalid_table(who + "gradient has " + std::to_string(gradient.size()) + " coefficients and kick has " +
                                std::to_string(kick.size()) + "; expected one gradient coefficient per stage");
        for (std::size_t i = 0; i < gradient.size(); ++i)
            if (!std::isfinite(gradient[i]))
                throw invalid_table(who + "gradient[" + std::to_string(i) + "] = " +
                                    detail::format_coefficient(gradient[i]) + "; expected a finite coefficient");
        if (order_ < 0)
            throw invalid_table(who + "order = " + std::to_string(order_) + "; expected >= 0 (0 = unknown)");
    }

    std::string name_;
    std::vector<coefficient> kick_, drift_, gradient_;
    int order_;
    std::string citation_;
    kinetic_requirement requirement_;
    std::string family_;
};

// ---- Conversions ------------------------------------------------------------

// From Gould & Tobochnik's convention (Gould & Tobochnik, eq. 3.74): M sub-steps of delta_t = dt/M
// with kick coefficients a_k and drift coefficients b_k summing to M.
// Verlet is M = 2, a = (1, 1), b = (2, 0) (Gould & Tobochnik eq. 3.75).
inline table from_seed(std::string name, const std::vector<coefficient>& a, const std::vector<coefficient>& b,
                       int order = 0, std::string citation = {},
                       kinetic_requirement requirement = kinetic_requirement::any) {
    const auto M = static_cast<coefficient>(a.size());
    if (a.empty() || a.size() != b.size())
        throw invalid_table("table '" + name + "': a has " + std::to_string(a.size()) + " coefficients and b has " +
                            std::to_string(b.size()) + "; expected M >= 1 of each (Gould & Tobochnik eq. 3.74)");
    auto scaled = [M](std::vector<coefficient> c) {
        for (auto& x : c) x /= M;
        return c;
    };
    for (const auto* c : {&a, &b}) {
        const coefficient sum = std::accumulate(c->begin(), c->end(), coefficient(0));
        if (std::isfinite(sum) && std::fabs(sum - M) > 1e-14L * M)
            throw invalid_table("table '" + name + "': sum(" + (c == &a ? "a" : "b") + ") = " +
                                detail::format_coefficient(sum) + "; expected M = " + detail::format_coefficient(M) +
                                " (Gould & Tobochnik eq. 3.74)");
    }
    return table(std::move(name), scaled(a), scaled(b), order, std::move(citation), requirement);
}

// From a drift-first table: q += drift[k] dt velocity(p), then p += kick[k] dt force(q).
// (Boost.Odeint's symplectic_rkn steppers: their `a` are drifts, their `b` kicks.)
inline table from_drift_first(std::string name, const std::vector<coefficient>& drift,
                              const std::vector<coefficient>& kick, int order = 0, std::string citation = {},
                              kinetic_requirement requirement = kinetic_requirement::any) {
    if (drift.empty() || drift.size() != kick.size())
        throw invalid_table("table '" + name + "': drift has " + std::to_string(drift.size()) +
                            " coefficients and kick has " + std::to_string(kick.size()) +
                            "; expected equal lengths of at least 1");
    std::vector<coefficient> k(1, 0), d(drift);
    k.insert(k.end(), kick.begin(), kick.end());
    d.push_back(0);
    return table(std::move(name), std::move(k), std::move(d), order, std::move(citation), requirement);
}

// ---- Composition --------------------------------------------------------------

namespace detail {
inline kinetic_requirement stricter(kinetic_requirement a, kinetic_requirement b) {
    return (a == kinetic_requirement::quadratic || b == kinetic_requirement::quadratic) ? kinetic_requirement::quadratic
                                                                                         : kinetic_requirement::any;
}
inline void append_scaled(std::vector<substep>& ops, const table& t, coefficient w) {
    for (substep s : t.substeps()) {
        s.weight *= w;
        s.gradient *= w * w * w;  // the term is dt^3 [V,[T,V]]: a step of w dt scales it by w^3
        ops.push_back(s);
    }
}
}  // namespace detail

// The adjoint method Phi*_dt = (Phi_{-dt})^{-1}: the sub-steps in reverse order.
// Same order; a method is symmetric when it equals its adjoint.
inline table adjoint(const table& t) {
    auto ops = t.substeps();
    std::reverse(ops.begin(), ops.end());
    const bool self = t.is_symmetric();
    return table::from_substeps(self ? t.name() : "adjoint(" + t.name() + ")", ops, t.order(), t.citation(),
                                t.requirement());
}

// Method a for the fraction `fraction` of the step, then b for the rest.
inline table concatenate(const table& a, const table& b, coefficient fraction = 0.5L) {
    if (!std::isfinite(fraction) || fraction <= 0 || fraction >= 1)
        throw invalid_argument("concatenate: fraction = " + detail::format_coefficient(fraction) +
                               "; expected a number strictly between 0 and 1");
    std::vector<substep> ops;
    detail::append_scaled(ops, a, fraction);
    detail::append_scaled(ops, b, 1 - fraction);
    // Each part's local error is O(dt^(p+1)), so the result has at least the
    // smaller order; a symmetric result has even order (Hairer, Lubich & Wanner,
    // GNI Thm. II.3.2), so an odd one is one more: Euler-Cromer then its adjoint
    // over half steps each is the leapfrog, order 2.
    int order = (a.order() == 0 || b.order() == 0) ? 0 : std::min(a.order(), b.order());
    table joined = table::from_substeps(a.name() + "+" + b.name(), ops, order, {},
                                        detail::stricter(a.requirement(), b.requirement()));
    if (order % 2 == 1 && joined.is_symmetric())
        joined = table::from_substeps(joined.name(), joined.substeps(), order + 1, {}, joined.requirement());
    return joined;
}

// base(w_1 dt) o base(w_2 dt) o ... : the weights must sum to 1. `order` is the
// order the composition is claimed to reach (0 = unknown).
inline table compose(const table& base, const std::vector<coefficient>& weights, std::string name = {}, int order = 0,
                     std::string citation = {}) {
    if (weights.empty())
        throw invalid_argument("compose: no weights given; expected at least one weight summing to 1");
    coefficient sum = 0;
    for (std::size_t i = 0; i < weights.size(); ++i) {
        if (!std::isfinite(weights[i]) || weights[i] == 0)
            throw invalid_argument("compose: weight[" + std::to_string(i) + "] = " +
                                   detail::format_coefficient(weights[i]) + "; expected a finite non-zero weight");
        sum += weights[i];
    }
    if (std::fabs(sum - 1) > 1e-14L)
        throw invalid_argument("compose: weights sum to " + detail::format_coefficient(sum) + "; expected 1 within 1e-14");
    std::vector<substep> ops;
    for (coefficient w : weights) detail::append_scaled(ops, base, w);
    if (name.empty()) name = "compose(" + base.name() + ", " + std::to_string(weights.size()) + ")";
    return table::from_substeps(std::move(name), ops, order, std::move(citation), base.requirement());
}

// Symmetric composition from the outer half of the weights and the centre:
// (w_m, ..., w_1, w_0, w_1, ..., w_m) with w_0 = 1 - 2 sum(w_i), the form in
// which Yoshida 1990, McLachlan 1995, Kahan-Li 1997 and Sofroniou-Spaletta 2005
// publish their constants (`outer` lists w_m first).
inline table compose_symmetric(const table& base, const std::vector<coefficient>& outer, std::string name, int order,
                               std::string citation) {
    std::vector<coefficient> w(outer);
    const coefficient centre = 1 - 2 * std::accumulate(outer.begin(), outer.end(), coefficient(0));
    w.push_back(centre);
    w.insert(w.end(), outer.rbegin(), outer.rend());
    return compose(base, w, std::move(name), order, std::move(citation));
}

namespace detail {
inline int raisable_order(const table& base, const char* who) {
    if (!base.is_symmetric() || base.order() < 2 || base.order() % 2 != 0)
        throw invalid_argument(std::string(who) + ": table '" + base.name() + "' has order " +
                               std::to_string(base.order()) + (base.is_symmetric() ? "" : " and is not symmetric") +
                               "; expected a symmetric method of known even order");
    return base.order();
}
}  // namespace detail

// Symmetric triple jump (Yoshida 1990, eq. 5.4; Forest-Ruth 1990, Candy-Rozmus 1991):
// order 2k -> 2k+2 with gamma = 1 / (2 - 2^(1/(2k+1))).
inline table triple_jump(const table& base) {
    const int p = detail::raisable_order(base, "triple_jump");
    const coefficient g = 1 / (2 - std::pow(2.0L, 1.0L / (p + 1)));
    return compose(base, {g, 1 - 2 * g, g}, "triple_jump(" + base.name() + ")", p + 2,
                   "Yoshida 1990, Phys. Lett. A 150, 262");
}

// Suzuki's 5-fold composition (Suzuki 1990, Phys. Lett. A 146, 319):
// order 2k -> 2k+2 with gamma = 1 / (4 - 4^(1/(2k+1))).
inline table suzuki_fractal(const table& base) {
    const int p = detail::raisable_order(base, "suzuki_fractal");
    // The cube root as cbrt, not pow(4, 1/3) with 1/3 rounded: correctly
    // rounded where pow may miss by an ulp, and so the same as the catalog's
    // suzuki_4 on every compiler and libm.
    const coefficient root = p + 1 == 3 ? std::cbrt(4.0L) : std::pow(4.0L, 1.0L / (p + 1));
    const coefficient g = 1 / (4 - root);
    return compose(base, {g, g, 1 - 4 * g, g, g}, "suzuki_fractal(" + base.name() + ")", p + 2,
                   "Suzuki 1990, Phys. Lett. A 146, 319");
}

}  // namespace sympl
