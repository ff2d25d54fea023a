// The interrupt thread (interrupt.hpp).
#include "output/interrupt.hpp"

#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <string>
#include <thread>

namespace sympl::app {

namespace fs = std::filesystem;

namespace {
std::mutex cleanup_mutex;
fs::path cleanup_path;

sigset_t stop_signals() {
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    return set;
}
}  // namespace

std::mutex& commit_mutex() {
    static std::mutex m;
    return m;
}

void set_interrupt_cleanup(const fs::path& staging) {
    const std::lock_guard<std::mutex> lock(cleanup_mutex);
    cleanup_path = staging;
}

void handle_interrupts() {
    const sigset_t set = stop_signals();
    pthread_sigmask(SIG_BLOCK, &set, nullptr);  // inherited by every later thread
    std::thread([set] {
        int sig = 0;
        while (sigwait(&set, &sig) != 0) {
        }
        const std::lock_guard<std::mutex> commit(commit_mutex());  // a commit in progress finishes first
        fs::path staging;
        {
            const std::lock_guard<std::mutex> lock(cleanup_mutex);
            staging = cleanup_path;
        }
        std::error_code ec;
        if (!staging.empty()) fs::remove_all(staging, ec);
        const std::string line = std::string("\nsympl: stopped by SIG") + sigabbrev_np(sig) +
                                 "; temporaries removed, the previous outputs are kept\n";
        (void)!::write(STDERR_FILENO, line.data(), line.size());
        ::_exit(128 + sig);
    }).detach();
}

}  // namespace sympl::app
