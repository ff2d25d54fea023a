#pragma once
// A directory under the system's temporary directory for one test, unique to
// this process: two test runs at once (two build trees) never share one.
#include <filesystem>
#include <string>

#include <unistd.h>

inline std::filesystem::path scratch_directory(const std::string& name) {
    return std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()));
}
