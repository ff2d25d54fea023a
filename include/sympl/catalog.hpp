#pragma once
// The catalog of published splitting methods, looked up by name.
//
// Every coefficient is given by role (kick: p += kick*dt*force(q); drift:
// q += drift*dt*velocity(p), kick first; see table.hpp) with all the digits of
// its source. Which letter a paper uses for which role was settled by
// measuring each method's order on nonlinear problems with quadratic and
// non-quadratic kinetic energy (tests/test_catalog.cpp), never by letter.
// Two RKN designs, SRKN6b and SB3A, are symmetric and of order 4: a symmetric
// method's error has odd powers of dt only, so the RKN simplification
// [V,[V,[V,T]]] = 0 first matters at order 6 and they keep order 4 for any T
// (measured); they are not flagged.
// Composition methods are given as the published weights of a symmetric
// composition of leapfrog (compose_symmetric, outermost weight first).
#include <cmath>
#include <string>
#include <vector>

#include "error.hpp"
#include "table.hpp"

namespace sympl {

namespace detail {
using K = std::vector<coefficient>;
constexpr auto rkn = kinetic_requirement::quadratic;
constexpr auto any = kinetic_requirement::any;

inline table leapfrog_kdk() {
    return table("leapfrog_kdk", {0.5L, 0.5L}, {1, 0}, 2, "Verlet 1967, Phys. Rev. 159, 98 (velocity form: Swope et al. 1982); seed 000 eq. 3.48");
}

// McLachlan & Atela 1992, order 3: closed form of their optimal 3-stage method.
inline table mclachlan_atela_3() {
    const coefficient z = -std::cbrt(2.0L / 27 - 1 / (9 * std::sqrt(3.0L)));
    const coefficient w = -2.0L / 3 + 1 / (9 * z) + z;
    const coefficient y = (1 + w * w) / 4;
    const coefficient d0 = std::sqrt(1 / (9 * y) - w / 2 + std::sqrt(y)) - 1 / (3 * std::sqrt(y));
    const coefficient d1 = 1 / (4 * d0) - d0 / 2, d2 = 1 - d0 - d1;
    return table("mclachlan_atela_3", {d2, d1, d0}, {d0, d1, d2}, 3, "McLachlan & Atela 1992, Nonlinearity 5, 541 (optimal order 3)");
}

// Omelyan, Mryglod & Folk 2002, eq. 20 (= McLachlan 1995's minimum-error S2): lambda in closed form.
inline coefficient omf_lambda() {
    const coefficient r = std::cbrt(2 * std::sqrt(326.0L) + 36);
    return 0.5L - r / 12 + 1 / (6 * r);
}
}  // namespace detail

// All catalog entries, built once.
inline const std::vector<table>& catalog() {
    using namespace detail;
    static const std::vector<table> entries = [] {
        const table lf = leapfrog_kdk();
        const coefficient rt2 = std::sqrt(2.0L), cr2 = std::cbrt(2.0L);
        const coefficient lam = omf_lambda();
        const coefficient xi = 0.1786178958448091L, la = -0.2123418310626054L, chi = -0.06626458266981849L;  // PEFRL
        std::vector<table> t;
        // -- order 1 and 2 --------------------------------------------------------------------------------------------
        t.push_back(table("euler_cromer", {1}, {1}, 1, "Cromer 1981, Am. J. Phys. 49, 455; seed 002 eq. 3.74 with M = 1 (kick, then drift)"));
        t.push_back(table("euler_cromer_dk", {0, 1}, {1, 0}, 1, "symplectic Euler, drift then kick (adjoint of euler_cromer); Hairer, Lubich & Wanner 2006, GNI ch. VI.3"));
        t.push_back(lf);
        t.push_back(table("leapfrog_dkd", {0, 1}, {0.5L, 0.5L}, 2, "position Verlet / Stormer; Hairer, Lubich & Wanner 2003, Acta Numerica 12, 399"));
        t.push_back(from_seed("verlet_seed", {1, 1}, {2, 0}, 2, "seed 002 eqs. 3.74-3.75: M = 2, a = (1, 1), b = (2, 0)"));
        t.push_back(table("mclachlan_atela_2", {1 - 1 / rt2, 1 / rt2}, {1 / rt2, 1 - 1 / rt2}, 2, "McLachlan & Atela 1992, Nonlinearity 5, 541 (optimal 2-stage order 2)"));
        t.push_back(table("omelyan_2", {lam, 1 - 2 * lam, lam}, {0.5L, 0.5L, 0}, 2, "Omelyan, Mryglod & Folk 2002, Comput. Phys. Commun. 146, 188, eq. 20 (lambda = 0.1931833275037836); McLachlan 1995, SIAM J. Sci. Comput. 16, 151 (S2)"));
        // -- order 3 ------------------------------------------------------------------------------------------------------
        t.push_back(table("ruth_3", {7.0L / 24, 3.0L / 4, -1.0L / 24}, {2.0L / 3, -2.0L / 3, 1}, 3, "Ruth 1983, IEEE Trans. Nucl. Sci. 30, 2669"));
        t.push_back(mclachlan_atela_3());
        // -- order 4 ------------------------------------------------------------------------------------------------------
        t.push_back(table("forest_ruth_4", {0, 1 / (2 - cr2), 1 / (1 - cr2 * cr2), 1 / (2 - cr2)}, {(2 + cr2 + 1 / cr2) / 6, (1 - cr2 - 1 / cr2) / 6, (1 - cr2 - 1 / cr2) / 6, (2 + cr2 + 1 / cr2) / 6}, 4, "Forest & Ruth 1990, Physica D 43, 105; Candy & Rozmus 1991, J. Comput. Phys. 92, 230"));
        t.push_back(table("pefrl_4", {0, (1 - 2 * la) / 2, la, la, (1 - 2 * la) / 2}, {xi, chi, 1 - 2 * (chi + xi), chi, xi}, 4, "Omelyan, Mryglod & Folk 2002, Comput. Phys. Commun. 146, 188, eq. 30 (PEFRL; xi, lambda, chi)"));
        t.push_back(table("mclachlan_atela_4", {0.134496199277431089L, -0.224819803079420806L, 0.756320000515668291L, 0.334003603286321425L}, {0.515352837431122936L, -0.085782019412973646L, 0.441583023616466524L, 0.128846158365384185L}, 4, "McLachlan & Atela 1992, Nonlinearity 5, 541 (optimal RKN order 4)", rkn));
        t.push_back(table("calvo_sanz_serna_4", {0.061758858135626L, 0.33897802655364L, 0.61479130717558L, -0.14054801465937L, 0.12501982279453L}, {0.205177661542290L, 0.403021281604210L, -0.12092087633891L, 0.512721933192410L, 0}, 4, "Calvo & Sanz-Serna 1993, SIAM J. Sci. Comput. 14, 936", rkn));
        t.push_back(table("blanes_moan_s6", {0, 0.209515106613362L, -0.143851773179818L, 0.5L - (0.209515106613362L - 0.143851773179818L), 0.5L - (0.209515106613362L - 0.143851773179818L), -0.143851773179818L, 0.209515106613362L}, {0.0792036964311957L, 0.353172906049774L, -0.0420650803577195L, 1 - 2 * (0.0792036964311957L + 0.353172906049774L - 0.0420650803577195L), -0.0420650803577195L, 0.353172906049774L, 0.0792036964311957L}, 4, "Blanes & Moan 2002, J. Comput. Appl. Math. 142, 313, Table 2 (S6)"));
        t.push_back(table("blanes_moan_srkn6b", {0.0829844064174052L, 0.396309801498368L, -0.0390563049223486L, 1 - 2 * (0.0829844064174052L + 0.396309801498368L - 0.0390563049223486L), -0.0390563049223486L, 0.396309801498368L, 0.0829844064174052L}, {0.245298957184271L, 0.604872665711080L, 0.5L - (0.245298957184271L + 0.604872665711080L), 0.5L - (0.245298957184271L + 0.604872665711080L), 0.604872665711080L, 0.245298957184271L, 0}, 4, "Blanes & Moan 2002, J. Comput. Appl. Math. 142, 313, Table 3 (SRKN6b)"));
        t.push_back(from_drift_first("odeint_sb3a_mclachlan", {0.40518861839525227722L, -0.28714404081652408900L, 0.5L - (0.40518861839525227722L - 0.28714404081652408900L), 0.5L - (0.40518861839525227722L - 0.28714404081652408900L), -0.28714404081652408900L, 0.40518861839525227722L}, {-3.0L / 73, 17.0L / 59, 1 - 2 * (-3.0L / 73 + 17.0L / 59), 17.0L / 59, -3.0L / 73, 0}, 4, "McLachlan 1995, SIAM J. Sci. Comput. 16, 151 (SB3A, 6 stages); Boost.Odeint symplectic_rkn_sb3a_mclachlan"));
        t.push_back(from_drift_first("odeint_sb3a_m4_mclachlan", {0.5L - std::sqrt(7.0L / 8) / 3, -1.0L / 3 + std::sqrt(7.0L / 8) / 3, 2.0L / 3, -1.0L / 3 + std::sqrt(7.0L / 8) / 3, 0.5L - std::sqrt(7.0L / 8) / 3}, {1, -0.5L, -0.5L, 1, 0}, 4, "McLachlan 1995, SIAM J. Sci. Comput. 16, 151 (SB3A, 5 stages); Boost.Odeint symplectic_rkn_sb3a_m4_mclachlan"));
        // -- order 5 ------------------------------------------------------------------------------------------------------
        t.push_back(table("mclachlan_atela_5", {0.1193900292875672758L, 0.6989273703824752308L, -0.1713123582716007754L, 0.4012695022513534480L, 0.0107050818482359840L, -0.0589796254980311632L}, {0.339839625839110000L, -0.088601336903027329L, 0.5858564768259621188L, -0.603039356536491888L, 0.3235807965546976394L, 0.4423637942197494587L}, 5, "McLachlan & Atela 1992, Nonlinearity 5, 541 (optimal RKN order 5)", rkn));
        // -- order 6 ------------------------------------------------------------------------------------------------------
        t.push_back(table("blanes_moan_s10", {0, 0.148816447901042L, -0.132385865767784L, 0.067307604692185L, 0.432666402578175L, 0.5L - (0.148816447901042L - 0.132385865767784L + 0.067307604692185L + 0.432666402578175L), 0.5L - (0.148816447901042L - 0.132385865767784L + 0.067307604692185L + 0.432666402578175L), 0.432666402578175L, 0.067307604692185L, -0.132385865767784L, 0.148816447901042L}, {0.0502627644003922L, 0.413514300428344L, 0.0450798897943977L, -0.188054853819569L, 0.541960678450780L, 1 - 2 * (0.0502627644003922L + 0.413514300428344L + 0.0450798897943977L - 0.188054853819569L + 0.541960678450780L), 0.541960678450780L, -0.188054853819569L, 0.0450798897943977L, 0.413514300428344L, 0.0502627644003922L}, 6, "Blanes & Moan 2002, J. Comput. Appl. Math. 142, 313, Table 2 (S10)"));
        t.push_back(table("blanes_moan_srkn11b", {0.0414649985182624L, 0.198128671918067L, -0.0400061921041533L, 0.0752539843015807L, -0.0115113874206879L, 0.5L - (0.0414649985182624L + 0.198128671918067L - 0.0400061921041533L + 0.0752539843015807L - 0.0115113874206879L), 0.5L - (0.0414649985182624L + 0.198128671918067L - 0.0400061921041533L + 0.0752539843015807L - 0.0115113874206879L), -0.0115113874206879L, 0.0752539843015807L, -0.0400061921041533L, 0.198128671918067L, 0.0414649985182624L}, {0.123229775946271L, 0.290553797799558L, -0.127049212625417L, -0.246331761062075L, 0.357208872795928L, 1 - 2 * (0.123229775946271L + 0.290553797799558L - 0.127049212625417L - 0.246331761062075L + 0.357208872795928L), 0.357208872795928L, -0.246331761062075L, -0.127049212625417L, 0.290553797799558L, 0.123229775946271L, 0}, 6, "Blanes & Moan 2002, J. Comput. Appl. Math. 142, 313, Table 3 (SRKN11b)", rkn));
        t.push_back(compose_symmetric(lf, {0.7845136104775572638194976338663498757768L, 0.2355732133593581336847931829785346016865L, -1.177679984178871006946415680964315734639L}, "yoshida_6", 6, "Yoshida 1990, Phys. Lett. A 150, 262, Table 1 (solution A)"));
        t.push_back(compose_symmetric(lf, {0.39216144400731413927925056L, 0.33259913678935943859974864L, -0.70624617255763935980996482L, 0.08221359629355080023149045L}, "kahan_li_6", 6, "Kahan & Li 1997, Math. Comp. 66, 1089 (s9odr6a)"));
        // -- order 8 and 10 -------------------------------------------------------------------------------------------------
        t.push_back(compose_symmetric(lf, {0.914844246229740L, 0.253693336566229L, -1.44485223686048L, -0.158240635368243L, 1.93813913762276L, -1.96061023297549L, 0.102799849391985L}, "yoshida_8", 8, "Yoshida 1990, Phys. Lett. A 150, 262, Table 2 (solution D)"));
        t.push_back(compose_symmetric(lf, {0.13020248308889008087881763L, 0.56116298177510838456196441L, -0.38947496264484728640807860L, 0.15884190655515560089621075L, -0.39590389413323757733623154L, 0.18453964097831570709183254L, 0.25837438768632204729397911L, 0.29501172360931029887096624L}, "kahan_li_8", 8, "Kahan & Li 1997, Math. Comp. 66, 1089 (s17odr8a)"));
        t.push_back(compose_symmetric(lf, {0.7416703643506129534482278017838063156035L, -0.4091008258000315939973000958935634173099L, 0.1907547102962383799538762564503716627355L, -0.5738624711160822666563877266355357421595L, 0.2990641813036559238444635406886029882258L, 0.3346249182452981837849579798821822886337L, 0.3152930923967665966320566638110024309941L}, "suzuki_umeno_8", 8, "Suzuki & Umeno 1993, Springer Proc. Phys. 76, 74; McLachlan 1995, SIAM J. Sci. Comput. 16, 151 (SS15 order 8)"));
        t.push_back(compose_symmetric(lf, {0.078795722521686419263907679337684L, 0.31309610341510852776481247192647L, 0.027918383235078066109520273275299L, -0.22959284159390709415121339679655L, 0.13096206107716486317465685927961L, -0.26973340565451071434460973222411L, 0.074973343155891435666137105641410L, 0.11199342399981020488957508073640L, 0.36613344954622675119314812353150L, -0.39910563013603589787862981058340L, 0.10308739852747107731580277001372L, 0.41143087395589023782070411897608L, -0.0048663605831352617621956593099771L, -0.39203335370863990644808193642610L, 0.051942502962449647037182904015976L, 0.050665090759924496335874344156866L, 0.049674370639729879054568800279461L}, "sofroniou_spaletta_10", 10, "Sofroniou & Spaletta 2005, Optim. Methods Softw. 20, 597 (35 stages, order 10)"));
        return t;
    }();
    return entries;
}

// Catalog names, in catalog order.
inline std::vector<std::string> catalog_names() {
    std::vector<std::string> names;
    for (const table& t : catalog()) names.push_back(t.name());
    return names;
}

// The catalog entry called `name`; an unknown name lists the valid ones.
inline const table& method(const std::string& name) {
    for (const table& t : catalog())
        if (t.name() == name) return t;
    std::string valid;
    for (const std::string& n : catalog_names()) valid += (valid.empty() ? "" : ", ") + n;
    throw invalid_argument("unknown method '" + name + "'; expected one of: " + valid);
}

}  // namespace sympl
