// The method-kind registry: how names resolve and what each kind needs.
#include <doctest/doctest.h>

#include <string>

#include <sympl/catalog.hpp>

#include "method_kinds.hpp"

using namespace sympl::app;

TEST_CASE("method kinds: a name resolves to its kind; a scene's table comes first") {
    CHECK(resolve_method("rk4", {})->kind == method_kind::classic);
    CHECK(resolve_method("odeint_rk4", {})->kind == method_kind::odeint_rk4);
    CHECK(resolve_method("odeint_dopri5", {})->kind == method_kind::odeint_dopri5);
    const auto table = resolve_method("yoshida_6", {});
    REQUIRE(table);
    CHECK(table->kind == method_kind::table);
    CHECK(table->coefficients->order() == 6);
    CHECK_FALSE(resolve_method("rk5", {}));
    for (const auto& name : sympl::catalog_names()) CHECK(resolve_method(name, {}));
    for (const auto& name : method_names_beside_tables()) CHECK(resolve_method(name, {}));
    CHECK(entry_of(method_kind::odeint_dopri5).adaptive);
    CHECK_FALSE(entry_of(method_kind::odeint_rk4).adaptive);
}

TEST_CASE("method kinds: what each needs, and the reason when a system lacks it") {
    const system_form hamiltonian{true, false, false}, damped{false, true, true};
    const auto m = [](const char* name) { return *resolve_method(name, {}); };
    CHECK(why_not(m("leapfrog_kdk"), hamiltonian).empty());
    CHECK(why_not(m("leapfrog_kdk"), damped) ==
          "method 'leapfrog_kdk' needs a separable Hamiltonian H = T(p) + V(q); this system is not Hamiltonian (use a "
          "classic method)");
    CHECK(why_not(m("leapfrog_two_step"), hamiltonian).find("needs Newton's form") != std::string::npos);
    CHECK(why_not(m("leapfrog_two_step"), damped).empty());
    CHECK(why_not(m("damped_leapfrog"), hamiltonian).find("F(x, t) - G(v)") != std::string::npos);
    for (const char* any : {"euler", "rk4", "velocity_verlet", "predictor_corrector", "odeint_rk4", "odeint_dopri5"}) {
        CHECK(why_not(m(any), hamiltonian).empty());
        CHECK(why_not(m(any), damped).empty());
    }
}
