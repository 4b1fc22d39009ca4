#include "cdi/line_counter.hpp"

#include <algorithm>
#include <cstring>

namespace olcb::cdi {

namespace {

// Sixteen bytes at a time through the compiler's generic vectors (SSE2 on x86-64, scalar code
// elsewhere): a matching byte compares to all ones, so subtracting the comparison counts it in
// its lane; lanes are added up before they can overflow.
using Bytes16 = std::uint8_t __attribute__((vector_size(16)));

std::size_t lane_sum(Bytes16 lanes) {
    std::size_t sum = 0;
    for (int i = 0; i < 16; ++i) sum += lanes[i];
    return sum;
}

}  // namespace

std::size_t count_newlines(const char* p, const char* end) {
    constexpr std::size_t kMaxRounds = 255;  // a lane holds at most 255 matches
    std::size_t total = 0;
    while (end - p >= 16) {
        Bytes16 lanes = {};
        for (std::size_t round = 0; round < kMaxRounds && end - p >= 16; ++round, p += 16) {
            Bytes16 v;
            std::memcpy(&v, p, sizeof v);
            lanes -= (v == '\n');  // NOLINT(bugprone-narrowing-conversions): 0 or -1 per lane
        }
        total += lane_sum(lanes);
    }
    for (; p < end; ++p) total += static_cast<std::size_t>(*p == '\n');
    return total;
}

std::uint32_t LineCounter::line_of(std::size_t offset) {
    offset = std::min(offset, text_.size());
    if (offset < offset_) {
        offset_ = 0;
        line_ = 1;
    }
    line_ +=
        static_cast<std::uint32_t>(count_newlines(text_.data() + offset_, text_.data() + offset));
    offset_ = offset;
    return line_;
}

}  // namespace olcb::cdi
