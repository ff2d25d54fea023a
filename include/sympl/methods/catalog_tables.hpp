#pragma once
// The published splitting tables of the catalog, as data: one function per
// group, one entry per table with its citation (catalog.hpp looks them up).
//
// Every coefficient is given by role (kick: p += kick*dt*force(q); drift:
// q += drift*dt*velocity(p); see table.hpp) with all the digits of its source,
// and every published literal appears once. Which letter a paper uses for
// which role was settled by measuring each method's order on nonlinear
// problems with quadratic and non-quadratic kinetic energy
// (tests/methods/test_catalog_tables.cpp), never by letter. For methods that are not of
// Runge-Kutta-Nystrom type the two roles can be exchanged without changing
// the order; their outer coefficient is taken as a drift throughout, as
// Blanes & Moan print S6.
//
// Two RKN designs, SRKN6b and SB3A, are symmetric and of order 4: a symmetric
// method's error has odd powers of dt only, so the RKN simplification
// [V,[V,[V,T]]] = 0 first matters at order 6 and they keep order 4 for any T
// (measured); they are not flagged.
#include <cmath>
#include <string>
#include <vector>

#include "../core/table.hpp"
#include "catalog_forms.hpp"
#include "processing.hpp"

namespace sympl {

namespace detail {
// McLachlan & Atela 1992, order 3: closed form of their optimal 3-stage method.
inline table mclachlan_atela_3() {
    const coefficient z = -std::cbrt(2.0L / 27 - 1 / (9 * std::sqrt(3.0L)));
    const coefficient w = -2.0L / 3 + 1 / (9 * z) + z;
    const coefficient y = (1 + w * w) / 4;
    const coefficient d0 = std::sqrt(1 / (9 * y) - w / 2 + std::sqrt(y)) - 1 / (3 * std::sqrt(y));
    const coefficient d1 = 1 / (4 * d0) - d0 / 2, d2 = 1 - d0 - d1;
    return table("mclachlan_atela_3", {d2, d1, d0}, {d0, d1, d2}, 3,
                 "McLachlan & Atela 1992, Nonlinearity 5, 541 (optimal order 3)");
}

// Omelyan, Mryglod & Folk 2002, eq. 20 (= McLachlan 1995's minimum-error S2): lambda in closed form.
inline coefficient omf_lambda() {
    const coefficient r = std::cbrt(2 * std::sqrt(326.0L) + 36);
    return 0.5L - r / 12 + 1 / (6 * r);
}

inline std::vector<table> basic_methods() {  // order 1 and 2
    const coefficient rt2 = std::sqrt(2.0L);
    return {
        table("euler_cromer", {1}, {1}, 1, "Cromer 1981, Am. J. Phys. 49, 455; Gould & Tobochnik eq. 3.74 with M = 1"),
        table("euler_cromer_dk", {0, 1}, {1, 0}, 1,
              "symplectic Euler, drift then kick (adjoint of euler_cromer); Hairer, Lubich & Wanner 2006, GNI VI.3"),
        palindrome("leapfrog_kdk", kick_first, {}, 2,
                   "Verlet 1967, Phys. Rev. 159, 98 (velocity form: Swope et al. 1982); Gould & Tobochnik eq. 3.48"),
        palindrome("leapfrog_dkd", drift_first, {}, 2,
                   "position Verlet / Stormer; Hairer, Lubich & Wanner 2003, Acta Numerica 12, 399"),
        from_seed("verlet_seed", {1, 1}, {2, 0}, 2, "Gould & Tobochnik eqs. 3.74-3.75: M = 2, a = (1, 1), b = (2, 0)"),
        table("mclachlan_atela_2", {1 - 1 / rt2, 1 / rt2}, {1 / rt2, 1 - 1 / rt2}, 2,
              "McLachlan & Atela 1992, Nonlinearity 5, 541 (optimal 2-stage order 2)"),
        palindrome("omelyan_2", kick_first, {omf_lambda()}, 2,
                   "Omelyan, Mryglod & Folk 2002, Comput. Phys. Commun. 146, 188, eq. 20 (lambda = 0.1931833275037836); "
                   "McLachlan 1995, SIAM J. Sci. Comput. 16, 151 (S2)"),
    };
}

// Laskar & Robutel 2001, Celest. Mech. Dyn. Astron. 80, 39: SABA_n (drift
// first) and SBAB_n (kick first), whose sub-steps are Gauss and Lobatto
// quadrature nodes and weights. Order 2 in general, with error O(eps dt^2n +
// eps^2 dt^2) when the kicks are a perturbation of size eps.
inline std::vector<table> laskar_robutel_methods() {
    const std::string lr = "Laskar & Robutel 2001, Celest. Mech. Dyn. Astron. 80, 39, ";
    const coefficient r30 = std::sqrt(30.0L), plus = std::sqrt(525 + 70 * r30), minus = std::sqrt(525 - 70 * r30);
    return {
        palindrome("saba_1", drift_first, {}, 2, lr + "SABA1 (= leapfrog_dkd)"),
        palindrome("saba_2", drift_first, {0.5L - std::sqrt(3.0L) / 6}, 2, lr + "SABA2"),
        palindrome("saba_3", drift_first, {0.5L - std::sqrt(15.0L) / 10, 5.0L / 18}, 2, lr + "SABA3"),
        palindrome("saba_4", drift_first, {0.5L - plus / 70, 0.25L - r30 / 72, (plus - minus) / 70}, 2, lr + "SABA4"),
        palindrome("sbab_1", kick_first, {}, 2, lr + "SBAB1 (= leapfrog_kdk)"),
        palindrome("sbab_2", kick_first, {1.0L / 6}, 2, lr + "SBAB2"),
        palindrome("sbab_3", kick_first, {1.0L / 12, 0.5L - std::sqrt(5.0L) / 10}, 2, lr + "SBAB3"),
        palindrome("sbab_4", kick_first, {1.0L / 20, 0.5L - std::sqrt(21.0L) / 14, 49.0L / 180}, 2, lr + "SBAB4"),
    };
}

inline std::vector<table> order_3_and_4_methods() {
    const coefficient cr2 = std::cbrt(2.0L);
    const std::string bm = "Blanes & Moan 2002, J. Comput. Appl. Math. 142, 313, ";
    const std::string mcl = "McLachlan 1995, SIAM J. Sci. Comput. 16, 151, ";
    const coefficient sb3a_drift = std::sqrt(7.0L / 8) / 3;
    return {
        table("ruth_3", {7.0L / 24, 3.0L / 4, -1.0L / 24}, {2.0L / 3, -2.0L / 3, 1}, 3,
              "Ruth 1983, IEEE Trans. Nucl. Sci. 30, 2669"),
        mclachlan_atela_3(),
        // Triple jump of the leapfrog (order 2 -> 4), in its two forms.
        palindrome("forest_ruth_4", drift_first, {(2 + cr2 + 1 / cr2) / 6, 1 / (2 - cr2)}, 4,
                   "Forest & Ruth 1990, Physica D 43, 105; Candy & Rozmus 1991, J. Comput. Phys. 92, 230 (drift first)"),
        leapfrog_composition("yoshida_4", {1 / (2 - cr2)}, 4, "Yoshida 1990, Phys. Lett. A 150, 262, eq. 5.4 (kick first)"),
        leapfrog_composition("suzuki_4", {1 / (4 - std::cbrt(4.0L)), 1 / (4 - std::cbrt(4.0L))}, 4,
                             "Suzuki 1990, Phys. Lett. A 146, 319 (five-fold fractal composition)"),
        palindrome("pefrl_4", drift_first, {0.1786178958448091L, 0.5L + 0.2123418310626054L, -0.06626458266981849L}, 4,
                   "Omelyan, Mryglod & Folk 2002, Comput. Phys. Commun. 146, 188, eq. 30 (PEFRL: xi, (1 - 2 lambda)/2, chi)"),
        table("mclachlan_atela_4",
              {0.134496199277431089L, -0.224819803079420806L, 0.756320000515668291L, 0.334003603286321425L},
              {0.515352837431122936L, -0.085782019412973646L, 0.441583023616466524L, 0.128846158365384185L}, 4,
              "McLachlan & Atela 1992, Nonlinearity 5, 541 (optimal RKN order 4)", rkn),
        table("calvo_sanz_serna_4",
              {0.061758858135626L, 0.33897802655364L, 0.61479130717558L, -0.14054801465937L, 0.12501982279453L},
              {0.205177661542290L, 0.403021281604210L, -0.12092087633891L, 0.512721933192410L, 0}, 4,
              "Calvo & Sanz-Serna 1993, SIAM J. Sci. Comput. 14, 936", rkn),
        palindrome("mclachlan_s4", drift_first, {0.16913927992207204518L, 0.54545454545454545455L, -0.29918620390405079951L},
                   4, mcl + "S4"),
        palindrome("mclachlan_s5", drift_first,
                   {0.089269454226475244887L, 0.4L, -0.097336042636895508015L, -0.1L}, 4, mcl + "S5"),
        leapfrog_composition("mclachlan_ss5", {0.28L, 0.62546642846767004501L}, 4, mcl + "SS5"),
        palindrome("blanes_moan_s6", drift_first,
                   {0.0792036964311957L, 0.209515106613362L, 0.353172906049774L, -0.143851773179818L,
                    -0.0420650803577195L},
                   4, bm + "Table 2 (S6)"),
        palindrome("blanes_moan_srkn6b", kick_first,
                   {0.0829844064174052L, 0.245298957184271L, 0.396309801498368L, 0.604872665711080L,
                    -0.0390563049223486L},
                   4, bm + "Table 3 (SRKN6b)")
            .with_family("RKN"),
        from_drift_first("odeint_sb3a_mclachlan",
                         {0.40518861839525227722L, -0.28714404081652408900L,
                          0.5L - (0.40518861839525227722L - 0.28714404081652408900L),
                          0.5L - (0.40518861839525227722L - 0.28714404081652408900L), -0.28714404081652408900L,
                          0.40518861839525227722L},
                         {-3.0L / 73, 17.0L / 59, 1 - 2 * (-3.0L / 73 + 17.0L / 59), 17.0L / 59, -3.0L / 73, 0}, 4,
                         mcl + "SB3A, 6 stages; Boost.Odeint symplectic_rkn_sb3a_mclachlan")
            .with_family("RKN"),
        from_drift_first("odeint_sb3a_m4_mclachlan",
                         {0.5L - sb3a_drift, -1.0L / 3 + sb3a_drift, 2.0L / 3, -1.0L / 3 + sb3a_drift, 0.5L - sb3a_drift},
                         {1, -0.5L, -0.5L, 1, 0}, 4,
                         mcl + "SB3A with 4 force evaluations; Boost.Odeint symplectic_rkn_sb3a_m4_mclachlan")
            .with_family("RKN"),
    };
}

// Blanes, Casas, Farres, Laskar, Makazaga & Murua 2013, Appl. Numer. Math.
// 68, 58: ABA(s, r1, r2, ...) methods for near-integrable systems (error
// O(eps dt^r1 + eps^2 dt^r2 + ...)), order 4 in general.
inline std::vector<table> near_integrable_methods() {
    const std::string b13 = "Blanes, Casas, Farres, Laskar, Makazaga & Murua 2013, Appl. Numer. Math. 68, 58, ";
    return {
        palindrome("blanes_2013_aba_10_4", drift_first,
                   {0.04706710064597250612947887637243678556564L, 0.1188819173681970199453503950853885936957L,
                    0.1847569354170881069247376193702560968574L, 0.2410504605515015657441667865901651105675L,
                    0.2827060056798362053243616565541452479160L, -0.2732866667053238060543113981664559460630L},
                   4, b13 + "ABA(10,4)"),
        palindrome("blanes_2013_aba_8_6_4", drift_first,
                   {0.0711334264982231177779387300061549964174L, 0.183083687472197221961703757166430291072L,
                    0.241153427956640098736487795326289649618L, 0.310782859898574869507522291054262796375L,
                    0.521411761772814789212136078067994229991L, -0.0265646185119588006972121379164987592663L},
                   4, b13 + "ABA(8,6,4)"),
        palindrome("blanes_2013_aba_10_6_4", drift_first,
                   {0.03809449742241219545697532230863756534060L, 0.09585888083707521061077150377145884776921L,
                    0.1452987161169137492940200726606637497442L, 0.2044461531429987806805077839164344779763L,
                    0.2076276957255412507162056113249882065158L, 0.2170703479789911017143385924306336714532L,
                    0.4359097036515261592231548624010651844006L},
                   4, b13 + "ABA(10,6,4)"),
        palindrome("blanes_2013_abah_8_4_4", drift_first,
                   {0.2741402689434018761640565440378637101205L, 0.6408857951625127177322491164716010349386L,
                    -0.1075684384401642306251105297063236526845L, -0.8585754489567828565881283246356000103664L,
                    -0.0480185025906016926911954171508475065370L},
                   4, b13 + "ABAH(8,4,4)"),
        palindrome("blanes_2013_abah_8_6_4", drift_first,
                   {0.06810235651658372084723976682061164571212L, 0.1684432593618954534310382697756917558148L,
                    0.2511360387221033233072829580455350680082L, 0.4243177173742677224300351657407231801453L,
                    -0.07507264957216562516006821767601620052338L, -0.5858109694681756812309015355404036521923L,
                    -0.009544719701745007811488218957217113269121L},
                   4, b13 + "ABAH(8,6,4)"),
        palindrome("blanes_2013_abah_10_6_4", drift_first,
                   {0.04731908697653382270404371796320813250988L, 0.1196884624585322035312864297489892143852L,
                    0.2651105235748785159539480036185693201078L, 0.3752955855379374250420128537687503199451L,
                    -0.009976522883811240843267468164812380613143L, -0.4684593418325993783650820409805381740605L,
                    -0.05992919973494155126395247987729676004016L, 0.3351397342755897010393098942949569049275L},
                   4, b13 + "ABAH(10,6,4)"),
    };
}

inline std::vector<table> order_5_to_8_methods() {  // order 5 and 6 splittings, order 8 RKN
    const std::string bm = "Blanes & Moan 2002, J. Comput. Appl. Math. 142, 313, ";
    const std::string bce = "Blanes, Casas & Escorihuela-Tomas 2022, Runge-Kutta-Nystrom symplectic splitting methods "
                            "of order 8, Appl. Numer. Math. (arXiv:2202.01541), ";
    return {
        table("mclachlan_atela_5",
              {0.1193900292875672758L, 0.6989273703824752308L, -0.1713123582716007754L, 0.4012695022513534480L,
               0.0107050818482359840L, -0.0589796254980311632L},
              {0.339839625839110000L, -0.088601336903027329L, 0.5858564768259621188L, -0.603039356536491888L,
               0.3235807965546976394L, 0.4423637942197494587L},
              5, "McLachlan & Atela 1992, Nonlinearity 5, 541 (optimal RKN order 5)", rkn),
        palindrome("blanes_moan_s10", drift_first,
                   {0.0502627644003922L, 0.148816447901042L, 0.413514300428344L, -0.132385865767784L,
                    0.0450798897943977L, 0.067307604692185L, -0.188054853819569L, 0.432666402578175L,
                    0.541960678450780L},
                   6, bm + "Table 2 (S10)"),
        palindrome("blanes_moan_srkn11b", kick_first,
                   {0.0414649985182624L, 0.123229775946271L, 0.198128671918067L, 0.290553797799558L,
                    -0.0400061921041533L, -0.127049212625417L, 0.0752539843015807L, -0.246331761062075L,
                    -0.0115113874206879L, 0.357208872795928L},
                   6, bm + "Table 3 (SRKN11b)", rkn),
        palindrome("blanes_moan_srkn14a", drift_first,
                   {0.037859319840611600L, 0.091719152624461650L, 0.10263563310243500L, 0.18398317000500600L,
                    -0.025867888266558700L, -0.056534365832888270L, 0.31424140307144700L, 0.0049146887747128540L,
                    -0.13014445951741500L, 0.14376112716835800L, 0.10641770036954300L, 0.32856769374680400L,
                    -0.0087942431285105800L},
                   6, bm + "Table 3 (SRKN14a)", rkn),
        // Order-8 RKN methods (quadratic T). The paper names drift weights a and
        // kick weights b (its eq. 1.2: f_a = (v, 0), f_b = (0, g)); sources that copy its
        // tables disagree, and read the other way round each measures order 4
        // (tests/methods/test_catalog_tables.cpp). Its 30-digit values, first half by role:
        palindrome("blanes_casas_escorihuela_a18", drift_first,
                   {0.0866003822712445920135805954462L, -0.08L, -0.0231572735424388070228714693753L,
                    0.209460550048243262121199483001L, 0.191410576083774088999564416369L,
                    0.274887805875735483503233064415L, 0.378895558692931579545387584925L,
                    -0.224214208870409561366168655624L, -0.0467359566364556111599485526051L,
                    0.347657740563761656321390026010L, -0.156198111997810415438979605642L,
                    -0.168783183866211679175007668385L, 0.156025836895094823718831871041L,
                    0.144209344805460873709120777707L, 0.252844012473796333586850465807L,
                    0.0116851121360265483381405054244L, -0.640644212172254239866860564270L},
                   8, bce + "Table 4 (A18)", rkn),
        palindrome("blanes_casas_escorihuela_b17", kick_first,
                   {0.0514196142537210073343152693459L, 0.160227696073839513690970240076L,
                    0.250497030318342871458417941091L, 0.306354507436867319879440957100L,
                    0.512412268300327350035492806653L, 0.308395508895171191756544975556L,
                    -0.231597138650894401279645184364L, 0.120362086566233408450063177659L,
                    0.116091323536875759881216298975L, -0.622888687549183872072186218718L,
                    -0.0098365173246965763985763034283L, 0.635560951632990078378672016548L,
                    -0.108032771466281638634277563747L, -0.144226974795419229640437363913L,
                    0.249039864198023642002940910070L, -0.284867527074173816678992817545L},
                   8, bce + "(B17)", rkn),
        palindrome("blanes_casas_escorihuela_b19", kick_first,
                   {0.036132460472136313416730168194L, 0.337548675291317241942440116575L,
                    0.012697863961074113381675193011L, -0.223647977575409990331768222380L,
                    0.201318391240629276109068041836L, 0.168949714872223740906385138015L,
                    0.135683350134504233201330671671L, 0.171179938816205886154783136334L,
                    -0.0579071833999963041504740663015L, -0.349765168067292877221144631312L,
                    -0.0772509501792649549463874931821L, 0.523808861006312397712070357524L,
                    -0.00264758266409925952822161203471L, -0.194208871063049124066394765282L,
                    -0.0329844384945603065320797537355L, -0.323496751337931087309823477561L,
                    0.0476781560950366927530646289755L, 0.322817287614899749216601693799L},
                   8, bce + "Table 5 (B19)", rkn),
    };
}

inline std::vector<table> order_6_methods() {
    // Yoshida's tables print 15 digits; these 21 are the roots of his eqs.
    // 5.4-5.17 (re-solved in the Principia project's methods table), which
    // agree with the printed ones to their last digit or two.
    const std::string yo = "Yoshida 1990, Phys. Lett. A 150, 262, Table 1 ";
    return {
        palindrome("okunbor_skeel_6", drift_first,
                   {-1.0130879789171747298L, 0.00016600692650009894L, 1.1874295737325427070L,
                    -0.37962421426377360608L, -0.018335852096460590340L, 0.68913741185181063674L},
                   6, "Okunbor & Skeel 1994, J. Comput. Appl. Math. 51, 375 (method 13, RKN order 6; "
                      "digits as tabulated by McLachlan 1995)", rkn),
        leapfrog_composition("yoshida_6",
                             {0.7845136104775572638194976338663498757768L, 0.2355732133593581336847931829785346016865L,
                              -1.177679984178871006946415680964315734639L},
                             6, yo + "(solution A)"),
        leapfrog_composition("yoshida_6b",
                             {1.43984816797678309102L, 0.00426068187079201616L, -2.13228522200145152088L}, 6,
                             yo + "(solution B)"),
        leapfrog_composition("yoshida_6c",
                             {1.44778256239929793290L, -2.14403531630538931060L, 0.00152886228424927025338L}, 6,
                             yo + "(solution C)"),
        leapfrog_composition("kahan_li_6",
                             {0.39216144400731413927925056L, 0.33259913678935943859974864L,
                              -0.70624617255763935980996482L, 0.08221359629355080023149045L},
                             6, "Kahan & Li 1997, Math. Comp. 66, 1089 (s9odr6a)"),
        leapfrog_composition("kahan_li_6b",
                             {0.39103020330868478817L, 0.33403728961113601749L, -0.70622728118756134346L,
                              0.081877549648059445768L},
                             6, "Kahan & Li 1997, Math. Comp. 66, 1089 (s9odr6b)"),
        leapfrog_composition("mclachlan_ss9",
                             {0.1867L, 0.55549702371247839916L, 0.12946694891347535806L, -0.84326562338773460855L},
                             6, "McLachlan 1995, SIAM J. Sci. Comput. 16, 151, SS9"),
    };
}

inline std::vector<table> order_8_and_10_methods() {
    const std::string yo = "Yoshida 1990, Phys. Lett. A 150, 262, Table 2 ";  // digits: see order_6_methods
    return {
        leapfrog_composition("yoshida_8",
                             {0.914844246229642658287L, 0.253693336566286009974L, -1.44485223686030647660L,
                              -0.158240635368502468458L, 1.93813913762291232471L, -1.96061023297558163691L,
                              0.102799849392219431139L},
                             8, yo + "(solution D)"),
        leapfrog_composition("yoshida_8a",
                             {1.04242620869970426435L, 1.82020630970698006933L, 0.157739928123708321343L,
                              2.44002732616634406382L, -0.00716989419709533209981L, -2.44699182370424588929L,
                              -1.61582374150065378479L},
                             8, yo + "(solution A)"),
        leapfrog_composition("yoshida_8b",
                             {1.48819229202921310080L, -2.33864815101041943098L, 2.89105148972198900311L,
                              -2.89688250330423987105L, 0.00378039588362668223674L, 2.89195744315817391244L,
                              -0.00169248587771706559145L},
                             8, yo + "(solution B)"),
        leapfrog_composition("yoshida_8c",
                             {0.629030650210427818049L, 1.36934946416874222370L, -1.06458714789183904181L,
                              1.66335809963311356298L, -1.67896928259637402925L, -1.55946803821449795876L,
                              0.311790812418431890510L},
                             8, yo + "(solution C)"),
        leapfrog_composition("yoshida_8e",
                             {1.30300165757516838484L, 0.107990467718098279648L, -2.04809795883490205633L,
                              0.00536018921375238082832L, -0.0719180053650705075005L, 2.52778927318028339169L,
                              0.0227738840126312259937L},
                             8, yo + "(solution E)"),
        leapfrog_composition("kahan_li_8",
                             {0.13020248308889008087881763L, 0.56116298177510838456196441L,
                              -0.38947496264484728640807860L, 0.15884190655515560089621075L,
                              -0.39590389413323757733623154L, 0.18453964097831570709183254L,
                              0.25837438768632204729397911L, 0.29501172360931029887096624L},
                             8, "Kahan & Li 1997, Math. Comp. 66, 1089 (s17odr8a)"),
        leapfrog_composition("kahan_li_8b",
                             {0.12713692773487857916L, 0.56170253798880269972L, -0.38253471994883018888L,
                              0.16007605629464743119L, -0.40181637432680696673L, 0.18736671654227849724L,
                              0.26070870920779240570L, 0.29039738812516162389L},
                             8, "Kahan & Li 1997, Math. Comp. 66, 1089 (s17odr8b)"),
        leapfrog_composition("suzuki_umeno_8",
                             {0.7416703643506129534482278017838063156035L, -0.4091008258000315939973000958935634173099L,
                              0.1907547102962383799538762564503716627355L, -0.5738624711160822666563877266355357421595L,
                              0.2990641813036559238444635406886029882258L, 0.3346249182452981837849579798821822886337L,
                              0.3152930923967665966320566638110024309941L},
                             8, "Suzuki & Umeno 1993, Springer Proc. Phys. 76, 74; McLachlan 1995, SIAM J. Sci. "
                                "Comput. 16, 151 (SS15)"),
        leapfrog_composition("mclachlan_ss17",
                             {0.12886597938144329897L, 0.5815140871052509624L, -0.41017537146985013753L,
                              0.1851469357165877327L, -0.40955234342085141934L, 0.14440594108001204106L,
                              0.27833550039367965131L, 0.31495668391629485789L},
                             8, "McLachlan 1995, SIAM J. Sci. Comput. 16, 151, SS17"),
        leapfrog_composition("kahan_li_10",
                             {0.070428877682658066880L, 0.87415651735353949041L, 0.055414604963802442707L,
                              -0.066800477898797011598L, -0.62641308958799555593L, 0.23682621087528762872L,
                              -0.42221063403170054210L, 0.24222942201040859249L, 0.047374515478601436594L,
                              0.54386826052472423338L, -0.93252230928447264311L, 0.16960179883676464855L,
                              0.71608567578450563608L, -0.80016730247310573512L, 0.23778185292256770747L,
                              -0.32330301550863943389L},
                             10, "Kahan & Li 1997, Math. Comp. 66, 1089 (s33odr10a)"),
        leapfrog_composition(
            "sofroniou_spaletta_10",
            {0.078795722521686419263907679337684L, 0.31309610341510852776481247192647L,
             0.027918383235078066109520273275299L, -0.22959284159390709415121339679655L,
             0.13096206107716486317465685927961L, -0.26973340565451071434460973222411L,
             0.074973343155891435666137105641410L, 0.11199342399981020488957508073640L,
             0.36613344954622675119314812353150L, -0.39910563013603589787862981058340L,
             0.10308739852747107731580277001372L, 0.41143087395589023782070411897608L,
             -0.0048663605831352617621956593099771L, -0.39203335370863990644808193642610L,
             0.051942502962449647037182904015976L, 0.050665090759924496335874344156866L,
             0.049674370639729879054568800279461L},
            10, "Sofroniou & Spaletta 2005, Optim. Methods Softw. 20, 597 (35 stages, order 10)"),
    };
}

inline std::vector<processed_method> processed_methods() {
    const std::string bcm = "Blanes, Casas & Murua 2006, SIAM J. Sci. Comput. 27, 1817";
    const coefficient a1 = 0.1705768865009222157L, b1 = 0.125696288720106L, c1 = 0.168L;
    return {
        processed_leapfrog("blanes_2001_p6", {0.513910778424374L, 0.364193022833858L, -0.867423280969274L},
                           {0, -0.461165940466494L, -0.074332422810238L, 0.384998538774070L, 0.375012038697862L}, 6,
                           "Blanes 2001, Appl. Numer. Math. 37, 289 (7-stage kernel, effective order 6)"),
        processed_leapfrog("bcm_2006_p6_11", {a1, a1, a1, a1, -0.423366140892658048L},
                           {0, -0.20621953139126L, 0.23651387483203L, 0.09086982276241L, 0.24687306977659L, -0.1L}, 6,
                           bcm + " (11-stage kernel, effective order 6)"),
        processed_leapfrog("bcm_2006_p6_13", {b1, b1, b1, b1, 0.148070660114965L, -0.350856370823828L},
                           {0.1L, 0.225080298761176L, 0.191244694511161L, -0.212763792194890L, -0.09660157306582295L, 0},
                           6, bcm + " (13-stage kernel, effective order 6)"),
        processed_leapfrog("bcm_2006_p8", {c1, c1, 0.585550530805562L, -0.460090457516872L, 0.172863148729731L,
                                           0.179664539695039L},
                           {0, -0.008488123494574411L, -0.337188967354338L, 0.333987768164597L, 0.588351189003849L,
                            0.162324207599241L, -0.511744926116413L, 0.236885952363384L, 0.598212975943381L,
                            -0.543415765371656L},
                           8, bcm + " (13-stage kernel, effective order 8)"),
    };
}

// Force-gradient methods (table.hpp): a kick of weight w and gradient g is the
// flow of w dt V + g dt^3 [V,[T,V]], [V,[T,V]] = F.M^-1.F; they need quadratic T.
inline std::vector<table> force_gradient_methods() {
    // Chin 1997, algorithm 4A: V/6, T/2, (2/3) V~, T/2, V/6 with V~ = V + (dt^2/48) [V,[T,V]],
    // so the middle kick's gradient coefficient is (2/3)(1/48) = 1/72.
    const table chin_4a("chin_4a", {1.0L / 6, 2.0L / 3, 1.0L / 6}, {0.5L, 0.5L, 0}, {0, 1.0L / 72, 0}, 4,
                        "Chin 1997, Phys. Lett. A 226, 344 (algorithm 4A)");
    // Its triple jump (Yoshida 1990), the order-6 construction of Chin & Kidwell 2000.
    const table jump = triple_jump(chin_4a);
    return {chin_4a, table::from_substeps("chin_4a_triple_jump", jump.substeps(), 6,
                                          "Chin & Kidwell 2000, Phys. Rev. E 62, 8746 (4A, triple jump)",
                                          kinetic_requirement::quadratic)};
}

}  // namespace detail

}  // namespace sympl
