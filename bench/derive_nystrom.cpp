// Derives symmetric Runge-Kutta-Nystrom splitting methods (quadratic kinetic
// energy) of a given order by solving their order conditions numerically: the
// parts of the modified vector field E_1 .. E_p outside the ideal of
// [V,[V,[V,T]]] must vanish (order_conditions.hpp). Levenberg-Marquardt from
// random starts, in long double, down to its rounding; each solution is rated
// by its leading error (the norm of E_(p+1), RKN part) and printed as the
// table sympl would store.
//   derive_nystrom [--order 8] [--kicks 17] [--shape aba|bab] [--starts 2000] [--seed 1] [--keep 5]
// aba: drift first and last (a step costs `kicks` forces); bab: kick first and
// last (the last kick joins the next step's first: `kicks` - 1 forces).
// Unknowns: the first half of the symmetric sequence of weights; conditions:
// 2 (consistency) + 2, 4, 10 (degrees 3, 5, 7) for order 8. Even degrees vanish
// by symmetry.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <sympl/order_conditions.hpp>

namespace {

using sympl::coefficient;
using sympl::kinetic_requirement;
using sympl::substep;
using matrix = Eigen::Matrix<coefficient, Eigen::Dynamic, Eigen::Dynamic>;
using vector = Eigen::Matrix<coefficient, Eigen::Dynamic, 1>;

struct shape {
    std::size_t kicks;
    bool kick_first;
    std::size_t operations() const { return kick_first ? 2 * kicks - 1 : 2 * kicks + 1; }
    std::size_t unknowns() const { return (operations() + 1) / 2; }
    std::size_t forces() const { return kick_first ? kicks - 1 : kicks; }

