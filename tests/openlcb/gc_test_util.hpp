// Test helpers: GridConnect text in, GridConnect text out, and the fact sheet's two nodes. A test
// of the core says `using namespace test;` for all of it.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "base/node_id.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/gridconnect.hpp"
#include "openlcb/message.hpp"

namespace olcb::test {

/// Node ID of the fact sheet's node under test (first alias 0x343).
inline constexpr NodeId kNodeId{0x05'01'01'01'22'00ull};
/// Node ID of the fact sheet's runner (first alias 0x12C).
inline constexpr NodeId kRunnerId{0x02'01'0D'00'00'01ull};
/// The start of time for the sans-I/O machines, which only compare instants.
inline const TimePoint t0{};
/// Frames as GridConnect text, in order.
using Strings = std::vector<std::string>;

/// Frame from GridConnect text; a malformed literal fails the calling test.
inline CanFrame gc(std::string_view text) {
    auto f = gridconnect::parse_frame(text);
    EXPECT_TRUE(f.has_value()) << "bad frame literal " << text;
    return f.value_or(CanFrame{});
}

/// A message from alias src, addressed to dst when given (node IDs left unknown).
inline Message make_message(Mti mti, std::uint16_t src, std::optional<std::uint16_t> dst,
                            std::vector<std::uint8_t> payload) {
    std::optional<NodeHandle> destination;
    if (dst) destination = NodeHandle{NodeId{}, *dst};
    return Message{.mti = mti,
                   .source = NodeHandle{NodeId{}, src},
                   .destination = destination,
                   .payload = std::move(payload)};
}

/// Pops every pending frame of a machine (anything with pop_frame()) as GridConnect text.
template <class Machine>
std::vector<std::string> drain(Machine& m) {
    std::vector<std::string> out;
    while (auto f = m.pop_frame()) out.push_back(gridconnect::format(*f));
    return out;
}

/// GridConnect text of a frame list.
inline std::vector<std::string> texts(const std::vector<CanFrame>& frames) {
    std::vector<std::string> out;
    out.reserve(frames.size());
    for (const auto& f : frames) out.push_back(gridconnect::format(f));
    return out;
}

}  // namespace olcb::test
