// A carried list read back as written, and every count, id, flag or size
// read from it range-checked: a damaged list (a checkpoint file edited or
// cut) is refused by name before it can size an allocation.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include <sympl/core/carried_state.hpp>

namespace test_core_test_carried_state {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using detail::carried_reader;
using detail::carried_writer;

TEST_CASE("carried state: numbers, flags and vectors read back as written, to the last bit") {
    std::vector<double> list;
    carried_writer<double> w{list};
    const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(5, -1.0 / 3, 7.0 / 3);
    const std::vector<double> u = {0.1, std::nextafter(0.1, 1.0)};
    w.number(-1.0 / 7);
    w.flag(true);
    w.flag(false);
    w.numbers(v);
    w.numbers(u);
    w.number(12345.0);
    REQUIRE(list.size() == 1 + 2 + (1 + 5) + (1 + 2) + 1);

    carried_reader<double> r{list, "stepper"};
    CHECK(r.number() == -1.0 / 7);
    CHECK(r.flag());
    CHECK(!r.flag());
    Eigen::VectorXd v2;
    r.numbers(v2);
    CHECK((v2.array() == v.array()).all());
    std::vector<double> u2(7);  // resized to what was written
    r.numbers(u2);
    CHECK(u2 == u);
    CHECK(r.left() == 1);
    CHECK(r.whole(1e6, "holds a bad count") == 12345);
    CHECK_NOTHROW(r.done());
}

TEST_CASE("carried state: a count beyond what is left, not whole, negative or past 2^53 is refused by name") {
    const double two53 = 9007199254740992.0;
    for (double bad : {1e15, 2.5, -1.0, std::nan(""), two53, 1e300}) {
        CAPTURE(bad);
        const std::vector<double> list = {bad, 0, 0, 0};
        carried_reader<double> r{list, "my_stepper"};
        CHECK_THROWS_WITH_AS(r.whole(r.left(), "holds a bad number of particles"),
                             doctest::Contains("my_stepper: the carried state of 4 numbers holds a bad number of "
                                               "particles (at number 1)"),
                             invalid_argument);
    }
    // At the bound: three numbers follow a count of 3, not of 4.
    const std::vector<double> three = {3, 0, 0, 0}, four = {4, 0, 0, 0};
    carried_reader<double> ok{three, "s"}, over{four, "s"};
    CHECK(ok.whole(ok.left(), "bad") == 3);
    CHECK_THROWS_AS(over.whole(over.left(), "bad"), invalid_argument);
    // An id may be any whole number below 2^53, and not 2^53.
    CHECK(carried_reader<double>::whole_limit == std::ldexp(1.0, 53));
    const std::vector<double> ids = {two53 - 1, two53};
    carried_reader<double> id{ids, "s"};
    CHECK(id.whole("bad id") == std::uint64_t(two53) - 1);
    CHECK_THROWS_WITH_AS(id.whole("holds a bad id"), doctest::Contains("holds a bad id (at number 2)"),
                         invalid_argument);
}

TEST_CASE("carried state: a list cut short, too long, with a bad flag or a bad size is refused by name") {
    const std::vector<double> list = {2, 1.5};
    {
        carried_reader<double> r{list, "s"};
        std::vector<double> v;
        CHECK_THROWS_WITH_AS(r.numbers(v), doctest::Contains("holds a bad vector size"), invalid_argument);
    }
    {
        carried_reader<double> r{list, "s"};
        CHECK_THROWS_WITH_AS(r.flag(), doctest::Contains("holds a flag that is neither 0 nor 1"), invalid_argument);
    }
    {
        carried_reader<double> r{list, "s"};
        r.number();
        CHECK_THROWS_WITH_AS(r.done(), doctest::Contains("is longer than what the stepper carries"), invalid_argument);
        r.number();
        CHECK_THROWS_WITH_AS(r.number(), doctest::Contains("ends early"), invalid_argument);
    }
    {
        const std::vector<double> sized = {3, 1, 2, 3};
        carried_reader<double> r{sized, "s"};
        Eigen::Vector2d fixed;
        CHECK_THROWS_WITH_AS(r.numbers(fixed), doctest::Contains("holds a vector of another size than the stepper's"),
                             invalid_argument);
    }
}

}  // namespace test_core_test_carried_state
