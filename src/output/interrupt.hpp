#pragma once
// SIGINT, SIGTERM and SIGHUP stop the program cleanly: a thread of its own
// waits for them (they are blocked everywhere else), removes the temporaries
// of the output set being written, says so on stderr and exits with 128 +
// the signal number. While an output set is being committed the signal waits
// until the commit is done, so the directory holds the old set or the new one.
#include <filesystem>
#include <mutex>

namespace sympl::app {

// Starts the waiting thread; call first in main, before any other thread exists.
void handle_interrupts();

// The staging directory to remove on an interrupt (empty: none).
void set_interrupt_cleanup(const std::filesystem::path& staging);

// Held while an output set moves its files into place.
std::mutex& commit_mutex();

}  // namespace sympl::app
