// What the JMRI-format backup suites share (backup/, run/config_backup): a CDI with every kind of
// variable, unnamed elements and nested replication, an in-memory node for it, and a CDI of wide
// integers whose backup lines round-trip.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "cdi/document.hpp"
#include "cdi/layout.hpp"
#include "conformance/conform_test_util.hpp"
#include "conformance/fake_memory.hpp"
#include "conformance/run/config_backup.hpp"

namespace olcb::conform::testing {

inline constexpr const char* kBackupCdi = R"(<?xml version="1.0"?>
<cdi>
<segment space="253">
  <name>Main</name>
  <int size="1"><name>Enabled</name></int>
  <int size="2"><min>-100</min><max>100</max><name>Trim</name></int>
  <string size="8"><name>Label</name></string>
  <eventid><name>Event</name></eventid>
  <float size="4"><name>Gain</name><min>-10</min><max>10</max></float>
  <int size="1"/>
  <group replication="2"><name>Port</name>
    <group replication="3"><name>Line</name><int size="1"><name>Mode</name></int></group>
    <int size="1"/>
  </group>
  <action size="1"><button>Go</button><value>1</value></action>
  <bit size="1"><name>Flag</name></bit>
</segment>
<segment space="251"><int size="1"/></segment>
</cdi>)";

/// A parsed and laid-out CDI.
struct Cdi {
    explicit Cdi(const char* text) { load_cdi(text, doc, layout); }
    cdi::Document doc;
    std::optional<cdi::Layout> layout;
};

/// kBackupCdi on a zeroed in-memory node (64 bytes of space 253, 4 of 251).
class ConfigBackupTest : public ::testing::Test {
protected:
    void SetUp() override {
        ASSERT_TRUE(cdi_.layout.has_value());
        memory_.spaces[253] = std::vector<std::uint8_t>(64, 0);
        memory_.spaces[251] = std::vector<std::uint8_t>(4, 0);
    }
    std::vector<std::string> keys() const {
        std::vector<std::string> out;
        for (const auto& e : config_entries(*cdi_.layout)) out.push_back(e.key);
        return out;
    }
    std::string backup() {
        std::vector<std::string> errors;
        std::string text = make_config_backup(*cdi_.layout, memory_, "05.01.01.01.22.00", errors);
        EXPECT_TRUE(errors.empty()) << ::testing::PrintToString(errors);
        return text;
    }

    Cdi cdi_{kBackupCdi};
    FakeMemory memory_;
};

inline constexpr const char* kWideCdi = R"(<?xml version="1.0"?>
<cdi><segment space="253"><name>W</name>
<int size="8"><name>U64</name></int>
<int size="8"><name>S64</name><min>-10</min></int>
<int size="2"><name>S16</name><min>-200</min><max>200</max></int>
</segment></cdi>)";

/// kWideCdi's 18 bytes: U64, S64 and S16, big-endian.
inline std::vector<std::uint8_t> wide(std::uint64_t u64, std::uint64_t s64, std::uint16_t s16) {
    std::vector<std::uint8_t> b;
    for (std::uint64_t v : {u64, s64}) {
        for (int k = 7; k >= 0; --k) b.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
    }
    b.push_back(static_cast<std::uint8_t>(s16 >> 8));
    b.push_back(static_cast<std::uint8_t>(s16));
    return b;
}

/// Backs up the bytes, checks the line, zeroes the node, restores the file text: bytes back.
inline void round_trip(const std::vector<std::uint8_t>& bytes, const std::string& line) {
    Cdi cdi(kWideCdi);
    FakeMemory memory;
    memory.spaces[253] = bytes;
    std::vector<std::string> errors;
    const std::string text = make_config_backup(*cdi.layout, memory, "05.01.01.01.22.00", errors);
    EXPECT_NE(text.find("\n" + line + "\n"), std::string::npos) << text;
    memory.spaces[253].assign(bytes.size(), 0);
    const auto out = restore_config(*cdi.layout, memory, text);
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(memory.spaces[253], bytes) << line;
}

}  // namespace olcb::conform::testing
