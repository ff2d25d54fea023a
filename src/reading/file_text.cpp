// Reading a file with a type check and a size limit (file_text.hpp).
#include "reading/file_text.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <system_error>

namespace sympl::app {

namespace {

const char* kind_of(std::filesystem::file_type t) {
    using enum std::filesystem::file_type;
    switch (t) {
        case directory: return "a directory";
        case character: return "a character device";
        case block: return "a block device";
        case fifo: return "a FIFO";
        case socket: return "a socket";
        default: return "not a regular file";
    }
}

}  // namespace

file_text read_file_text(const std::filesystem::path& path, std::size_t limit) {
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (ec) return {{}, "cannot be opened: " + ec.message()};
    if (status.type() != std::filesystem::file_type::regular)
        return {{}, std::string("is ") + kind_of(status.type()) + "; expected a regular file"};
    std::ifstream in(path, std::ios::binary);
    if (!in) return {{}, std::string("cannot be opened: ") + std::strerror(errno)};
    // In pieces, so memory follows what the file holds, not the limit; a
    // file that grows while read is cut one byte past the limit all the same.
    std::string text;
    constexpr std::size_t piece = std::size_t(1) << 20;
    while (in && text.size() <= limit) {
        const std::size_t at = text.size(), want = std::min(piece, limit + 1 - at);
        text.resize(at + want);
        in.read(text.data() + at, std::streamsize(want));
        text.resize(at + std::size_t(in.gcount()));
    }
    if (text.size() > limit)
        return {{}, "is larger than " + std::to_string(limit) + " bytes; expected at most that"};
    return {std::move(text), {}};
}

}  // namespace sympl::app
