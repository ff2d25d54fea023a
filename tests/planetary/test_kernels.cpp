// The composition kernel's sub-steps (Wisdom, Holman & Touma 1996; Rein,
// Tamayo & Brown 2019).
#include <doctest/doctest.h>

#include <cmath>
#include <utility>
#include <vector>

#include <sympl/planetary/kernels.hpp>

namespace test_planetary_test_kernels {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

// The composition kernel's sub-steps (kernel_substeps): in total one kick and
// no drift; every side kick cancelled by one of opposite weight at the same
// Kepler phase (so to first order in the interaction the kernel is kick(h)
// and the leapfrog's corrector still fits); 2ab = 1/24, the weight of the
// commutator that cancels the corrected leapfrog's -h^2/24 [B,[A,B]].
TEST_CASE("wisdom_holman: the composition kernel's sub-steps") {
    const std::vector<substep> ops = kernel_substeps(wh_kernel::composition);
    long double time = 0, kicks = 0;
    std::vector<std::pair<long double, long double>> at;  // (Kepler phase, kick weight)
    for (const substep& o : ops) {
        if (o.kind == substep::drift) time += o.weight;
        else kicks += o.weight, at.emplace_back(time, o.weight);
    }
    CHECK(time == 0);
    CHECK(kicks == 1);
    for (const auto& [t, w] : at) {
        long double sum = 0;
        for (const auto& [u, v] : at) sum += (u == t ? v : 0);
        CHECK(sum == (t == 0 ? 1 : 0));
    }
    CHECK(std::fabs(2 * composition_kernel_drift * composition_kernel_kick - 1.0L / 24) < 1e-18L);
    CHECK(kernel_substeps(wh_kernel::kick).size() == 1);
}

// Wisdom, Holman & Touma 1996; Rein, Tamayo & Brown 2019: corrector and
// kernel leave O(eps h^(2K+2) + eps^2 h^4), the corrector alone O(eps^2 h^2).
// eps = 1e-3 and h from 1/20 to 1/40 of the inner period with corrector 17:
// the eps h^18 term is far below both (the corrector-17 test above), so the

}  // namespace test_planetary_test_kernels
