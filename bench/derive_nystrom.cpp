// Derives symmetric Runge-Kutta-Nystrom splitting methods (quadratic kinetic
// energy) of a given order by solving their order conditions numerically: the
// parts of the modified vector field E_1 .. E_p outside the ideal of
// [V,[V,[V,T]]] must vanish (order_conditions.hpp). Levenberg-Marquardt from
// random starts, in long double, down to its rounding; each solution is rated
// by its leading error (the norm of E_(p+1), RKN part) and printed as the
// table sympl would store.
//
// With --processor M the table is the kernel K of a processed method
// P K^n P^-1 (processing.hpp) and the conditions are those of P K P^-1 (all
// degrees: the conjugated step is not symmetric); P is M (drift, kick) pairs
// whose drift and kick weights each sum to zero.
//
// With --effective the kernel is solved alone, from its effective-order
// conditions (order_conditions.hpp: what conjugation by some processor cannot
// remove, degree by degree), far fewer than those of P K P^-1; with
// --processor M as well, a processor is then solved for each kernel root
// (the conditions of P K P^-1 with K fixed, from random starts).
//
// With --polish N, each root then descends N times along the family of roots
// (the defects' null space, where there are more unknowns than conditions)
// to lower its leading error, projected back onto the roots after each step.
//
// --gradient every|centre gives every kick (or the centre kick) a
// force-gradient coefficient as one more unknown; --from P solves order P
// first and the full order from there; --accept sets the scaled residual
// below which a root counts (1e-11; ~1e-8 with 14 kicks or more).
//
//   derive_nystrom [--order 8] [--kicks 17] [--shape aba|bab] [--processor M] [--effective]
//                  [--gradient every|centre] [--accept 1e-11] [--from P] [--processor-starts 60] [--polish N]
//                  [--starts 2000] [--seed 1] [--keep 5]
// aba: drift first and last (a step costs `kicks` forces); bab: kick first and
// last (the last kick joins the next step's first: `kicks` - 1 forces).
// Unknowns: the first half of the symmetric sequence of weights (and the
// processor's weights but its last pair); conditions without a processor:
// 2 (consistency) + 2, 4, 10 (degrees 3, 5, 7) for order 8, the even degrees
// vanishing by symmetry.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <sympl/analysis/order_conditions.hpp>
#include <sympl/methods/processing.hpp>

namespace {

using sympl::coefficient;
using sympl::kinetic_requirement;
using sympl::substep;
using matrix = Eigen::Matrix<coefficient, Eigen::Dynamic, Eigen::Dynamic>;
using vector = Eigen::Matrix<coefficient, Eigen::Dynamic, 1>;

struct shape {
    std::size_t kicks;
    bool kick_first;
    std::size_t processor_pairs = 0;
    bool effective = false;  // kernel alone, effective-order conditions; the processor solved after
    std::size_t operations() const { return kick_first ? 2 * kicks - 1 : 2 * kicks + 1; }
    // Force-gradient coefficients (table.hpp): on no kick, on every kick, or on
    // the centre kick only (odd kick counts).
    enum { none, every_kick, centre_kick } gradient = none;
    std::size_t weight_unknowns() const { return (operations() + 1) / 2; }
    // The kicks of the first half (with the centre): one gradient coefficient each.
    std::size_t gradient_unknowns() const { return gradient == every_kick ? (kicks + 1) / 2 : gradient == centre_kick; }
    std::size_t kernel_unknowns() const { return weight_unknowns() + gradient_unknowns(); }
    std::size_t processor_unknowns() const { return processor_pairs > 0 ? 2 * processor_pairs - 2 : 0; }
    std::size_t unknowns() const { return kernel_unknowns() + (effective ? 0 : processor_unknowns()); }
    std::size_t forces() const { return kick_first ? kicks - 1 : kicks; }
    // What a step costs, counting a force's derivative J_F u as one force.
    std::size_t cost() const { return forces() + (gradient == every_kick ? forces() : gradient == centre_kick); }

