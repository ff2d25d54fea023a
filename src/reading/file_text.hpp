#pragma once
// The one way the program reads a file it is given or made: a regular file
// only (a directory, a device such as /dev/zero or a FIFO is refused unread,
// a symlink is followed to what it names and judged by that), and at most a
// stated number of bytes, read to one byte past the limit so that no file
// is held whole before it is refused (docs/reliability.md, "Files").
#include <cstddef>
#include <filesystem>
#include <string>

namespace sympl::app {

// Checkpoints and rank files; the scene, states and elements files have
// their own limits beside their readers (docs/reliability.md lists them).
inline constexpr std::size_t max_checkpoint_file_bytes = std::size_t(1) << 30;

struct file_text {
    std::string text;
    // Empty when read; else why not, to follow the file's name:
    // "is a directory; expected a regular file", "cannot be opened: ...".
    std::string failure;
};

file_text read_file_text(const std::filesystem::path& path, std::size_t limit);

}  // namespace sympl::app
