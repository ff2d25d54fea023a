#include <doctest/doctest.h>

#include <cmath>

#include <sympl/sympl.hpp>
#include <sympl/hamiltonians/fpu_beta.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>

// The loop under splitting_stepper (core/splitting_loop.hpp), run through the stepper.
namespace test_core_test_splitting_loop {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
// The table walked sub-step by sub-step, n times, a fresh force at every kick:
// the definition the stepper's loop must reproduce.
template <class H, class State>
void walk(const H& h, const table& t, State& x, double dt, int n, std::uint64_t& forces) {
    typename State::vector f(x.q.size()), v(x.q.size());
    for (int s = 0; s < n; ++s)
        for (const substep& o : t.substeps()) {
            const double w = double(o.weight) * dt;
            if (o.kind == substep::kick) {
                force(h, x.q, f);
                ++forces;
                x.p += w * f;
            } else {
                velocity(h, x.p, v);
                x.q += w * v;
            }
        }
}
}  // namespace

namespace {
// steps(n) and resume_steps against the walk, for one state type.
template <class State>
void check_against_walk(const char* name) {
    const hamiltonians::henon_heiles h;
    const table t = method(name);
    const auto ops = t.substeps();
    const bool joined = ops.front().kind == ops.back().kind;
    const auto start = hamiltonians::henon_heiles::initial_state(0.125, 0.1, 0.0);
    State a(start.q, start.p), b = a;
    auto s = make_stepper<State>(h, t);
    std::uint64_t walked = 0;
    const int n = 500;
    s.steps(a, 0.05, n);
    walk(h, t, b, 0.05, n, walked);
    const double gap = max_difference(a, b);
    if (!joined) CHECK(gap == 0);
    else CHECK(gap < 1e-13);
    // A force per kick, less one per step boundary when a kick ends the step and starts the next.
    const bool reuse = ops.back().kind == substep::kick && ops.front().kind == substep::kick;
    CHECK(s.force_evaluations() == walked - (reuse ? n - 1 : 0));
    // In chunks with resume_steps: the same counts; bit for bit where nothing is joined.
    State c(start.q, start.p);
    auto r = make_stepper<State>(h, t);
    r.steps(c, 0.05, 1);
    r.resume_steps(c, 0.05, 199);
    r.resume_steps(c, 0.05, 300);
    CHECK(r.force_evaluations() == s.force_evaluations());
    if (!joined) CHECK(max_difference(c, a) == 0);
    else CHECK(max_difference(c, a) < 1e-13);
}
}  // namespace

TEST_CASE("splitting_loop: runs the table's sub-steps in order, the last force reused, ends joined") {
    // ruth_3 and mclachlan_atela_4 start and end with different kinds: nothing
    // is joined, so steps(n) is the walk bit for bit. leapfrog_kdk and
    // blanes_moan_s6 end with the kind they start with: one sub-step joined per
    // step boundary, a rounding apart. Kick-first and drift-first tables both,
    // on a small fixed-size state (run as drift-kick pairs) and a dynamic one
    // (kick-drift pairs): each shape meets a body it has to rotate.
    for (const char* name : {"ruth_3", "mclachlan_atela_4", "leapfrog_kdk", "blanes_moan_s6", "odeint_sb3a_mclachlan"}) {
        CAPTURE(name);
        check_against_walk<phase_space<double, 2>>(name);
        check_against_walk<phase_space<double>>(name);
    }
}

namespace {
// FPU-beta with velocity(p, v) writing v = p: the drift is a pass of its own.
struct fpu_velocity_into : hamiltonians::fpu_beta {
    template <class V> void velocity(const V& p, V& v) const { v = p; }
};
}  // namespace

TEST_CASE("splitting_loop: a kick and its drift fused in one pass (velocity(p) = p) give the numbers of two passes") {
    using State = phase_space<double>;
    const int n = 37;
    State a(n);
    for (int i = 0; i < n; ++i) a.q[i] = 0.3 * std::sin(0.7 * i + 0.2), a.p[i] = 0.1 * std::cos(1.3 * i);
    State b = a;
    for (const char* name : {"leapfrog_kdk", "odeint_sb3a_mclachlan", "blanes_moan_s10", "ruth_3"}) {
        CAPTURE(name);
        auto fused = make_stepper<State>(hamiltonians::fpu_beta{1.0}, method(name));
        auto separate = make_stepper<State>(fpu_velocity_into{{1.0}}, method(name));
        fused.steps(a, 0.02, 300);
        separate.steps(b, 0.02, 300);
        CHECK(max_difference(a, b) == 0);
    }
}

namespace {
// The same, saying at run time that velocity(p) is p, as a system behind
// function pointers does (the program's erased_separable).
struct fpu_says_velocity_is_p : fpu_velocity_into {
    bool velocity_is_p() const { return true; }
};
}  // namespace

TEST_CASE("splitting_loop: a system that says velocity(p) = p at run time drifts in the fused pass, same numbers") {
    using State = phase_space<double>;
    const int n = 29;
    State start(n);
    for (int i = 0; i < n; ++i) start.q[i] = 0.3 * std::sin(0.9 * i + 0.4), start.p[i] = 0.1 * std::cos(1.1 * i);
    // Drift-last tables leave a velocity the next call could reuse; the fused
    // pass does not write it, so the chunks must not take a stale one.
    for (const char* name : {"leapfrog_dkd", "leapfrog_kdk", "ruth_3", "blanes_moan_s6"}) {
        CAPTURE(name);
        State a = start, b = start;
        auto says = make_stepper<State>(fpu_says_velocity_is_p{{{1.0}}}, method(name));
        auto separate = make_stepper<State>(fpu_velocity_into{{1.0}}, method(name));
        for (int chunk = 0; chunk < 5; ++chunk) {
            says.resume_steps(a, 0.02, 60);
            separate.resume_steps(b, 0.02, 60);
        }
        CHECK(max_difference(a, b) == 0);
        CHECK(says.force_evaluations() == separate.force_evaluations());
    }
}

}  // namespace test_core_test_splitting_loop
