// The Memory Configuration and CDI rules of the client audit, as frame scripts on a simulated
// clock, against the default node (scenarios/default.xml: space 0xFD is 179 bytes, Enabled @0
// 1-byte int map 0/1, Trim @1 2-byte int -1000..1000, Mode @15 map 1/2/3, Gain @16 half float
// 0..4, Label @30 16-byte string, the Port group @46 (4 x 33 bytes), the action @178 value 1;
// 0xFB lays out the user name @1 and description @64).
#include <gtest/gtest.h>

#include "audit_script.hpp"

namespace olcb::simnode::audit::test {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

class MemoryRules : public AuditScript {
protected:
    MemoryRules() { login(); }

    // A write and the node's plain OK: each write is its own finished exchange.
    void write(std::uint8_t space, std::uint32_t address, const std::vector<std::uint8_t>& data) {
        client_datagram(write_cmd(space, address, data));
        node_ok(0);
        advance(5ms);
    }
    void update_complete() {
        client_datagram({0x20, 0xA8});
        node_ok(0);
    }
    std::vector<std::uint8_t> text(std::string_view s, std::size_t size) {
        std::vector<std::uint8_t> out(s.begin(), s.end());
        out.resize(size, 0);
        return out;
    }
};

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

TEST_F(MemoryRules, AWriteOfPartOfAnIntOrAcrossTwoVariablesStraddles) {
    write(0xFD, 1, {0x00});                           // the first byte of Trim only...
    write(0xFD, 7, std::vector<std::uint8_t>(8, 0));  // ...not continued: Counter, whole
    write(0xFD, 2, {0x05});                           // Trim's second byte alone: starts inside it
    write(0xFD, 0, {1, 0x00});                        // Enabled and half of Trim
    update_complete();
    const auto f = found(RuleId::kMemoryWriteStraddles);
    ASSERT_EQ(f.size(), 1u);  // all about Trim
    EXPECT_EQ(f[0].count, 3u);
    EXPECT_NE(f[0].message.find("'Settings/Trim'"), std::string::npos) << f[0].message;
}

TEST_F(MemoryRules, ConsecutiveWritesOfOneRangeAreOneWrite) {
    // As lcc-conform's restore writes a merged range: 64-byte chunks cutting variables.
    std::vector<std::uint8_t> image(179, 0);
    image[0] = 1;   // Enabled
    image[15] = 2;  // Mode
    for (std::uint32_t at = 0; at < image.size(); at += 64) {
        const auto n = std::min<std::size_t>(64, image.size() - at);
        const auto from = image.begin() + static_cast<std::ptrdiff_t>(at);
        write(0xFD, at, std::vector<std::uint8_t>(from, from + static_cast<std::ptrdiff_t>(n)));
    }
    update_complete();
    EXPECT_THAT(rules_found(), ElementsAre("cdi.action-value"));  // the action's 0 is no trigger
}

TEST_F(MemoryRules, AWriteOfBytesNoVariableCoversIsAFinding) {
    write(0xFB, 0, {2});  // the ACDI version byte (lcc-conform's acdi.version-write-refused)
    const auto f = found(RuleId::kMemoryWriteUncovered);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NE(f[0].message.find("0xFB @0x00000000"), std::string::npos) << f[0].message;
}

TEST_F(MemoryRules, OutOfRangeIntsAreFindings) {
    write(0xFD, 1, {0x07, 0xD0});  // Trim = 2000 > 1000
    const auto f = found(RuleId::kCdiIntOutOfRange);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NE(f[0].message.find("2000"), std::string::npos) << f[0].message;
}

TEST_F(MemoryRules, OutOfRangeFloatsAndNanAreFindings) {
    write(0xFD, 16, {0x45, 0x00});  // Gain = 5 > 4
    write(0xFD, 16, {0x7E, 0x00});  // NaN
    const auto f = found(RuleId::kCdiFloatOutOfRange);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].count, 2u);
}

TEST_F(MemoryRules, StringsWithoutNulOrWithBadUtf8AreFindings) {
    write(0xFD, 30, std::vector<std::uint8_t>(16, 'A'));  // no NUL within its 16 bytes
    write(0xFB, 64, text("\xC3(", 64));                   // not UTF-8
    const auto f = found(RuleId::kCdiStringInvalid);
    ASSERT_EQ(f.size(), 2u);
    EXPECT_NE(f[0].message.find("NUL"), std::string::npos) << f[0].message;
    EXPECT_NE(f[1].message.find("UTF-8"), std::string::npos) << f[1].message;
}

TEST_F(MemoryRules, AStringCutShortWithoutNulStraddles) {
    write(0xFD, 30, {'a', 'b'});  // two bytes, no NUL: the rest is whatever was there
    update_complete();
    EXPECT_THAT(rules_found(), ElementsAre("memory.write-straddles"));
}

TEST_F(MemoryRules, ValuesOutsideAMapAreFindings) {
    write(0xFD, 0, {2});   // Enabled: 0 or 1
    write(0xFD, 15, {0});  // Mode: 1, 2 or 3
    const auto f = found(RuleId::kCdiNotInMap);
    ASSERT_EQ(f.size(), 2u);
    EXPECT_NE(f[0].message.find("'Settings/Enabled'"), std::string::npos) << f[0].message;
}

TEST_F(MemoryRules, AnActionWrittenWithAnotherValueIsAFinding) {
    write(0xFD, 178, {2});
    EXPECT_THAT(rules_found(), ElementsAre("cdi.action-value"));
}

TEST_F(MemoryRules, ALongStringInTwoWritesIsJudgedWhole) {
    // The user description (64 bytes @64 of 0xFB) as a 40-byte and a 24-byte write.
    auto desc = text("a description that fills the first chunk and goes on", 64);
    write(0xFB, 64, std::vector<std::uint8_t>(desc.begin(), desc.begin() + 40));
    write(0xFB, 104, std::vector<std::uint8_t>(desc.begin() + 40, desc.end()));
    update_complete();
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(MemoryRules, WriteUnderMaskIsJudgedForCoverageOnly) {
    // lcc-conform's memory.write-under-mask: mask 0xFF on the first byte of the user name.
    client_datagram({0x20, 0x08, 0, 0, 0, 1, 0xFB, 0xFF, 's'});
    node_ok(0);
    client_datagram({0x20, 0x09, 0, 0, 0, 0, 0xFF, 7});  // Enabled, whole: 7 is not judged
    node_ok(0);
    update_complete();
    EXPECT_THAT(rules_found(), ElementsAre("memory.write-straddles"));
}

TEST_F(MemoryRules, WritesWithoutUpdateCompleteAreANoteAtTheEnd) {
    write(0xFD, 0, {1});
    advance(5s);
    EXPECT_THAT(rules_found(), IsEmpty());
    finish();
    const auto f = found(RuleId::kMemoryNoUpdateComplete);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NE(f[0].message.find("end of the run"), std::string::npos) << f[0].message;
    EXPECT_EQ(rule(f[0].rule).level, Level::kNote);
}

TEST_F(MemoryRules, WritesWithoutUpdateCompleteAreANoteAfter10QuietSeconds) {
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

TEST_F(MemoryRules, WritesWithoutUpdateCompleteAreANoteWhenTheClientLeaves) {
    write(0xFD, 0, {1});
    audit_.on_disconnect(kConnection, now_);
    advance(2100ms);
    const auto f = found(RuleId::kMemoryNoUpdateComplete);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NE(f[0].message.find("connection ended"), std::string::npos) << f[0].message;
}

}  // namespace
}  // namespace olcb::simnode::audit::test
