#pragma once
// The outputs of one `sympl run` or `sympl report`, committed as one set.
//
// Everything is written into a staging directory inside the output directory
// and moved into place at the end, with SIGINT/SIGTERM/SIGHUP held off during
// the moves (interrupt.hpp): a run that fails, is interrupted or is killed
// leaves the previous complete set as it was, never new CSVs beside an old
// summary.md. One process at a time owns an output directory (an flock the
// kernel drops when the process dies, even by SIGKILL); the second is told
// which process holds it. Holding the lock also makes every staging directory
// or `.NAME.sympl-part-PID` temporary found there stale: removed on entry.
#include <filesystem>
#include <string>

namespace sympl::app {

class output_set {
public:
    explicit output_set(std::filesystem::path directory);
    ~output_set();
    output_set(const output_set&) = delete;
    output_set& operator=(const output_set&) = delete;

    // Where the outputs are written until commit().
    const std::filesystem::path& staging() const { return staging_; }
    const std::filesystem::path& directory() const { return directory_; }
    // Moves every staged file into the directory (replacing older ones of the
    // same name) and removes the staging directory.
    void commit();
    // What a stale-cleanup on entry removed (for the tests and the user).
    std::size_t stale_removed() const { return stale_removed_; }

private:
    std::filesystem::path directory_, staging_;
    int lock_fd_ = -1;
    bool committed_ = false;
    std::size_t stale_removed_ = 0;
};

}  // namespace sympl::app
