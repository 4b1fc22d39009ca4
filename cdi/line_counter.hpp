// Source lines of byte offsets, for diagnostics about a text read through a tree.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace olcb::cdi {

/// The number of '\n' bytes in [p, end).
std::size_t count_newlines(const char* p, const char* end);

/// Maps a byte offset to a 1-based line. Callers visit the text in document order, so lines are
/// counted incrementally from the previous offset; a backwards step recounts from the start.
class LineCounter {
public:
    /// Counts lines of `text`, which must outlive the counter.
    explicit LineCounter(std::string_view text) : text_(text) {}

    /// The line holding byte `offset` (the last line for an offset past the end).
    std::uint32_t line_of(std::size_t offset);

private:
    std::string_view text_;
    std::size_t offset_ = 0;
    std::uint32_t line_ = 1;
};

}  // namespace olcb::cdi
