// Test helpers: GridConnect text in, GridConnect text out.
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <vector>

#include "openlcb/gridconnect.hpp"

namespace olcb::test {

/// Frame from GridConnect text; a malformed literal fails the calling test.
inline CanFrame gc(std::string_view text) {
    auto f = gridconnect::parse_frame(text);
    EXPECT_TRUE(f.has_value()) << "bad frame literal " << text;
    return f.value_or(CanFrame{});
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
    for (const auto& f : frames) out.push_back(gridconnect::format(f));
    return out;
}

}  // namespace olcb::test
