// Restoring a JMRI-format backup: only what differs is written, every problem listed.
#include "conformance/backup/config_restore.hpp"

#include <gtest/gtest.h>

#include "conformance/backup_test_util.hpp"

namespace olcb::conform {
namespace {

using testing::Cdi;
using testing::ConfigBackupTest;
using testing::FakeMemory;

TEST_F(ConfigBackupTest, RestoreAcceptsSignedAndUnsignedIntegers) {
    auto out = restore_config(*cdi_.layout, memory_, "Main.Trim=-5\n");
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(memory_.spaces[253][1], 0xFF);
    EXPECT_EQ(memory_.spaces[253][2], 0xFB);
    memory_.spaces[253][1] = memory_.spaces[253][2] = 0;
    out = restore_config(*cdi_.layout, memory_, "Main.Trim=65531\r\n");  // OpenLCB_Java's form
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(memory_.spaces[253][1], 0xFF);
    EXPECT_EQ(memory_.spaces[253][2], 0xFB);
    out = restore_config(*cdi_.layout, memory_, "Main.Trim=70000\n");  // fits neither form
    EXPECT_FALSE(out.ok());
    EXPECT_NE(out.summary().find("out of range"), std::string::npos) << out.summary();
    EXPECT_EQ(out.written, 0u);
}

TEST_F(ConfigBackupTest, UnknownKeysAreListedWithTheirLine) {
    auto out = restore_config(*cdi_.layout, memory_, "# comment\n\nNo.Such=1\nMain.Enabled=7\n");
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(out.written, 1u);
    EXPECT_EQ(out.unknown_keys, std::vector<std::string>{"line 3: No.Such"});
    EXPECT_EQ(memory_.spaces[253][0], 7);
    EXPECT_NE(out.summary().find("No.Such"), std::string::npos);
}

TEST_F(ConfigBackupTest, RestoreRoundTripPutsEveryValueBackAndWritesOnlyWhatDiffers) {
    auto& m = memory_.spaces[253];
    for (std::size_t i = 0; i < m.size(); ++i) m[i] = static_cast<std::uint8_t>(i * 7 + 1);
    m[1] = 0xFF, m[2] = 0xFB;                                   // Trim -5, within min/max
    m[3] = 'h', m[4] = 'i', m[5] = '=', m[6] = '\\', m[7] = 0;  // Label "hi=\"
    m[19] = 0x3F, m[20] = 0xC0, m[21] = 0, m[22] = 0;           // Gain 1.5
    memory_.spaces[251][0] = 42;
    const std::string text = backup();
    const auto before253 = memory_.spaces[253];
    // An identical node: nothing to write.
    auto out = restore_config(*cdi_.layout, memory_, text);
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(out.written, 0u);
    EXPECT_EQ(memory_.writes, 0u);
    // Change every backed-up byte, then restore.
    for (auto& b : memory_.spaces[253]) b = 0;
    memory_.spaces[251][0] = 0;
    out = restore_config(*cdi_.layout, memory_, text);
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_TRUE(out.unknown_keys.empty());
    EXPECT_EQ(out.written, keys().size());
    EXPECT_EQ(memory_.spaces[251][0], 42);
    // The action byte (offset 32) and the bit (33) are never written; every variable is back.
    for (std::size_t i = 0; i < 32; ++i) {
        if (i >= 8 && i < 11) continue;  // bytes of the 8-byte string after its NUL
        EXPECT_EQ(memory_.spaces[253][i], before253[i]) << "byte " << i;
    }
    EXPECT_EQ(memory_.spaces[253][32], 0);
    EXPECT_EQ(memory_.spaces[253][33], 0);
}

TEST_F(ConfigBackupTest, RestoreReportsFailedWritesAndValuesTheNodeDidNotKeep) {
    memory_.spaces.erase(251);
    auto out = restore_config(*cdi_.layout, memory_, "seg3.child0=3\n");
    EXPECT_FALSE(out.ok());
    EXPECT_NE(out.summary().find("seg3.child0: write failed"), std::string::npos) << out.summary();
    memory_.drop_writes = true;
    out = restore_config(*cdi_.layout, memory_, "Main.Enabled=9\n");
    EXPECT_FALSE(out.ok());
    EXPECT_EQ(out.written, 0u);
    EXPECT_NE(out.summary().find("wrote \"9\", the node holds \"0\""), std::string::npos)
        << out.summary();
}

TEST_F(ConfigBackupTest, ValuesTheCdiForbidsAreRefusedWithTheirRuleAndNotWritten) {
    // Trim: min -100, max 100 (the <int> on line 6 of kBackupCdi); Label: 8 bytes.
    const std::string text = "Main.Trim=2000\nMain.Label=12345678\nMain.Enabled=4\n";
    const auto before = memory_.spaces[253];
    auto out = restore_config(*cdi_.layout, memory_, text);
    EXPECT_FALSE(out.ok());
    EXPECT_EQ(out.written, 1u);  // Enabled only
    EXPECT_EQ(memory_.spaces[253][0], 4);
    EXPECT_EQ(memory_.spaces[253][1], before[1]);  // Trim untouched
    EXPECT_EQ(memory_.spaces[253][2], before[2]);
    EXPECT_EQ(memory_.spaces[253][3], before[3]);  // Label untouched
    ASSERT_EQ(out.errors.size(), 2u) << out.summary();
    EXPECT_EQ(out.errors[0],
              "line 1: Main.Trim=\"2000\": out-of-range: value 2000 above max 100 of 'Trim' "
              "(<int> at CDI line 6; CDI §5.1.4.2: invalid values shall not be written)");
    EXPECT_NE(out.errors[1].find("line 2: Main.Label=\"12345678\": too-long: "), std::string::npos)
        << out.errors[1];
    EXPECT_NE(out.errors[1].find("CDI §5.1.4.3"), std::string::npos) << out.errors[1];

    // --force writes them (a value with no bytes at all still cannot be).
    out = restore_config(*cdi_.layout, memory_, text + "Main.Event=1.2\n", true);
    EXPECT_EQ(out.written, 2u) << out.summary();
    EXPECT_EQ(out.forced, 2u);
    EXPECT_EQ(memory_.spaces[253][1], 0x07);
    EXPECT_EQ(memory_.spaces[253][2], 0xD0);
    EXPECT_EQ(std::string(memory_.spaces[253].begin() + 3, memory_.spaces[253].begin() + 11),
              "12345678");
    ASSERT_EQ(out.errors.size(), 1u) << out.summary();
    EXPECT_NE(out.errors[0].find("line 4: Main.Event=\"1.2\": malformed"), std::string::npos)
        << out.errors[0];
}

TEST_F(ConfigBackupTest, AValueTheNodeAlreadyHoldsIsNeverRefused) {
    memory_.spaces[253][1] = 0x07;  // the node holds Trim 2000 already: nothing is written
    memory_.spaces[253][2] = 0xD0;
    const auto out = restore_config(*cdi_.layout, memory_, "Main.Trim=2000\n");
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(memory_.writes, 0u);
}

TEST(ConfigBackupPlan, RefusedValuesAreInThePlanWithTheirBytes) {
    Cdi cdi(testing::kBackupCdi);
    const std::vector<ConfigEntry> entries = config_entries(*cdi.layout);
    const std::vector<ConfigValue> values(entries.size());
    const RestorePlan plan = plan_restore(
        entries, parse_backup_file("Main.Trim=-101\nMain.Event=1.2\nMain.Trim=5\n"), values);
    ASSERT_EQ(plan.refused.size(), 2u);
    EXPECT_EQ(plan.refused[0].entry->key, "Main.Trim");
    EXPECT_EQ(plan.refused[0].line, 1u);
    EXPECT_EQ(plan.refused[0].verdict.broken, ValueRule::kOutOfRange);
    EXPECT_EQ(plan.refused[1].verdict.broken, ValueRule::kMalformed);
    EXPECT_EQ(plan.forcible(), 1u);
    EXPECT_FALSE(plan.clean());
    EXPECT_EQ(plan.unknown_keys.size(), 1u);  // the second Main.Trim: there is one
}

TEST(ConfigBackupPlan, ARefusedLineIsPrintableWhateverTheFileHolds) {
    Cdi cdi(R"(<?xml version="1.0"?>
<cdi><segment space="253"><name>S</name><string size="4"><name>Bell</name></string>
</segment></cdi>)");
    const std::vector<ConfigEntry> entries = config_entries(*cdi.layout);
    const std::vector<ConfigValue> values(entries.size());
    BackupFile file;  // as a CSV row holds it: raw, a terminal's escape sequence included
    file.records.push_back({"S.Bell", "\x1B[2J\xC2\x9B", 2, std::nullopt});
    const RestorePlan plan = plan_restore(entries, file, values);
    ASSERT_EQ(plan.refused.size(), 1u);
    const std::string line = refused_text(plan.refused[0]);
    for (char c : line) EXPECT_GE(static_cast<unsigned char>(c), 0x20) << line;
    EXPECT_EQ(line.find("\xC2\x9B"), std::string::npos) << line;  // no C1 CSI either
}

TEST(ConfigBackupDuplicates, RepeatedKeysMapToVariablesInOrder) {
    Cdi cdi(R"(<?xml version="1.0"?>
<cdi><segment space="253"><name>S</name>
<int size="1"><name>X</name></int><int size="1"><name>X</name></int>
</segment></cdi>)");
    FakeMemory memory;
    memory.spaces[253] = std::vector<std::uint8_t>(2, 0);
    auto out = restore_config(*cdi.layout, memory, "S.X=1\nS.X=2\nS.X=3\n");
    EXPECT_EQ(out.written, 2u);
    EXPECT_EQ(memory.spaces[253], (std::vector<std::uint8_t>{1, 2}));
    EXPECT_EQ(out.unknown_keys, std::vector<std::string>{"line 3: S.X"});  // no third variable
}

TEST(ConfigBackupPlan, AFileMatchingLessThanHalfOfTheKeysIsForAnotherNode) {
    Cdi cdi(testing::kBackupCdi);
    const std::vector<ConfigEntry> entries = config_entries(*cdi.layout);
    const std::vector<ConfigValue> values(entries.size());
    RestorePlan plan = plan_restore(entries, parse_backup_file("Main.Enabled=1\nX.y=2\n"), values);
    EXPECT_EQ(plan.node_keys, entries.size() - 1);  // the float does not count
    EXPECT_EQ(plan.matched, 1u);
    EXPECT_TRUE(plan.for_another_node());
    EXPECT_FALSE(plan.clean());
    std::string half;
    for (std::size_t i : {0, 1, 2, 5, 6, 7, 8}) half += entries[i].key + "=0\n";  // no float
    plan = plan_restore(entries, parse_backup_file(half), values);
    EXPECT_EQ(plan.matched, 7u);  // 7 of 14
    EXPECT_FALSE(plan.for_another_node());
    EXPECT_EQ(plan.changes.size(), 7u);  // the node's values are unknown: all are written
    EXPECT_EQ(plan.missing.size(), entries.size() - 7);
}

}  // namespace
}  // namespace olcb::conform
