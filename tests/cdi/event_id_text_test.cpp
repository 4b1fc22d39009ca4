#include "cdi/event_id_text.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace olcb::cdi {
namespace {

std::string error_of(std::string_view text) {
    const auto r = parse_event_id(text);
    EXPECT_FALSE(r.ok()) << text;
    return r.ok() ? std::string() : r.error().message;
}

bool contains(const std::string& haystack, const std::string& needle) {
    return haystack.find(needle) != std::string::npos;
}

TEST(EventIdText, FormatsDottedUppercaseHex) {
    EXPECT_EQ(format_event_id(0x0501010122000001), "05.01.01.01.22.00.00.01");
    EXPECT_EQ(format_event_id(0), "00.00.00.00.00.00.00.00");
    EXPECT_EQ(format_event_id(0xFFFFFFFFFFFFFFFF), "FF.FF.FF.FF.FF.FF.FF.FF");
    EXPECT_EQ(format_event_id(0x0A0B0C0D0E0F1A2B), "0A.0B.0C.0D.0E.0F.1A.2B");
}

TEST(EventIdText, ParsesEitherCaseAndUndotted) {
    EXPECT_EQ(parse_event_id("05.01.01.01.22.00.00.01").value(), 0x0501010122000001u);
    EXPECT_EQ(parse_event_id("0a.0B.0c.0D.0e.0F.1a.2B").value(), 0x0A0B0C0D0E0F1A2Bu);
    EXPECT_EQ(parse_event_id("ff.ff.ff.ff.ff.ff.ff.ff").value(), 0xFFFFFFFFFFFFFFFFu);
    EXPECT_EQ(parse_event_id("0501010122000001").value(), 0x0501010122000001u);
    EXPECT_EQ(parse_event_id("abcdefABCDEF0123").value(), 0xABCDEFABCDEF0123u);
}

TEST(EventIdText, FormatParseRoundTrip) {
    for (EventIdValue id : {0ull, 1ull, 0x0501010122000001ull, 0x8000000000000000ull, ~0ull}) {
        EXPECT_EQ(parse_event_id(format_event_id(id)).value(), id);
    }
}

TEST(EventIdText, ErrorsSayWhatIsWrong) {
    EXPECT_EQ(error_of(""), "empty event ID");
    EXPECT_TRUE(contains(error_of("05.01.01.01.22.00.00"), "has 7 groups; expected 8"));
    EXPECT_TRUE(contains(error_of("05.01.01.01.22.00.00.01.02"), "has 9 groups; expected 8"));
    EXPECT_EQ(error_of("05.01..01.22.00.00.01"),
              "byte 3 of event ID '05.01..01.22.00.00.01' is empty");
    EXPECT_TRUE(contains(error_of("05.01.01.01.22.00.00."), "byte 8 of event ID"));
    EXPECT_TRUE(contains(error_of(".01.01.01.22.00.00.01"), "byte 1 of event ID"));
    EXPECT_EQ(error_of("5.01.01.01.22.00.00.01"),
              "byte 1 of event ID '5.01.01.01.22.00.00.01' has 1 hex digit; expected exactly 2");
    EXPECT_TRUE(contains(error_of("05.01.01.01.22.00.00.001"), "byte 8 of event ID"));
    EXPECT_TRUE(contains(error_of("05.0G.01.01.22.00.00.01"), "'G' is not a hex digit"));
    EXPECT_TRUE(contains(error_of(" 05.01.01.01.22.00.00.01"), "'\\x20' is not a hex digit"));
    EXPECT_TRUE(contains(error_of("0x0501010122000001"), "'x' is not a hex digit"));
    EXPECT_TRUE(contains(error_of(std::string(65, '0')), "too long"));
    EXPECT_TRUE(contains(error_of("050101012200001"), "15 hex digits; expected 16"));
    EXPECT_TRUE(contains(error_of("05010101220000011"), "17 hex digits"));
    EXPECT_TRUE(contains(error_of("05:01:01:01:22:00:00:01"), "':' is not a hex digit"));
}

TEST(EventIdText, BytesAreBigEndian) {
    const auto bytes = encode_event_id(0x0501010122000001);
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin(), bytes.end()),
              (std::vector<std::uint8_t>{0x05, 0x01, 0x01, 0x01, 0x22, 0x00, 0x00, 0x01}));
    EXPECT_EQ(decode_event_id(bytes).value(), 0x0501010122000001u);
    const std::vector<std::uint8_t> seven(7, 0);
    const auto r = decode_event_id(seven);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message, "an event ID has 8 bytes, not 7");
}

}  // namespace
}  // namespace olcb::cdi
