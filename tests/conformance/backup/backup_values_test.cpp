// The JMRI backup values: escaping, integer forms (signed or unsigned) and canonical forms.
#include "conformance/backup/backup_values.hpp"

#include <gtest/gtest.h>

#include "conformance/backup_test_util.hpp"

namespace olcb::conform {
namespace {

using testing::Cdi;
using testing::ConfigBackupTest;
using testing::FakeMemory;

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

TEST(ConfigBackupValues, EightByteIntsAreWrittenSignedAndReadEitherWay) {
    testing::round_trip(testing::wide(1ull << 63, 0, 0), "W.U64=-9223372036854775808");  // 2^63
    testing::round_trip(testing::wide(~0ull, 0, 0), "W.U64=-1");                         // 2^64 - 1
    testing::round_trip(testing::wide(0, ~0ull, 0), "W.S64=-1");      // signed -1
    testing::round_trip(testing::wide(0, 0, 0xFF85), "W.S16=65413");  // 2-byte -123
    Cdi cdi(testing::kWideCdi);
    FakeMemory memory;
    memory.spaces[253] = std::vector<std::uint8_t>(18, 0);
    // The unsigned forms older lcc-conform wrote, and the signed one a user may type.
    const auto out = restore_config(*cdi.layout, memory,
                                    "W.U64=9223372036854775808\nW.S64=18446744073709551615\n"
                                    "W.S16=-123\n");
    EXPECT_TRUE(out.ok()) << out.summary();
    EXPECT_EQ(memory.spaces[253], testing::wide(1ull << 63, ~0ull, 0xFF85));
    EXPECT_FALSE(
        restore_config(*cdi.layout, memory, "W.U64=18446744073709551616\nW.S16=-32769\n").ok());
}

TEST(ConfigBackupValues, CanonicalFormsCompareEqual) {
    Cdi cdi(testing::kWideCdi);
    const cdi::Element& s16 = cdi.doc.segments[0].children[2];
    std::string error;
    EXPECT_EQ(canonical_backup_value(s16, "-123", error), "65413");
    EXPECT_EQ(canonical_backup_value(s16, " 65413 ", error), "65413");
    EXPECT_FALSE(canonical_backup_value(s16, "12x", error));
    EXPECT_NE(error.find("not a decimal integer"), std::string::npos) << error;
}

}  // namespace
}  // namespace olcb::conform
