// Reading a CDI file with the size limit applied while reading, so that an oversized file, a
// FIFO fed without end or /dev/zero costs at most the limit, never the whole input.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

#include "base/bounded_read.hpp"
#include "cdi/schema_validator.hpp"

namespace olcb::cdi {

/// The bytes of the CDI file at `path`, at most `max_bytes` of them: base::read_bounded_file()
/// reading streams too, as lcc-cdi must (`cat x.xml | lcc-cdi layout /dev/stdin`). A regular file
/// larger than that is refused by its size before any byte is read; any other file (a FIFO, a
/// device, a pipe such as /dev/fd/N) is read until its end or until it has given one byte more
/// than the limit, and refused then. nullopt with `error` set to "cannot read PATH: REASON",
/// REASON from strerror or "N bytes, over the CDI limit of M bytes" (a stream: "more than M
/// bytes, ...").
inline std::optional<std::string> read_cdi_file(const std::filesystem::path& path,
                                                std::size_t max_bytes, std::string& error) {
    return base::read_bounded_file(path, max_bytes, base::Streams::kReadBounded, error,
                                   "CDI limit");
}

/// read_cdi_file() with the limit every CDI reader of this project applies (kMaxCdiBytes).
inline std::optional<std::string> read_cdi_file(const std::filesystem::path& path,
                                                std::string& error) {
    return read_cdi_file(path, kMaxCdiBytes, error);
}

}  // namespace olcb::cdi
