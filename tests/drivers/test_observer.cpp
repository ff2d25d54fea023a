// observer_ref: one driver for observed and unobserved runs. Held over a
// callable it must see what the callable itself sees, bit for bit; empty it
// must change nothing of the unobserved run, including where a resumed run
// may start.
#include <doctest/doctest.h>

#include <cmath>
#include <utility>
#include <vector>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/hamiltonians/pendulum.hpp>

namespace test_drivers_test_observer {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
using S1 = phase_space<double, 1>;
using V1 = Eigen::Matrix<double, 1, 1>;
using seen = std::vector<std::pair<double, S1>>;

bool same_bits(const S1& a, const S1& b) { return a.q[0] == b.q[0] && a.p[0] == b.p[0]; }
bool same_bits(const seen& a, const seen& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].first != b[i].first || !same_bits(a[i].second, b[i].second)) return false;
    return true;
}
S1 start() { return {V1(1.2), V1(0.3)}; }
}  // namespace

TEST_CASE("observer_ref sees what its callable sees, and empty it is the unobserved run") {
    const hamiltonians::pendulum h{};
    const table t = method("blanes_moan_s6");
    seen direct, through;
    const auto record = [](seen& into) { return [&into](const S1& x, double time) { into.emplace_back(time, x); }; };
    // 1003 steps of 0.01 to 10.035: a shortened last step, observed at its end.
    splitting_stepper<hamiltonians::pendulum, S1> a(h, t), b(h, t), c(h, t), d(h, t);
    S1 xa = start(), xb = start(), xc = start(), xd = start();
    auto to_direct = record(direct);
    auto to_through = record(through);
    const run_summary ra = integrate_until(a, xa, 0.0, 10.035, 0.01, to_direct);
    const run_summary rb = integrate_until(b, xb, 0.0, 10.035, 0.01, observer_ref<S1, double>(to_through));
    CHECK(direct.size() == 1005);  // t0, 1003 full steps, the short one
    CHECK(same_bits(direct, through));
    CHECK(same_bits(xa, xb));
    CHECK(ra.force_evaluations == rb.force_evaluations);

    const run_summary rc = integrate_until(c, xc, 0.0, 10.035, 0.01);
    const run_summary rd = integrate_until(d, xd, 0.0, 10.035, 0.01, observer_ref<S1, double>{});
    CHECK(same_bits(xc, xd));
    CHECK(rc.steps == rd.steps);
    CHECK(rc.force_evaluations == rd.force_evaluations);
    CHECK(rc.force_evaluations == ra.force_evaluations);  // the observer changes nothing of the run
}

TEST_CASE("observer_ref: an empty one resumes where the unobserved run may, at check_every") {
    const hamiltonians::pendulum h{};
    const table t = method("leapfrog_kdk");
    splitting_stepper<hamiltonians::pendulum, S1> whole(h, t), first(h, t);
    S1 x = start(), y = start();
    integrate_steps(whole, x, 0.0, 0.05, 640);
    run_options o;
    integrate_steps(first, y, 0.0, 0.05, 128, observer_ref<S1, double>{});
    splitting_stepper<hamiltonians::pendulum, S1> second(h, t);
    second.restore(first.memory());
    o.first_step = 128;  // a multiple of check_every (64): the unobserved cadence
    integrate_steps(second, y, 0.0, 0.05, 640, observer_ref<S1, double>{}, o);
    CHECK(same_bits(x, y));
    o.first_step = 100;
    CHECK_THROWS_AS(integrate_steps(second, y, 0.0, 0.05, 640, observer_ref<S1, double>{}, o), invalid_argument);
}

TEST_CASE("observer_ref in the controlled driver and in LogH's: the same bits, empty or not") {
    const hamiltonians::pendulum h{};
    control_options co;
    co.absolute_tolerance = co.relative_tolerance = 1e-9;
    seen direct, through;
    auto to_direct = [&](const S1& x, double time) { direct.emplace_back(time, x); };
    auto to_through = [&](const S1& x, double time) { through.emplace_back(time, x); };
    auto s1 = make_rkn_stepper<dprkn8, S1>(h);
    auto s2 = make_rkn_stepper<dprkn8, S1>(h);
    auto s3 = make_rkn_stepper<dprkn8, S1>(h);
    S1 x1 = start(), x2 = start(), x3 = start();
    const control_summary r1 = integrate_controlled(s1, x1, 0.0, 20.0, co, to_direct);
    integrate_controlled(s2, x2, 0.0, 20.0, co, observer_ref<S1, double>(to_through));
    const control_summary r3 = integrate_controlled(s3, x3, 0.0, 20.0, co, observer_ref<S1, double>{});
    CHECK(direct.size() == r1.accepted + 1);
    CHECK(same_bits(direct, through));
    CHECK(same_bits(x1, x2));
    CHECK(same_bits(x1, x3));
    CHECK(r3.accepted == r1.accepted);

    using K = phase_space<double, 2>;
    using KX = phase_space<double, 3>;
    const hamiltonians::kepler k{};
    std::vector<double> times_direct, times_through;
    auto time_direct = [&](const KX&, double time) { times_direct.push_back(time); };
    auto time_through = [&](const KX&, double time) { times_through.push_back(time); };
    const auto orbit = [&](auto&& observer) {
        KX X = to_extended(k, hamiltonians::kepler::initial_state(0.7));
        splitting_stepper<logh<hamiltonians::kepler>, KX> s({k}, method("forest_ruth_4"));
        const run_summary r = integrate_to_time(s, X, 6.0, 0.01, observer);
        return std::pair{physical_state(X), r.steps};
    };
    const auto [kd, nd] = orbit(time_direct);
    const auto [kt, nt] = orbit(observer_ref<KX, double>(time_through));
    const auto [ke, ne] = orbit(observer_ref<KX, double>{});
    CHECK(times_direct == times_through);
    CHECK(times_direct.size() == nd);
    CHECK(nd == ne);
    CHECK((kd.q == kt.q && kd.p == kt.p && kd.q == ke.q && kd.p == ke.p));
    static_assert(std::is_same_v<decltype(kd), const K>);
}

}  // namespace test_drivers_test_observer
