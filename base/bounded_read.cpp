#include "base/bounded_read.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

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

std::optional<std::string> fail(std::string& error, std::string message) {
    error = std::move(message);
    return std::nullopt;
}

std::string cannot_read(const std::filesystem::path& path, const char* reason) {
    return "cannot read " + path.string() + ": " + reason;
}

}  // namespace

std::optional<std::string> read_regular_file(const std::filesystem::path& path,
                                             std::size_t max_bytes, std::string& error) {
    // O_NONBLOCK: opening a FIFO without a writer (or a modem line) would wait for one; a
    // regular file ignores the flag. O_NOCTTY: a terminal named here must not become ours.
    const Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
    if (fd.get() < 0) return fail(error, cannot_read(path, std::strerror(errno)));
    struct stat info {};
    if (::fstat(fd.get(), &info) != 0) return fail(error, cannot_read(path, std::strerror(errno)));
    if (!S_ISREG(info.st_mode)) return fail(error, cannot_read(path, "not a regular file"));
    const std::string limit = "over the limit of " + std::to_string(max_bytes) + " bytes";
    const auto size = static_cast<std::uintmax_t>(std::max<off_t>(info.st_size, 0));
    if (size > max_bytes) {
        // Refused unread: a sparse 100 GB file costs nothing to refuse.
        return fail(error, path.string() + " is " + std::to_string(size) + " bytes, " + limit);
    }
    std::string bytes;
    bytes.reserve(static_cast<std::size_t>(size));
    char chunk[65536];
    for (;;) {
        // One byte past the limit tells a file over it from one exactly at it.
        const std::size_t room = max_bytes - bytes.size();
        const ssize_t got = ::read(fd.get(), chunk, room >= sizeof chunk ? sizeof chunk : room + 1);
        if (got < 0) {
            if (errno == EINTR) continue;
            return fail(error, cannot_read(path, std::strerror(errno)));
        }
        if (got == 0) return bytes;
        bytes.append(chunk, static_cast<std::size_t>(got));
        if (bytes.size() > max_bytes) return fail(error, path.string() + " is " + limit);
    }
}

}  // namespace olcb::base
