// MemoryWatch (the Memory Configuration rules of the client audit: reads and writes past a
// space's end, writes to read-only spaces, writes left without Update Complete), as frame
// scripts on a simulated clock against the default node (MemoryRules, audit_script.hpp).
#include <gtest/gtest.h>

#include "audit_script.hpp"

namespace olcb::simnode::audit::test {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

TEST_F(MemoryRules, WholeVariablesWithAllowedValuesAndUpdateCompleteAreClean) {
    write(0xFD, 0, {1});                            // Enabled = 1
    write(0xFD, 1, {0xFC, 0x18});                   // Trim = -1000
    write(0xFD, 15, {3});                           // Mode = 3
    write(0xFD, 16, {0x3E, 0x00});                  // Gain = 1.5
    write(0xFD, 30, text("label", 16));             // Label
    write(0xFD, 30, text("abc", 4));                // a string up to its NUL is whole
    write(0xFD, 178, {1});                          // the action, triggered
    write(0xFB, 1, text("\xC3\xA9t\xC3\xA9", 63));  // the user name, UTF-8
    update_complete();
    advance(20s);
    finish();
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(MemoryRules, AReadAtOrPastTheEndOfASpaceIsAFinding) {
    client_datagram(read_cmd(0xFD, 178, 8));  // the last byte: a short read, fine
    node_ok();
    node_datagram({0x20, 0x51, 0, 0, 0, 0xB2, 0});
    client_ok();
    client_datagram(read_cmd(0xFD, 179, 8));
    const auto f = found(RuleId::kMemoryReadPastEnd);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NE(f[0].message.find("179 bytes"), std::string::npos) << f[0].message;
    EXPECT_THAT(f[0].frames, ElementsAre(":X1A34312CN2041000000B308;"));
}

TEST_F(MemoryRules, AReadOfASpaceTheNodeDoesNotServeIsNotJudged) {
    client_datagram(read_cmd(0x50, 0x1000, 8));  // the node rejects it 0x1081
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(MemoryRules, AWriteToAReadOnlySpaceIsAFinding) {
    write(0xFF, 0, {'<'});  // lcc-conform's memory.readonly-refused.ff
    write(0xFC, 0, {4});    // and .fc
    const auto f = found(RuleId::kMemoryWriteReadOnly);
    ASSERT_EQ(f.size(), 2u);
    EXPECT_NE(f[0].message.find("0xFF"), std::string::npos) << f[0].message;
    EXPECT_NE(f[1].message.find("0xFC"), std::string::npos) << f[1].message;
    finish();  // refused writes change nothing: no Update Complete is owed
    EXPECT_THAT(found(RuleId::kMemoryNoUpdateComplete), IsEmpty());
}

TEST_F(MemoryRules, AWriteRunningPastTheEndIsAFinding) {
    write(0xFD, 178, {1, 1});  // lcc-conform --thorough memory.write-past-end.fd
    write(0xFD, 200, {1});
    const auto f = found(RuleId::kMemoryWritePastEnd);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].count, 2u);
}

TEST_F(MemoryRules, WritesWithoutUpdateCompleteAreAWarningAtTheEnd) {
    write(0xFD, 0, {1});
    advance(5s);
    EXPECT_THAT(rules_found(), IsEmpty());
    finish();
    const auto f = found(RuleId::kMemoryNoUpdateComplete);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NE(f[0].message.find("end of the run"), std::string::npos) << f[0].message;
    EXPECT_EQ(rule(f[0].rule).level, Level::kWarning);
}

TEST_F(MemoryRules, WritesWithoutUpdateCompleteAreAWarningAfter10QuietSeconds) {
    write(0xFD, 0, {1});
    advance(9s);
    client_datagram(read_cmd(0xFD, 0, 1));  // any datagram keeps the sequence open
    node_ok();
    node_datagram({0x20, 0x51, 0, 0, 0, 0, 1});
    client_ok();
    advance(9s);
    EXPECT_THAT(rules_found(), IsEmpty());
    advance(2s);
    EXPECT_THAT(rules_found(), ElementsAre("memory.no-update-complete"));
}

TEST_F(MemoryRules, WritesWithoutUpdateCompleteAreAWarningWhenTheClientLeaves) {
    write(0xFD, 0, {1});
    audit_.on_disconnect(kConnection, now_);
    advance(2100ms);
    const auto f = found(RuleId::kMemoryNoUpdateComplete);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NE(f[0].message.find("connection ended"), std::string::npos) << f[0].message;
}

}  // namespace
}  // namespace olcb::simnode::audit::test
