#include "cdi/cdi_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>

namespace olcb::cdi {
namespace {

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

std::optional<std::string> fail(const std::filesystem::path& path, const std::string& reason,
                                std::string& error) {
    error = "cannot read " + path.string() + ": " + reason;
    return std::nullopt;
}

std::string over_limit(const std::string& what, std::size_t max_bytes) {
    return what + ", over the CDI limit of " + std::to_string(max_bytes) + " bytes";
}

}  // namespace

std::optional<std::string> read_cdi_file(const std::filesystem::path& path, std::size_t max_bytes,
                                         std::string& error) {
    const Descriptor fd(::open(path.c_str(), O_RDONLY | O_CLOEXEC));
    if (fd.get() < 0) return fail(path, std::strerror(errno), error);
    struct stat info {};
    if (::fstat(fd.get(), &info) != 0) return fail(path, std::strerror(errno), error);
    if (S_ISDIR(info.st_mode)) return fail(path, std::strerror(EISDIR), error);
    std::string bytes;
    if (S_ISREG(info.st_mode)) {
        const auto size = static_cast<std::uintmax_t>(std::max<off_t>(info.st_size, 0));
        // Refused by its size alone: a 100 MB file costs one fstat, not 100 MB of reading.
        if (size > max_bytes) {
            return fail(path, over_limit(std::to_string(size) + " bytes", max_bytes), error);
        }
        bytes.reserve(static_cast<std::size_t>(size));
    }
    // Everything else (and a regular file growing meanwhile) is bounded by reading: one byte past
    // the limit is enough to know it is too large, so a FIFO that never ends is not read forever.
    std::array<char, 65536> chunk{};
    while (bytes.size() <= max_bytes) {
        const std::size_t want = std::min(chunk.size(), max_bytes + 1 - bytes.size());
        const ssize_t got = ::read(fd.get(), chunk.data(), want);
        if (got < 0) {
            if (errno == EINTR) continue;
            return fail(path, std::strerror(errno), error);
        }
        if (got == 0) return bytes;
        bytes.append(chunk.data(), static_cast<std::size_t>(got));
    }
    return fail(path, over_limit("more than " + std::to_string(max_bytes) + " bytes", max_bytes),
                error);
}

}  // namespace olcb::cdi