    std::vector<substep> sequence(const vector& half) const {
        const std::size_t n = operations();
        std::vector<substep> ops(n);
        for (std::size_t i = 0; i < n; ++i) {
            const std::size_t j = std::min(i, n - 1 - i);
            const bool kick = (i % 2 == 0) == kick_first;
            ops[i] = {kick ? substep::kick : substep::drift, half[Eigen::Index(j)]};
        }
        return ops;
    }
};

// The conditions of degrees 1, 3, .., order - 1 (the odd ones; even ones
// vanish for symmetric sequences), stacked.
vector defects(const shape& s, const vector& half, int order) {
    const sympl::word_series field = sympl::modified_field(s.sequence(half), order - 1);
    std::vector<coefficient> all;
    for (int k = 1; k < order; k += 2) {
        // Scaled by kicks^(k-1): with M steps of about 1/M the degree-k defect is
        // of size M^(1-k), and unscaled the high degrees look solved long before they are.
        const coefficient scale = std::pow(coefficient(s.kicks), coefficient(k - 1));
        for (coefficient d : sympl::condition_defect(field, k, kinetic_requirement::quadratic)) all.push_back(scale * d);
    }
    return Eigen::Map<const vector>(all.data(), Eigen::Index(all.size()));
}

matrix jacobian(const shape& s, const vector& x, int order) {
    const coefficient h = 1e-8L;
    matrix j;
    for (Eigen::Index i = 0; i < x.size(); ++i) {
        vector up = x, down = x;
        up[i] += h, down[i] -= h;
        const vector d = (defects(s, up, order) - defects(s, down, order)) / (2 * h);
        if (j.size() == 0) j.resize(d.size(), x.size());
        j.col(i) = d;
    }
    return j;
}

// Levenberg-Marquardt; returns the final residual norm.
coefficient solve(const shape& s, vector& x, int order) {
    coefficient lambda = 1e-3L;
    vector r = defects(s, x, order);
    coefficient norm = r.norm();
    coefficient earlier = norm;
    for (int iteration = 0; iteration < 200 && norm > 1e-17L; ++iteration) {  // down to long double's rounding
        if (iteration % 25 == 24) {  // a start that stalls far from a root is abandoned
            if (norm > 1e-6L && norm > 0.5L * earlier) break;
            earlier = norm;
        }
        const matrix j = jacobian(s, x, order);
        const matrix jtj = j.transpose() * j;
        const vector g = j.transpose() * r;
        bool improved = false;
        for (int tries = 0; tries < 12 && !improved; ++tries) {
            matrix a = jtj;
            a.diagonal() += lambda * (jtj.diagonal().array() + 1e-12L).matrix();
            const vector step = a.ldlt().solve(-g);
            const vector trial = x + step;
            const vector rt = defects(s, trial, order);
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

struct found {
    vector half;
    coefficient residual, error, effective, total;
};

}  // namespace

int main(int argc, char** argv) {
    int order = 8, keep = 5;
    long starts = 2000;
    unsigned seed = 1;
    shape s{17, false};
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        const bool more = i + 1 < argc;
        if (a == "--order" && more) order = std::atoi(argv[++i]);
        else if (a == "--kicks" && more) s.kicks = std::size_t(std::atol(argv[++i]));
        else if (a == "--shape" && more) s.kick_first = std::string(argv[++i]) == "bab";
        else if (a == "--starts" && more) starts = std::atol(argv[++i]);
        else if (a == "--seed" && more) seed = unsigned(std::atol(argv[++i]));
        else if (a == "--keep" && more) keep = std::atoi(argv[++i]);
        else {
            std::fprintf(stderr, "usage: derive_nystrom [--order 8] [--kicks 17] [--shape aba|bab] [--starts N] [--seed S] [--keep K]\n");
            return 2;
        }
    }
    if (order < 2 || order > 10 || order % 2 || s.kicks < 2 || s.kicks > 40 || starts < 1 || keep < 1) {
        std::fprintf(stderr, "derive_nystrom: expected an even order in 2 .. 10, 2 .. 40 kicks, starts and keep >= 1\n");
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
            const bool kick = (i % 2 == 0) == s.kick_first;
            const double share = kick ? 1.0 / double(s.kicks) : 1.0 / double(s.operations() - s.kicks);
            x[i] = coefficient(share * (1 + 1.5 * normal(random)));
        }
        const coefficient residual = solve(s, x, order);
        if ((start + 1) % 100 == 0) std::fprintf(stderr, "%ld starts, %ld converged\n", start + 1, converged);
        if (!(residual < 1e-11L)) {
            if (std::getenv("DERIVE_VERBOSE")) std::fprintf(stderr, "start %ld: stopped at residual %.2Le, max |w| %.2Lf\n", start, residual, x.cwiseAbs().maxCoeff());
            continue;
        }
        ++converged;
        const auto ops = s.sequence(x);
        const sympl::word_series field = sympl::modified_field(ops, order + 1);
        const coefficient error = sympl::condition_residual(field, order + 1, kinetic_requirement::quadratic);
        coefficient total = 0;
        for (const substep& o : ops) total += std::fabs(o.weight);
        solutions.push_back({x, residual, error, coefficient(s.forces()) * std::pow(error, 1.0L / order), total});
        std::fprintf(stderr, "start %ld: residual %.1Le, error %.3Le, effective %.4Lf, sum |w| %.3Lf\n", start, residual,
                     error, solutions.back().effective, total);
    }
    std::sort(solutions.begin(), solutions.end(), [](const found& a, const found& b) { return a.effective < b.effective; });
    // The same root reached from several starts is printed once.
    solutions.erase(std::unique(solutions.begin(), solutions.end(),
                                [](const found& a, const found& b) { return (a.half - b.half).norm() < 1e-9L; }),
                    solutions.end());
    std::printf("# order %d, %zu kicks, %s, %zu forces a step: %ld of %ld starts converged, %zu distinct roots\n", order,
                s.kicks, s.kick_first ? "kick first" : "drift first", s.forces(), converged, starts, solutions.size());
    for (int k = 0; k < keep && k < int(solutions.size()); ++k) {
        const found& f = solutions[std::size_t(k)];
        std::printf("# error %.4Le, effective error %.4Lf, sum |w| %.4Lf, residual %.1Le\n", f.error, f.effective, f.total,
                    f.residual);
        std::vector<coefficient> kick, drift;
        for (const substep& o : s.sequence(f.half)) (o.kind == substep::kick ? kick : drift).push_back(o.weight);
        std::printf("kick  {");
        for (std::size_t i = 0; i < kick.size(); ++i) std::printf("%s%.21LgL", i ? ", " : "", kick[i]);
        std::printf("}\ndrift {");
        for (std::size_t i = 0; i < drift.size(); ++i) std::printf("%s%.21LgL", i ? ", " : "", drift[i]);
        std::printf("}\n");
    }
    return solutions.empty() ? 1 : 0;
}