    // The kernel: the symmetric sequence whose first half leads x.
    std::vector<substep> kernel(const vector& x) const {
        const std::size_t n = operations();
        std::vector<substep> ops(n);
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t j = std::min(i, n - 1 - i);
            const bool kick = (i % 2 == 0) == kick_first;
            ops[i] = {kick ? substep::kick : substep::drift, x[Eigen::Index(j)]};
            if (kick && gradient == every_kick) ops[i].gradient = x[Eigen::Index(weight_unknowns() + j / 2)];
            if (kick && gradient == centre_kick && j == (n - 1) / 2) ops[i].gradient = x[Eigen::Index(weight_unknowns())];
        }
        return ops;
    }

    // P, in order of application: the pairs after the kernel's unknowns, and
    // a last pair that brings both sums to zero.
    std::vector<substep> processor(const vector& x) const {
        std::vector<substep> ops;
        if (processor_pairs == 0) return ops;
        coefficient drifts = 0, kicks_sum = 0;
        for (std::size_t i = 0; i + 1 < processor_pairs; ++i) {
            const Eigen::Index at = Eigen::Index(kernel_unknowns() + 2 * i);
            ops.push_back({substep::drift, x[at]});
            ops.push_back({substep::kick, x[at + 1]});
            drifts += x[at], kicks_sum += x[at + 1];
        }
        ops.push_back({substep::drift, -drifts});
        ops.push_back({substep::kick, -kicks_sum});
        return ops;
    }

    // One step of the method the conditions are about: K, or P K P^-1.
    std::vector<substep> step(const vector& x) const {
        std::vector<substep> ops = sympl::inverse(processor(x));
        const std::vector<substep> k = kernel(x), p = processor(x);
        ops.insert(ops.end(), k.begin(), k.end());
        ops.insert(ops.end(), p.begin(), p.end());
        return ops;
    }
};

namespace effective {
// The effective-order defects of a kernel (order_conditions.hpp), degrees
// `from` .. order stacked, each scaled by scale_base^(k-1).
vector defects(const std::vector<substep>& kernel, int order, coefficient scale_base, int from = 1) {
    const auto per_degree = sympl::effective_condition_defects(kernel, order, kinetic_requirement::quadratic);
    std::vector<coefficient> all;
    for (int k = from; k <= order; ++k)
        for (coefficient d : per_degree[std::size_t(k - 1)]) all.push_back(std::pow(scale_base, coefficient(k - 1)) * d);
    return Eigen::Map<const vector>(all.data(), Eigen::Index(all.size()));
}
}  // namespace effective

// The conditions of degrees 1 .. order (without a processor only the odd
// ones: the even ones vanish for symmetric sequences), stacked.
vector defects(const shape& s, const vector& x, int order) {
    if (s.effective) return effective::defects(s.kernel(x), order, coefficient(s.kicks));
    const sympl::word_series field = sympl::modified_field(s.step(x), order);
    std::vector<coefficient> all;
    for (int k = 1; k <= order; k += s.processor_pairs > 0 ? 1 : 2) {
        // Scaled by kicks^(k-1): with M steps of about 1/M the degree-k defect is
        // of size M^(1-k), and unscaled the high degrees look solved long before they are.
        const coefficient scale = std::pow(coefficient(s.kicks), coefficient(k - 1));
        for (coefficient d : sympl::condition_defect(field, k, kinetic_requirement::quadratic)) all.push_back(scale * d);
    }
    return Eigen::Map<const vector>(all.data(), Eigen::Index(all.size()));
}


// The leading error: |E_(order + 1)|, RKN part.
coefficient leading_error(const shape& s, const vector& x, int order) {
    if (s.effective) return effective::defects(s.kernel(x), order + 1, 1, order + 1).norm();
    return sympl::condition_residual(sympl::modified_field(s.step(x), order + 1), order + 1,
                                     kinetic_requirement::quadratic);
}

template <class F>
matrix central_differences(const vector& x, F&& f) {
    const coefficient h = 1e-8L;
    matrix j;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
        vector up = x, down = x;
        up[i] += h, down[i] -= h;
        const vector d = (f(up) - f(down)) / (2 * h);
        if (j.size() == 0) j.resize(d.size(), x.size());
        j.col(i) = d;
    }
    return j;
}

