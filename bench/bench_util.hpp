// What the benchmark programs share: reading their input files and a scratch directory.
#pragma once

#include <filesystem>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>

#include "base/file.hpp"

namespace olcb::bench {

/// The whole file, or a runtime_error saying why not: a benchmark without its input is void.
inline std::string read_text(const std::filesystem::path& path) {
    std::string error;
    auto bytes = base::read_file(path, error);
    if (!bytes) throw std::runtime_error(error);
    return std::move(*bytes);
}

/// A fresh directory under the system's temporary directory, removed with everything in it.
class TempDir {
public:
    /// Creates "<tmp>/<prefix>-<random>".
    explicit TempDir(const std::string& prefix) {
        std::random_device rd;
        path_ = std::filesystem::temp_directory_path() / (prefix + "-" + std::to_string(rd()));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    /// The directory.
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

}  // namespace olcb::bench
