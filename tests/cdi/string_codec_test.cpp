#include "cdi/string_codec.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace olcb::cdi {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes bytes_of(std::string_view s) {
    return Bytes(s.begin(), s.end());
}

Bytes encoded(std::string_view text, std::uint64_t size, CodecMode mode = CodecMode::kStrict) {
    auto r = encode_string(text, size, mode);
    EXPECT_TRUE(r.ok()) << r.error().message;
    return r.ok() ? r.value() : Bytes{};
}

const std::string euro = "\xE2\x82\xAC";          // U+20AC, 3 bytes
const std::string grinning = "\xF0\x9F\x98\x80";  // U+1F600, 4 bytes

TEST(StringCodec, EncodeWritesTextNulAndPadding) {
    EXPECT_EQ(encoded("abc", 6), (Bytes{'a', 'b', 'c', 0, 0, 0}));
    EXPECT_EQ(encoded("", 1), (Bytes{0}));
    EXPECT_EQ(encoded("", 4), (Bytes{0, 0, 0, 0}));
    EXPECT_EQ(encoded("abcd", 5), (Bytes{'a', 'b', 'c', 'd', 0}));  // full length
    EXPECT_EQ(encoded(euro, 4), (Bytes{0xE2, 0x82, 0xAC, 0}));
}

TEST(StringCodec, StrictRejectsTooLongText) {
    const auto r = encode_string("abcde", 5);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.error().message,
              "text of 5 bytes is longer than the 4 bytes a string of size 5 holds");
}

TEST(StringCodec, LenientTruncatesOnACharacterBoundary) {
    EXPECT_EQ(encoded("abcde", 5, CodecMode::kLenient), (Bytes{'a', 'b', 'c', 'd', 0}));
    EXPECT_EQ(encoded("ab" + euro, 4, CodecMode::kLenient), (Bytes{'a', 'b', 0, 0}));
}

TEST(StringCodec, RejectsBadSizesAndNul) {
    EXPECT_FALSE(encode_string("", 0).ok());
    EXPECT_FALSE(encode_string("", kMaxStringSize + 1).ok());
    EXPECT_TRUE(encode_string("", kMaxStringSize).ok());
    const auto nul = encode_string(std::string("a\0b", 3), 8, CodecMode::kLenient);
    ASSERT_FALSE(nul.ok());
    EXPECT_NE(nul.error().message.find("NUL byte at offset 1"), std::string::npos);
}

TEST(StringCodec, InvalidUtf8StrictErrorLenientRaw) {
    const std::string bad = "a\xFF";
    const auto r = encode_string(bad, 8);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("not valid UTF-8 (byte 1)"), std::string::npos);
    EXPECT_EQ(encoded(bad, 4, CodecMode::kLenient), (Bytes{'a', 0xFF, 0, 0}));
}

TEST(StringCodec, DecodeReadsUpToTheFirstNul) {
    const auto s = decode_string(bytes_of(std::string("ab\0c\0", 5)));
    EXPECT_EQ(s.text, "ab");
    EXPECT_TRUE(s.terminated);
    EXPECT_TRUE(s.valid_utf8);
    const auto empty = decode_string(Bytes{0, 0, 0});
    EXPECT_EQ(empty.text, "");
    EXPECT_TRUE(empty.terminated);
}

TEST(StringCodec, DecodeReportsUnterminatedAndInvalid) {
    const auto full = decode_string(bytes_of("abcd"));
    EXPECT_EQ(full.text, "abcd");
    EXPECT_FALSE(full.terminated);
    const auto bad = decode_string(Bytes{0xC3, 0x28, 0x00});
    EXPECT_EQ(bad.text, "\xC3(");
    EXPECT_TRUE(bad.terminated);
    EXPECT_FALSE(bad.valid_utf8);
    const auto none = decode_string(Bytes{});
    EXPECT_FALSE(none.terminated);
    EXPECT_EQ(none.text, "");
}

TEST(StringCodec, RoundTrip) {
    for (const std::string& text : {std::string(""), std::string("Node 1"), grinning + euro}) {
        const auto d = decode_string(encoded(text, 16));
        EXPECT_EQ(d.text, text);
        EXPECT_TRUE(d.terminated);
        EXPECT_TRUE(d.valid_utf8);
    }
}

}  // namespace
}  // namespace olcb::cdi
