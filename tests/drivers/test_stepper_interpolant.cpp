// A stepper's own interpolation (stepper_interpolant over rkn_pair_stepper):
// the end states exactly; dprkn6 by its continuous extension, at no force;
// dprkn8 and dprkn12 by a partial step, bit for bit the pair's step of
// theta dt from the step's start, at s - 1 forces.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <sympl/drivers/stepper_interpolant.hpp>
#include <sympl/methods/rkn_pairs.hpp>
#include <sympl/hamiltonians/kepler.hpp>

namespace test_drivers_test_stepper_interpolant {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using S2 = phase_space<double, 2>;

namespace {
template <class Pair>
void check_pair() {
    auto s = make_rkn_stepper<Pair, S2>(hamiltonians::kepler{});
    static_assert(interpolating_stepper<decltype(s)>);
    const S2 x0 = hamiltonians::kepler::initial_state(0.5);
    S2 x = x0;
    stepper_interpolant<decltype(s)> dense(s);
    dense.start(x, 0.0);
    s.step(x, 0.02);
    dense.push(x, 0.02);
    S2 out = x0;
    dense.evaluate(0.0, out);
    CHECK(max_difference(out, x0) == 0);
    dense.evaluate(0.02, out);
    CHECK(max_difference(out, x) == 0);
    dense.evaluate_fraction(0.375, out);
    if constexpr (rkn_dense_table<Pair>) {
        CHECK(max_difference(out, s.dense_output(0.375)) == 0);
        CHECK(dense.force_evaluations() == 0);
    } else {
        auto fresh = make_rkn_stepper<Pair, S2>(hamiltonians::kepler{});
        S2 y = x0;
        fresh.step(y, 0.375 * 0.02);
        CHECK(max_difference(out, y) == 0);
        CHECK(dense.force_evaluations() == std::uint64_t(Pair::stages - 1));
    }
    // Either way, within the pair's local error of Kepler's exact state: at
    // pericentre dprkn6's step of 0.25 is 5e-5 off; its error, O(dt^7) in q
    // and dt^6 in p for the extension, is below 5e-5 (0.02 / 0.25)^6 = 1.3e-11 here.
    const double error = max_difference(out, hamiltonians::kepler::exact_state(0.5, 0.375 * 0.02));
    MESSAGE(std::string(Pair::name), ": interpolated 0.375 into a step of 0.02 at pericentre, off by ", error);
    CHECK(error < 1e-10);
}
}  // namespace

TEST_CASE("stepper interpolant: the RKN pairs interpolate themselves inside their last step") {
    check_pair<dprkn6>();
    check_pair<dprkn8>();
    check_pair<dprkn12>();
}

}  // namespace test_drivers_test_stepper_interpolant
