// Writing files: complete or not at all, quoted CSV, and gnuplot strings that
// cannot run commands.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sympl/core/error.hpp>

#include "read_csv.hpp"
#include "scratch_directory.hpp"
#include "output/writers.hpp"

namespace test_program_test_writers {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;
namespace fs = std::filesystem;

namespace {
std::string contents(const fs::path& file) {
    std::ifstream in(file);
    return (std::stringstream() << in.rdbuf()).str();
}
}  // namespace

TEST_CASE("writers: an atomic file appears on commit, and a file not committed leaves the old one") {
    const fs::path dir = scratch_directory("sympl_test_writers");
    fs::remove_all(dir);
    fs::create_directories(dir);
    {
        atomic_file f(dir / "out.csv");
        f.stream() << "old\n";
        CHECK_FALSE(fs::exists(dir / "out.csv"));
        f.commit();
    }
    CHECK(contents(dir / "out.csv") == "old\n");
    {
        atomic_file f(dir / "out.csv");
        f.stream() << "new, half-written";
    }  // not committed: a run that failed
    CHECK(contents(dir / "out.csv") == "old\n");
    std::size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
    CHECK(files == 1);  // no temporary left behind
    CHECK_THROWS_WITH_AS(atomic_file(dir / "no such dir" / "x.csv"), doctest::Contains("cannot write"), sympl::error);
    fs::remove_all(dir);
}

TEST_CASE("writers: a commit that cannot complete is an error naming the file, and leaves nothing behind") {
    const fs::path dir = scratch_directory("sympl_test_writers_fail");
    fs::remove_all(dir);
    fs::create_directories(dir / "taken" / "inside");  // a non-empty directory where the file should go
    {
        atomic_file f(dir / "taken");
        f.stream() << "data\n";
        const std::string path = (dir / "taken").string();
        CHECK_THROWS_WITH_AS(f.commit(), doctest::Contains(path.c_str()), sympl::error);
    }
    std::size_t files = 0;
    for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
    CHECK(files == 0);
    fs::remove_all(dir);
}

TEST_CASE("writers: CSV fields with commas, quotes and line breaks read back as written") {
    CHECK(csv_field("plain") == "plain");
    CHECK(csv_field("a,b") == "\"a,b\"");
    CHECK(csv_field("say \"hi\"") == "\"say \"\"hi\"\"\"");
    const fs::path file = scratch_directory("sympl_test_quoted.csv");
    {
        std::ofstream out(file);
        out << csv_line({"name", "value"}) << csv_line({"a, \"b\"\nc", "1"});
    }
    const auto rows = read_csv(file);
    REQUIRE(rows.size() == 2);
    CHECK(rows[1] == std::vector<std::string>{"a, \"b\"\nc", "1"});
    fs::remove(file);
}

TEST_CASE("writers: names become safe file names and gnuplot strings") {
    CHECK(file_name_part("ho_../../x") == "ho_.._.._x");
    CHECK(file_name_part("../x").find('/') == std::string::npos);
    CHECK(file_name_part(".hidden")[0] != '.');
    CHECK(file_name_part("") == "_");
    CHECK(gnuplot_string("x' ; system \"touch /tmp/p\" ; #") == "'x'' ; system \"touch /tmp/p\" ; #'");
    CHECK(gnuplot_string("a\nb") == "'a b'");
    CHECK(markdown_cell("a|b\nc") == "a\\|b c");
}

TEST_CASE("writers: gnuplot starts without a shell: a hostile script path runs nothing") {
    if (!have_gnuplot()) return;
    const fs::path marker = scratch_directory("sympl_test_gnuplot_marker");
    fs::remove(marker);
    const fs::path dir = scratch_directory("sympl_test_o'; touch " + marker.string() + "; '");
    fs::create_directories(dir);
    {
        std::ofstream gp(dir / "plot.gp");
        gp << "set terminal pngcairo\nset output " << gnuplot_string((dir / "plot.png").string()) << "\nplot x\n";
    }
    run_gnuplot(dir / "plot.gp", dir / "plot.png");
    CHECK(fs::exists(dir / "plot.png"));
    CHECK_FALSE(fs::exists(marker));
    fs::remove_all(dir);
}

}  // namespace test_program_test_writers
