// Reading a work-precision curve: log-log interpolation between the runs that bracket a level.
#include <doctest/doctest.h>

#include <cmath>

#include "report/work_precision.hpp"

namespace test_program_test_work_precision {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;

TEST_CASE("work precision: the time to a level is interpolated log-log between the bracketing runs") {
    // Two runs: 1 ms at error 1e-4 and 16 ms at error 1e-12; error ~ time^-2 between them.
    const std::vector<work_point> curve = {{0.016, 1e-12, 0.001}, {0.001, 1e-4, 0.1}};
    const auto r = time_to_reach(curve, 1e-8);
    REQUIRE(r);
    CHECK(r->bracketed);
    CHECK(r->seconds == doctest::Approx(0.004));  // halfway in log error: sqrt(1 ms * 16 ms)
    CHECK(r->above.error == 1e-4);
    CHECK(r->below.error == 1e-12);
    // A level the cheapest run already meets: that run's time, not bracketed.
    const auto easy = time_to_reach(curve, 1e-3);
    REQUIRE(easy);
    CHECK_FALSE(easy->bracketed);
    CHECK(easy->seconds == 0.001);
    // Never reached, or only by unusable points.
    CHECK_FALSE(time_to_reach(curve, 1e-13));
    CHECK_FALSE(time_to_reach({{0, 1e-20, 1}, {-1, 1e-20, 1}}, 1e-8));
}

TEST_CASE("work precision: the first crossing counts when roundoff makes the curve turn back up") {
    const std::vector<work_point> curve = {{1e-3, 1e-6, 0}, {2e-3, 1e-10, 0}, {4e-3, 1e-9, 0}, {8e-3, 1e-11, 0}};
    const auto r = time_to_reach(curve, 1e-8);
    REQUIRE(r);
    CHECK(r->below.seconds == 2e-3);
    CHECK(std::log(r->seconds) == doctest::Approx(std::log(1e-3) + 0.5 * std::log(2.0)));
}

}  // namespace test_program_test_work_precision