matrix jacobian(const shape& s, const vector& x, int order) {
    return central_differences(x, [&](const vector& y) { return defects(s, y, order); });
}

// Levenberg-Marquardt; returns the final residual norm.
template <class F>
coefficient solve_for(F&& defects_of, vector& x, int iterations = 200) {
    coefficient lambda = 1e-3L;
    vector r = defects_of(x);
    coefficient norm = r.norm();
    coefficient earlier = norm;
    for (int iteration = 0; iteration < iterations && norm > 1e-17L; ++iteration) {  // down to long double's rounding
        if (iteration % 25 == 24) {  // a start that stalls far from a root is abandoned
            if (norm > 1e-6L && norm > 0.5L * earlier) break;
            earlier = norm;
        }
        const matrix j = central_differences(x, defects_of);
        const matrix jtj = j.transpose() * j;
        const vector g = j.transpose() * r;
        bool improved = false;
        for (int tries = 0; tries < 12 && !improved; ++tries) {
            matrix a = jtj;
            a.diagonal() += lambda * (jtj.diagonal().array() + 1e-12L).matrix();
            const vector step = a.ldlt().solve(-g);
            const vector trial = x + step;
            const vector rt = defects_of(trial);
            const coefficient nt = rt.norm();
            if (std::isfinite(nt) && nt < norm) {
                x = trial, r = rt, norm = nt;
                lambda = std::max(lambda / 4, 1e-15L);
                improved = true;
            } else {
                lambda *= 8;
            }
        }
        if (!improved || x.cwiseAbs().maxCoeff() > 5) break;
    }
    return norm;
}

coefficient solve(const shape& s, vector& x, int order, int iterations = 200) {
    return solve_for([&](const vector& y) { return defects(s, y, order); }, x, iterations);
}

// Descends the leading error along the family of roots through x: the
// error's gradient projected onto the null space of the defects' Jacobian,
// a step that halves until the root, restored by solve(), has a smaller
// error. Returns the number of accepted steps.
int polish(const shape& s, vector& x, int order, int steps, coefficient accept) {
    coefficient error = leading_error(s, x, order), length = 0.05L;
    int accepted = 0;
    for (int k = 0; k < steps && length > 1e-9L; ++k) {
        const matrix j = jacobian(s, x, order);
        const vector grad = central_differences(x, [&](const vector& y) {
                                return vector::Constant(1, leading_error(s, y, order));
                            }).row(0).transpose();
        // The family's tangent space: the null space of J, from the
        // eigenvalues of J^T J (increasing) below 1e-14 of the largest, that
        // is singular values below 1e-7 (J's rows are the defects of all
        // words, dependent, and known to ~1e-11 relative).
        const Eigen::SelfAdjointEigenSolver<matrix> eigen(j.transpose() * j);
        const auto& values = eigen.eigenvalues();
        Eigen::Index null = 0;
        while (null < values.size() && values[null] < 1e-14L * values[values.size() - 1]) ++null;
        const matrix tangent = eigen.eigenvectors().leftCols(null);
        const vector along = tangent * (tangent.transpose() * grad);
        if (!(along.norm() > 1e-30L)) break;  // no family, or already at its minimum
        bool better = false;
        while (!better && length > 1e-9L) {
            vector trial = x - length * along / along.norm();
            if (solve(s, trial, order, 30) < accept) {
                const coefficient e = leading_error(s, trial, order);
                if (e < error) x = trial, error = e, better = true, ++accepted, length *= 1.5L;
            }
            if (!better) length /= 2;
        }
    }
    return accepted;
}

struct found {
    vector x;
    coefficient residual, error, effective, total;
};

}  // namespace

