// What every suite needs of the file system, once: a temporary directory removed at the end of a
// test, and a whole file read as bytes.
#pragma once

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <string_view>

namespace olcb::test_support {

/// A fresh empty directory <base>/<prefix>-<pid>-<n>-<random>, removed with what it holds at
/// destruction. pid and random keep parallel test processes apart; base defaults to $TMPDIR.
class TempDir {
public:
    explicit TempDir(std::string_view prefix = "olcb-test", std::filesystem::path base = {}) {
        static std::atomic<unsigned> counter{0};
        std::random_device rd;
        if (base.empty()) base = std::filesystem::temp_directory_path();
        path_ = base / (std::string(prefix) + "-" + std::to_string(::getpid()) + "-" +
                        std::to_string(counter++) + "-" + std::to_string(rd()));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    /// The directory.
    const std::filesystem::path& path() const { return path_; }
    /// The directory as a string.
    std::string str() const { return path_.string(); }

private:
    std::filesystem::path path_;
};

/// The whole file as bytes ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace olcb::test_support
