// Checkpoint files (checkpoint.hpp).
#include "output/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cinttypes>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>

#include "output/format.hpp"
#include "output/writers.hpp"
#include "reading/file_text.hpp"

#include <sympl/core/error.hpp>

namespace sympl::app {

namespace fs = std::filesystem;

std::string fnv1a_hex(const std::string& bytes) {
    std::uint64_t h = 14695981039346656037ull;
    for (unsigned char c : bytes) {
        h ^= c;
        h *= 1099511628211ull;
    }
    char out[17];
    std::snprintf(out, sizeof out, "%016" PRIx64, h);
    return out;
}

namespace {
std::string hex(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%a", v);
    return b;
}

void put(std::ostringstream& o, const char* key, const std::vector<double>& v) {
    o << key << ' ' << v.size();
    for (double x : v) o << ' ' << hex(x);
    o << '\n';
}

[[noreturn]] void refuse(const fs::path& file, const std::string& why) {
    throw error("checkpoint " + printable(file.string()) + ": " + why + "; not resumed from (remove it to start over)");
}

// A line "key values..." of the body, in order.
struct body_reader {
    std::istringstream in;
    fs::path file;
    std::istringstream line(const char* key) {
        std::string text, word;
        if (!std::getline(in, text)) refuse(file, std::string("ends before '") + key + "'");
        std::istringstream l(text);
        if (!(l >> word) || word != key) refuse(file, std::string("expected '") + key + "', found '" + word + "'");
        return l;
    }
    double number(std::istringstream& l, const char* key) {
        std::string word;
        if (!(l >> word)) refuse(file, std::string("a number missing in '") + key + "'");
        char* end = nullptr;
        const double v = std::strtod(word.c_str(), &end);
        if (end != word.c_str() + word.size()) refuse(file, std::string("'") + word + "' in '" + key + "' is not a number");
        return v;
    }
    std::uint64_t count(std::istringstream& l, const char* key, std::uint64_t largest) {
        std::uint64_t v = 0;
        if (!(l >> v) || v > largest) refuse(file, std::string("a bad count in '") + key + "'");
        return v;
    }
    // Nothing may follow a line's values (`step 5 junk`: a hand edit).
    void finished(std::istringstream& l, const char* key) {
        std::string word;
        if (l >> word)
            refuse(file, "holds '" + printable(word) + "' after the values of '" + key + "'; expected the line's end");
    }
    // Nothing may follow the last line (the checksum covers whatever does).
    void end(const char* last) {
        const std::string rest(std::istreambuf_iterator<char>(in), {});
        if (!rest.empty())
            refuse(file, std::string("holds ") + std::to_string(rest.size()) + " more bytes after '" + last +
                             "'; expected its end");
    }
    std::vector<double> numbers(const char* key) {
        auto l = line(key);
        const auto n = count(l, key, 1u << 24);
        std::vector<double> v(n);
        for (auto& x : v) x = number(l, key);
        finished(l, key);
        return v;
    }
};
}  // namespace

void write_checkpoint(const fs::path& file, const checkpoint_record& r) {
    std::ostringstream body;
    body << "scene " << r.scene_hash << "\nmethod " << r.method.size() << ' ' << r.method << "\ndt " << hex(r.dt)
         << "\nstep " << r.step << "\ntime " << hex(r.time) << '\n';
    put(body, "state", r.state);
    put(body, "force", r.memory.force);
    put(body, "velocity", r.memory.velocity);
    put(body, "q_error", r.memory.q_error);
    put(body, "p_error", r.memory.p_error);
    put(body, "carried", r.carried);
    body << "fresh " << r.memory.force_fresh << ' ' << r.memory.velocity_fresh << "\nevaluations " << r.memory.force_evaluations << ' '
         << r.memory.velocity_evaluations << "\nmax_energy_error " << hex(r.max_energy_error) << "\ntrajectory_bytes "
         << r.trajectory_bytes << '\n';
    const std::string text = "sympl-checkpoint " + std::to_string(checkpoint_format) + "\n" + body.str() +
                             "checksum " + fnv1a_hex(body.str()) + "\n";
    write_durably(file, text);
}

void write_durably(const fs::path& file, const std::string& text) {
    const fs::path temporary = temporary_for(file, false);
    const int fd = create_new_file(temporary);
    if (fd < 0) throw error("cannot write checkpoint " + printable(temporary.string()) + ": " + std::strerror(errno));
    std::size_t done = 0;
    while (done < text.size()) {
        const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int reason = errno;
            ::close(fd);
            ::unlink(temporary.c_str());
            throw error("could not write checkpoint " + printable(file.string()) + ": " + std::strerror(reason ? reason : EIO) +
                        " (the previous checkpoint is kept)");
        }
        done += std::size_t(n);
    }
    if (::fsync(fd) != 0 || ::close(fd) != 0) {
        const int reason = errno;
        ::unlink(temporary.c_str());
        throw error("could not write checkpoint " + printable(file.string()) + ": " + std::strerror(reason) +
                    " (the previous checkpoint is kept)");
    }
    if (::rename(temporary.c_str(), file.c_str()) != 0) {
        const int reason = errno;
        ::unlink(temporary.c_str());
        throw error("could not move checkpoint into " + printable(file.string()) + ": " + std::strerror(reason));
    }
    // The rename itself reaches the disk with the directory.
    const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
    if (const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC); dfd >= 0) {
        (void)::fsync(dfd);
        ::close(dfd);
    }
}

