// Reading and writing a whole file, with an error a person can act on.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace olcb::base {

/// The bytes of the file at `path`, as they are (binary); nullopt with `error` set to
/// "cannot read PATH: REASON" (REASON from strerror, e.g. "No such file or directory").
std::optional<std::string> read_file(const std::filesystem::path& path, std::string& error);

/// Replaces the file at `path` with `bytes`, so that a reader (or the disk after a crash) finds
/// the old file or the whole new one, never a part. The bytes go to a new file in the same
/// directory, PATH.tmp-XXXXXXXX (X random), created with O_CREAT|O_EXCL|O_NOFOLLOW: a file or
/// link already at a temporary name is never opened, followed or removed, and a stale one of a
/// crashed run blocks nothing. The new file is synced, renamed over `path` and its directory
/// synced. A link at `path` is replaced, its target left alone; the new file's mode is 0644 less
/// the umask. A FIFO, device or socket at `path`, or a name through /proc (/dev/stdout,
/// /dev/fd/N), is an open stream, not a file to replace: it is written in place. False with
/// `error` set to "cannot open PATH for writing: REASON" or "cannot write PATH: REASON"; no
/// temporary file is left behind.
bool write_file(const std::filesystem::path& path, std::string_view bytes, std::string& error);

}  // namespace olcb::base