int main(int argc, char** argv) {
    int order = 8, keep = 5, polish_steps = 0, from_order = 0, processor_attempts = 60;
    // A root is accepted below this scaled residual; with many kicks the
    // scaling (kicks^(k-1)) lifts long double's rounding towards 1e-10.
    coefficient accept = 1e-11L;
    long starts = 2000;
    unsigned seed = 1;
    shape s{17, false};
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool more = i + 1 < argc;
        if (a == "--order" && more) order = std::atoi(argv[++i]);
        else if (a == "--kicks" && more) s.kicks = std::size_t(std::atol(argv[++i]));
        else if (a == "--shape" && more) s.kick_first = std::string(argv[++i]) == "bab";
        else if (a == "--processor" && more) s.processor_pairs = std::size_t(std::atol(argv[++i]));
        else if (a == "--effective") s.effective = true;
        else if (a == "--from" && more) from_order = std::atoi(argv[++i]);
        else if (a == "--processor-starts" && more) processor_attempts = std::atoi(argv[++i]);
        else if (a == "--accept" && more) accept = std::strtold(argv[++i], nullptr);
        else if (a == "--gradient" && more && (std::string(argv[i + 1]) == "every" || std::string(argv[i + 1]) == "centre"))
            s.gradient = std::string(argv[++i]) == "every" ? shape::every_kick : shape::centre_kick;
        else if (a == "--polish" && more) polish_steps = std::atoi(argv[++i]);
        else if (a == "--starts" && more) starts = std::atol(argv[++i]);
        else if (a == "--seed" && more) seed = unsigned(std::atol(argv[++i]));
        else if (a == "--keep" && more) keep = std::atoi(argv[++i]);
        else {
            std::fprintf(stderr, "usage: derive_nystrom [--order 8] [--kicks 17] [--shape aba|bab] [--processor M] "
                                 "[--effective] [--gradient every|centre] [--accept 1e-11] [--from P] [--processor-starts 60] [--polish N] [--starts N] [--seed S] [--keep K]\n");
            return 2;
        }
    }
    if (order < 2 || order > 10 || order % 2 || s.kicks < 2 || s.kicks > 40 || s.processor_pairs > 40 ||
        (s.gradient == shape::centre_kick && s.kicks % 2 == 0) || polish_steps < 0 || polish_steps > 100000 ||
        starts < 1 || keep < 1) {
        std::fprintf(stderr, "derive_nystrom: expected an even order in 2 .. 10, 2 .. 40 kicks (odd with --gradient "
                             "centre), at most 40 processor pairs, 0 .. 100000 polish steps, starts and keep >= 1\n");
        return 2;
    }
    std::mt19937_64 random(seed);
    std::normal_distribution<double> normal;
    const Eigen::Index n = Eigen::Index(s.unknowns());
    std::vector<found> solutions;
    long converged = 0;
    for (long start = 0; start < starts; ++start) {
        vector x(n);
        for (Eigen::Index i = 0; i < n; ++i) {
            if (i >= Eigen::Index(s.kernel_unknowns())) {  // the processor: near the identity
                x[i] = coefficient(0.2 * normal(random));
                continue;
            }
            if (i >= Eigen::Index(s.weight_unknowns())) {  // a gradient: of the size of a kick's cube
                x[i] = coefficient(0.05 * normal(random) / std::pow(double(s.kicks), 3));
                continue;
            }
            const bool kick = (i % 2 == 0) == s.kick_first;
            const double share = kick ? 1.0 / double(s.kicks) : 1.0 / double(s.operations() - s.kicks);
            x[i] = coefficient(share * (1 + 1.5 * normal(random)));
        }
        // With --from P: a root of order P first (many more of those), then
        // its family walked down the error at degree P + 1 (--polish) before
        // the conditions of the full order are solved from there.
        if (from_order > 0) {
            if (!(solve(s, x, from_order) < accept)) continue;
            if (polish_steps > 0) polish(s, x, from_order, polish_steps, accept);
        }
        coefficient residual = solve(s, x, order, 400);
        if ((start + 1) % 100 == 0) std::fprintf(stderr, "%ld starts, %ld converged\n", start + 1, converged);
        if (!(residual < accept)) {
            if (std::getenv("DERIVE_VERBOSE")) std::fprintf(stderr, "start %ld: stopped at residual %.2Le, max |w| %.2Lf\n", start, residual, x.cwiseAbs().maxCoeff());
            continue;
        }
        ++converged;
        if (polish_steps > 0 && from_order == 0) {
            const coefficient before = leading_error(s, x, order);
            const int accepted = polish(s, x, order, polish_steps, accept);
            residual = solve(s, x, order);
            std::fprintf(stderr, "start %ld: polished %d steps, error %.3Le -> %.3Le\n", start, accepted, before,
                         leading_error(s, x, order));
            if (!(residual < accept)) continue;
        }
        const coefficient error = leading_error(s, x, order);
        if (s.effective && s.processor_pairs > 0) {  // the processor for this kernel, solved alone
            shape full = s;
            full.effective = false;
            const vector kernel_x = x;
            const auto conjugated = [&](const vector& p) {
                vector y(Eigen::Index(full.unknowns()));
                y << kernel_x, p;
                return defects(full, y, order);
            };
            coefficient best = 1e300L;
            vector chosen;
            for (int attempt = 0; attempt < processor_attempts && best > accept; ++attempt) {
                vector p(Eigen::Index(full.processor_unknowns()));
                const double spread = 0.1 * double(1 << (attempt % 3));  // 0.1, 0.2, 0.4 in turn
                for (Eigen::Index i = 0; i < p.size(); ++i) p[i] = coefficient(spread * normal(random));
                const coefficient r = solve_for(conjugated, p, 300);
                if (r < best) best = r, chosen = p;
            }
            std::fprintf(stderr, "start %ld: processor residual %.1Le\n", start, best);
            if (!(best < accept)) continue;
            x.conservativeResize(Eigen::Index(full.unknowns()));
            x.tail(chosen.size()) = chosen;
        }
        coefficient total = 0;
        for (const substep& o : s.kernel(x)) total += std::fabs(o.weight);
        solutions.push_back({x, residual, error, coefficient(s.cost()) * std::pow(error, 1.0L / order), total});
        std::fprintf(stderr, "start %ld: residual %.1Le, error %.3Le, effective %.4Lf, sum |w| %.3Lf\n", start, residual,
                     error, solutions.back().effective, total);
    }
    std::sort(solutions.begin(), solutions.end(), [](const found& a, const found& b) { return a.effective < b.effective; });
    // The same root reached from several starts is printed once.
    solutions.erase(std::unique(solutions.begin(), solutions.end(),
                                [](const found& a, const found& b) { return (a.x - b.x).norm() < 1e-9L; }),
                    solutions.end());
    std::printf("# order %d%s, %zu kicks, %s, %zu forces a step: %ld of %ld starts converged, %zu distinct roots\n",
                order, s.processor_pairs > 0 ? " (effective, processed)" : "", s.kicks,
                s.kick_first ? "kick first" : "drift first", s.forces(), converged, starts, solutions.size());
    for (int k = 0; k < keep && k < int(solutions.size()); ++k) {
        const found& f = solutions[std::size_t(k)];
        std::printf("# error %.4Le, effective error %.4Lf, sum |w| %.4Lf, residual %.1Le\n", f.error, f.effective, f.total,
                    f.residual);
        std::vector<coefficient> kick, drift, gradient;
        for (const substep& o : s.kernel(f.x)) {
            (o.kind == substep::kick ? kick : drift).push_back(o.weight);
            if (o.kind == substep::kick) gradient.push_back(o.gradient);
        }
        const auto list = [](const char* label, const std::vector<coefficient>& w) {
            std::printf("%s{", label);
            for (std::size_t i = 0; i < w.size(); ++i) std::printf("%s%.21LgL", i ? ", " : "", w[i]);
            std::printf("}\n");
        };
        list("kick  ", kick);
        list("drift ", drift);
        if (s.gradient != shape::none) list("gradient ", gradient);
        if (s.processor_pairs > 0) {  // in order of application, pairs (drift, kick)
            shape full = s;
            full.effective = false;
            std::vector<coefficient> pd, pk;
            for (const substep& o : full.processor(f.x)) (o.kind == substep::kick ? pk : pd).push_back(o.weight);
            list("processor drift ", pd);
            list("processor kick  ", pk);
        }
    }
    return solutions.empty() ? 1 : 0;
}
