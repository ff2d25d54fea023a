// The whole catalog, entry by entry: an entry that fails here does not ship.
#include <doctest/doctest.h>

#include <cmath>
#include <numeric>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/analysis/table_order.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

namespace test_methods_test_catalog {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using V1 = Eigen::Matrix<double, 1, 1>;
using State1 = phase_space<double, 1>;

// Measured order within 0.15 of the claim (the house threshold).
void check_order(const table& t, order_problem problem, int expected) {
    const order_measurement m = measure_order(t, problem);
    CAPTURE(to_string(problem));
    CAPTURE(m.order);
    CHECK(std::fabs(m.order - expected) <= 0.15);
}
}  // namespace

TEST_CASE("catalog: coefficient sums are 1 and every entry has a citation") {
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        const coefficient ks = std::accumulate(t.kick().begin(), t.kick().end(), coefficient(0));
        const coefficient ds = std::accumulate(t.drift().begin(), t.drift().end(), coefficient(0));
        CHECK(std::fabs(static_cast<double>(ks - 1)) <= 1e-14);
        CHECK(std::fabs(static_cast<double>(ds - 1)) <= 1e-14);
        CHECK(t.order() >= 1);
        CHECK(t.citation().size() > 10);
    }
}

TEST_CASE("catalog: measured order on the pendulum and Kepler (quadratic T)") {
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        check_order(t, order_problem::pendulum, t.order());
        check_order(t, order_problem::kepler, t.order());
    }
}

TEST_CASE("catalog: measured order with non-quadratic kinetic energy") {
    // Methods not flagged RKN-only keep their order for T = sqrt(1 + p^2);
    // the flagged ones must really lose it (else the flag is wrong).
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        if (!t.needs_quadratic_kinetic()) {
            check_order(t, order_problem::nonquadratic_kinetic, t.order());
        } else {
            const double o = measure_order(t, order_problem::nonquadratic_kinetic).order;
            CAPTURE(o);
            CHECK(o < t.order() - 0.5);
        }
    }
}

TEST_CASE("catalog: force-gradient methods, order measured, and they need quadratic T") {
    for (const table& t : force_gradient_catalog()) {
        CAPTURE(t.name());
        CHECK(t.has_force_gradient());
        CHECK(t.needs_quadratic_kinetic());
        CHECK(t.family() == "force-gradient");
        CHECK(t.citation().size() > 10);
        check_order(t, order_problem::pendulum, t.order());
        check_order(t, order_problem::kepler, t.order());
        // With T = sqrt(1 + p^2), [V,[T,V]] depends on p and is no kick: the order must drop.
        const double o = measure_order(t, order_problem::nonquadratic_kinetic).order;
        CAPTURE(o);
        CHECK(o < t.order() - 0.5);
    }
    // The sign of the gradient term matters: Chin's 4A with its gradient negated is a second-order method.
    const table& chin = force_gradient_method("chin_4a");
    std::vector<coefficient> flipped = chin.gradient();
    for (coefficient& g : flipped) g = -g;
    const table wrong("chin_4a_flipped", chin.kick(), chin.drift(), flipped, 4, "test");
    CHECK(std::fabs(measure_order(wrong, order_problem::kepler).order - 2) <= 0.15);
    CHECK_THROWS_WITH_AS(force_gradient_method("chin_4b"), doctest::Contains("chin_4a, chin_4a_triple_jump"),
                         invalid_argument);
}

TEST_CASE("catalog: symmetric methods retrace their steps, step(dt) then step(-dt)") {
    for (const table& t : catalog()) {
        if (!t.is_symmetric()) continue;
        CAPTURE(t.name());
        splitting_stepper<hamiltonians::pendulum, State1> s({}, t);
        const State1 x0(V1(1.1), V1(-0.4));
        State1 x = x0;
        for (int i = 0; i < 10; ++i) s.step(x, 0.1);
        for (int i = 0; i < 10; ++i) s.step(x, -0.1);
        CHECK(max_difference(x, x0) <= 1e-13);
    }
}

TEST_CASE("catalog: adjoint(adjoint(t)) == t, and symmetric entries are their own adjoint") {
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        CHECK(adjoint(adjoint(t)) == t);
        if (t.is_symmetric()) CHECK(adjoint(t) == t);
    }
}

TEST_CASE("catalog: Gould & Tobochnik's Verlet table is velocity Verlet") {
    // Gould & Tobochnik eq. 3.75: M = 2, a = (1, 1), b = (2, 0) reduces to eq. 3.48.
    CHECK(method("verlet_seed") == method("leapfrog_kdk"));
    splitting_stepper<hamiltonians::pendulum, State1> seed({}, method("verlet_seed"));
    State1 x(V1(1.0), V1(0.2)), y = x;
    seed.steps(x, 0.05, 100);
    const auto verlet_by_hand = [](State1& s, double dt) {  // Gould & Tobochnik eq. 3.48
        const double a0 = -std::sin(s.q[0]);
        s.q[0] += s.p[0] * dt + 0.5 * a0 * dt * dt;
        s.p[0] += 0.5 * (a0 - std::sin(s.q[0])) * dt;
    };
    for (int i = 0; i < 100; ++i) verlet_by_hand(y, 0.05);
    CHECK(max_difference(x, y) <= 1e-13);
}

