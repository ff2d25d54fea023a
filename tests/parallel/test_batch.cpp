// batch.hpp: W lanes, each computed as the same operation on one double.
#include <doctest/doctest.h>

#include <cmath>
#include <random>

#include <sympl/parallel/batch.hpp>
#include <sympl/hamiltonians/henon_heiles.hpp>
#include <sympl/hamiltonians/kepler.hpp>
#include <sympl/sympl.hpp>

namespace test_parallel_test_batch {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

namespace {
template <int W>
batch<double, W> random_batch(std::mt19937_64& g, double lo, double hi) {
    std::uniform_real_distribution<double> u(lo, hi);
    batch<double, W> b;
    for (int i = 0; i < W; ++i) b.set(i, u(g));
    return b;
}
}  // namespace

TEST_CASE("batch: every operation gives in each lane the bits of the same operation on one double") {
    constexpr int W = 8;  // wider than any native width here: the split form is checked too
    std::mt19937_64 g(7);
    for (int trial = 0; trial < 200; ++trial) {
        const auto a = random_batch<W>(g, 0.1, 3), b = random_batch<W>(g, -3, 3);
        const double c = 1.25;
        const batch<double, W> sum = a + b, dif = a - b, pro = a * b, quo = b / a, mix = 2 * a - b / c + 1, neg = -a;
        const batch<double, W> r = sqrt(a), e = exp(b), l = log(a), s = sin(b), co = cos(b), m = lane_max(a, b);
        for (int i = 0; i < W; ++i) {
            CHECK(sum[i] == a[i] + b[i]);
            CHECK(dif[i] == a[i] - b[i]);
            CHECK(pro[i] == a[i] * b[i]);
            CHECK(quo[i] == b[i] / a[i]);
            CHECK(mix[i] == (2 * a[i] - b[i] / c) + 1);
            CHECK(neg[i] == -a[i]);
            CHECK(r[i] == std::sqrt(a[i]));
            CHECK(e[i] == std::exp(b[i]));
            CHECK(l[i] == std::log(a[i]));
            CHECK(s[i] == std::sin(b[i]));
            CHECK(co[i] == std::cos(b[i]));
            CHECK(m[i] == std::max(a[i], b[i]));
        }
    }
    batch<double, 4> x(1.0);
    CHECK(isfinite(x));
    x.set(2, std::nan(""));
    CHECK_FALSE(isfinite(x));
    CHECK(lane_max(batch<double, 4>(1.0), x)[2] == 1.0);  // a NaN lane keeps the other value
}

TEST_CASE("batch: W trajectories stepped in one state agree with each run alone to rounding") {
    // The same stepper loop on a state of batches: each lane does the same
    // IEEE operations as the trajectory alone. Only FMA contraction may differ
    // between the vector and the scalar code, at most one rounding per
    // operation: 2000 steps x 7 stages x ~8 operations x 2^-53 = 1.2e-11 on
    // these regular orbits (errors grow linearly there). Measured: 0, bit for
    // bit, with g++ 12 -O3 with and without -march=native (W = 2 and 8).
    constexpr int W = native_double_width;
    using H = hamiltonians::henon_heiles;
    using B = phase_space<batch<double, W>, 2>;
    B x;
    std::vector<phase_space<double, 2>> alone;
    for (int i = 0; i < W; ++i) {
        const auto s = H::initial_state(0.08, -0.2 + 0.05 * i, 0.01 * i);
        alone.push_back(s);
        for (int k = 0; k < 2; ++k) {
            x.q[k].set(i, s.q[k]);
            x.p[k].set(i, s.p[k]);
        }
    }
    auto batch_stepper = make_stepper<B>(H{}, method("blanes_moan_s6"));
    batch_stepper.steps(x, batch<double, W>(0.05), 2000);
    std::uint64_t single_forces = 0;
    for (int i = 0; i < W; ++i) {
        auto single = make_stepper<phase_space<double, 2>>(H{}, method("blanes_moan_s6"));
        single.steps(alone[i], 0.05, 2000);
        single_forces = single.force_evaluations();
        for (int k = 0; k < 2; ++k) {
            CHECK(std::fabs(x.q[k][i] - alone[i].q[k]) <= 1.2e-11);
            CHECK(std::fabs(x.p[k][i] - alone[i].p[k]) <= 1.2e-11);
        }
    }
    // One force evaluation advances every lane: counted as for one trajectory.
    CHECK(batch_stepper.force_evaluations() == single_forces);
}

}  // namespace test_parallel_test_batch
