#include "base/bounded_read.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <string>

#include "base/descriptor.hpp"

namespace olcb::base {
namespace {

std::optional<std::string> fail(const std::filesystem::path& path, const std::string& reason,
                                std::string& error) {
    error = "cannot read " + path.string() + ": " + reason;
    return std::nullopt;
}

std::string over_limit(const std::string& what, std::string_view limit_name,
                       std::size_t max_bytes) {
    return what + ", over the " + std::string(limit_name) + " of " + std::to_string(max_bytes) +
           " bytes";
}

int open_flags(Streams streams) {
    // O_NOCTTY: a terminal named here must not become ours.
    const int flags = O_RDONLY | O_CLOEXEC | O_NOCTTY;
    // O_NONBLOCK when streams are refused: opening a FIFO without a writer (or a modem line)
    // would wait for one, and the refusal comes only after the open. A stream that is read must
    // block instead, or a FIFO whose writer has not come yet would read as empty.
    return streams == Streams::kRefuse ? flags | O_NONBLOCK : flags;
}

}  // namespace

std::optional<std::string> read_bounded_file(const std::filesystem::path& path,
                                             std::size_t max_bytes, Streams streams,
                                             std::string& error, std::string_view limit_name) {
    const Descriptor fd(::open(path.c_str(), open_flags(streams)));
    if (fd.get() < 0) return fail(path, std::strerror(errno), error);
    struct stat info {};
    if (::fstat(fd.get(), &info) != 0) return fail(path, std::strerror(errno), error);
    std::string bytes;
    if (S_ISREG(info.st_mode)) {
        const auto size = static_cast<std::uintmax_t>(std::max<off_t>(info.st_size, 0));
        // Refused by its size alone: a sparse 100 GB file costs one fstat, not a read.
        if (size > max_bytes) {
            return fail(path, over_limit(std::to_string(size) + " bytes", limit_name, max_bytes),
                        error);
        }
        bytes.reserve(static_cast<std::size_t>(size));
    } else if (streams == Streams::kRefuse) {
        return fail(path, "not a regular file", error);
    } else if (S_ISDIR(info.st_mode)) {
        return fail(path, std::strerror(EISDIR), error);
    }
    // Everything else (and a regular file growing meanwhile, or a /proc file whose size says 0) is
    // bounded by reading: one byte past the limit tells a file over it from one exactly at it.
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
    const std::string more = "more than " + std::to_string(max_bytes) + " bytes";
    return fail(path, over_limit(more, limit_name, max_bytes), error);
}

}  // namespace olcb::base
