// Compiling and loading a scene's formulas (machine_code.hpp).
#include "formulas/machine_code.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "output/format.hpp"
#include "output/writers.hpp"

extern char** environ;

namespace sympl::app::formulas {

namespace fs = std::filesystem;

#ifndef SYMPL_FORMULA_COMPILER
#define SYMPL_FORMULA_COMPILER ""
#endif
#ifndef SYMPL_FORMULA_COMPILER_GNU
#define SYMPL_FORMULA_COMPILER_GNU 0
#endif

const char* formula_compiler() { return SYMPL_FORMULA_COMPILER; }

void* machine_code::function(const std::string& name) const {
    void* f = ::dlsym(library.get(), name.c_str());
    if (!f) throw std::runtime_error("compiled formulas: no function " + name);
    return f;
}

namespace {

// A folder of this process's own under the temporary directory (mode 0700,
// a new name), and everything it made there removed when done.
class private_folder {
public:
    private_folder() {
        std::error_code ec;
        fs::path base = fs::temp_directory_path(ec);
        if (ec) base = "/tmp";
        std::string pattern = (base / "sympl-formulas-XXXXXX").string();
        if (!::mkdtemp(pattern.data())) throw std::runtime_error("cannot make a folder in " + printable(base.string()) + ": " +
                                                                  std::strerror(errno));
        path_ = pattern;
    }
    ~private_folder() {
        for (const char* name : made_) ::unlink((path_ / name).c_str());
        ::rmdir(path_.c_str());
    }
    private_folder(const private_folder&) = delete;
    private_folder& operator=(const private_folder&) = delete;

    // A name in the folder that this process will remove.
    fs::path file(const char* name) {
        made_.push_back(name);
        return path_ / name;
    }

private:
    fs::path path_;
    std::vector<const char*> made_;
};

std::string first_lines(const fs::path& path, std::size_t lines) {
    std::ifstream in(path);
    std::string out, line;
    for (std::size_t k = 0; k < lines && std::getline(in, line); ++k) out += (k ? "\n" : "") + line.substr(0, 200);
    return out;
}

}  // namespace

compiled_or_reason compile_c(const std::string& source) {
    const auto start = std::chrono::steady_clock::now();
    const std::string compiler = formula_compiler();
    if (compiler.empty() || ::access(compiler.c_str(), X_OK) != 0)
        return {nullptr, "no compiler at '" + compiler + "' (the one sympl was built with)"};
    try {
        private_folder folder;
        const fs::path c_file = folder.file("formulas.c"), library = folder.file("formulas.so"),
                       log = folder.file("compiler.log");
        {
            const int fd = create_new_file(c_file);
            if (fd < 0) return {nullptr, "cannot write " + printable(c_file.string()) + ": " + std::strerror(errno)};
            std::size_t written = 0;
            while (written < source.size()) {
                const ssize_t n = ::write(fd, source.data() + written, source.size() - written);
                if (n <= 0) {
                    ::close(fd);
                    return {nullptr, "cannot write " + printable(c_file.string()) + ": " + std::strerror(errno)};
                }
                written += std::size_t(n);
            }
            ::close(fd);
        }
        const int log_fd = create_new_file(log);
        if (log_fd < 0) return {nullptr, "cannot write " + printable(log.string()) + ": " + std::strerror(errno)};
        // IEEE arithmetic as the interpreter's (no contraction into FMA, no
        // fast-math); errno is never read, so the math builtins are pure. A
        // gradient's zeroing stays a loop, not a call to memset (38 against
        // 48 ns a force on FPU-32; -O3 took 124 ns: docs/formulas.md).
        std::vector<std::string> args{compiler, "-x", "c", "-std=gnu11", "-O2", "-ffp-contract=off", "-fno-math-errno"};
        if (SYMPL_FORMULA_COMPILER_GNU) args.push_back("-fno-tree-loop-distribute-patterns");
        args.insert(args.end(), {"-fPIC", "-shared", "-o", library.string(), c_file.string(), "-lm"});
        std::vector<char*> argv;
        for (auto& a : args) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
        posix_spawn_file_actions_adddup2(&actions, log_fd, 1);
        posix_spawn_file_actions_adddup2(&actions, log_fd, 2);
        pid_t pid = 0;
        const int spawned = ::posix_spawn(&pid, compiler.c_str(), &actions, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        ::close(log_fd);
        if (spawned != 0) return {nullptr, "cannot start " + compiler + ": " + std::strerror(spawned)};
        int status = 0;
        while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
            return {nullptr, compiler + " failed on the formulas' C source: " + first_lines(log, 5)};
        void* handle = ::dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) return {nullptr, std::string("cannot load the compiled formulas: ") + ::dlerror()};
        auto code = std::make_shared<machine_code>();
        code->library = std::shared_ptr<void>(handle, [](void* h) { ::dlclose(h); });
        code->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        return {std::move(code), ""};
    } catch (const std::exception& e) {
        return {nullptr, e.what()};
    }
}

}  // namespace sympl::app::formulas
