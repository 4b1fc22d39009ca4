// The JMRI-format configuration backup: OpenLCB_Java's keys and value forms, escaping, and
// restore (only what differs is written, every problem listed) on an in-memory node.
#include "conformance/run/config_backup.hpp"

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
  <bit size="1"><name>Flag</name></bit>
</segment>
<segment space="251"><int size="1"/></segment>
</cdi>)";

// A parsed and laid-out CDI.
struct Cdi {
    explicit Cdi(const char* text) {
        auto parsed = cdi::parse(text);
        EXPECT_TRUE(parsed.document.has_value());
        if (!parsed.document) return;
        doc = std::make_unique<cdi::Document>(std::move(*parsed.document));
        auto laid = cdi::build_layout(*doc);
        EXPECT_TRUE(laid.layout.has_value());
        if (laid.layout) layout.emplace(std::move(*laid.layout));
    }
    std::unique_ptr<cdi::Document> doc;
    std::optional<cdi::Layout> layout;
};

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

    Cdi cdi_{kCdi};
    FakeMemory memory_;
};

TEST_F(ConfigBackupTest, UnnamedElementsAreNumberedByTheirContentNodeIndex) {
    // Main's children: "\n  ", <name>, "\n  ", Enabled, ... so the unnamed int is node 13;
    // <cdi>'s: "\n", <segment>, "\n", <segment>, so the unnamed segment is seg3.
    const std::vector<std::string> expected = {"Main.Enabled",
                                               "Main.Trim",
                                               "Main.Label",
                                               "Main.Event",
                                               "Main.Gain",
                                               "Main.child13",
                                               "Main.Port(0).Line(0).Mode",
                                               "Main.Port(0).Line(1).Mode",
                                               "Main.Port(0).Line(2).Mode",
                                               "Main.Port(0).child4",
                                               "Main.Port(1).Line(0).Mode",
                                               "Main.Port(1).Line(1).Mode",
                                               "Main.Port(1).Line(2).Mode",
                                               "Main.Port(1).child4",
                                               "seg3.child0"};
    EXPECT_EQ(keys(), expected);  // the action and the bit are left out, as OpenLCB_Java does
}

TEST(ConfigBackupEscape, EscapesSeparatorsBackslashAndControlsInLowerCaseHex) {
    EXPECT_EQ(escape_backup_text("a=b\\c\nd\x7f"), "a\\x003db\\x005cc\\x000ad\\x007f");
    EXPECT_EQ(escape_backup_text("Gr\xC3\xBC\xC3\x9F"), "Gr\xC3\xBC\xC3\x9F");  // kept as UTF-8
    EXPECT_EQ(escape_backup_text("\xC2\x85"), "\\x0085");                       // C1 control
    EXPECT_EQ(unescape_backup_text("\\x003D\\x003d"), "==");                    // both cases
}

TEST(ConfigBackupEscape, RoundTripsEveryAwkwardString) {
    for (const std::string& s :
         {std::string("plain"), std::string("x=1\\y"), std::string("\t\r\n"),
          std::string("\\x0041 literal"), std::string("\xE2\x82\xAC=\x01")}) {
        EXPECT_EQ(unescape_backup_text(escape_backup_text(s)), s) << s;
    }
    EXPECT_EQ(unescape_backup_text("\\x00"), "\\x00");  // malformed escape kept as written
}

TEST_F(ConfigBackupTest, WritesOneLinePerVariableAsOpenLcbJavaDoes) {
    memory_.spaces[253][1] = 0xFF;  // Trim = -5 (signed, big-endian): written unsigned
    memory_.spaces[253][2] = 0xFB;
    const std::string label = "a=b";
    std::copy(label.begin(), label.end(), memory_.spaces[253].begin() + 3);
    for (int i = 0; i < 8; ++i) memory_.spaces[253][11 + i] = static_cast<std::uint8_t>(i + 1);
    const std::string text = backup();
    EXPECT_EQ(text.find("\n\n"), std::string::npos);
    EXPECT_EQ(text.rfind("# ", 0), 0u);
    EXPECT_NE(text.find("\nMain.Trim=65531\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\nMain.Label=a\\x003db\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\nMain.Event=01.02.03.04.05.06.07.08\n"), std::string::npos) << text;
    EXPECT_NE(text.find("\nMain.Gain=0\n"), std::string::npos) << text;
    EXPECT_EQ(config_backup_node(text), "05.01.01.01.22.00");
    EXPECT_EQ(memory_.writes, 0u);
}

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

