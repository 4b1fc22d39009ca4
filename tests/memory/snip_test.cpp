#include "memory/snip.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

namespace olcb::memory {
namespace {

std::vector<std::uint8_t> bytes_of(std::string_view text) {
    return std::vector<std::uint8_t>(text.begin(), text.end());
}

// The 46-byte payload of the fact sheet's worked example, frame by frame.
constexpr std::array<std::uint8_t, 46> kExample{
    0x04, 0x41, 0x43, 0x4D, 0x45, 0x20, 0x53, 0x69, 0x6D, 0x00, 0x43, 0x44, 0x49, 0x20, 0x4E, 0x6F,
    0x64, 0x65, 0x00, 0x31, 0x2E, 0x30, 0x00, 0x30, 0x2E, 0x33, 0x2E, 0x31, 0x00, 0x02, 0x54, 0x65,
    0x73, 0x74, 0x20, 0x6E, 0x6F, 0x64, 0x65, 0x00, 0x42, 0x65, 0x6E, 0x63, 0x68, 0x00};

Snip example_snip() {
    Snip snip;
    snip.manufacturer = "ACME Sim";
    snip.model = "CDI Node";
    snip.hardware_version = "1.0";
    snip.software_version = "0.3.1";
    snip.user_name = "Test node";
    snip.user_description = "Bench";
    return snip;
}

TEST(Snip, EncodesTheWorkedExampleExactly) {
    const auto payload = encode_snip(example_snip());
    EXPECT_EQ(payload.size(), 46u);
    EXPECT_EQ(payload, std::vector<std::uint8_t>(kExample.begin(), kExample.end()));
}

TEST(Snip, DecodesTheWorkedExample) {
    EXPECT_EQ(decode_snip(kExample), example_snip());
    EXPECT_TRUE(is_complete_snip(kExample));
    EXPECT_EQ(complete_snip_size(kExample), 46u);
}

TEST(Snip, EmptyStringsStillCarryTheirNul) {
    const auto payload = encode_snip(Snip{});
    EXPECT_EQ(payload, (std::vector<std::uint8_t>{4, 0, 0, 0, 0, 2, 0, 0}));
    EXPECT_TRUE(is_complete_snip(payload));
}

TEST(Snip, EncoderAlwaysSendsVersions4And2) {
    Snip snip = example_snip();
    snip.manufacturer_version = 1;
    snip.user_version = 9;
    const auto payload = encode_snip(snip);
    EXPECT_EQ(payload.front(), 4);
    EXPECT_EQ(payload[29], 2);
}

TEST(Snip, EncoderClampsToMaximumSizes) {
    Snip snip;
    snip.manufacturer = std::string(100, 'm');
    snip.model = std::string(100, 'o');
    snip.hardware_version = std::string(100, 'h');
    snip.software_version = std::string(100, 's');
    snip.user_name = std::string(100, 'n');
    snip.user_description = std::string(100, 'd');
    const auto payload = encode_snip(snip);
    EXPECT_EQ(payload.size(), kSnipMaxPayload);
    const Snip back = decode_snip(payload);
    EXPECT_EQ(back.manufacturer.size(), kSnipManufacturerMax - 1);
    EXPECT_EQ(back.model.size(), kSnipModelMax - 1);
    EXPECT_EQ(back.hardware_version.size(), kSnipHardwareVersionMax - 1);
    EXPECT_EQ(back.software_version.size(), kSnipSoftwareVersionMax - 1);
    EXPECT_EQ(back.user_name.size(), kSnipUserNameMax - 1);
    EXPECT_EQ(back.user_description.size(), kSnipUserDescriptionMax - 1);
}

TEST(Snip, ClampNeverSplitsUtf8) {
    // 19 ASCII bytes then "é" (2 bytes): a 20-byte limit must drop the whole "é".
    const std::string text = std::string(19, 'a') + "\xC3\xA9";
    EXPECT_EQ(clamp_utf8(text, 20), std::string(19, 'a'));
    EXPECT_EQ(clamp_utf8(text, 21), text);
    // A 4-byte sequence straddling the limit goes entirely.
    const std::string emoji = "ab\xF0\x9F\x98\x80";
    EXPECT_EQ(clamp_utf8(emoji, 5), "ab");
    EXPECT_EQ(clamp_utf8(emoji, 6), emoji);
    Snip snip;
    snip.hardware_version = text;
    EXPECT_EQ(decode_snip(encode_snip(snip)).hardware_version, std::string(19, 'a'));
}

TEST(Snip, ClampStopsAtEmbeddedNul) {
    EXPECT_EQ(clamp_utf8(std::string_view("ab\0cd", 5), 10), "ab");
    Snip snip;
    snip.model = std::string("ab\0cd", 5);
    EXPECT_EQ(decode_snip(encode_snip(snip)).model, "ab");
}

TEST(Snip, LegacyVersionOneMeansFourAndTwo) {
    auto payload = kExample;
    payload[0] = 1;
    payload[29] = 1;
    const Snip snip = decode_snip(payload);
    EXPECT_EQ(snip.manufacturer_version, 1);
    EXPECT_EQ(snip.user_version, 1);
    EXPECT_EQ(snip.software_version, "0.3.1");
    EXPECT_EQ(snip.user_name, "Test node");
    EXPECT_EQ(snip.user_description, "Bench");
    EXPECT_TRUE(is_complete_snip(payload));
}

TEST(Snip, ExtraStringsOfHigherVersionsAreSkipped) {
    const auto payload =
        bytes_of(std::string("\x05"
                             "M\0m\0h\0s\0EXTRA\0"
                             "\x03"
                             "n\0d\0more\0",
                             25));
    const Snip snip = decode_snip(payload);
    EXPECT_EQ(snip.manufacturer, "M");
    EXPECT_EQ(snip.software_version, "s");
    EXPECT_EQ(snip.user_name, "n");
    EXPECT_EQ(snip.user_description, "d");
    EXPECT_EQ(complete_snip_size(payload), payload.size());
    // Without the last extra string the payload is not complete yet.
    EXPECT_FALSE(is_complete_snip(std::span(payload).first(payload.size() - 5)));
}

TEST(Snip, MissingTrailingFieldsAreEmpty) {
    const auto payload =
        bytes_of(std::string("\x04"
                             "ACME\0Mod",
                             9));
    const Snip snip = decode_snip(payload);
    EXPECT_EQ(snip.manufacturer, "ACME");
    EXPECT_EQ(snip.model, "Mod");  // unterminated: runs to the end
    EXPECT_EQ(snip.hardware_version, "");
    EXPECT_EQ(snip.user_name, "");
    EXPECT_EQ(snip.user_version, kSnipUserVersion);
    EXPECT_FALSE(is_complete_snip(payload));
    EXPECT_EQ(decode_snip({}), Snip{});
}

TEST(Snip, CompletenessGrowsFrameByFrame) {
    // Legacy nodes send each 6-byte piece as its own message: the requester appends and asks.
    std::vector<std::uint8_t> received;
    for (std::size_t i = 0; i < kExample.size(); i += 6) {
        EXPECT_FALSE(is_complete_snip(received)) << i;
        const auto piece =
            std::span(kExample).subspan(i, std::min<std::size_t>(6, kExample.size() - i));
        received.insert(received.end(), piece.begin(), piece.end());
    }
    EXPECT_TRUE(is_complete_snip(received));
    for (std::size_t n = 0; n < kExample.size(); ++n) {
        EXPECT_FALSE(is_complete_snip(std::span(kExample).first(n))) << n;
    }
}

TEST(Snip, CompleteSizeIgnoresBytesAfterThePayload) {
    std::vector<std::uint8_t> payload(kExample.begin(), kExample.end());
    payload.push_back(0x55);
    EXPECT_EQ(complete_snip_size(payload), 46u);
}

}  // namespace
}  // namespace olcb::memory
