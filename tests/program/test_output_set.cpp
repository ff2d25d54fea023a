// Output sets: staged, committed together, one process per directory, and
// the temporaries of a killed process cleaned on the next run.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sympl/core/error.hpp>

#include "output/output_set.hpp"
#include "output/writers.hpp"
#include "scratch_directory.hpp"

namespace test_program_test_output_set {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;
namespace fs = std::filesystem;

namespace {
void write(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }
std::string read(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}
}  // namespace

TEST_CASE("output_set: a set not committed leaves the previous one whole, a committed one replaces it") {
    const fs::path dir = scratch_directory("sympl_test_output_set");
    fs::remove_all(dir);
    fs::create_directories(dir);
    write(dir / "summary.md", "old summary");
    write(dir / "work_precision.csv", "old csv");
    fs::path staging;
    {
        output_set set(dir);
        staging = set.staging();
        CHECK(staging.parent_path() == dir);
        write(staging / "work_precision.csv", "new csv");  // a report that stops before its summary
    }
    CHECK_FALSE(fs::exists(staging));
    CHECK(read(dir / "summary.md") == "old summary");
    CHECK(read(dir / "work_precision.csv") == "old csv");
    {
        output_set set(dir);
        write(set.staging() / "work_precision.csv", "new csv");
        write(set.staging() / "summary.md", "new summary");
        set.commit();
        CHECK_FALSE(fs::exists(set.staging()));
    }
    CHECK(read(dir / "summary.md") == "new summary");
    CHECK(read(dir / "work_precision.csv") == "new csv");
    fs::remove_all(dir);
}

TEST_CASE("output_set: a second process is told who holds the directory, a killed one's temporaries are removed") {
    const fs::path dir = scratch_directory("sympl_test_output_lock");
    fs::remove_all(dir);
    fs::create_directories(dir / "cache");
    // What a process killed with SIGKILL leaves: a staging directory and .part temporaries.
    fs::create_directories(dir / ".sympl-staging-4194304");
    write(dir / ".sympl-staging-4194304" / "work_precision.csv", "half");
    write(dir / ".summary.md.sympl-part-4194304", "half");
    write(dir / "cache" / ".reference_1.txt.sympl-part-4194304", "half");
    write(dir / "keep.csv", "a user's file");
    {
        output_set first(dir);
        CHECK(first.stale_removed() == 3);
        CHECK_FALSE(fs::exists(dir / ".sympl-staging-4194304"));
        CHECK_FALSE(fs::exists(dir / ".summary.md.sympl-part-4194304"));
        CHECK_FALSE(fs::exists(dir / "cache" / ".reference_1.txt.sympl-part-4194304"));
        CHECK(fs::exists(dir / "keep.csv"));
        // Another run into the same directory while this one holds it.
        try {
            output_set second(dir);
            FAIL("a second output set on one directory was accepted");
        } catch (const sympl::error& e) {
            const std::string what = e.what();
            CHECK(what.find("is being written by another sympl (process " + std::to_string(::getpid()) + ")") !=
                  std::string::npos);
        }
        CHECK(fs::exists(first.staging()));  // the loser touched nothing of the winner's
    }
    output_set again(dir);  // released with the first
    CHECK(again.stale_removed() == 0);
    fs::remove_all(dir);
}

TEST_CASE("output_set: only this program's own leftovers are removed, and no symlink is written through") {
    const fs::path dir = scratch_directory("sympl_test_output_own_files");
    fs::remove_all(dir);
    fs::create_directories(dir);
    // A user's files named like the old temporaries, or like a staging
    // directory but not one, and symlinks of the temporaries' form: all kept.
    write(dir / ".notes.part-2024", "a user's notes");
    write(dir / ".sympl-staging-notes", "a user's file");
    write(dir / "target.txt", "a user's file a symlink points to");
    fs::create_symlink(dir / "target.txt", dir / ".summary.md.sympl-part-77");
    fs::create_directories(dir / "elsewhere");
    fs::create_directory_symlink(dir / "elsewhere", dir / ".sympl-staging-78");
    {
        output_set set(dir);
        CHECK(set.stale_removed() == 0);
    }
    CHECK(fs::exists(dir / ".notes.part-2024"));
    CHECK(fs::exists(dir / ".sympl-staging-notes"));
    CHECK(fs::is_symlink(dir / ".summary.md.sympl-part-77"));
    CHECK(fs::is_symlink(dir / ".sympl-staging-78"));
    CHECK(fs::exists(dir / "elsewhere"));
    // A lock planted as a symlink to a user's file: refused, the file untouched.
    const fs::path other = scratch_directory("sympl_test_output_planted_lock");
    fs::remove_all(other);
    fs::create_directories(other);
    fs::create_symlink(dir / "target.txt", other / ".sympl.lock");
    const std::string refusal = (other / ".sympl.lock").string() +
                                " is a symlink; expected the lock file this program makes there (or none): it writes "
                                "no file through a symlink; remove it";
    CHECK_THROWS_WITH_AS(output_set{other}, refusal.c_str(), sympl::error);
    CHECK((std::stringstream() << std::ifstream(dir / "target.txt").rdbuf()).str() == "a user's file a symlink points to");
    // A temporary planted as a symlink where an atomic_file would write: refused, the target untouched.
    fs::create_symlink(dir / "target.txt", temporary_for(dir / "out.csv", true));
    CHECK_THROWS_AS(atomic_file{dir / "out.csv"}, sympl::error);
    CHECK((std::stringstream() << std::ifstream(dir / "target.txt").rdbuf()).str() == "a user's file a symlink points to");
    fs::remove_all(dir);
    fs::remove_all(other);
}

}  // namespace test_program_test_output_set
