// The charged kind in the program: each pusher and splitting runs the charged
// systems through the program's run path at its order, keeping H, and what
// does not fit (a system that is no charged particle, a field not symmetric
// about z, Newton-only methods on a relativistic particle) is refused with
// the reason.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "running/systems.hpp"

namespace test_program_test_run_charged {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;

namespace {
run_result run(const runnable_system& p, const std::string& method, double dt, double t_end) {
    run_request rq;
    rq.dt = dt;
    rq.timing_repeats = 0;
    rq.energy = true;
    return p.run(*resolve_method(method, {}), rq, 0.0, t_end, p.x0);
}
}  // namespace

TEST_CASE("run_charged: the charged methods at their order on charged_particle, H kept") {
    const runnable_system p = make_system("charged_particle", {}, {}, {}, "test");
    CHECK(p.form.charged);
    const double t_end = 4;
    const std::vector<double> reference = p.reference(0.0, t_end, 0.002, p.x0);
    for (const auto& [name, order] : {std::pair<const char*, double>{"boris", 2}, {"boris(relativistic = true)", 2},
                                      {"cartesian_split(yoshida_4)", 4}, {"cylindrical_split(blanes_moan_srkn6b)", 4}}) {
        const std::string method = name;
        const double expected = order;
        CAPTURE(method);
        const run_result coarse = run(p, method, 0.1, t_end), fine = run(p, method, 0.05, t_end);
        REQUIRE(coarse.stable);
        REQUIRE(fine.stable);
        const double slope = std::log2(relative_difference(coarse.final_state, reference) /
                                       relative_difference(fine.final_state, reference));
        CAPTURE(slope);
        CHECK(std::abs(slope - expected) < 0.15);
        CHECK(fine.max_energy_error < 1e-3);
    }
}

TEST_CASE("run_charged: charged_uniform runs the pushers and the canonical splitting, refusals name the reason") {
    const runnable_system p = make_system("charged_uniform", {}, {}, {}, "test");
    for (const char* method : {"boris", "boris(relativistic = true)", "cartesian_split(kahan_li_8)", "gauss_6",
                               "odeint_rk4"}) {
        CAPTURE(std::string(method));
        const run_result r = run(p, method, 0.05, 10);
        CHECK(r.stable);
        CHECK(r.max_energy_error < 1e-4);
    }
    CHECK_THROWS_WITH_AS(run(p, "cylindrical_split(leapfrog_kdk)", 0.1, 1), doctest::Contains("symmetric about the z axis"),
                         sympl::invalid_argument);
    const runnable_system relativistic = make_system("charged_uniform", {{"speed_of_light", 3}}, {}, {}, "test");
    CHECK(run(relativistic, "boris(relativistic = true)", 0.05, 10).max_energy_error < 1e-3);
    CHECK_THROWS_WITH_AS(run(relativistic, "boris", 0.1, 1), doctest::Contains("needs Newton's motion"),
                         sympl::invalid_argument);
    const runnable_system pendulum = make_system("pendulum", {}, {}, {}, "test");
    CHECK_THROWS_WITH_AS(run(pendulum, "boris", 0.1, 1), doctest::Contains("needs a charged particle"),
                         sympl::invalid_argument);
    CHECK_THROWS_WITH_AS(resolve_method("cartesian_split(blanes_moan_s6)", {}), doctest::Contains("blanes_moan_s6"),
                         sympl::invalid_argument);
}

}  // namespace test_program_test_run_charged