TEST_CASE("catalog: symplectic methods show no energy drift over 1e5 pendulum steps") {
    // A symplectic method's energy error stays bounded: its largest excursion in
    // the last tenth of the run is no larger than in the first tenth (a drifting
    // method grows ~10x). dt is chosen per method so that the energy error sits
    // between 1e-10 and 1e-4, far above roundoff.
    const hamiltonians::pendulum h;
    const State1 x0(V1(2.0), V1(0.0));
    const double e0 = energy(h, x0);
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        splitting_stepper<hamiltonians::pendulum, State1> s(h, t);
        double dt = 0.5 * t.stability_interval();
        for (;; dt /= 2) {
            State1 x = x0;
            double worst = 0;
            for (int i = 0; i < 200; ++i) {
                s.step(x, dt);
                worst = std::max(worst, std::fabs(energy(h, x) - e0));
            }
            if (worst < 1e-4) break;
        }
        CAPTURE(dt);
        const int n = 100000;
        double first = 0, last = 0;
        State1 x = x0;
        for (int i = 1; i <= n; ++i) {
            s.steps(x, dt, 1);
            const double err = std::fabs(energy(h, x) - e0);
            if (i <= n / 10) first = std::max(first, err);
            if (i > n - n / 10) last = std::max(last, err);
        }
        CAPTURE(first);
        CAPTURE(last);
        CHECK(last <= 1.5 * first + 1e-13);
    }
    // The same criterion catches a method that drifts: explicit Euler.
    State1 x = x0;
    double first = 0, last = 0;
    for (int i = 1; i <= 100000; ++i) {
        const double q = x.q[0];
        x.q[0] += 1e-3 * x.p[0];
        x.p[0] -= 1e-3 * std::sin(q);
        const double err = std::fabs(energy(h, x) - e0);
        if (i <= 10000) first = std::max(first, err);
        if (i > 90000) last = std::max(last, err);
    }
    CHECK(last > 1.5 * first);
}

TEST_CASE("catalog: composition weights match the published centre weight") {
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

TEST_CASE("catalog: Blanes, Casas & Escorihuela's order-8 tables read with kick and drift swapped measure 4") {
    // Some public copies of these tables put the paper's a (drift) weights on
    // the kicks; read that way each is an order-4 method.
    for (const char* name : {"blanes_casas_escorihuela_a18", "blanes_casas_escorihuela_b17",
                             "blanes_casas_escorihuela_b19"}) {
        CAPTURE(name);
        const table& t = method(name);
        std::vector<substep> ops = t.substeps();  // the same sequence, each weight given the other role
        for (substep& o : ops) o.kind = o.kind == substep::kick ? substep::drift : substep::kick;
        const table swapped = table::from_substeps("swapped", ops, 4, "", kinetic_requirement::quadratic);
        const double right = measure_order(t, order_problem::pendulum).order;
        const double wrong = measure_order(swapped, order_problem::pendulum).order;
        CAPTURE(right);
        CAPTURE(wrong);
        CHECK(std::fabs(right - 8) <= 0.15);
        CHECK(std::fabs(wrong - 4) <= 0.15);
    }
}

TEST_CASE("catalog: coefficients computed by palindrome() match the published ones") {
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

TEST_CASE("catalog: at least 50 entries, each in a family, the Laskar-Robutel first members are the leapfrogs") {
    CHECK(catalog().size() >= 50);
    for (const table& t : catalog()) {
        CAPTURE(t.name());
        CHECK(!t.family().empty());
        CHECK(t.family() == (t.needs_quadratic_kinetic() ? "RKN" : t.family()));
    }
    CHECK(method("saba_1") == method("leapfrog_dkd"));
    CHECK(method("sbab_1") == method("leapfrog_kdk"));
    CHECK(method("yoshida_4") == triple_jump(method("leapfrog_kdk")));
    CHECK(method("suzuki_4") == suzuki_fractal(method("leapfrog_kdk")));
}

TEST_CASE("catalog: unknown names list the valid ones") {
    try {
        (void)method("leapfrog_kdx");
        FAIL("no exception");
    } catch (const invalid_argument& e) {
        const std::string what = e.what();
        CHECK(what.find("'leapfrog_kdx'") != std::string::npos);
        CHECK(what.find("leapfrog_kdk") != std::string::npos);
        CHECK(what.find("sofroniou_spaletta_10") != std::string::npos);
    }
}

}  // namespace test_methods_test_catalog
