// Reading a whole file, with an error a person can act on.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace olcb::base {

/// The bytes of the file at `path`, as they are (binary); nullopt with `error` set to
/// "cannot read PATH: REASON" (REASON from strerror, e.g. "No such file or directory").
std::optional<std::string> read_file(const std::filesystem::path& path, std::string& error);

}  // namespace olcb::base
