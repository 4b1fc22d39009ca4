// What the conformance suites share: the node IDs of the simulated device and of the tool, and
// reading a CDI file.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "openlcb/node_id.hpp"

namespace olcb::conform {

/// The simulated device under test.
inline constexpr NodeId kDut{0x050101012200ull};
/// The runner's own node.
inline constexpr NodeId kTool{0x0501010122FFull};

/// The whole file ("" when it cannot be read).
inline std::string read_text(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

}  // namespace olcb::conform
