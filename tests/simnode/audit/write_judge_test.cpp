// WriteJudge (the CDI rules of memory writes: cut variables, uncovered bytes, values the CDI
// does not allow), through the client audit against the default node (MemoryRules,
// audit_script.hpp), and on its own against a small CDI.
#include "simnode/audit/write_judge.hpp"

#include <gtest/gtest.h>

#include "audit_script.hpp"

namespace olcb::simnode::audit::test {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

TEST_F(MemoryRules, AWriteOfPartOfAnIntOrAcrossTwoVariablesStraddles) {
    write(0xFD, 1, {0x00});                           // the first byte of Trim only...
    write(0xFD, 7, std::vector<std::uint8_t>(8, 0));  // ...not continued: Counter, whole
    write(0xFD, 2, {0x05});                           // Trim's second byte alone: starts inside it
    write(0xFD, 0, {1, 0x00});                        // Enabled and half of Trim
    update_complete();
    const auto f = found(RuleId::kMemoryWriteStraddles);
    ASSERT_EQ(f.size(), 1u);  // all about Trim
    EXPECT_EQ(f[0].count, 3u);
    EXPECT_NE(f[0].message.find("'Settings.Trim'"), std::string::npos) << f[0].message;
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
    EXPECT_NE(f[0].message.find("'Settings.Enabled'"), std::string::npos) << f[0].message;
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

// WriteJudge on its own, against the default node's profile.
std::vector<Verdict> judge(WriteJudge& j, std::uint8_t space, std::uint32_t address,
                           const std::vector<std::uint8_t>& data, bool judge_values = true) {
    return j.write(default_profile(), space, address, data, {}, judge_values);
}

TEST(WriteJudge, AWholeVariableIsJudgedByItsCdiValueRules) {
    WriteJudge j;
    EXPECT_THAT(judge(j, 0xFD, 1, {0xFC, 0x18}), IsEmpty());  // Trim = -1000
    const auto v = judge(j, 0xFD, 1, {0x07, 0xD0});           // Trim = 2000
    ASSERT_EQ(v.size(), 1u);
    EXPECT_EQ(v[0].rule, RuleId::kCdiIntOutOfRange);
    EXPECT_EQ(v[0].key, "FD:00000001");
    EXPECT_NE(v[0].message.find("'Settings.Trim'"), std::string::npos) << v[0].message;
    EXPECT_THAT(judge(j, 0xFD, 1, {0x07, 0xD0}, false), IsEmpty()) << "coverage only";
}

TEST(WriteJudge, AVariableCutAtItsEndWaitsForTheRestOrForFlush) {
    WriteJudge j;
    EXPECT_THAT(judge(j, 0xFD, 1, {0x07}), IsEmpty());
    const auto whole = judge(j, 0xFD, 2, {0xD0});  // goes on where the last ended
    ASSERT_EQ(whole.size(), 1u);
    EXPECT_EQ(whole[0].rule, RuleId::kCdiIntOutOfRange) << "judged as one value, 2000";
    EXPECT_THAT(judge(j, 0xFD, 1, {0x00}), IsEmpty());
    const auto cut = j.flush();
    ASSERT_EQ(cut.size(), 1u);
    EXPECT_EQ(cut[0].rule, RuleId::kMemoryWriteStraddles);
    EXPECT_THAT(j.flush(), IsEmpty()) << "nothing waits any more";
}

TEST(WriteJudge, BytesNoVariableCoversAndAStartInsideAVariableAreVerdicts) {
    WriteJudge j;
    const auto uncovered = judge(j, 0xFB, 0, {2});
    ASSERT_EQ(uncovered.size(), 1u);
    EXPECT_EQ(uncovered[0].rule, RuleId::kMemoryWriteUncovered);
    EXPECT_EQ(uncovered[0].key, "FB:00000000");
    const auto inside = judge(j, 0xFD, 2, {0x05});
    ASSERT_EQ(inside.size(), 1u);
    EXPECT_EQ(inside[0].rule, RuleId::kMemoryWriteStraddles);
    EXPECT_NE(inside[0].message.find("starts at byte 1"), std::string::npos) << inside[0].message;
}

}  // namespace
}  // namespace olcb::simnode::audit::test
