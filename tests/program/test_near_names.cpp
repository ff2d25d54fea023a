// Near-name suggestions: which names count as near, and the words they make.
#include <doctest/doctest.h>

#include <string>
#include <vector>

#include "reading/near_names.hpp"

namespace test_program_test_near_names {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;

TEST_CASE("near names: edits counted as insert, delete, replace and a swap of neighbours") {
    CHECK(edit_distance("run", "run") == 0);
    CHECK(edit_distance("rn", "run") == 1);         // a letter left out
    CHECK(edit_distance("reprot", "report") == 1);  // two neighbours swapped: one edit, not two
    CHECK(edit_distance("kepplr", "kepler") == 2);
    CHECK(edit_distance("", "abc") == 3);
}

TEST_CASE("near names: a typo gets its name, a stranger gets none, and the list is cut short") {
    const std::vector<std::string> commands{"tables", "systems", "check-table", "run", "report", "ensemble"};
    CHECK(did_you_mean("rn", commands) == "did you mean 'run'? ");
    CHECK(did_you_mean("RUN", commands) == "did you mean 'run'? ");  // capitals: the nearest of all
    CHECK(did_you_mean("reprot", commands) == "did you mean 'report'? ");
    CHECK(did_you_mean("xyz", commands).empty());  // nothing within one edit of a 3-letter word
    CHECK(expected_one_of("tabels", commands) ==
          "did you mean 'tables'? expected one of: tables, systems, check-table, run, report, ensemble");
    // A name's start typed in full: "yoshida" for the catalog's yoshida_4, behind the one-edit typos.
    CHECK(near_names("yoshida", {"yoshida_4", "yoshida_6", "leapfrog_kdk"}) ==
          std::vector<std::string>{"yoshida_4", "yoshida_6"});
    CHECK(near_names("leapfrog", {"leapfrog_kdk", "leapfrog_dkd", "leapfrog_two_step", "rk4"}).size() == 3);
}

}  // namespace test_program_test_near_names
