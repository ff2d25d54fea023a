// Writing files: atomically, quoted, and gnuplot without a shell.
#include "output/writers.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iostream>

#include <sympl/core/error.hpp>

#include "output/format.hpp"

extern char** environ;

namespace sympl::app {

namespace fs = std::filesystem;

namespace {
const std::string temporary_mark = ".sympl-part-";
}  // namespace

fs::path temporary_for(const fs::path& path, bool hidden) {
    return path.parent_path() /
           ((hidden ? "." : "") + path.filename().string() + temporary_mark + std::to_string(::getpid()));
}

bool is_temporary_name(const std::string& name) {
    const std::size_t at = name.rfind(temporary_mark);
    if (at == std::string::npos || at == 0 || at + temporary_mark.size() == name.size()) return false;
    return std::all_of(name.begin() + std::ptrdiff_t(at + temporary_mark.size()), name.end(),
                       [](char c) { return c >= '0' && c <= '9'; });
}

int create_new_file(const fs::path& path) {
    for (int attempt = 0; attempt < 2; ++attempt) {
        const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
        if (fd >= 0 || errno != EEXIST) return fd;
        struct stat st {};
        if (::lstat(path.c_str(), &st) != 0 || !S_ISREG(st.st_mode)) {
            errno = EEXIST;  // a symlink or anything but a regular file: left alone, refused
            return -1;
        }
        ::unlink(path.c_str());
    }
    return -1;
}

// The temporary is created new (no symlink followed, nothing overwritten),
// then opened by name for the stream.
atomic_file::atomic_file(fs::path path) : path_(std::move(path)), temporary_(temporary_for(path_, true)) {
    const int fd = create_new_file(temporary_);
    if (fd < 0) throw error("cannot write " + printable(temporary_.string()) + ": " + std::strerror(errno));
    ::close(fd);
    out_.open(temporary_);
    if (!out_) throw error("cannot write " + printable(temporary_.string()) + ": " + std::strerror(errno));
}

atomic_file::~atomic_file() {
    if (!committed_) {
        out_.close();
        std::error_code ec;
        fs::remove(temporary_, ec);
    }
}

void atomic_file::commit() {
    out_.flush();
    const bool written = out_.good();
    const int reason = errno;
    out_.close();
    if (!written || out_.fail())
        throw error("could not write " + printable(path_.string()) + ": " + std::strerror(reason ? reason : EIO) +
                    " (the previous file, if any, is kept)");
    std::error_code ec;
    fs::rename(temporary_, path_, ec);
    if (ec) throw error("could not move " + printable(temporary_.string()) + " to " + printable(path_.string()) + ": " + ec.message());
    committed_ = true;
}

std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
    std::string out = "\"";
    for (char c : text) {
        if (c == '"') out += '"';
        out += c;
    }
    return out + "\"";
}

std::string csv_line(const std::vector<std::string>& fields) {
    std::string out;
    for (std::size_t i = 0; i < fields.size(); ++i) {
        if (i) out += ',';
        out += csv_field(fields[i]);
    }
    out += '\n';
    return out;
}

std::string markdown_cell(const std::string& text) {
    std::string out;
    for (char c : text) {
        if (c == '|') out += "\\|";
        else if (c == '\n' || c == '\r') out += ' ';
        else out += c;
    }
    return out;
}

std::string file_name_part(const std::string& name) {
    std::string out = name;
    for (char& c : out)
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_' && c != '.') c = '_';
    if (out.empty() || out[0] == '.') out.insert(out.begin(), '_');
    return out;
}

std::string gnuplot_string(const std::string& text) {
    std::string out = "'";
    for (char c : text) {
        if (c == '\'') out += "''";
        else if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) out += ' ';
        else out += c;
    }
    return out + "'";
}

namespace {
// Runs gnuplot with `args` (argv[1..]) in directory `cwd` (empty: this one),
// its stdout and stderr to /dev/null, with no signal blocked (the program
// blocks its stop signals for interrupt.hpp): its exit status.
int spawn_gnuplot(std::vector<std::string> args, const fs::path& cwd = {}) {
    args.insert(args.begin(), "gnuplot");
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
    if (!cwd.empty()) posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    sigset_t none;
    sigemptyset(&none);
    posix_spawnattr_setsigmask(&attributes, &none);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
    pid_t pid = 0;
    const int started = posix_spawnp(&pid, "gnuplot", &actions, &attributes, argv.data(), environ);
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
    if (started != 0) return -1;
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
}  // namespace

bool have_gnuplot() { return spawn_gnuplot({"--version"}) == 0; }

void run_gnuplot(const fs::path& script, const fs::path& png) {
    std::error_code ec;
    // In the script's directory: the scripts name their files relative to it,
    // so they still work once the output set is moved into place.
    const fs::path where = fs::absolute(script, ec);
    if (spawn_gnuplot({where.filename().string()}, where.parent_path()) != 0 || !fs::exists(png, ec) ||
        fs::file_size(png, ec) == 0) {
        fs::remove(png, ec);
        std::cerr << "sympl: gnuplot could not draw " << png.string() << " (script: " << script.string() << ")\n";
    }
}

}  // namespace sympl::app