TEST_F(ConfigBackupTest, ReadFailuresAreListedAndTheVariableLeftOut) {
    memory_.spaces.erase(251);
    std::vector<std::string> errors;
    const std::string text = make_config_backup(*cdi_.layout, memory_, "05.01.01.01.22.00", errors);
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("seg3.child0"), std::string::npos);
    EXPECT_EQ(text.find("seg3.child0="), std::string::npos);
    EXPECT_NE(text.find("Main.Enabled=0"), std::string::npos);
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

constexpr const char* kWideCdi = R"(<?xml version="1.0"?>
<cdi><segment space="253"><name>W</name>
<int size="8"><name>U64</name></int>
<int size="8"><name>S64</name><min>-10</min></int>
<int size="2"><name>S16</name><min>-200</min><max>200</max></int>
</segment></cdi>)";

// Backs up the bytes, checks the line, zeroes the node, restores the file text: bytes back.
void round_trip(const std::vector<std::uint8_t>& bytes, const std::string& line) {
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

std::vector<std::uint8_t> wide(std::uint64_t u64, std::uint64_t s64, std::uint16_t s16) {
    std::vector<std::uint8_t> b;
    for (std::uint64_t v : {u64, s64}) {
        for (int k = 7; k >= 0; --k) b.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
    }
    b.push_back(static_cast<std::uint8_t>(s16 >> 8));
    b.push_back(static_cast<std::uint8_t>(s16));
    return b;
}

TEST(ConfigBackupValues, EightByteIntsAreWrittenSignedAndReadEitherWay) {
    round_trip(wide(1ull << 63, 0, 0), "W.U64=-9223372036854775808");  // 2^63
    round_trip(wide(~0ull, 0, 0), "W.U64=-1");                         // 2^64 - 1
    round_trip(wide(0, ~0ull, 0), "W.S64=-1");                         // signed -1
    round_trip(wide(0, 0, 0xFF85), "W.S16=65413");                     // 2-byte -123
    Cdi cdi(kWideCdi);
    FakeMemory memory;
    memory.spaces[253] = std::vector<std::uint8_t>(18, 0);
    // The unsigned forms older lcc-conform wrote, and the signed one a user may type.
    const auto out = restore_config(*cdi.layout, memory,
                                    "W.U64=9223372036854775808\nW.S64=18446744073709551615\n"
                                    "W.S16=-123\n");
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(memory.spaces[253], wide(1ull << 63, ~0ull, 0xFF85));
    EXPECT_FALSE(
        restore_config(*cdi.layout, memory, "W.U64=18446744073709551616\nW.S16=-32769\n").ok());
}

TEST(ConfigBackupValues, CanonicalFormsCompareEqual) {
    Cdi cdi(kWideCdi);
    const cdi::Element& s16 = cdi.doc->segments[0].children[2];
    std::string error;
    EXPECT_EQ(canonical_backup_value(s16, "-123", error), "65413");
    EXPECT_EQ(canonical_backup_value(s16, " 65413 ", error), "65413");
    EXPECT_FALSE(canonical_backup_value(s16, "12x", error));
    EXPECT_NE(error.find("not a decimal integer"), std::string::npos) << error;
}

TEST(ConfigBackupFile, ReadsCommentsBlankLinesCrLfBomAndMalformedLines) {
    const BackupFile f = parse_backup_file(
        "\xEF\xBB\xBF# node 05.01.01.01.22.00\r\n\r\nA.b=1\r\nno equals\nC.d=\n"
        "E.x\\x003Dy=v\\x003d\n");
    EXPECT_EQ(f.node, "05.01.01.01.22.00");
    ASSERT_EQ(f.records.size(), 3u);
    EXPECT_EQ(f.records[0].key, "A.b");
    EXPECT_EQ(f.records[0].line, 3u);
    EXPECT_EQ(f.records[1].value, "");
    EXPECT_EQ(f.records[2].key, "E.x\\x003dy");  // upper-case escapes read as OpenLCB_Java's
    EXPECT_EQ(f.records[2].value, "v=");
    EXPECT_EQ(f.errors, std::vector<std::string>{"line 4: not key=value"});
}

TEST(ConfigBackupPlan, AFileMatchingLessThanHalfOfTheKeysIsForAnotherNode) {
    Cdi cdi(kCdi);
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
