// Reading a whole file named by someone else (a scenario, a control request, a command line)
// without letting the name decide what the reader does: a device or a FIFO fed without end costs
// at most the limit, and a caller that must not block (simnode's io thread) refuses them unread.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace olcb::base {

/// What read_bounded_file() does with a file that is not regular (a FIFO, a pipe such as
/// /dev/stdin, a device, a socket).
enum class Streams : bool {
    kRefuse,       ///< refused unread, without waiting for a FIFO's writer
    kReadBounded,  ///< read until its end or one byte past the limit, waiting for data as it comes
};

/// The bytes of the file at `path` when it holds at most `max_bytes`. A regular file larger than
/// that is refused by its size, unread; anything else is as `streams` says, and every file is
/// read no further than max_bytes + 1 bytes whatever its size says (/proc files say 0).
/// nullopt with `error` set to "cannot read PATH: REASON", REASON being strerror's, "not a
/// regular file" (Streams::kRefuse: a FIFO, device, socket or directory), "N bytes, over the
/// LIMIT_NAME of MAX bytes" or "more than MAX bytes, over the LIMIT_NAME of MAX bytes".
std::optional<std::string> read_bounded_file(const std::filesystem::path& path,
                                             std::size_t max_bytes, Streams streams,
                                             std::string& error,
                                             std::string_view limit_name = "limit");

}  // namespace olcb::base
