// What the conformance suites share: the node IDs of the simulated device and of the tool,
// reading a CDI file, and a CDI text parsed and laid out.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "cdi/layout.hpp"
#include "cdi/parser.hpp"

#include "openlcb/node_id.hpp"
#include "support/temp_files.hpp"

namespace olcb::conform {

/// The simulated device under test.
inline constexpr NodeId kDut{0x050101012200ull};
/// The runner's own node.
inline constexpr NodeId kTool{0x0501010122FFull};

using test_support::read_text;

/// Parses and lays out a CDI text into doc and layout (the layout points into doc).
inline void load_cdi(const char* text, cdi::Document& doc, std::optional<cdi::Layout>& layout) {
    auto parsed = cdi::parse(text);
    ASSERT_TRUE(parsed.document.has_value());
    doc = std::move(*parsed.document);
    auto laid = cdi::build_layout(doc);
    ASSERT_TRUE(laid.layout.has_value());
    layout.emplace(std::move(*laid.layout));
}

}  // namespace olcb::conform
