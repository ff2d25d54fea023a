// The one check of a run's span: finite t0 and t_end with t_end > t0, the
// caller and both times named.
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include <sympl/core/time_span.hpp>

namespace test_core_test_time_span {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;

TEST_CASE("time span: t_end > t0, both finite, or an error naming the caller and both times") {
    CHECK_NOTHROW(check_time_span("f", 0.0, 1.0));
    CHECK_NOTHROW(check_time_span("f", -1e300, 1e300));
    CHECK_THROWS_WITH_AS(check_time_span("f", 1.0, 1.0),
                         doctest::Contains("f: t_end = 1 with t0 = 1; expected finite times with t_end > t0"),
                         invalid_argument);
    CHECK_THROWS_WITH_AS(check_time_span("g", 2.0, 1.0), doctest::Contains("g: t_end = 1 with t0 = 2"), invalid_argument);
    CHECK_THROWS_WITH_AS(check_time_span("h", 0.0, HUGE_VAL), doctest::Contains("t_end = inf"), invalid_argument);
    CHECK_THROWS_WITH_AS(check_time_span("h", std::nan(""), 1.0), doctest::Contains("t0 = nan"), invalid_argument);
    CHECK_THROWS_AS(check_time_span("h", 0.0L, -1.0L), invalid_argument);
}

}  // namespace test_core_test_time_span
