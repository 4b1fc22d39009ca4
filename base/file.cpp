#include "base/file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace olcb::base {

namespace {

// Closes the descriptor on every way out.
class Descriptor {
public:
    explicit Descriptor(int fd) : fd_(fd) {}
    ~Descriptor() {
        if (fd_ >= 0) ::close(fd_);
    }
    Descriptor(const Descriptor&) = delete;
    Descriptor& operator=(const Descriptor&) = delete;
    int get() const { return fd_; }

private:
    int fd_;
};

std::optional<std::string> fail(const std::filesystem::path& path, int err, std::string& error) {
    error = "cannot read " + path.string() + ": " + std::strerror(err);
    return std::nullopt;
}

}  // namespace

std::optional<std::string> read_file(const std::filesystem::path& path, std::string& error) {
    const Descriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
    if (fd.get() < 0) return fail(path, errno, error);
    struct stat info {};
    if (::fstat(fd.get(), &info) != 0) return fail(path, errno, error);
    // A directory opens but cannot be read; say so instead of returning nothing.
    if (S_ISDIR(info.st_mode)) return fail(path, EISDIR, error);
    std::string bytes;
    if (S_ISREG(info.st_mode) && info.st_size > 0)
        bytes.reserve(static_cast<std::size_t>(info.st_size));
    char chunk[65536];
    for (;;) {
        const ssize_t got = ::read(fd.get(), chunk, sizeof chunk);
        if (got < 0) {
            if (errno == EINTR) continue;
            return fail(path, errno, error);
        }
        if (got == 0) break;
        bytes.append(chunk, static_cast<std::size_t>(got));
    }
    return bytes;
}

}  // namespace olcb::base
