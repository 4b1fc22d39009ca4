// Reading a whole file named by someone else (a scenario, a control request) without letting
// the name decide what simnode does: a FIFO, a device or /proc file would otherwise block the
// reader or feed it without end.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace olcb::base {

/// The bytes of the regular file at `path` when it holds at most `max_bytes`; nullopt with
/// `error` set to "cannot read PATH: REASON" (REASON from strerror, or "not a regular file" for a
/// FIFO, device, socket or directory, which is refused unread) or "PATH is N bytes, over the
/// limit of MAX bytes" / "PATH is over the limit of MAX bytes" (a file whose size says less than
/// it holds, as /proc files do). Never blocks on the file: it is opened O_NONBLOCK, and at most
/// max_bytes + 1 bytes are read whatever its size says.
std::optional<std::string> read_regular_file(const std::filesystem::path& path,
                                             std::size_t max_bytes, std::string& error);

}  // namespace olcb::base
