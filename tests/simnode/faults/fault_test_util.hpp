// Fixtures of the fault tests (tests/simnode/faults/<family>_faults_test.cpp): a node with faults
// on, and one that restarts; each used by several families.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode::test {

/// A node with faults on, and its Get Address Space Information.
class FaultTest : public SimNodeTest {
protected:
    std::uint32_t highest(std::uint8_t space) {
        const auto r = exchange({0x20, 0x84, space}).reply;
        if (!r || r->size() < 7) return 0;
        return static_cast<std::uint32_t>((*r)[3]) << 24 | (*r)[4] << 16 | (*r)[5] << 8 | (*r)[6];
    }
};

// A string as stored in an ACDI field: its bytes and the NUL.
inline std::vector<std::uint8_t> with_nul(std::string_view s) {
    auto bytes = bytes_of(s);
    bytes.push_back(0);
    return bytes;
}

inline std::string hex3(std::uint16_t alias) {
    char text[8];
    std::snprintf(text, sizeof text, "%03X", alias & 0xFFFu);
    return text;
}

/// A node that restarts: its start-up frames, a reboot asked for and one it makes itself.
class RestartFaultTest : public SimNodeTest {
protected:
    /// Asserts that frames[from..] are a power-up on alias: CID7..4 (carrying the node ID's
    /// 12-bit groups), RID, AMD, Initialization Complete.
    static void expect_startup(const std::vector<std::string>& frames, std::uint16_t alias,
                               std::size_t from = 0) {
        const std::string a = hex3(alias);
        const std::vector<std::string> prefixes = {":X17050" + a + "N;",
                                                   ":X16101" + a + "N;",
                                                   ":X15012" + a + "N;",
                                                   ":X14200" + a + "N;",
                                                   ":X10700" + a + "N;",
                                                   ":X10701" + a + "N050101012200;",
                                                   ":X19100" + a + "N050101012200;"};
        ASSERT_GE(frames.size(), from + prefixes.size());
        for (std::size_t i = 0; i < prefixes.size(); ++i) {
            EXPECT_EQ(frames[from + i], prefixes[i]) << i;
        }
    }
    /// Sends Reset/Reboot, expects the OK and runs until the node is initialized again.
    void reboot() {
        EXPECT_TRUE(exchange({0x20, 0xA9}).ok);
        ASSERT_TRUE(net_.run_until([this] { return node_->stack().initialized(); }, 1s));
        net_.run_for(10ms);
    }
    /// Runs until the node is initialized again after a restart it began by itself.
    void wait_restarted(Duration max) {
        ASSERT_TRUE(net_.run_until([this] { return node_->stack().initialized(); }, max));
        net_.run_for(10ms);
    }
};

}  // namespace olcb::simnode::test
