// A carried list read back as written, and every count, id, flag or size
// read from it range-checked: a damaged list (a checkpoint file edited or
// cut) is refused by name before it can size an allocation.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include <sympl/core/carried_state.hpp>

namespace test_core_test_carried_state {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl;
using detail::carried_reader;
using detail::carried_writer;
using detail::carried_list;
using detail::restore_carried_list;

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

namespace {
// A stepper's carried list described once: a flag, a number, a vector, ids,
// a part of its own and a variant of parts.
struct inner_a {
    double x = 0;
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.number(self.x);
    }
};
struct inner_b {
    std::vector<double> v;
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.numbers(self.v);
        l.check(self.v.size() <= 3, "holds more than 3 numbers in b");
    }
};
struct outer {
    bool loaded = false;
    double dt = 0;
    Eigen::VectorXd q;
    std::vector<std::uint64_t> id;
    inner_a a;
    std::variant<inner_a, inner_b> which;
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        l.flag(self.loaded);
        l.number(self.dt);
        l.numbers(self.q);
        l.ids(self.id, "holds a bad id");
        l.check(self.id.size() == std::size_t(self.q.size()), "holds an id for each q, or not");
        l.part(self.a);
        l.part(self.which);
    }
};
}  // namespace

TEST_CASE("carried_fields: one list written and read back, a list that does not fit refused, nothing changed") {
    outer o;
    o.loaded = true;
    o.dt = 0.1;
    o.q = Eigen::Vector2d(1.5, -2.5);
    o.id = {7, 9007199254740991ull};  // 2^53 - 1: the largest id a double holds exactly
    o.a.x = 3;
    o.which = inner_b{{4, 5}};
    const std::vector<double> list = carried_list<double>(o);
    // flag, dt, 2 + 2 numbers, 1 + 2 ids, a, 1 + 2 numbers of b
    CHECK(list.size() == 1 + 1 + 3 + 3 + 1 + 3);

    outer back;
    back.which = inner_b{};  // the alternative is the reader's: the list does not say which
    restore_carried_list<double>(back, list, "outer");
    CHECK(back.loaded);
    CHECK(back.dt == 0.1);
    CHECK(back.q == o.q);
    CHECK(back.id == o.id);
    CHECK(back.a.x == 3);
    CHECK(std::get<inner_b>(back.which).v == std::vector<double>{4, 5});
    CHECK(carried_list<double>(back) == list);

    // A check that fails names what; the object keeps what it had.
    std::vector<double> bad = list;
    bad[5] = 1;  // one id where there are 2 q
    outer kept = back;
    kept.dt = 0.25;
    CHECK_THROWS_WITH_AS(restore_carried_list<double>(kept, bad, "outer"),
                         doctest::Contains("outer: the carried state of 12 numbers holds an id for each q, or not"),
                         invalid_argument);
    CHECK(kept.dt == 0.25);
    std::vector<double> longer = list;
    longer.push_back(0);
    CHECK_THROWS_WITH_AS(restore_carried_list<double>(kept, longer, "outer"),
                         doctest::Contains("is longer than what the stepper carries"), invalid_argument);
    CHECK(kept.dt == 0.25);
}

}  // namespace test_core_test_carried_state
