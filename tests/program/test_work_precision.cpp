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
    const std::vector<work_point> curve = {{1e-3, 1e-6, 0.4}, {2e-3, 1e-10, 0.2}, {4e-3, 1e-9, 0.1}, {8e-3, 1e-11, 0.05}};
    const auto r = time_to_reach(curve, 1e-8);
    REQUIRE(r);
    CHECK(r->below.seconds == 2e-3);
    CHECK(std::log(r->seconds) == doctest::Approx(std::log(1e-3) + 0.5 * std::log(2.0)));
}

TEST_CASE("work precision: the runs are read in sweep order, so timing noise cannot swap them") {
    // Two tolerances whose runs take nearly the same time: measured in one
    // order in one report and in the other in the next. The bracket of 1e-8
    // (the looser tolerance above it, the tighter below) stays the same.
    for (const double tighter_seconds : {0.99e-3, 1.01e-3}) {
        const std::vector<work_point> curve = {{tighter_seconds, 1e-9, 1e-8}, {1e-3, 1e-7, 1e-6}, {0.5e-3, 1e-5, 1e-4}};
        const auto r = time_to_reach(curve, 1e-8);
        REQUIRE(r);
        CHECK(r->bracketed);
        CHECK(r->above.parameter == 1e-6);
        CHECK(r->below.parameter == 1e-8);
    }
    // The largest setting already below the level: that run's time, whatever the others'.
    const auto first = time_to_reach({{2e-3, 1e-9, 1e-3}, {1e-3, 1e-12, 1e-4}}, 1e-8);
    REQUIRE(first);
    CHECK_FALSE(first->bracketed);
    CHECK(first->seconds == 2e-3);
}

}  // namespace test_program_test_work_precision
