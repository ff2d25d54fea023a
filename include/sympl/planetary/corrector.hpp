#pragma once
// Symplectic correctors (Wisdom, Holman & Touma 1996, "Symplectic
// correctors", Fields Inst. Commun. 10, 217) for the Wisdom-Holman
// splittings: the weights of the corrector of order 2K + 1 for the two
// leapfrogs (tabulated; order 17 as in REBOUND's WHFast, Rein & Tamayo 2015,
// MNRAS 452, 376) and for any symmetric table (solved), and the corrector C
// itself, a composition of the splitting's own flows:
//     C = Z(-a_K, -c_K) ... Z(-a_1, -c_1) Z(a_1, c_1) ... Z(a_K, c_K),
//     Z(a, b) = drift(a dt) kick(b dt) drift(-2a dt) kick(-b dt) drift(a dt),
// a_i = i sqrt(7/40). The derivation (first-order Baker-Campbell-Hausdorff,
// the conditions on the c_i, the sign settled by measurement) is in
// docs/planetary.md ("The symplectic corrector").
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/table.hpp"

namespace sympl {

// Which leapfrog a corrector is for: kick(h/2) drift(h) kick(h/2) or
// drift(h/2) kick(h) drift(h/2) (drift = Kepler flow, kick = perturbation).
enum class leapfrog_kernel { kick_drift_kick, drift_kick_drift };

// The node spacing of the correctors, a_i = i alpha (Wisdom, Holman & Touma 1996).
inline constexpr coefficient corrector_alpha = 0.41833001326703777398908601289259374469640768464934L;  // sqrt(7/40)

// The weights c_1..c_K of the symplectic corrector of order 2K + 1 for the
// leapfrog `kernel`, c_i with the node a_i = i alpha; they solve, for k = 1..K,
//     4 sum_i c_i a_i^(2k-1) / (2k-1)! = -[u^(2k)] f(u),
//     f(u) = (u/2) / sinh(u/2)  (drift-kick-drift),  (u/2) coth(u/2)  (kick-drift-kick)
// (derived in docs/planetary.md). Orders 3, 5, 7,
// 9, 11, 17; anything else is an invalid_argument.
inline std::vector<coefficient> corrector_weights(int order, leapfrog_kernel kernel) {
    // Drift-kick-drift: Wisdom, Holman & Touma 1996 (Fields Inst. Commun. 10,
    // 217), orders 3 to 11, and order 17 as tabulated with them in REBOUND's
    // WHFast (Rein & Tamayo 2015, MNRAS 452, 376; Rein, Tamayo & Brown 2019,
    // MNRAS 489, 4632), listed there last node first; the third-order weight
    // is listed there with the opposite sign, here in the convention of the
    // others. Order 9 is not in that list: derived here
    // from the conditions above, as are all the kick-drift-kick weights.
    // tests/planetary/test_corrector.cpp checks every set against the conditions.
    static const std::vector<coefficient> dkd3 = {0.024900596027799867499350357910273437184309981229127L};
    static const std::vector<coefficient> dkd5 = {0.041500993379666445832250596517122395307183302048545L,
                                                  -0.0083001986759332891664501193034244790614366604097090L};
    static const std::vector<coefficient> dkd7 = {0.053964399093127498721765893493510877532452806339655L,
                                                  -0.018270923246702131478062356884535264841652263842597L,
                                                  0.0024926811426922105779030593952776964450539008582219L};
    static const std::vector<coefficient> dkd9 = {0.0640415312967437851275674L, -0.0283480554503184178838639L,  // derived
                                                  0.00681145208709919046610370L, -0.000719795157401163314700107L};
    static const std::vector<coefficient> dkd11 = {0.072593394748842738674253180742744961827622366521517L,
                                                   -0.038121613681288650508647613260247372125243616270670L,
                                                   0.012309078592019946317544564763237909911330686448336L,
                                                   -0.0023487215292295354188307328851055489876255097419754L,
                                                   0.00020361579647854651301632818774633716473696537436847L};
    static const std::vector<coefficient> dkd17 = {0.093056103771425958591541059067553547100903397724386L,
                                                   -0.065192863576377893658290760803725762027864651086787L,
                                                   0.032422198864713580293681523029577130832258806467604L,
                                                   -0.012071760822342291062449751726959664253913904872527L,
                                                   0.0033132577069380655655490196833451994080066801611459L,
                                                   -0.00063599983075817658983166881625078545864140848560259L,
                                                   0.000076436355227935738363241846979413475106795392377415L,
                                                   -0.0000043347415473373580190650223498124944896789841432241L};
    // Kick-drift-kick: derived here (60-digit solve of the conditions above).
    static const std::vector<coefficient> kdk3 = {-0.0498011920555997349987007L};
    static const std::vector<coefficient> kdk5 = {-0.0758875307513900723789725L, 0.0130431693478951686901359L};
    static const std::vector<coefficient> kdk7 = {-0.0933429534284742684491358L, 0.0270075074895625255462666L,
                                                  -0.00349108453541683921403266L};
    static const std::vector<coefficient> kdk9 = {-0.106498512897734520225491L, 0.0401630669588227773226213L,
                                                  -0.00912918145081408997532756L, 0.000939682819232875126882483L};
    static const std::vector<coefficient> kdk11 = {-0.117138179727557266931154L, 0.0523226861929059164148086L,
                                                   -0.0159689672699858557146829L, 0.00296628602491339830891370L,
                                                   -0.000253325400710065397753902L};
    static const std::vector<coefficient> kdk17 = {-0.141145021791536283325715L, 0.0840532782569635626416991L,
                                                   -0.0395047158916151646192265L, 0.0143144674267565145453236L,
                                                   -0.00386896812574578830945957L, 0.000735606570239877964660653L,
                                                   -0.0000878464443772894551519141L, 0.00000495968846994483317479279L};
    const bool dkd = kernel == leapfrog_kernel::drift_kick_drift;
    switch (order) {
        case 3: return dkd ? dkd3 : kdk3;
        case 5: return dkd ? dkd5 : kdk5;
        case 7: return dkd ? dkd7 : kdk7;
        case 9: return dkd ? dkd9 : kdk9;
        case 11: return dkd ? dkd11 : kdk11;
        case 17: return dkd ? dkd17 : kdk17;
        default:
            throw invalid_argument("symplectic corrector of order " + std::to_string(order) +
                                   "; expected 3, 5, 7, 9, 11 or 17");
    }
}

// The weights c_1..c_K of the corrector of order 2K + 1 for any symmetric
// table of plain kicks and drifts (drift = Kepler flow, kick = perturbation),
// e.g. Laskar & Robutel 2001's SABA_n or Blanes et al. 2013's ABA(10,6,4). To
// first order in B such a table is the flow over h of A + f(u) B with
//     f(u) = (u/2) / sinh(u/2) * sum_i b_i cosh((tau_i - 1/2) u),
// b_i the kick weights and tau_i the kicks' times in the step (the sum of the
// drift weights before them): each kick is carried by the Kepler flow to the
// middle of the step (the factor e^((tau_i - 1/2) u), paired into a cosh by the
// symmetry), and the first-order Baker-Campbell-Hausdorff formula joins the
// whole to the Kepler flow over h (the factor (u/2) / sinh(u/2)). For the two
// leapfrogs this is the f of corrector_weights(order, kernel) above; a table
// built for near-integrable systems has f(u) - 1 = O(u^(2n)) (its eps h^(2n)
// term), and the corrector removes the even terms up to u^(2K): the error
// left is O(eps h^(2K+2)) plus the table's own eps^2 terms. The c_i solve the
// same conditions, 4 sum_i c_i a_i^(2k-1) / (2k-1)! = -[u^(2k)] f(u), k = 1..K,
// here by Gaussian elimination in long double (for the leapfrogs it matches the
// tabulated weights to 1e-15 relative; tests/planetary/test_corrector.cpp).
// Orders 3, 5, 7, 9, 11, 17; a table that is not symmetric, or has
// force-gradient kicks, is an invalid_argument.
inline std::vector<coefficient> corrector_weights(int order, const table& method) {
    if (order != 3 && order != 5 && order != 7 && order != 9 && order != 11 && order != 17)
        throw invalid_argument("symplectic corrector of order " + std::to_string(order) +
                               "; expected 3, 5, 7, 9, 11 or 17");
    if (method.has_force_gradient() || !method.is_symmetric())
        throw invalid_argument("symplectic corrector of order " + std::to_string(order) + " with table '" +
                               method.name() + "'" +
                               (method.has_force_gradient() ? " (force-gradient kicks)" : " (not symmetric)") +
                               "; expected a symmetric table of plain kicks and drifts (one that reads the same "
                               "backwards, as leapfrog_kdk, saba_3, blanes_2013_aba_10_6_4)");
    const int K = (order - 1) / 2;
    // [u^(2k)] of sum_i b_i cosh((tau_i - 1/2) u), k = 0..K.
    std::vector<coefficient> kicks(std::size_t(K) + 1, 0), shift(std::size_t(K) + 1, 0), f(std::size_t(K) + 1, 0);
    coefficient tau = 0;
    for (const substep& s : method.substeps()) {
        if (s.kind == substep::drift) {
            tau += s.weight;
            continue;
        }
        const coefficient d = tau - 0.5L;
        coefficient term = s.weight;  // b d^(2k) / (2k)!
        for (int k = 0; k <= K; ++k) {
            kicks[std::size_t(k)] += term;
            term *= d * d / ((2 * k + 1) * (2 * k + 2));
        }
    }
    // [u^(2k)] of (u/2) / sinh(u/2), the reciprocal of sum_n (u/2)^(2n) / (2n + 1)!.
    std::vector<coefficient> series(std::size_t(K) + 1, 0);
    coefficient term = 1;
    for (int n = 0; n <= K; ++n) {
        series[std::size_t(n)] = term;
        term *= 0.25L / ((2 * n + 2) * (2 * n + 3));
    }
    shift[0] = 1;
    for (int n = 1; n <= K; ++n)
        for (int j = 1; j <= n; ++j) shift[std::size_t(n)] -= series[std::size_t(j)] * shift[std::size_t(n - j)];
    for (int k = 0; k <= K; ++k)
        for (int j = 0; j <= k; ++j) f[std::size_t(k)] += kicks[std::size_t(j)] * shift[std::size_t(k - j)];
    // M c = -f_k: M_ki = 4 a_i^(2k-1) / (2k-1)!, a_i = i alpha; partial pivoting.
    std::vector<std::vector<coefficient>> M(std::size_t(K), std::vector<coefficient>(std::size_t(K) + 1));
    for (int k = 1; k <= K; ++k) {
        for (int i = 1; i <= K; ++i) {
            coefficient v = 4;
            for (int m = 1; m <= 2 * k - 1; ++m) v *= corrector_alpha * i / m;
            M[std::size_t(k - 1)][std::size_t(i - 1)] = v;
        }
        M[std::size_t(k - 1)][std::size_t(K)] = -f[std::size_t(k)];
    }
    for (std::size_t c = 0; c < std::size_t(K); ++c) {
        std::size_t pivot = c;
        for (std::size_t r = c + 1; r < std::size_t(K); ++r)
            if (std::fabs(M[r][c]) > std::fabs(M[pivot][c])) pivot = r;
        std::swap(M[c], M[pivot]);
        for (std::size_t r = c + 1; r < std::size_t(K); ++r) {
            const coefficient q = M[r][c] / M[c][c];
            for (std::size_t j = c; j <= std::size_t(K); ++j) M[r][j] -= q * M[c][j];
        }
    }
    std::vector<coefficient> weights(static_cast<std::size_t>(K));
    for (std::size_t c = std::size_t(K); c-- > 0;) {
        coefficient v = M[c][std::size_t(K)];
        for (std::size_t j = c + 1; j < std::size_t(K); ++j) v -= M[c][j] * weights[j];
        weights[c] = v / M[c][c];
    }
    return weights;
}

// The corrector C (direction +1) or its inverse C^-1 (direction -1, every c_i
// negated: Z(a, b)^-1 = Z(-a, b)) for steps of dt, run by `flows` (kepler(t)
// and kick(t) of the splitting), neighbouring drifts joined (Kepler flows add).
template <class Flows, class S>
void apply_corrector(Flows& flows, const std::vector<S>& weights, int direction, S dt) {
    S pending = 0;  // drift time not yet applied
    const auto Z = [&](S a, S b) {
        if (pending + a != S(0)) flows.kepler((pending + a) * dt);
        flows.kick(b * dt);
        flows.kepler(S(-2) * a * dt);
        flows.kick(-b * dt);
        pending = a;
    };
    const S alpha = static_cast<S>(corrector_alpha), s = S(direction);
    for (std::size_t i = weights.size(); i-- > 0;) Z(-alpha * S(i + 1), -s * weights[i]);
    for (std::size_t i = 0; i < weights.size(); ++i) Z(alpha * S(i + 1), s * weights[i]);
    flows.kepler(pending * dt);
}

}  // namespace sympl
