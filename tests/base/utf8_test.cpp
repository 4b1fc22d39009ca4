#include "base/utf8.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace olcb::base {
namespace {

const std::string e_acute = "\xC3\xA9";           // U+00E9, 2 bytes
const std::string euro = "\xE2\x82\xAC";          // U+20AC, 3 bytes
const std::string grinning = "\xF0\x9F\x98\x80";  // U+1F600, 4 bytes
// All three and a 'z': 2 + 3 + 4 + 1 bytes.
const std::string mixed = "\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80z";

TEST(Utf8, FindsInvalidUtf8) {
    for (const std::string& ok : {std::string(""), std::string("plain"), e_acute, euro, grinning,
                                  std::string("\xF4\x8F\xBF\xBF"), std::string("\xED\x9F\xBF"),
                                  std::string("\xEF\xBF\xBD"), std::string("\xEF\xBF\xBF")}) {
        EXPECT_TRUE(is_valid_utf8(ok)) << ok;
        EXPECT_FALSE(find_invalid_utf8(ok).has_value()) << ok;
    }
    struct Bad {
        std::string text;
        std::size_t offset;
    };
    for (const Bad& bad : {
             Bad{"\x80", 0},              // lone continuation
             Bad{"ab\xC0\x80", 2},        // overlong NUL
             Bad{"\xC1\xBF", 0},          // overlong
             Bad{"\xE0\x80\x80", 0},      // overlong 3-byte
             Bad{"\xF0\x80\x80\x80", 0},  // overlong 4-byte
             Bad{"\xED\xA0\x80", 0},      // surrogate U+D800
             Bad{"\xF4\x90\x80\x80", 0},  // above U+10FFFF
             Bad{"\xF5\x80\x80\x80", 0},  // invalid lead
             Bad{"\xFF", 0},
             Bad{"ok\xE2\x82", 2},  // truncated at the end
             Bad{"\xC3(", 0},       // lead followed by ASCII
             Bad{"a" + euro + "\xF0\x9F\x98", 4},
         }) {
        const auto at = find_invalid_utf8(bad.text);
        ASSERT_TRUE(at.has_value()) << bad.text;
        EXPECT_EQ(*at, bad.offset) << bad.text;
        EXPECT_FALSE(is_valid_utf8(bad.text));
    }
}

TEST(Utf8, BytesOverloadAgreesWithText) {
    const std::vector<std::uint8_t> ok{'a', 0xC3, 0xA9, 0xF0, 0x9F, 0x98, 0x80};
    const std::vector<std::uint8_t> bad{'a', 0xED, 0xA0, 0x80};
    EXPECT_TRUE(is_valid_utf8(std::span<const std::uint8_t>(ok)));
    EXPECT_FALSE(is_valid_utf8(std::span<const std::uint8_t>(bad)));
    EXPECT_TRUE(is_valid_utf8(std::span<const std::uint8_t>()));
}

// Well-formed per Unicode table 3-7: the lead byte's range decides the second byte's range.
bool well_formed_3(unsigned b0, unsigned b1, unsigned b2) {
    if ((b2 & 0xC0) != 0x80) return false;
    if (b0 == 0xE0) return b1 >= 0xA0 && b1 <= 0xBF;
    if (b0 == 0xED) return b1 >= 0x80 && b1 <= 0x9F;
    return b0 >= 0xE1 && b0 <= 0xEF && (b1 & 0xC0) == 0x80;
}

TEST(Utf8, EveryTwoAndThreeByteSequenceIsJudgedAsUnicodeSays) {
    for (unsigned b0 = 0x80; b0 <= 0xFF; ++b0) {
        for (unsigned b1 = 0; b1 <= 0xFF; ++b1) {
            const std::string two{static_cast<char>(b0), static_cast<char>(b1)};
            // Only a 2-byte lead with a continuation; a longer lead cut off is invalid.
            const bool expected = b0 >= 0xC2 && b0 <= 0xDF && (b1 & 0xC0) == 0x80;
            if (expected != is_valid_utf8(two)) ADD_FAILURE() << std::hex << b0 << " " << b1;
            if (b0 < 0xE0 || b0 > 0xEF) continue;
            for (unsigned b2 = 0x00; b2 <= 0xFF; ++b2) {
                const std::string three{static_cast<char>(b0), static_cast<char>(b1),
                                        static_cast<char>(b2)};
                if (is_valid_utf8(three) != well_formed_3(b0, b1, b2)) {
                    ADD_FAILURE() << std::hex << b0 << " " << b1 << " " << b2;
                    return;
                }
            }
        }
    }
}

TEST(Utf8, TruncateNeverSplitsASequence) {
    const std::string two = "a" + e_acute;    // 3 bytes
    const std::string three = "a" + euro;     // 4 bytes
    const std::string four = "a" + grinning;  // 5 bytes
    EXPECT_EQ(truncate_utf8(two, 1), "a");
    EXPECT_EQ(truncate_utf8(two, 2), "a");
    EXPECT_EQ(truncate_utf8(two, 3), two);
    EXPECT_EQ(truncate_utf8(three, 2), "a");
    EXPECT_EQ(truncate_utf8(three, 3), "a");
    EXPECT_EQ(truncate_utf8(three, 4), three);
    EXPECT_EQ(truncate_utf8(four, 2), "a");
    EXPECT_EQ(truncate_utf8(four, 3), "a");
    EXPECT_EQ(truncate_utf8(four, 4), "a");
    EXPECT_EQ(truncate_utf8(four, 5), four);
    EXPECT_EQ(truncate_utf8(four + "b", 5), four);
    EXPECT_EQ(truncate_utf8(grinning, 3), "");
    EXPECT_EQ(truncate_utf8("abc", 0), "");
    EXPECT_EQ(truncate_utf8("abc", 100), "abc");
    EXPECT_EQ(truncate_utf8(std::string(20, 'a'), 19), std::string(19, 'a'));
    for (std::size_t max = 0; max <= 12; ++max) {
        const auto cut = truncate_utf8(mixed, max);
        EXPECT_LE(cut.size(), max);
        EXPECT_TRUE(is_valid_utf8(cut)) << max;
        EXPECT_EQ(mixed.compare(0, cut.size(), cut), 0);
        // The longest such prefix: whatever follows the cut does not fit.
        if (cut.size() < std::min(max, mixed.size())) {
            EXPECT_FALSE(is_valid_utf8(std::string_view(mixed).substr(0, max))) << max;
        }
    }
}

TEST(Utf8, TruncateOnInvalidInputCutsBytes) {
    // A stray continuation byte after a complete sequence: the sequence is kept.
    EXPECT_EQ(truncate_utf8(e_acute + "\x80", 2), e_acute);
    EXPECT_EQ(truncate_utf8("ab\xC3\xA9\x80\x80", 4), "ab\xC3\xA9");
    // Only continuation bytes belong to no sequence: cut as bytes, never longer than asked.
    EXPECT_EQ(truncate_utf8("\x80\x80\x80\x80\x80", 4), "\x80\x80\x80\x80");
    EXPECT_EQ(truncate_utf8("\x80\x80", 1), "\x80");
    // A lead byte whose sequence would run past the limit goes, even when it is cut off later.
    EXPECT_EQ(truncate_utf8("a\xE2\x82(", 2), "a");
}

TEST(Utf8, PrintableLeavesPrintableTextAlone) {
    for (const std::string& ok :
         {std::string(""), std::string("Signal 12 \"East\""), mixed, std::string("\xEF\xBF\xBD")}) {
        EXPECT_EQ(printable(ok), ok);
    }
}

TEST(Utf8, PrintableReplacesEachBadByteAndEveryControl) {
    const std::string r(kReplacementCharacter);
    EXPECT_EQ(printable("ab\xFF\xFE"), "ab" + r + r);
    EXPECT_EQ(printable("\xC3("), r + "(");
    EXPECT_EQ(printable("ok\xE2\x82"), "ok" + r + r);
    EXPECT_EQ(printable("a\nb\tc\x7F"), "a?b?c?");
    EXPECT_EQ(printable(std::string("a\0b", 3)), "a?b");
    EXPECT_EQ(printable("\xC2\x9B[31m"), "?[31m");  // C1 CSI: a terminal escape
    EXPECT_EQ(printable("\xC2\xA0"), "\xC2\xA0");   // U+00A0 is no control
    EXPECT_EQ(printable("x\xEF\xBF\xBEy\xEF\xBF\xBF"), "x" + r + "y" + r);
    const std::string out = printable("\x80\xC0\xAF\xED\xA0\x80\x1B");
    EXPECT_TRUE(is_valid_utf8(out));
    EXPECT_EQ(out, r + r + r + r + r + r + "?");
}

}  // namespace
}  // namespace olcb::base
