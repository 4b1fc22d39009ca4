// The JMRI-format configuration backup: keys, escaping, value forms and a restore round trip.
#include "conformance/config_backup.hpp"

#include <gtest/gtest.h>

#include "cdi/parser.hpp"
#include "conformance/fake_memory.hpp"

namespace olcb::conform {
namespace {

using testing::FakeMemory;

constexpr const char* kCdi = R"(<?xml version="1.0"?>
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
</segment>
<segment space="251"><int size="1"/></segment>
</cdi>)";

class ConfigBackupTest : public ::testing::Test {
protected:
    void SetUp() override {
        auto parsed = cdi::parse(kCdi);
        ASSERT_TRUE(parsed.document.has_value());
        doc_ = std::move(*parsed.document);
        auto laid = cdi::build_layout(doc_);
        ASSERT_TRUE(laid.layout.has_value());
        layout_.emplace(std::move(*laid.layout));
        memory_.spaces[253] = std::vector<std::uint8_t>(64, 0);
        memory_.spaces[251] = std::vector<std::uint8_t>(4, 0);
    }
    std::vector<std::string> keys() const {
        std::vector<std::string> out;
        for (const auto& e : config_entries(*layout_)) out.push_back(e.key);
        return out;
    }

    cdi::Document doc_;
    std::optional<cdi::Layout> layout_;
    FakeMemory memory_;
};

TEST_F(ConfigBackupTest, KeysNameUnnamedReplicatedAndNestedElements) {
    const std::vector<std::string> expected = {"Main.Enabled",
                                               "Main.Trim",
                                               "Main.Label",
                                               "Main.Event",
                                               "Main.Gain",
                                               "Main.child5",
                                               "Main.Port(0).Line(0).Mode",
                                               "Main.Port(0).Line(1).Mode",
                                               "Main.Port(0).Line(2).Mode",
                                               "Main.Port(0).child1",
                                               "Main.Port(1).Line(0).Mode",
                                               "Main.Port(1).Line(1).Mode",
                                               "Main.Port(1).Line(2).Mode",
                                               "Main.Port(1).child1",
                                               "seg1.child0"};
    EXPECT_EQ(keys(), expected);  // the action is left out
}

TEST(ConfigBackupEscape, EscapesSeparatorsBackslashAndControls) {
    EXPECT_EQ(escape_backup_text("a=b\\c\nd\x7f"), "a\\x003Db\\x005Cc\\x000Ad\\x007F");
    EXPECT_EQ(escape_backup_text("Gr\xC3\xBC\xC3\x9F"), "Gr\xC3\xBC\xC3\x9F");  // kept as UTF-8
    EXPECT_EQ(escape_backup_text("\xC2\x85"), "\\x0085");                       // C1 control
}

TEST(ConfigBackupEscape, RoundTripsEveryAwkwardString) {
    for (std::string s : {std::string("plain"), std::string("x=1\\y"), std::string("\t\r\n"),
                          std::string("\\x0041 literal"), std::string("\xE2\x82\xAC=\x01")}) {
        EXPECT_EQ(unescape_backup_text(escape_backup_text(s)), s) << s;
    }
    EXPECT_EQ(unescape_backup_text("\\x00"), "\\x00");  // malformed escape kept as written
}

TEST_F(ConfigBackupTest, WritesOneLinePerVariableWithHeaderAndNoBlankLines) {
    memory_.spaces[253][1] = 0xFF;  // Trim = -5 (signed, big-endian)
    memory_.spaces[253][2] = 0xFB;
    const std::string label = "a=b";
    std::copy(label.begin(), label.end(), memory_.spaces[253].begin() + 3);
    for (int i = 0; i < 8; ++i) memory_.spaces[253][11 + i] = static_cast<std::uint8_t>(i + 1);
    std::vector<std::string> errors;
    const std::string text = make_config_backup(*layout_, memory_, "05.01.01.01.22.00", errors);
    EXPECT_TRUE(errors.empty());
    EXPECT_EQ(text.find("\n\n"), std::string::npos);
    EXPECT_EQ(text.rfind("# ", 0), 0u);
    EXPECT_NE(text.find("\nMain.Trim=-5\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\nMain.Label=a\\x003Db\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\nMain.Event=01.02.03.04.05.06.07.08\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\nMain.Gain=0\n"), std::string::npos) << text;
    EXPECT_EQ(config_backup_node(text), "05.01.01.01.22.00");
    EXPECT_EQ(memory_.writes, 0u);
}

TEST_F(ConfigBackupTest, RestoreAcceptsSignedAndUnsignedIntegers) {
    auto out = restore_config(*layout_, memory_, "Main.Trim=-5\n");
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(memory_.spaces[253][1], 0xFF);
    EXPECT_EQ(memory_.spaces[253][2], 0xFB);
    memory_.spaces[253][1] = memory_.spaces[253][2] = 0;
    out = restore_config(*layout_, memory_, "Main.Trim=65531\r\n");  // OpenLCB_Java's reading
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(memory_.spaces[253][1], 0xFF);
    EXPECT_EQ(memory_.spaces[253][2], 0xFB);
    out = restore_config(*layout_, memory_, "Main.Trim=70000\n");  // fits neither form
    EXPECT_FALSE(out.ok());
    EXPECT_EQ(out.written, 0u);
}

TEST_F(ConfigBackupTest, UnknownKeysAreReportedNotFatal) {
    auto out = restore_config(*layout_, memory_, "# comment\n\nNo.Such=1\nMain.Enabled=7\n");
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(out.written, 1u);
    ASSERT_EQ(out.unknown_keys.size(), 1u);
    EXPECT_EQ(out.unknown_keys[0], "No.Such");
    EXPECT_EQ(memory_.spaces[253][0], 7);
    EXPECT_NE(out.summary().find("No.Such"), std::string::npos);
}

TEST_F(ConfigBackupTest, RestoreRoundTripPutsEveryValueBack) {
    auto& m = memory_.spaces[253];
    for (std::size_t i = 0; i < m.size(); ++i) m[i] = static_cast<std::uint8_t>(i * 7 + 1);
    m[3] = 'h', m[4] = 'i', m[5] = '=', m[6] = '\\', m[7] = 0;  // Label "hi=\"
    m[19] = 0x3F, m[20] = 0xC0, m[21] = 0, m[22] = 0;           // Gain 1.5
    memory_.spaces[251][0] = 42;
    std::vector<std::string> errors;
    const std::string text = make_config_backup(*layout_, memory_, "05.01.01.01.22.00", errors);
    ASSERT_TRUE(errors.empty());
    const auto before253 = memory_.spaces[253];
    // Change every backed-up byte, then restore.
    for (auto& b : memory_.spaces[253]) b = 0;
    memory_.spaces[251][0] = 0;
    auto out = restore_config(*layout_, memory_, text);
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_TRUE(out.unknown_keys.empty());
    EXPECT_EQ(out.written, keys().size());
    EXPECT_EQ(memory_.spaces[251][0], 42);
    // The action byte (offset 32) is never written; every variable byte is back.
    for (std::size_t i = 0; i < 32; ++i) {
        if (i >= 8 && i < 11) continue;  // bytes of the 8-byte string after its NUL
        EXPECT_EQ(memory_.spaces[253][i], before253[i]) << "byte " << i;
    }
    EXPECT_EQ(memory_.spaces[253][32], 0);
}

TEST_F(ConfigBackupTest, RestoreReportsFailedWrites) {
    memory_.spaces.erase(251);
    auto out = restore_config(*layout_, memory_, "seg1.child0=3\n");
    EXPECT_FALSE(out.ok());
    EXPECT_NE(out.summary().find("seg1.child0"), std::string::npos);
}

TEST_F(ConfigBackupTest, ReadFailuresAreListedAndTheVariableLeftOut) {
    memory_.spaces.erase(251);
    std::vector<std::string> errors;
    const std::string text = make_config_backup(*layout_, memory_, "05.01.01.01.22.00", errors);
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("seg1.child0"), std::string::npos);
    EXPECT_EQ(text.find("seg1.child0="), std::string::npos);
}

TEST(ConfigBackupDuplicates, RepeatedKeysMapToVariablesInOrder) {
    auto parsed = cdi::parse(R"(<?xml version="1.0"?>
<cdi><segment space="253"><name>S</name>
<int size="1"><name>X</name></int><int size="1"><name>X</name></int>
</segment></cdi>)");
    ASSERT_TRUE(parsed.document.has_value());
    auto laid = cdi::build_layout(*parsed.document);
    ASSERT_TRUE(laid.layout.has_value());
    FakeMemory memory;
    memory.spaces[253] = std::vector<std::uint8_t>(2, 0);
    auto out = restore_config(*laid.layout, memory, "S.X=1\nS.X=2\nS.X=3\n");
    EXPECT_EQ(out.written, 2u);
    EXPECT_EQ(memory.spaces[253], (std::vector<std::uint8_t>{1, 2}));
    EXPECT_EQ(out.unknown_keys, std::vector<std::string>{"S.X"});  // the third has no variable
}

}  // namespace
}  // namespace olcb::conform