checkpoint_record read_checkpoint(const fs::path& file, const std::string& scene_hash, const std::string& method,
                                  double dt) {
    file_text read = read_file_text(file, max_checkpoint_file_bytes);
    if (!read.failure.empty()) refuse(file, read.failure);
    const std::string text = std::move(read.text);
    const std::string head = "sympl-checkpoint " + std::to_string(checkpoint_format) + "\n";
    if (text.rfind("sympl-checkpoint ", 0) != 0) refuse(file, "is not a sympl checkpoint");
    if (text.rfind(head, 0) != 0) refuse(file, "has another format version; expected " + std::to_string(checkpoint_format));
    const auto mark = text.rfind("checksum ");
    if (mark == std::string::npos || mark < head.size()) refuse(file, "is truncated (no checksum)");
    const std::string body = text.substr(head.size(), mark - head.size());
    if (text.substr(mark) != "checksum " + fnv1a_hex(body) + "\n") refuse(file, "is corrupted (checksum mismatch)");
    body_reader b{std::istringstream(body), file};
    checkpoint_record r;
    {
        auto l = b.line("scene");
        l >> r.scene_hash;
        b.finished(l, "scene");
    }
    if (r.scene_hash != scene_hash) refuse(file, "belongs to another scene (or the scene file changed)");
    {
        auto l = b.line("method");
        const auto n = b.count(l, "method", 4096);
        l.get();
        r.method.resize(n);
        l.read(r.method.data(), std::streamsize(n));
        if (l.gcount() != std::streamsize(n)) refuse(file, "ends inside the method's name");
        b.finished(l, "method");
        if (r.method != method)
            refuse(file, "is of method '" + printable(r.method) + "', not '" + printable(method) + "'");
    }
    {
        auto l = b.line("dt");
        r.dt = b.number(l, "dt");
        b.finished(l, "dt");
        if (r.dt != dt) refuse(file, "was written at another dt");
    }
    {
        auto l = b.line("step");
        r.step = b.count(l, "step", UINT64_MAX / 2);
        b.finished(l, "step");
    }
    {
        auto l = b.line("time");
        r.time = b.number(l, "time");
        b.finished(l, "time");
    }
    r.state = b.numbers("state");
    r.memory.force = b.numbers("force");
    r.memory.velocity = b.numbers("velocity");
    r.memory.q_error = b.numbers("q_error");
    r.memory.p_error = b.numbers("p_error");
    r.carried = b.numbers("carried");
    {
        auto l = b.line("fresh");
        r.memory.force_fresh = b.count(l, "fresh", 1) == 1;
        r.memory.velocity_fresh = b.count(l, "fresh", 1) == 1;
        b.finished(l, "fresh");
    }
    {
        auto l = b.line("evaluations");
        r.memory.force_evaluations = b.count(l, "evaluations", UINT64_MAX);
        r.memory.velocity_evaluations = b.count(l, "evaluations", UINT64_MAX);
        b.finished(l, "evaluations");
    }
    {
        auto l = b.line("max_energy_error");
        r.max_energy_error = b.number(l, "max_energy_error");
        b.finished(l, "max_energy_error");
    }
    {
        auto l = b.line("trajectory_bytes");
        r.trajectory_bytes = b.count(l, "trajectory_bytes", UINT64_MAX / 2);
        b.finished(l, "trajectory_bytes");
    }
    b.end("trajectory_bytes");
    return r;
}

void check_checkpoint_fields(const checkpoint_record& r, const fs::path& file, std::size_t state_size, double t0,
                             double t_end, bool fixed_step) {
    const auto field = [&](const std::string& what, const std::string& value, const std::string& expected) {
        refuse(file, "holds " + what + " = " + value + "; expected " + expected);
    };
    const auto count = [&](const std::string& what, std::size_t n, const std::string& expected) {
        refuse(file, "holds " + what + " of " + std::to_string(n) + " numbers; expected " + expected);
    };
    if (r.state.size() != state_size) count("a state", r.state.size(), std::to_string(state_size) + ", q then p");
    const auto finite = [&](const std::vector<double>& v, const char* what) {
        for (std::size_t k = 0; k < v.size(); ++k)
            if (!std::isfinite(v[k])) field(std::string(what) + "[" + std::to_string(k) + "]", shortest(v[k]), "a finite number");
    };
    finite(r.state, "state");
    if (!(std::isfinite(r.time) && r.time >= t0 && r.time <= t_end))
        field("time", shortest(r.time), "a time in the scene's span [" + shortest(t0) + ", " + shortest(t_end) + "]");
    if (fixed_step && r.dt > 0) {
        const double most = std::ceil((t_end - t0) / r.dt) + 1;
        if (!(double(r.step) <= most))
            field("step", std::to_string(r.step), "at most " + shortest(most) + " steps of dt = " + shortest(r.dt));
    }
    // LogH's memory is of its extended state, q and t (or p and p_t): one more.
    const std::size_t half = state_size / 2;
    const auto sized = [&](const std::vector<double>& v, const char* what, bool needed) {
        if (!(v.size() == half || (!fixed_step && v.size() == half + 1) || (v.empty() && !needed)))
            count(std::string("a ") + what, v.size(), std::to_string(half) + (needed ? " (it is marked fresh)" : " or none"));
        finite(v, what);
    };
    sized(r.memory.force, "force", r.memory.force_fresh);
    sized(r.memory.velocity, "velocity", r.memory.velocity_fresh);
    sized(r.memory.q_error, "q_error", false);
    sized(r.memory.p_error, "p_error", false);
    finite(r.carried, "carried");
    if (!(r.max_energy_error == -1 || (std::isfinite(r.max_energy_error) && r.max_energy_error >= 0)))
        field("max_energy_error", shortest(r.max_energy_error), "-1 (not measured) or a finite value >= 0");
}

}  // namespace sympl::app
