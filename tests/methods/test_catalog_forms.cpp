// The published forms: what palindrome() and leapfrog_composition() compute
// matches the digits the papers print.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include <sympl/sympl.hpp>

namespace test_methods_test_catalog_forms {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

TEST_CASE("catalog_forms: palindrome() completes a half to a symmetric table whose roles each sum to 1") {
    // Laskar & Robutel's SABA2 from its first drift alone: kick 1/2, drift 1 - 2 c1 in the centre.
    const coefficient c1 = 0.5L - std::sqrt(3.0L) / 6;
    const table t = detail::palindrome("saba_2_again", substep::drift, {c1}, 2, "test");
    CHECK(t == method("saba_2"));
    CHECK(t.is_symmetric(1e-18L));
    for (const auto& role : {t.kick(), t.drift()})
        CHECK(std::fabs(static_cast<double>(std::accumulate(role.begin(), role.end(), coefficient(0)) - 1)) <= 1e-18);
    CHECK(detail::leapfrog_composition("lf3", {0.25L}, 2, "test") == compose(method("leapfrog_kdk"), {0.25L, 0.5L, 0.25L}));
}


TEST_CASE("catalog_forms: composition weights match the published centre weight") {
    // compose_symmetric computes the centre as 1 - 2*sum(outer); each paper
    // prints it too, so this checks every outer digit as typed.
    struct published {
        const char* name;
        long double centre;
        double tolerance;  // the published digits
    };
    const published rows[] = {
        {"yoshida_6", 1.315186320683911218884249728238862514352L, 1e-18},     // Yoshida 1990, solution A
        {"yoshida_8", 1.7084530707866603157L, 1e-18},                         // Yoshida 1990, solution D (w0)
        {"yoshida_6b", 2.37635274430775282740L, 1e-18},                       // Yoshida 1990, solution B
        {"yoshida_6c", 2.38944778324368421490L, 1e-18},                       // Yoshida 1990, solution C
        {"yoshida_8a", -1.7808286265894834253L, 1e-18},                       // Yoshida 1990, solution A
        {"yoshida_8b", -3.0755169612012526619L, 1e-18},                       // Yoshida 1990, solution B
        {"yoshida_8c", 1.6589908845439910692L, 1e-18},                        // Yoshida 1990, solution C
        {"yoshida_8e", -2.6937990149999221983L, 1e-18},                       // Yoshida 1990, solution E
        {"kahan_li_6b", 0.79856447723936218406L, 1e-18},                      // Kahan & Li 1997, s9odr6b
        {"kahan_li_8b", -0.60607448323584816258L, 1e-18},                     // Kahan & Li 1997, s17odr8b
        {"kahan_li_10", 0.95529818470370207691L, 1e-18},                      // Kahan & Li 1997, s33odr10a
        {"mclachlan_ss5", -0.8109328569353400900L, 1e-18},                    // McLachlan 1995, SS5
        {"mclachlan_ss9", 0.9432033015235617027L, 1e-18},                     // McLachlan 1995, SS9
        {"mclachlan_ss17", -0.626994825405133975L, 1e-17},                    // McLachlan 1995, SS17
        {"kahan_li_6", 0.79854399093482996339895035L, 1e-18},                 // Kahan & Li 1997
        {"kahan_li_8", -0.60550853383003451169892108L, 1e-18},                // Kahan & Li 1997
        {"suzuki_umeno_8", -0.7968879393529163540197888401737330534463L, 1e-18},  // McLachlan 1995
        {"sofroniou_spaletta_10", 0.049317735759594537917680008339338L, 1e-18},   // Sofroniou & Spaletta 2005
    };
    for (const published& row : rows) {
        CAPTURE(row.name);
        const table& t = method(row.name);
        // The centre of a KDK leapfrog composition is the middle drift.
        const auto& d = t.drift();
        const coefficient centre = d[d.size() / 2 - (d.size() % 2 == 0 ? 1 : 0)];
        CAPTURE(static_cast<double>(centre));
        CHECK(std::fabs(static_cast<double>(centre - row.centre)) <= row.tolerance);
    }
}

TEST_CASE("catalog_forms: coefficients computed by palindrome() match the published ones") {
    // palindrome() computes the two sub-steps before the centre from the
    // published half; papers that print them check every digit typed.
    struct published {
        const char* name;
        bool kick;           // role
        std::size_t index;   // position among that role's non-zero coefficients
        long double value;
    };
    const published rows[] = {
        {"blanes_2013_aba_10_4", true, 3, 0.8267085775712504407295884329818044835997L},
        {"blanes_2013_aba_10_4", false, 3, -0.01453004174289681837857815229683813033908L},
        {"blanes_2013_aba_10_6_4", false, 4, -0.6538612258327867093807117373907094120024L},
        {"blanes_2013_aba_10_6_4", true, 3, -0.01737538195906509300561788011852699719871L},
        {"blanes_2013_abah_8_4_4", true, 2, 0.7176896537942701388558792081639989754277L},
        {"blanes_2013_abah_8_4_4", false, 3, 0.7628933441747280943044988056386148982021L},
        {"blanes_2013_abah_8_6_4", true, 3, 0.4930499927320125053698281000239887162321L},
        {"blanes_2013_abah_10_6_4", true, 4, 0.2766711191210800975049457263356834696055L},
        {"blanes_2013_abah_10_6_4", false, 4, 0.2574761120673404534492282264603316880356L},
        {"blanes_2013_aba_8_6_4", true, 3, 0.0653961422823734184559721793911134363710L},
        {"saba_4", false, 2, 0.3399810435848562648026657591032446872006L},  // Laskar & Robutel 2001
        {"saba_4", true, 1, 0.3260725774312730713134680253890002963823L},
        {"saba_3", true, 1, 0.4444444444444444444444444444444444444444L},
        {"mclachlan_s4", false, 2, 1.2600938479639575087L},                 // McLachlan 1995
        {"mclachlan_s5", false, 2, 0.50806658841042026313L},
        {"blanes_moan_srkn14a", false, 7, 0.2073050690568954L},             // Blanes & Moan 2002, 16 digits
        {"blanes_moan_srkn14a", true, 6, -0.19641146648645423L},
        {"okunbor_skeel_6", true, 3, 0.38064159097092574080L},
        {"okunbor_skeel_6", false, 3, 0.34399425728109261313L},
    };
    for (const published& row : rows) {
        CAPTURE(row.name);
        CAPTURE(row.index);
        std::vector<coefficient> nonzero;
        for (coefficient c : row.kick ? method(row.name).kick() : method(row.name).drift())
            if (c != 0) nonzero.push_back(c);
        REQUIRE(row.index < nonzero.size());
        CHECK(std::fabs(static_cast<double>(nonzero[row.index] - row.value)) <= 1e-15);
    }
}

TEST_CASE("catalog_forms: leapfrog_composition_weights() reads back the weights leapfrog_composition() was given") {
    const composition_weights w = detail::leapfrog_composition_weights(method("yoshida_4"), "test");
    const coefficient outer = 1 / (2 - std::cbrt(2.0L));  // Yoshida 1990, eq. 5.4
    REQUIRE(w.gamma.size() == 3);
    CHECK(std::fabs(static_cast<double>(w.gamma[0] - outer)) <= 1e-18);
    CHECK(std::fabs(static_cast<double>(w.gamma[1] - (1 - 2 * outer))) <= 1e-18);
    CHECK(w.order == 4);
    CHECK_THROWS_WITH_AS(detail::leapfrog_composition_weights(method("pefrl_4"), "test"),
                         doctest::Contains("expected a symmetric composition of leapfrog steps"), invalid_argument);
}

}  // namespace test_methods_test_catalog_forms
