#pragma once
// The Wisdom-Holman splitting of a star and N planets in democratic
// heliocentric coordinates (Wisdom & Holman 1991, Astron. J. 102, 1528, for
// the idea; Duncan, Levison & Lee 1998, Astron. J. 116, 2067, sec. 2, for the
// coordinates and the split), run by any sympl::table.
//
// With heliocentric positions Q_i and barycentric momenta P_i (i = 1..N;
// planetary_coordinates.hpp), Q_0 the centre of mass and P_0 the total
// momentum, M = sum_j m_j, the Hamiltonian of the point masses is
// (Duncan, Levison & Lee 1998, eq. 4-7)
//     H = H_Kepler + H_interaction + H_jump + H_centre,
//     H_Kepler      = sum_i |P_i|^2 / (2 m_i) - G m_0 m_i / |Q_i|
//     H_interaction = - sum_{1 <= i < j} G m_i m_j / |Q_i - Q_j|
//     H_jump        = |sum_i P_i|^2 / (2 m_0)
//     H_centre      = |P_0|^2 / (2 M).
// H_Kepler is N independent Kepler problems about GM = G m_0 (velocity
// v_i = P_i / m_i), solved exactly by kepler_drift_all (kepler_drift.hpp).
// H_interaction (a function of the Q_i alone) is a kick; H_jump (a function
// of the P_i alone) moves every Q_i by the same vector dt sum_j P_j / m_0.
//
// The two commute: {H_interaction, H_jump} = -sum_i F_i . (sum_j P_j) / m_0 = 0
// because the interaction forces F_i are pairwise equal and opposite (sum F_i
// = 0), and the jump moves no Q_i - Q_j. So the flow of
// H_interaction + H_jump over t is exactly the kick by t followed by the jump
// by t, with no splitting error of its own; it is the "kick" of the table.
// (Duncan, Levison & Lee compose jump(h/2) interaction(h/2) Kepler(h)
// interaction(h/2) jump(h/2); by the commutation this is the kick-drift-kick
// leapfrog below, the same map.) H_centre commutes with everything and moves
// Q_0 uniformly; it is applied with each drift.
//
// The roles in a table (table.hpp): drift weights apply to the integrable
// part H_Kepler, kick weights to the perturbation H_interaction + H_jump, as
// Laskar & Robutel 2001 (Celest. Mech. Dyn. Astron. 80, 39) assign A
// (integrable) and B (perturbation) in SABA_n / SBAB_n. With planet masses of
// relative size eps, H_Kepler = O(eps) and the kick O(eps^2), so the leapfrog
// has relative energy error O(eps h^2) and SABA_n / SBAB_n
// O(eps h^(2n) + eps^2 h^2) (Laskar & Robutel 2001). Tables designed for
// T = p^2/2 (RKN) do not keep their extra order here: H_Kepler is not
// quadratic in P, and H_jump is not a function of Q.
//
// State: what the user sees is the inertial layout of
// hamiltonians/outer_solar_system.hpp (q = x_0, y_0, z_0, x_1, ...; p_i = m_i v_i).
// The stepper converts to democratic heliocentric coordinates on the way in
// and back on the way out, and keeps its internal state between calls: when
// step() or steps() is handed exactly the state it returned last, it goes on
// from its internal coordinates (no conversion, no rounding of a round trip,
// and the last interaction forces reused). steps(x, dt, n) also joins a
// step's last sub-step with the next step's first when they are of one kind
// (two kicks, or two Kepler drifts: both flows add), so the leapfrog costs one
// Kepler drift and one interaction evaluation per step.
//
// Symplectic corrector (Wisdom, Holman & Touma 1996, "Symplectic correctors",
// Fields Inst. Commun. 10, 217), for the leapfrog and any symmetric table:
// wisdom_holman_options{.corrector_order = 3, 5, 7, 9, 11 or 17}. Write
// A = H_Kepler, B = H_interaction + H_jump, u = h ad_A (ad_A X = {A, X}). To
// first order in B (Baker-Campbell-Hausdorff), the leapfrog is the exact flow
// over h of
//     A + f(u) B,   f(u) = (u/2) coth(u/2)  kick-drift-kick,  (u/2) / sinh(u/2)  drift-kick-drift,
// and f(u) - 1 = u^2/12 - u^4/720 ... (or -u^2/24 + 7 u^4/5760 ...) is the
// O(eps h^2) error: even powers of ad_A acting on B, all in the range of
// ad_A. So a near-identity canonical map C, the flow over h of g(u) B with
// u g(u) = +-(f(u) - 1) (odd in u), removes them: C (leapfrog) C^-1 is the
// flow over h of A + B + O(eps^2 h^2). C is built of
// the two flows themselves: Z(a, b) = drift(a h) kick(b h) drift(-2a h)
// kick(-b h) drift(a h) is, to first order in B, the flow of
// 2 h b sinh(a u) B (the kick carried along the Kepler flow and back), and
//     C = Z(-a_K, -c_K) ... Z(-a_1, -c_1) Z(a_1, c_1) ... Z(a_K, c_K)
// that of 4 h sum_i c_i sinh(a_i u) B. The a_i = i sqrt(7/40) scale the
// drifts (Kepler flows), the c_i the kicks; corrector_weights() gives c_i
// solving the conditions for u, u^3 .. u^(2K-1), which leaves
// O(eps h^(2K+2) + eps^2 h^2): "order 2K + 1". The sign is settled by
// measurement: with the c_i negated the leapfrog's energy error doubles
// instead of dropping 100-fold (tests/methods/test_wisdom_holman.cpp).
// The stepper applies C^-1 on the way in (after the conversion to democratic
// heliocentric coordinates) and C on the way out, and keeps the uncorrected
// state to go on from: a run in chunks equals one run to rounding. C depends
// on dt: a call with another dt converts the state handed in afresh. Each of
// C and C^-1 costs 4K Kepler drifts and 4K - 1 interaction evaluations, once
// per call of step() or steps(). The corrector changes what the state means
// (the output is corrected), not the run: the long-run error left is
// O(eps^2 h^2), a drift of the mean motions, so positions still converge as h^2.
// Any other symmetric table takes the same C, with the weights solved for its
// own f(u) (corrector_weights(order, table)): its eps h^(2n) terms go, its
// eps^2 terms stay, e.g. O(eps h^(2K+2) + eps^2 h^6 + eps^3 h^4) for Blanes et
// al. 2013's ABA(10,6,4) and ABA(8,6,4), O(eps h^(2K+2) + eps^2 h^2) for SABA_n.
// As C is applied at every return, steps_per_check() asks the drivers of
// integrate.hpp for chunks long enough that it costs under 1/32 of the run.
//
// Kernel (Wisdom, Holman & Touma 1996, sec. on kernels; Rein, Tamayo & Brown
// 2019, MNRAS 489, 4632, sec. on kernel methods, their WHCKC): the corrector
// removes the terms first order in B, the O(eps h^2); what is left, O(eps^2 h^2),
// is second order in B. To third order in h the drift-kick-drift leapfrog is
// the flow of A + B - h^2/24 [A,[A,B]] - h^2/12 [B,[A,B]] ([X,Y] the Lie
// bracket of the flows), and conjugating by C (whose generator is a multiple
// of h^2 [A,B], fixed by cancelling the [A,[A,B]] term) adds +h^2/24 [B,[A,B]]:
// the corrected leapfrog keeps -h^2/24 [B,[A,B]], the same for kick-drift-kick.
// A kernel replaces the middle kick(h) by a map whose generator is
// h B + h^3/24 [B,[A,B]] + O(eps^2 h^5), which cancels it: corrector and
// kernel together leave O(eps h^(2K+2) + eps^2 h^4).
// wisdom_holman_options{.kernel = wh_kernel::composition} builds that map of
// the two flows themselves, with Z(a, b) as for the corrector:
//     Z(a, -b) kick(h) Z(-a, -b),   a = 1/8, b = 1/6,
// i.e. drift(a h) kick(-b h) drift(-2a h) kick(b h) drift(a h) kick(h)
// drift(-a h) kick(-b h) drift(2a h) kick(b h) drift(-a h). The kicks of the
// two Z sit at the same Kepler phases with opposite weights, so to first order
// in B the kernel is kick(h) exactly (the leapfrog's corrector still fits);
// to second order it adds the commutator of Z's generator, -2 b sinh(a u) h B
// ~ -2ab h^2 [A,B], with h B: 2ab = 1/24. The sign is settled by measurement,
// as the corrector's: with b negated the corrected leapfrog's eps^2 h^2 error
// doubles (2.1e-8 against 1.1e-8, corrector 17, eps = 1e-3, h = 2 pi / 40)
// instead of giving way to eps^2 h^4 (4.5e-11). The stepper runs the leapfrog's half
// drifts joined to the kernel's outer drifts, drift(5h/8) ... drift(3h/8), and
// the last joined to the next step's first: 5 Kepler drifts and 5 interaction
// evaluations a step instead of 1 and 1. Only the drift-kick-drift leapfrog
// takes a kernel (the form Wisdom, Holman & Touma and Rein, Tamayo & Brown
// give); anything else is an invalid_argument.
// Not for democratic heliocentric coordinates: the "modified kick" and the
// "lazy implementer's" kernels of the same papers (kick by the gradient of the
// potential {B,{A,B}}, or, Wisdom, Holman & Touma 1996 eq. 10.6 as REBOUND cites it,
// the kick evaluated at positions displaced by h^2/12 times the
// acceleration). Both need B to be a function of the positions alone, as in
// Jacobi coordinates (below); here B holds H_jump, a function of the momenta, and
// {B,{A,B}} has terms in the momenta ({H_jump,{T,H_interaction}} and
// {H_jump,{V_Kepler,H_jump}}) that no kick represents. REBOUND's WHFast
// allows every non-default kernel in Jacobi coordinates only (and correctors
// in Jacobi and barycentric ones): corrector and composition kernel in these
// coordinates are this library's combination, resting on the derivation above
// and on the measurements of tests/methods/test_wisdom_holman.cpp. The composition kernel,
// built of the flows alone, needs nothing of B; its O(B^3) term
// h^4 [B,[B,[A,B]]] (zero when B is a function of the positions alone, not
// here) is O(eps^3 h^3), below eps^2 h^4 while eps < h.
//
// Jacobi coordinates (wisdom_holman_options{.coordinates = wh_coordinates::jacobi};
// Wisdom & Holman 1991, sec. 3; planetary_coordinates.hpp): Q_i the position
// of planet i relative to the centre of mass of the bodies inside it, P_i =
// m'_i dQ_i/dt. The split is H_Kepler = sum_i |P_i|^2 / 2m'_i - G m_0 m_i / |Q_i|
// (planet i about GM_i = G m_0 eta_i / eta_{i-1}) and the rest, a function of
// the positions alone (no jump term), whose accelerations
// jacobi_accelerations() derives. Corrector and composition kernel work as
// above. With B a function of the positions, {B,{A,B}} = sum_i |dB/dQ_i|^2 / m'_i
// (only A's kinetic part counts), and a kick by the gradient of
// B + c h^2 {B,{A,B}} is, to first order in c h^2 (an error O(eps^3 h^4)), the
// kick by B at the positions displaced by -2c h^2 dB/dQ_i / m'_i = 2c h^2 a_i:
// the lazy implementer's kernel (wh_kernel::lazy; Wisdom, Holman & Touma 1996,
// eq. 10.6, as Rein, Tamayo & Brown 2019 and REBOUND's WHFast run it), one
// Kepler drift and two interaction evaluations a step. The kernel needs
// c = 1/24 (the composition kernel's 2ab): displacement h^2/12 along the
// accelerations, the sign settled by measurement as for the others: negated,
// the corrected leapfrog's eps^2 h^2 error doubles (9.4e-9 against 4.7e-9,
// corrector 17, eps = 1e-3, h = 2 pi / 40) instead of giving way to eps^2 h^4
// (3.1e-11).
//
// MEGNO (Cincotta & Simo 2000, A&AS 147, 205): start_megno() puts a tangent
// vector on the planets' coordinates in the stepper; each Kepler drift carries
// it by the drift's exact tangent map (kepler_tangent.hpp), each kick by the
// interaction's Jacobian (the accelerations evaluated on dual numbers,
// dual.hpp; the jump's linear move in democratic heliocentric coordinates; the
// lazy kernel's displaced positions included). So it is the tangent map of the
// method itself, as for the T + V tables (chaos_indicator.hpp), and <Y> is
// sampled every step. tests/methods/test_wisdom_holman.cpp checks the tangent
// against differences of two runs (1e-9 relative) and <Y> on quasi-periodic
// and chaotic orbits.
//
// Bad input is an invalid_argument naming the body: a non-positive or
// non-finite mass, a non-finite coordinate, a planet at the star's position or
// two planets at one position. A state that becomes non-finite during a run
// (a blow-up) is returned as non-finite, as splitting_stepper does, for the
// drivers of integrate.hpp to report.
//
// Not done: the modified-kick kernel (the exact gradient of {B,{A,B}}), close encounters, Laskar & Robutel 2001's corrector term
// of SABA_n (a kick by {{A,B},B} against eps^2 h^2), a kernel for the
// kick-drift-kick leapfrog, Rein, Tamayo & Brown 2019's second corrector (for
// the eps^2 h^4 term left with a kernel).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "../analysis/chaos_indicator.hpp"
#include "../core/dual.hpp"
#include "../core/error.hpp"
#include "../core/phase_space.hpp"
#include "../core/table.hpp"
#include "kepler_drift.hpp"
#include "kepler_tangent.hpp"
#include "planetary_coordinates.hpp"

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
// (the header comment of wisdom_holman_stepper derives this). Orders 3, 5, 7,
// 9, 11, 17; anything else is an invalid_argument.
inline std::vector<coefficient> corrector_weights(int order, leapfrog_kernel kernel) {
    // Drift-kick-drift: Wisdom, Holman & Touma 1996 (Fields Inst. Commun. 10,
    // 217), orders 3 to 11, and order 17 as tabulated with them in REBOUND's
    // WHFast (Rein & Tamayo 2015, MNRAS 452, 376; Rein, Tamayo & Brown 2019,
    // MNRAS 489, 4632), listed there last node first; the third-order weight
    // is listed there with the opposite sign, here in the convention of the
    // others. Order 9 is not in that list: derived here
    // from the conditions above, as are all the kick-drift-kick weights.
    // tests/methods/test_wisdom_holman.cpp checks every set against the conditions.
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
// tabulated weights to 1e-15 relative; tests/methods/test_wisdom_holman.cpp).
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

// What stands between the drift-kick-drift leapfrog's two half drifts (see the
// header comment of wisdom_holman_stepper): the leapfrog's own kick, or Wisdom,
// Holman & Touma 1996's composition kernel, or their "lazy implementer's"
// kernel (Jacobi coordinates only).
enum class wh_kernel { kick, composition, lazy };

// The coordinates of the splitting: democratic heliocentric (Duncan, Levison
// & Lee 1998) or Jacobi (Wisdom & Holman 1991).
enum class wh_coordinates { democratic_heliocentric, jacobi };

inline std::string coordinates_name(wh_coordinates c) {
    switch (c) {
        case wh_coordinates::democratic_heliocentric: return "democratic_heliocentric";
        case wh_coordinates::jacobi: return "jacobi";
    }
    return "unknown (" + std::to_string(int(c)) + ")";
}

inline std::string kernel_name(wh_kernel k) {
    switch (k) {
        case wh_kernel::kick: return "kick";
        case wh_kernel::composition: return "composition";
        case wh_kernel::lazy: return "lazy";
    }
    return "unknown (" + std::to_string(int(k)) + ")";
}

// The composition kernel's two weights, a of the Kepler drifts and b of the
// side kicks, in units of the step: the kernel of Wisdom, Holman & Touma 1996
// (Fields Inst. Commun. 10, 217) with the sub-steps and weights of Rein,
// Tamayo & Brown 2019's WHCKC (MNRAS 489, 4632) as REBOUND's WHFast runs it
// (kernel "composition"). Only 2ab = 1/24 is forced by the theory.
inline constexpr coefficient composition_kernel_drift = 1.0L / 8;  // a (Kepler drifts), WHT96 / RTB2019
inline constexpr coefficient composition_kernel_kick = 1.0L / 6;   // b (kicks), WHT96 / RTB2019

// The lazy implementer's kernel: the kick(h) by the interaction at the
// positions displaced by this times h^2 times the interaction's acceleration
// (Wisdom, Holman & Touma 1996, eq. 10.6 as Rein, Tamayo & Brown 2019 cite
// it): to first order in the displacement the kick by the gradient of
// B + h^2/24 {B,{A,B}} (see the stepper's header comment; the sign by measurement).
inline constexpr coefficient lazy_kernel_displacement = 1.0L / 12;

// The kernel's sub-steps in place of kick(h), in time order, weights in units
// of h: Z(a, -b) kick(1) Z(-a, -b), Z(a, b) = drift(a) kick(b) drift(-2a) kick(-b) drift(a).
// The lazy kernel is one kick(1), which the stepper takes at displaced positions.
inline std::vector<substep> kernel_substeps(wh_kernel k) {
    if (k == wh_kernel::kick || k == wh_kernel::lazy) return {{substep::kick, 1}};
    if (k != wh_kernel::composition)
        throw invalid_argument("Wisdom-Holman kernel " + kernel_name(k) + "; expected kick, composition or lazy");
    const coefficient a = composition_kernel_drift, b = composition_kernel_kick;
    const auto Z = [](coefficient x, coefficient y) {
        return std::vector<substep>{{substep::drift, x}, {substep::kick, y}, {substep::drift, -2 * x},
                                    {substep::kick, -y}, {substep::drift, x}};
    };
    std::vector<substep> ops = Z(a, -b);
    ops.push_back({substep::kick, 1});
    for (const substep& o : Z(-a, -b)) ops.push_back(o);
    return ops;
}

// Options of wisdom_holman_stepper.
struct wisdom_holman_options {
    // 0: none; 3, 5, 7, 9, 11 or 17: the symplectic corrector of that order
    // (symmetric tables; corrector_weights).
    int corrector_order = 0;
    // The drift-kick-drift leapfrog's kernel; wh_kernel::composition with a
    // corrector leaves O(eps h^(2K+2) + eps^2 h^4) (leapfrog_dkd only).
    // wh_kernel::lazy: the same in Jacobi coordinates at one Kepler drift and
    // two interaction evaluations a step.
    wh_kernel kernel = wh_kernel::kick;
    wh_coordinates coordinates = wh_coordinates::democratic_heliocentric;
};

// What one Wisdom-Holman step of `method` with `options` runs: its sub-steps
// (the kernel in place of the leapfrog's kick) and its corrector's weights.
// An invalid_argument, starting with `who`, when they do not fit: a
// force-gradient table, a corrector or kernel on a table that is not the
// leapfrog (the kernel: drift-kick-drift only), an order or kernel unknown.
// The stepper's constructor and the program (before a run) both ask it.
struct wisdom_holman_plan {
    std::vector<substep> substeps;
    std::vector<coefficient> corrector;  // c_1..c_K, empty without a corrector
    bool lazy_kernel = false;            // the kick of weight 1 is the lazy kernel's
};

inline wisdom_holman_plan plan_wisdom_holman(const table& method, const wisdom_holman_options& options,
                                             const std::string& who) {
    const std::string prefix = who + ": ";
    if (options.coordinates != wh_coordinates::democratic_heliocentric && options.coordinates != wh_coordinates::jacobi)
        throw invalid_argument(prefix + "coordinates " + coordinates_name(options.coordinates) +
                               "; expected democratic_heliocentric or jacobi");
    if (method.has_force_gradient())
        throw invalid_argument(prefix + "table '" + method.name() +
                               "' has force-gradient kicks; expected a table of plain kicks and drifts");
    wisdom_holman_plan plan{method.substeps(), {}};
    const auto& ops = plan.substeps;
    const auto is = [&](substep::kind_t outer) {
        return ops.size() == 3 && ops[0].kind == outer && ops[0].weight == 0.5L && ops[1].weight == 1 &&
               ops[2].weight == 0.5L;
    };
    if (options.corrector_order != 0) {
        // The corrector undoes a table's error terms first order in the
        // perturbation (see the stepper's header comment): the leapfrogs'
        // weights are tabulated, any other symmetric table's solved for.
        try {
            if (is(substep::kick) || is(substep::drift))
                plan.corrector = corrector_weights(options.corrector_order, is(substep::kick)
                                                                                ? leapfrog_kernel::kick_drift_kick
                                                                                : leapfrog_kernel::drift_kick_drift);
            else
                plan.corrector = corrector_weights(options.corrector_order, method);
        } catch (const invalid_argument& e) {
            throw invalid_argument(prefix + e.what());
        }
    }
    if (options.kernel != wh_kernel::kick) {
        // The kernel replaces the middle kick of drift(h/2) kick(h) drift(h/2).
        const std::string kernel = "kernel " + kernel_name(options.kernel);
        if (options.kernel != wh_kernel::composition && options.kernel != wh_kernel::lazy)
            throw invalid_argument(prefix + kernel + "; expected kick, composition or lazy");
        if (options.kernel == wh_kernel::lazy && options.coordinates != wh_coordinates::jacobi)
            throw invalid_argument(prefix + kernel + " in " + coordinates_name(options.coordinates) +
                                   " coordinates; expected coordinates jacobi (the kernel needs an interaction "
                                   "that is a function of the positions alone)");
        if (!is(substep::drift))
            throw invalid_argument(prefix + kernel + " with table '" + method.name() +
                                   "'; expected the drift-kick-drift leapfrog with weights 1/2, 1, 1/2 "
                                   "(leapfrog_dkd, saba_1)");
        std::vector<substep> with_kernel{{substep::drift, 0.5L}};
        for (const substep& o : kernel_substeps(options.kernel)) with_kernel.push_back(o);
        with_kernel.push_back({substep::drift, 0.5L});
        plan.substeps = detail::canonical(with_kernel);  // drift(5/8) ... drift(3/8)
        plan.lazy_kernel = options.kernel == wh_kernel::lazy;
    }
    return plan;
}

template <class State>
    requires phase_space_state<State> && std::is_floating_point_v<typename State::scalar>
class wisdom_holman_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    // The tangent vector rides as the derivative part of these (MEGNO).
    using tangent_scalar = dual<scalar, 1>;

    // mass[0] is the star, mass[1..N] the planets (all finite and > 0), G > 0.
    wisdom_holman_stepper(std::vector<double> mass, double G, table method, wisdom_holman_options options = {})
        : mass_(std::move(mass)), G_(G), table_(std::move(method)), options_(options) {
        const std::string who = "wisdom_holman_stepper: ";
        if (mass_.size() < 2)
            throw invalid_argument(who + std::to_string(mass_.size()) +
                                   " masses; expected a star and at least one planet");
        for (std::size_t i = 0; i < mass_.size(); ++i)
            if (!(std::isfinite(mass_[i]) && mass_[i] > 0))
                throw invalid_argument(who + "mass of body " + std::to_string(i) + " = " +
                                       detail::number_text(mass_[i]) + "; expected a finite mass > 0");
        if (!(std::isfinite(G_) && G_ > 0))
            throw invalid_argument(who + "G = " + detail::number_text(G_) + "; expected a finite G > 0");
        if (State::dimension != Eigen::Dynamic && std::size_t(State::dimension) != 3 * mass_.size())
            throw invalid_argument(who + std::to_string(mass_.size()) + " masses for a state of fixed dimension " +
                                   std::to_string(State::dimension) + "; expected 3 degrees of freedom per body");
        const wisdom_holman_plan plan = plan_wisdom_holman(table_, options_, "wisdom_holman_stepper");
        ops_ = plan.substeps;
        lazy_ = plan.lazy_kernel;
        jacobi_ = options_.coordinates == wh_coordinates::jacobi;
        for (coefficient w : plan.corrector) corrector_weights_.push_back(static_cast<scalar>(w));
        for (const substep& o : ops_) weights_.push_back(static_cast<scalar>(o.weight));
        joined_weight_ = static_cast<scalar>(ops_.back().weight + ops_.front().weight);
        joined_ = ops_.size() > 1 && ops_.front().kind == ops_.back().kind;
        const std::size_t n = mass_.size() - 1;
        for (auto* v : {&x_, &y_, &z_, &vx_, &vy_, &vz_, &ax_, &ay_, &az_, &kept_x_, &kept_y_, &kept_z_}) v->assign(n, scalar(0));
        total_mass_ = 0;
        for (double m : mass_) total_mass_ += scalar(m);
        gm_ = scalar(G_) * scalar(mass_[0]);
        if (jacobi_) {
            // Jacobi: planet i's Kepler problem is -G m_0 m_i / |Q_i| with mass
            // m'_i = m_i eta_{i-1} / eta_i, i.e. about GM_i = G m_0 eta_i / eta_{i-1}
            // (Wisdom & Holman 1991, eq. 10-11).
            const std::vector<double> eta = interior_masses(mass_), jm = jacobi_masses(mass_);
            for (std::size_t i = 1; i < mass_.size(); ++i) {
                eta_.push_back(scalar(eta[i - 1]));  // eta_{i-1}, the mass inside planet i
                jacobi_mass_.push_back(scalar(jm[i]));
                gm_body_.push_back(scalar(G_) * scalar(mass_[0]) * (scalar(eta[i]) / scalar(eta[i - 1])));
            }
            scratch_.resize(mass_.size());
            tangent_scratch_.resize(mass_.size());
        }
        for (auto* v : {&dx_, &dy_, &dz_, &dvx_, &dvy_, &dvz_}) v->assign(n, scalar(0));
        for (int c = 0; c < 3; ++c) tq_[std::size_t(c)].assign(n, tangent_scalar(0)), ta_[std::size_t(c)] = tq_[std::size_t(c)];
    }

    // One step of size dt (dt < 0 runs backwards).
    void step(State& x, scalar dt) { steps(x, dt, 1); }

    // n steps of size dt, converted in and out once; a step's last sub-step
    // is joined with the next one's first when they are of one kind.
    void steps(State& x, scalar dt, std::size_t n) {
        if (!std::isfinite(dt) || dt == scalar(0))
            throw invalid_argument("wisdom_holman_stepper: dt = " + detail::number_text(dt) +
                                   "; expected a finite, non-zero step");
        load(x, dt);
        const std::size_t L = ops_.size();
        // With MEGNO on, every step ends at its own end, where it is sampled.
        const bool join = joined_ && !megno_on_;
        for (std::size_t k = 0; k < n && finite_; ++k) {
            for (std::size_t j = 0; j < L && finite_; ++j) {
                if (join && k > 0 && j == 0) continue;  // done with the previous step's last sub-step
                const scalar w = (join && j == L - 1 && k + 1 < n) ? joined_weight_ : weights_[j];
                if (ops_[j].kind == substep::kick) {
                    if (lazy_) lazy_kick(w * dt, dt);
                    else kick(w * dt);
                } else {
                    drift(w * dt);
                }
            }
            if (megno_on_ && finite_) sample_megno(dt);
        }
        store(x, dt);
    }

    // Batched Kepler drifts of all planets (one per drift sub-step), and
    // evaluations of the planet-planet interaction.
    std::uint64_t kepler_drifts() const { return kepler_drifts_; }
    std::uint64_t interaction_evaluations() const { return interaction_evaluations_; }
    // The drivers' name (integrate.hpp) for the interaction evaluations.
    std::uint64_t force_evaluations() const { return interaction_evaluations_; }
    // Planets the batched drift left to its scalar solve (kepler_drift_all).
    std::uint64_t kepler_fallbacks() const { return kepler_fallbacks_; }
    void reset_counters() { kepler_drifts_ = interaction_evaluations_ = kepler_fallbacks_ = 0; }

    // MEGNO (Cincotta & Simo 2000; chaos_indicator.hpp) from now on: a
    // tangent vector of the planets' coordinates in the stepper (heliocentric
    // or Jacobi positions and velocities, (dQ_1, dv_1, ..., dQ_N, dv_N), 6N
    // numbers) rides along every Kepler drift (kepler_drift_tangent) and every
    // kick (the interaction's Jacobian, by dual numbers), and ln|tangent| is
    // sampled at the end of every step, at the time since the start. The
    // corrector's C, a change of coordinates, is left out; the centre of mass
    // too. `tangent` empty: every component 1 / sqrt(6N). While it is on,
    // steps() joins no sub-steps across steps (a step ends where it is sampled),
    // and the tangent's work is not counted in the counters.
    void start_megno(std::span<const scalar> tangent = {}) {
        const std::size_t n = planets();
        if (!tangent.empty() && tangent.size() != 6 * n)
            throw invalid_argument("wisdom_holman_stepper::start_megno: " + std::to_string(tangent.size()) +
                                   " tangent components for " + std::to_string(n) +
                                   " planets; expected 6 per planet (dQ, dv), " + std::to_string(6 * n));
        scalar norm2 = 0;
        for (std::size_t i = 0; i < n; ++i) {
            scalar* parts[] = {&dx_[i], &dy_[i], &dz_[i], &dvx_[i], &dvy_[i], &dvz_[i]};
            for (std::size_t c = 0; c < 6; ++c) {
                *parts[c] = tangent.empty() ? scalar(1) / std::sqrt(scalar(6 * n)) : tangent[6 * i + c];
                norm2 += *parts[c] * *parts[c];
            }
        }
        if (!(norm2 > 0) || !std::isfinite(norm2))
            throw invalid_argument("wisdom_holman_stepper::start_megno: |tangent|^2 = " + detail::number_text(norm2) +
                                   "; expected a finite, non-zero tangent vector");
        megno_ = megno_accumulator<scalar>{};
        megno_.last_log_norm = std::log(norm2) / 2;
        megno_time_ = 0;
        log_scale_ = 0;
        megno_on_ = true;
    }
    void stop_megno() { megno_on_ = false; }
    // <Y> over the steps since start_megno (NaN before the first), and Y at the last.
    scalar megno() const { return megno_.mean(); }
    scalar megno_y() const { return megno_.y; }
    // The tangent vector, (dQ_1, dv_1, ..., dQ_N, dv_N), in units of exp(log_scale)
    // (the stepper rescales it when it grows past 1e100).
    std::vector<scalar> tangent() const {
        std::vector<scalar> t;
        for (std::size_t i = 0; i < planets(); ++i)
            for (scalar c : {dx_[i], dy_[i], dz_[i], dvx_[i], dvy_[i], dvz_[i]}) t.push_back(c);
        return t;
    }
    scalar tangent_log_scale() const { return log_scale_; }

    // Steps per call the drivers of integrate.hpp should take at least: C
    // (4K Kepler drifts and 4K - 1 interactions) is applied at every return,
    // so chunks of 32 (8K / sub-steps per step) steps keep it under 1/32 of
    // the run; 1 without a corrector.
    std::size_t steps_per_check() const {
        const std::size_t per_step = std::max<std::size_t>(1, ops_.size() - (joined_ ? 1 : 0));
        return corrector_weights_.empty() ? 1 : 32 * 8 * corrector_weights_.size() / per_step + 1;
    }

    const table& method() const { return table_; }
    const wisdom_holman_options& options() const { return options_; }
    const std::vector<double>& masses() const { return mass_; }
    double G() const { return G_; }

private:
    std::size_t planets() const { return mass_.size() - 1; }

    // a_i = sum_{j != i} G m_j (r_j - r_i) / |r_j - r_i|^3 over n bodies of
    // masses m[0..n), for any scalar T (double, or a dual number for the
    // tangent map).
    template <class T>
    void pair_accelerations(std::size_t n, const T* x, const T* y, const T* z, const double* m, T* ax, T* ay,
                            T* az) const {
        using std::sqrt;
        for (std::size_t i = 0; i < n; ++i) ax[i] = ay[i] = az[i] = T(0);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t j = i + 1; j < n; ++j) {
                const T dx = x[j] - x[i], dy = y[j] - y[i], dz = z[j] - z[i];
                const T r2 = dx * dx + dy * dy + dz * dz;
                const T k = scalar(G_) / (r2 * sqrt(r2));
                const T ki = k * scalar(m[j]), kj = k * scalar(m[i]);
                ax[i] += ki * dx, ay[i] += ki * dy, az[i] += ki * dz;
                ax[j] -= kj * dx, ay[j] -= kj * dy, az[j] -= kj * dz;
            }
    }

    // All bodies' positions (less X_N) and accelerations, for the Jacobi kick.
    template <class T>
    struct bodies_scratch {
        std::vector<T> x, y, z, ax, ay, az;
        void resize(std::size_t n) {
            for (auto* v : {&x, &y, &z, &ax, &ay, &az}) v->assign(n, T(0));
        }
    };

    // The interaction accelerations at planet positions (x, y, z): democratic
    // heliocentric, the planets' pairs (pair_accelerations); Jacobi, as below.
    //
    // Jacobi coordinates (Wisdom & Holman 1991): with H_Kepler = sum_i
    // |P_i|^2 / 2m'_i - G m_0 m_i / |Q_i|, the rest H_interaction = V(x) +
    // sum_i G m_0 m_i / |Q_i|, V the potential of all pairs (the star's
    // included), is a function of the positions alone. x_j = X_N + (eta_{j-1}
    // / eta_j) Q_j - sum_{k > j} (m_k / eta_k) Q_k (from_jacobi), so
    // dV/dQ_i = (eta_{i-1} / eta_i) dV/dx_i - (m_i / eta_i) sum_{j < i} dV/dx_j,
    // and with dV/dx_j = -m_j a_j (a_j the inertial accelerations of all
    // pairs), divided by m'_i:
    //     a'_i = a_i - sum_{j < i} m_j a_j / eta_{i-1} + G M_i Q_i / |Q_i|^3,   GM_i = G m_0 eta_i / eta_{i-1}
    // (the last term the Kepler part's, which cancels a_i's pull of the
    // interior masses to leading order).
    template <class T>
    void interaction(const T* x, const T* y, const T* z, T* ax, T* ay, T* az, bodies_scratch<T>& b) const {
        using std::sqrt;
        const std::size_t n = planets();
        if (!jacobi_) return pair_accelerations(n, x, y, z, mass_.data() + 1, ax, ay, az);
        T X(0), Y(0), Z(0);  // X_{j-1} - X_N, from the outside in
        for (std::size_t j = n; j-- > 0;) {
            const scalar w = scalar(mass_[j + 1]) / (eta_[j] + scalar(mass_[j + 1]));
            X -= w * x[j], Y -= w * y[j], Z -= w * z[j];
            b.x[j + 1] = x[j] + X, b.y[j + 1] = y[j] + Y, b.z[j + 1] = z[j] + Z;
        }
        b.x[0] = X, b.y[0] = Y, b.z[0] = Z;
        pair_accelerations(n + 1, b.x.data(), b.y.data(), b.z.data(), mass_.data(), b.ax.data(), b.ay.data(),
                           b.az.data());
        T sx = scalar(mass_[0]) * b.ax[0], sy = scalar(mass_[0]) * b.ay[0], sz = scalar(mass_[0]) * b.az[0];
        for (std::size_t i = 0; i < n; ++i) {
            const T r2 = x[i] * x[i] + y[i] * y[i] + z[i] * z[i];
            const T k = gm_body_[i] / (r2 * sqrt(r2));
            const scalar inner = 1 / eta_[i];
            ax[i] = b.ax[i + 1] - sx * inner + k * x[i];
            ay[i] = b.ay[i + 1] - sy * inner + k * y[i];
            az[i] = b.az[i + 1] - sz * inner + k * z[i];
            const scalar m(mass_[i + 1]);
            sx += m * b.ax[i + 1], sy += m * b.ay[i + 1], sz += m * b.az[i + 1];
        }
    }

    void accelerations() {
        interaction(x_.data(), y_.data(), z_.data(), ax_.data(), ay_.data(), az_.data(), scratch_);
        ++interaction_evaluations_;
        forces_fresh_ = true;
    }

    // The tangent's change of velocity over a kick of t, J dQ t with J the
    // interaction's Jacobian at the positions (or, lazy: at the displaced
    // positions, along the displaced tangent), from the dual numbers'
    // derivative parts; into tx, ty, tz.
    void tangent_kick(scalar t, scalar lazy_h) {
        const std::size_t n = planets();
        for (std::size_t i = 0; i < n; ++i) {
            tq_[0][i] = tangent_dual(x_[i], dx_[i]);
            tq_[1][i] = tangent_dual(y_[i], dy_[i]);
            tq_[2][i] = tangent_dual(z_[i], dz_[i]);
        }
        interaction(tq_[0].data(), tq_[1].data(), tq_[2].data(), ta_[0].data(), ta_[1].data(), ta_[2].data(),
                    tangent_scratch_);
        if (lazy_h != scalar(0)) {
            const scalar d = static_cast<scalar>(lazy_kernel_displacement) * lazy_h * lazy_h;
            for (int c = 0; c < 3; ++c)
                for (std::size_t i = 0; i < n; ++i) tq_[std::size_t(c)][i] += d * ta_[std::size_t(c)][i];
            interaction(tq_[0].data(), tq_[1].data(), tq_[2].data(), ta_[0].data(), ta_[1].data(), ta_[2].data(),
                        tangent_scratch_);
        }
        for (std::size_t i = 0; i < n; ++i)
            dvx_[i] += t * ta_[0][i].grad[0], dvy_[i] += t * ta_[1][i].grad[0], dvz_[i] += t * ta_[2][i].grad[0];
    }

    static tangent_scalar tangent_dual(scalar value, scalar change) {
        tangent_scalar d(value);
        d.grad[0] = change;
        return d;
    }

    bool tangent_on() const { return megno_on_ && !tangent_paused_; }

    // One MEGNO sample at the end of a step of dt.
    void sample_megno(scalar dt) {
        scalar norm2 = 0;
        for (std::size_t i = 0; i < planets(); ++i)
            for (scalar c : {dx_[i], dy_[i], dz_[i], dvx_[i], dvy_[i], dvz_[i]}) norm2 += c * c;
        megno_time_ += dt;
        megno_.add(megno_time_, log_scale_ + std::log(norm2) / 2);
        if (norm2 > scalar(1e200) || norm2 < scalar(1e-200)) {  // rescaled, the growth kept in log_scale_
            const scalar f = 1 / std::sqrt(norm2);
            for (auto* v : {&dx_, &dy_, &dz_, &dvx_, &dvy_, &dvz_})
                for (scalar& c : *v) c *= f;
            log_scale_ += std::log(norm2) / 2;
        }
    }

    // The lazy implementer's kernel in place of the leapfrog's kick(t) (t the
    // kick's time, h the step): the kick by the accelerations at the positions
    // moved by lazy_kernel_displacement h^2 times the accelerations there.
    void lazy_kick(scalar t, scalar h) {
        if (tangent_on()) tangent_kick(t, h);
        if (!forces_fresh_) accelerations();
        const std::size_t n = planets();
        const scalar d = static_cast<scalar>(lazy_kernel_displacement) * h * h;
        for (std::size_t i = 0; i < n; ++i) {
            kept_x_[i] = x_[i], kept_y_[i] = y_[i], kept_z_[i] = z_[i];
            x_[i] += d * ax_[i], y_[i] += d * ay_[i], z_[i] += d * az_[i];
        }
        accelerations();
        for (std::size_t i = 0; i < n; ++i) {
            x_[i] = kept_x_[i], y_[i] = kept_y_[i], z_[i] = kept_z_[i];
            vx_[i] += t * ax_[i], vy_[i] += t * ay_[i], vz_[i] += t * az_[i];
        }
        forces_fresh_ = false;  // they are the displaced positions'
    }

    // The flow of H_interaction + H_jump over t: kick, then jump (they commute).
    // In Jacobi coordinates there is no jump.
    void kick(scalar t) {
        const std::size_t n = planets();
        if (tangent_on()) {
            tangent_kick(t, 0);
            if (!jacobi_) {  // the jump: dQ_i += t sum_j m_j dv_j / m_0
                scalar px = 0, py = 0, pz = 0;
                for (std::size_t i = 0; i < n; ++i) {
                    const scalar m(mass_[i + 1]);
                    px += m * dvx_[i], py += m * dvy_[i], pz += m * dvz_[i];
                }
                const scalar s = t / scalar(mass_[0]);
                for (std::size_t i = 0; i < n; ++i) dx_[i] += s * px, dy_[i] += s * py, dz_[i] += s * pz;
            }
        }
        if (!forces_fresh_) accelerations();
        if (jacobi_) {
            for (std::size_t i = 0; i < n; ++i) vx_[i] += t * ax_[i], vy_[i] += t * ay_[i], vz_[i] += t * az_[i];
            return;
        }
        scalar px = 0, py = 0, pz = 0;
        for (std::size_t i = 0; i < n; ++i) {
            vx_[i] += t * ax_[i], vy_[i] += t * ay_[i], vz_[i] += t * az_[i];
            const scalar m(mass_[i + 1]);
            px += m * vx_[i], py += m * vy_[i], pz += m * vz_[i];
        }
        const scalar s = t / scalar(mass_[0]);
        for (std::size_t i = 0; i < n; ++i) x_[i] += s * px, y_[i] += s * py, z_[i] += s * pz;
        // The jump keeps every Q_i - Q_j (to rounding): the forces stay fresh.
    }

    // The flow of H_Kepler + H_centre over t.
    void drift(scalar t) {
        kepler(t);
        centre_ += (t / total_mass_) * momentum_;
    }

    // The flow of H_Kepler over t.
    void kepler(scalar t) {
        if (tangent_on() && finite_) {
            for (std::size_t i = 0; i < planets(); ++i) {
                const scalar r[3] = {x_[i], y_[i], z_[i]}, v[3] = {vx_[i], vy_[i], vz_[i]};
                scalar dr[3] = {dx_[i], dy_[i], dz_[i]}, dv[3] = {dvx_[i], dvy_[i], dvz_[i]};
                try {
                    kepler_drift_tangent(r, v, dr, dv, jacobi_ ? gm_body_[i] : gm_, t);
                } catch (const invalid_argument&) {
                    for (int c = 0; c < 3; ++c) dr[c] = dv[c] = std::numeric_limits<scalar>::quiet_NaN();
                }
                dx_[i] = dr[0], dy_[i] = dr[1], dz_[i] = dr[2], dvx_[i] = dv[0], dvy_[i] = dv[1], dvz_[i] = dv[2];
            }
        }
        try {
            if (jacobi_)
                kepler_fallbacks_ += kepler_drift_all<scalar>({x_, y_, z_, vx_, vy_, vz_}, std::span<const scalar>(gm_body_), t);
            else
                kepler_fallbacks_ += kepler_drift_all<scalar>({x_, y_, z_, vx_, vy_, vz_}, gm_, t);
        } catch (const invalid_argument&) {
            // Only a state gone non-finite (or a planet driven into the star)
            // gets here: hand back a non-finite state, as a blow-up.
            finite_ = false;
            for (auto* v : {&x_, &y_, &z_, &vx_, &vy_, &vz_}) v->assign(planets(), std::numeric_limits<scalar>::quiet_NaN());
        }
        ++kepler_drifts_;
        forces_fresh_ = false;
    }

    static bool same(const State& a, const State& b) {
        return a.size() == b.size() && (a.q.array() == b.q.array()).all() && (a.p.array() == b.p.array()).all();
    }

    void check(const State& x) const {
        const std::string who = "wisdom_holman_stepper: ";
        const std::size_t bodies = mass_.size();
        if (std::size_t(x.size()) != 3 * bodies)
            throw invalid_argument(who + "a state of " + std::to_string(x.size()) + " degrees of freedom for " +
                                   std::to_string(bodies) + " bodies; expected 3 per body, " +
                                   std::to_string(3 * bodies));
        const char* axis[] = {"x", "y", "z"};
        for (std::size_t i = 0; i < bodies; ++i)
            for (int k = 0; k < 3; ++k) {
                const Eigen::Index c = Eigen::Index(3 * i) + k;
                if (!std::isfinite(x.q[c]))
                    throw invalid_argument(who + "position " + axis[k] + " of body " + std::to_string(i) + " = " +
                                           detail::number_text(x.q[c]) + "; expected a finite number");
                if (!std::isfinite(x.p[c]))
                    throw invalid_argument(who + "momentum " + axis[k] + " of body " + std::to_string(i) + " = " +
                                           detail::number_text(x.p[c]) + "; expected a finite number");
            }
        for (std::size_t i = 1; i < bodies; ++i)
            for (std::size_t j = 0; j < i; ++j) {
                const auto d = (x.q.template segment<3>(Eigen::Index(3 * i)) - x.q.template segment<3>(Eigen::Index(3 * j))).eval();
                if (!(d.squaredNorm() > 0))
                    throw invalid_argument(who + "body " + std::to_string(i) + " is at the position of body " +
                                           std::to_string(j) + (j == 0 ? " (the star)" : "") + ", (" +
                                           detail::number_text(x.q[Eigen::Index(3 * i)]) + ", " +
                                           detail::number_text(x.q[Eigen::Index(3 * i) + 1]) + ", " +
                                           detail::number_text(x.q[Eigen::Index(3 * i) + 2]) +
                                           "); expected distinct positions");
            }
    }

    // The corrector C (direction +1) or its inverse C^-1 (direction -1) for
    // steps of dt, on the planets' state (the centre of mass is left alone:
    // H_centre commutes with everything and C's drifts add up to zero):
    //     C = Z(-a_K, -c_K) ... Z(-a_1, -c_1) Z(a_1, c_1) ... Z(a_K, c_K)   (applied left first)
    //     Z(a, b) = drift(a dt) kick(b dt) drift(-2a dt) kick(-b dt) drift(a dt).
    // Z(a, b)^-1 = Z(-a, b), so C^-1 is C with every c_i negated. Neighbouring
    // drifts are joined (Kepler flows add).
    void correct(int direction, scalar dt) {
        // C is a change of coordinates, not part of the run: the tangent stays.
        const bool paused = tangent_paused_;
        tangent_paused_ = true;
        const std::size_t K = corrector_weights_.size();
        scalar pending = 0;  // drift time not yet applied
        const auto Z = [&](scalar a, scalar b) {
            if (pending + a != scalar(0)) kepler((pending + a) * dt);
            kick(b * dt);
            kepler(scalar(-2) * a * dt);
            kick(-b * dt);
            pending = a;
        };
        const scalar alpha = static_cast<scalar>(corrector_alpha), s = scalar(direction);
        for (std::size_t i = K; i-- > 0;) Z(-alpha * scalar(i + 1), -s * corrector_weights_[i]);
        for (std::size_t i = 0; i < K; ++i) Z(alpha * scalar(i + 1), s * corrector_weights_[i]);
        kepler(pending * dt);
        tangent_paused_ = paused;
    }

    // Inertial -> democratic heliocentric, unless x is what this stepper
    // returned last (and, with a corrector, for steps of the same dt), then
    // C^-1 into the leapfrog's coordinates.
    void load(const State& x, scalar dt) {
        if (loaded_ && same(x, last_) && (corrector_weights_.empty() || dt == corrected_dt_)) return;
        check(x);
        const State y = jacobi_ ? to_jacobi(x, std::span<const double>(mass_))
                                : to_democratic_heliocentric(x, std::span<const double>(mass_));
        for (std::size_t i = 0; i < planets(); ++i) {
            const Eigen::Index c = Eigen::Index(3 * (i + 1));
            const scalar m = jacobi_ ? jacobi_mass_[i] : scalar(mass_[i + 1]);
            x_[i] = y.q[c], y_[i] = y.q[c + 1], z_[i] = y.q[c + 2];
            vx_[i] = y.p[c] / m, vy_[i] = y.p[c + 1] / m, vz_[i] = y.p[c + 2] / m;
        }
        centre_ = y.q.template segment<3>(0);
        momentum_ = y.p.template segment<3>(0);
        forces_fresh_ = false;
        finite_ = true;
        loaded_ = true;
        if (!corrector_weights_.empty()) {
            correct(-1, dt);
            corrected_dt_ = dt;
        }
    }

    std::array<std::vector<scalar>*, 9> planet_arrays() { return {&x_, &y_, &z_, &vx_, &vy_, &vz_, &ax_, &ay_, &az_}; }

    // C out of the leapfrog's coordinates, democratic heliocentric -> inertial,
    // into x; x is remembered for the next call, the leapfrog's uncorrected
    // state kept to go on from.
    void store(State& x, scalar dt) {
        std::vector<scalar> kept[9];
        const bool fresh = forces_fresh_;
        const bool corrected = !corrector_weights_.empty() && finite_;
        if (corrected) {
            for (int k = 0; k < 9; ++k) kept[k] = *planet_arrays()[k];
            correct(+1, dt);
        }
        State y = x;
        y.q.template segment<3>(0) = centre_;
        y.p.template segment<3>(0) = momentum_;
        for (std::size_t i = 0; i < planets(); ++i) {
            const Eigen::Index c = Eigen::Index(3 * (i + 1));
            const scalar m = jacobi_ ? jacobi_mass_[i] : scalar(mass_[i + 1]);
            y.q[c] = x_[i], y.q[c + 1] = y_[i], y.q[c + 2] = z_[i];
            y.p[c] = m * vx_[i], y.p[c + 1] = m * vy_[i], y.p[c + 2] = m * vz_[i];
        }
        x = jacobi_ ? from_jacobi(y, std::span<const double>(mass_))
                    : from_democratic_heliocentric(y, std::span<const double>(mass_));
        last_ = x;
        loaded_ = finite_;
        if (corrected) {
            for (int k = 0; k < 9; ++k) *planet_arrays()[k] = std::move(kept[k]);
            forces_fresh_ = fresh;
            finite_ = loaded_;
        }
    }

    std::vector<double> mass_;
    double G_;
    table table_;
    wisdom_holman_options options_;
    std::vector<scalar> corrector_weights_;  // c_1..c_K, empty without a corrector
    scalar corrected_dt_ = 0;                // the dt of the C^-1 applied at the last load
    std::vector<substep> ops_;
    std::vector<scalar> weights_;
    scalar joined_weight_ = 0;
    bool joined_ = false;
    scalar total_mass_ = 0, gm_ = 0;
    // Planets, structure of arrays: heliocentric (or Jacobi) Q_i, v_i = P_i / m_i
    // (P_i / m'_i), interaction accelerations; positions kept by the lazy kernel.
    std::vector<scalar> x_, y_, z_, vx_, vy_, vz_, ax_, ay_, az_, kept_x_, kept_y_, kept_z_;
    bool jacobi_ = false, lazy_ = false;
    // Jacobi only: eta_{i-1}, m'_i and GM_i per planet; all bodies' inertial
    // positions (less X_N) and accelerations.
    std::vector<scalar> eta_, jacobi_mass_, gm_body_;
    bodies_scratch<scalar> scratch_;
    // MEGNO: the tangent (dQ, dv) per planet, the dual positions and
    // accelerations of its kicks, the accumulator.
    std::vector<scalar> dx_, dy_, dz_, dvx_, dvy_, dvz_;
    std::array<std::vector<tangent_scalar>, 3> tq_, ta_;
    bodies_scratch<tangent_scalar> tangent_scratch_;
    megno_accumulator<scalar> megno_;
    scalar megno_time_ = 0, log_scale_ = 0;
    bool megno_on_ = false, tangent_paused_ = false;
    Eigen::Matrix<scalar, 3, 1> centre_ = Eigen::Matrix<scalar, 3, 1>::Zero();
    Eigen::Matrix<scalar, 3, 1> momentum_ = Eigen::Matrix<scalar, 3, 1>::Zero();
    bool forces_fresh_ = false, loaded_ = false, finite_ = true;
    State last_;
    std::uint64_t kepler_drifts_ = 0, interaction_evaluations_ = 0, kepler_fallbacks_ = 0;
};

// The stepper for a system with members `mass` (star first) and `G`, e.g.
// hamiltonians::outer_solar_system: make_wisdom_holman<State>(system, method("saba_2")).
template <class State, class System>
wisdom_holman_stepper<State> make_wisdom_holman(const System& system, table method,
                                                wisdom_holman_options options = {}) {
    return wisdom_holman_stepper<State>(std::vector<double>(std::begin(system.mass), std::end(system.mass)),
                                        double(system.G), std::move(method), options);
}

}  // namespace sympl
