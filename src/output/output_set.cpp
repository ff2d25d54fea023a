// Output sets (output_set.hpp).
#include "output/output_set.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include <sympl/core/error.hpp>

#include "output/format.hpp"
#include "output/interrupt.hpp"
#include "output/writers.hpp"

namespace sympl::app {

namespace fs = std::filesystem;

namespace {
const std::string staging_prefix = ".sympl-staging-";

// Left by a process that died: a staging directory `.sympl-staging-PID` (a
// directory, not a symlink) or a temporary `.NAME.sympl-part-PID` (a regular
// file). Nothing else is ever removed: a user's `.notes.part-2024` stays.
bool is_stale_temporary(const fs::directory_entry& entry) {
    const std::string name = entry.path().filename().string();
    std::error_code ec;
    const fs::file_type type = entry.symlink_status(ec).type();
    if (name.rfind(staging_prefix, 0) == 0)
        return type == fs::file_type::directory && name.size() > staging_prefix.size() &&
               name.find_first_not_of("0123456789", staging_prefix.size()) == std::string::npos;
    return type == fs::file_type::regular && name[0] == '.' && is_temporary_name(name);
}

std::string read_all(int fd) {
    std::string text(64, '\0');
    const ssize_t n = ::pread(fd, text.data(), text.size(), 0);
    text.resize(n > 0 ? std::size_t(n) : 0);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\0')) text.pop_back();
    return text;
}
}  // namespace

output_set::output_set(fs::path directory) : directory_(std::move(directory)) {
    fs::create_directories(directory_);
    const fs::path lock = directory_ / ".sympl.lock";
    // Never through a symlink: a planted .sympl.lock -> file would be truncated.
    lock_fd_ = ::open(lock.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
    struct stat st {};
    if (lock_fd_ < 0 && errno == ELOOP && ::lstat(lock.c_str(), &st) == 0 && S_ISLNK(st.st_mode))
        throw error(printable(lock.string()) + " is a symlink; expected the lock file this program makes there (or "
                    "none): it writes no file through a symlink; remove it");
    if (lock_fd_ < 0) throw error("cannot open " + printable(lock.string()) + ": " + std::strerror(errno));
    if (::flock(lock_fd_, LOCK_EX | LOCK_NB) != 0) {
        const std::string holder = read_all(lock_fd_);
        ::close(lock_fd_);
        throw error(printable(directory_.string()) + " is being written by another sympl (process " +
                    (holder.empty() ? std::string("unknown") : holder) +
                    "); expected one run per output directory: wait for it or choose another directory");
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(lock_fd_, 0) != 0 || ::pwrite(lock_fd_, pid.data(), pid.size(), 0) != ssize_t(pid.size())) {
        // The pid is only for the message of a second process: not worth failing for.
    }
    // Holding the lock, every temporary here (and in the reference cache) is a dead process's.
    for (const fs::path& d : {directory_, directory_ / "cache"}) {
        std::error_code ec;
        for (const auto& entry : fs::directory_iterator(d, ec))
            if (is_stale_temporary(entry)) {
                fs::remove_all(entry.path(), ec);
                ++stale_removed_;
            }
    }
    staging_ = directory_ / (staging_prefix + std::to_string(::getpid()));
    fs::create_directories(staging_);
    set_interrupt_cleanup(staging_);
}

output_set::~output_set() {
    set_interrupt_cleanup({});
    std::error_code ec;
    if (!committed_) fs::remove_all(staging_, ec);
    if (lock_fd_ >= 0) ::close(lock_fd_);  // releases the lock
}

void output_set::commit() {
    const std::lock_guard<std::mutex> hold(commit_mutex());
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(staging_))
        if (entry.is_regular_file() && !is_temporary_name(entry.path().filename().string()))
            files.push_back(entry.path());
    for (const fs::path& f : files) {
        std::error_code ec;
        fs::rename(f, directory_ / f.filename(), ec);
        if (ec) throw error("could not move " + printable(f.string()) + " into " + printable(directory_.string()) + ": " + ec.message());
    }
    std::error_code ec;
    fs::remove_all(staging_, ec);
    committed_ = true;
    set_interrupt_cleanup({});
}

}  // namespace sympl::app
