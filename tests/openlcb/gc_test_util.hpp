// Test helpers: GridConnect text in, GridConnect text out.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "openlcb/gridconnect.hpp"
#include "openlcb/message.hpp"

namespace olcb::test {

/// Frame from GridConnect text; a malformed literal fails the calling test.
inline CanFrame gc(std::string_view text) {
    auto f = gridconnect::parse_frame(text);
    EXPECT_TRUE(f.has_value()) << "bad frame literal " << text;
    return f.value_or(CanFrame{});
}

/// A message from alias src, addressed to dst when given (node IDs left unknown).
inline Message make_message(Mti mti, std::uint16_t src, std::optional<std::uint16_t> dst,
                            std::vector<std::uint8_t> payload) {
    Message m;
    m.mti = mti;
    m.source.alias = src;
    if (dst) m.destination = NodeHandle{NodeId{}, *dst};
    m.payload = std::move(payload);
    return m;
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
