// The grammar of a method's name: head(inside), its last argument outside
// parentheses, key = value. What each head means is test_method_kinds.cpp's.
#include <doctest/doctest.h>

#include "methods/method_name.hpp"

namespace test_program_test_method_name {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;

TEST_CASE("method names: a call's head and inside, plain names none") {
    const auto call = call_of("extrapolated(logh(leapfrog_dkd), 6)");
    REQUIRE(call);
    CHECK(call->head == "extrapolated");
    CHECK(call->inside == "logh(leapfrog_dkd), 6");
    CHECK(call_of("wh( saba_2 , corrector = 5 )")->inside == "saba_2 , corrector = 5");
    CHECK_FALSE(call_of("leapfrog_kdk"));
    CHECK_FALSE(call_of("(leapfrog_kdk)"));  // no head
    CHECK_FALSE(call_of("wh()"));            // nothing inside
    CHECK_FALSE(call_of("wh(saba_2"));       // not closed
}

TEST_CASE("method names: the last argument is split at the last comma outside parentheses") {
    const auto outer = split_last("logh(leapfrog_dkd), 6");
    REQUIRE(outer);
    CHECK(outer->before == "logh(leapfrog_dkd)");
    CHECK(outer->argument == "6");
    // A comma inside the inner name's parentheses is the inner name's.
    const auto nested = split_last("my(a, b)");
    CHECK_FALSE(nested);
    const auto wh = split_last("saba_2, kernel = lazy, corrector = 5");
    REQUIRE(wh);
    CHECK(wh->before == "saba_2, kernel = lazy");
    CHECK(wh->argument == "corrector = 5");
    CHECK_FALSE(split_last("leapfrog_kdk"));
}

TEST_CASE("method names: key = value, and a bare word without a value") {
    const method_option o = option_of(" corrector =  5 ");
    CHECK(o.key == "corrector");
    REQUIRE(o.value);
    CHECK(*o.value == "5");
    const method_option bare = option_of("corrector");
    CHECK(bare.key == "corrector");
    CHECK_FALSE(bare.value);
    CHECK(*option_of("omega =").value == "");
}

}  // namespace test_program_test_method_name
