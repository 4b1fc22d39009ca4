// Helpers shared by the memory library's tests.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace olcb::memory::test {

/// "20 43 00000000 40" -> bytes; spaces are only for reading.
inline std::vector<std::uint8_t> hex(std::string_view text) {
    std::vector<std::uint8_t> out;
    std::string digits;
    for (const char c : text) {
        if (c != ' ') digits += c;
    }
    for (std::size_t i = 0; i + 1 < digits.size(); i += 2) {
        out.push_back(static_cast<std::uint8_t>(std::stoi(digits.substr(i, 2), nullptr, 16)));
    }
    return out;
}

}  // namespace olcb::memory::test
