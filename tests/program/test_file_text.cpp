// Files read with a type check and a size limit (src/reading/file_text.hpp).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "reading/file_text.hpp"
#include "scratch_directory.hpp"

namespace test_program_test_file_text {  // one per file: the tests build in batches (CMakeLists.txt)

using namespace sympl::app;
namespace fs = std::filesystem;

TEST_CASE("file_text: a regular file up to the limit is read whole, anything else says what it is") {
    const fs::path dir = scratch_directory("sympl_test_file_text");
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string ten = "0123456789";
    std::ofstream(dir / "ten") << ten;
    const file_text whole = read_file_text(dir / "ten", 10);
    CHECK(whole.failure.empty());
    CHECK(whole.text == ten);
    // One byte over: refused, with the limit.
    CHECK(read_file_text(dir / "ten", 9).failure == "is larger than 9 bytes; expected at most that");
    // A file larger than one reading piece (1 MiB) comes back byte for byte.
    const std::string big(3 * (std::size_t(1) << 20) + 7, 'x');
    std::ofstream(dir / "big", std::ios::binary) << big;
    CHECK(read_file_text(dir / "big", big.size()).text == big);
    CHECK(read_file_text(dir / "big", big.size() - 1).failure.find("is larger than") == 0);
    // Not regular files: refused by kind before any byte is read (/dev/zero
    // never ends), and a symlink judged by what it names.
    CHECK(read_file_text(dir, 100).failure == "is a directory; expected a regular file");
    CHECK(read_file_text("/dev/zero", 100).failure == "is a character device; expected a regular file");
    fs::create_symlink(dir / "ten", dir / "link");
    CHECK(read_file_text(dir / "link", 10).text == ten);
    CHECK(read_file_text(dir / "missing", 10).failure.rfind("cannot be opened: ", 0) == 0);
    fs::remove_all(dir);
}

}  // namespace test_program_test_file_text
