#include "base/node_id.hpp"

#include <gtest/gtest.h>

#include <unordered_set>
#include <vector>

namespace olcb::base {
namespace {

TEST(NodeId, BytesAreBigEndian) {
    const NodeId id(0x050101012200);
    const auto bytes = id.to_bytes();
    EXPECT_EQ(std::vector<std::uint8_t>(bytes.begin(), bytes.end()),
              (std::vector<std::uint8_t>{0x05, 0x01, 0x01, 0x01, 0x22, 0x00}));
    EXPECT_EQ(NodeId::from_bytes(bytes), id);
}

TEST(NodeId, FromBytesNeedsSixBytes) {
    const std::uint8_t five[] = {1, 2, 3, 4, 5};
    EXPECT_FALSE(NodeId::from_bytes(five));
    const std::uint8_t seven[] = {1, 2, 3, 4, 5, 6, 7};
    EXPECT_EQ(NodeId::from_bytes(seven), NodeId(0x010203040506));
}

TEST(NodeId, ConstructorKeeps48Bits) {
    EXPECT_EQ(NodeId(0xFFFF'0102'0304'0506).value(), 0x0102'0304'0506u);
}

TEST(NodeId, DottedTextRoundTrip) {
    EXPECT_EQ(NodeId(0x050101012200).to_string(), "05.01.01.01.22.00");
    EXPECT_EQ(NodeId(0x02010D000001).to_string(), "02.01.0D.00.00.01");
    EXPECT_EQ(NodeId::parse("05.01.01.01.22.00"), NodeId(0x050101012200));
    EXPECT_EQ(NodeId::parse("02.01.0d.00.00.01"), NodeId(0x02010D000001));
    EXPECT_EQ(NodeId::parse("02010d000001"), NodeId(0x02010D000001));
}

TEST(NodeId, ParseErrorsSayWhy) {
    std::string err;
    EXPECT_FALSE(NodeId::parse("05.01.01.01.22", &err));
    EXPECT_NE(err.find("has 5 groups; expected 6"), std::string::npos) << err;
    EXPECT_FALSE(NodeId::parse("05.01.01.01.22.00.01", &err));
    EXPECT_NE(err.find("has 7 groups; expected 6"), std::string::npos) << err;
    EXPECT_FALSE(NodeId::parse("05.01.0G.01.22.00", &err));
    EXPECT_NE(err.find("'G' is not a hex digit"), std::string::npos) << err;
    EXPECT_FALSE(NodeId::parse("05..01.01.22.00", &err));
    EXPECT_NE(err.find("byte 2"), std::string::npos) << err;
    EXPECT_FALSE(NodeId::parse("123.01.01.01.22.00", &err));
    EXPECT_NE(err.find("byte 1"), std::string::npos) << err;
    EXPECT_FALSE(NodeId::parse("", &err));
    EXPECT_NE(err.find("empty"), std::string::npos) << err;
    EXPECT_FALSE(NodeId::parse("0501010122", &err));
    EXPECT_NE(err.find("12 hex digits"), std::string::npos) << err;
    EXPECT_FALSE(NodeId::parse("05.01.01.01.22.00."));  // trailing dot: empty 7th byte
}

// Every dotted byte has both its digits: a truncated ID is an error naming the byte, never a
// different node (lcc-conform and simnode once disagreed on this one).
TEST(NodeId, DottedByteNeedsTwoDigits) {
    std::string err;
    EXPECT_FALSE(NodeId::parse("05.01.01.01.22.0", &err));
    EXPECT_EQ(err, "byte 6 of node ID '05.01.01.01.22.0' has 1 hex digit; expected exactly 2");
    EXPECT_FALSE(NodeId::parse("2.1.d.0.0.1", &err));
    EXPECT_NE(err.find("byte 1 of node ID"), std::string::npos) << err;
    EXPECT_FALSE(NodeId::parse("05.01.01.01.22.000", &err));
    EXPECT_NE(err.find("byte 6 of node ID '05.01.01.01.22.000' has 3 hex digits"),
              std::string::npos)
        << err;
}

TEST(NodeId, ErrorsQuoteTheTextSafely) {
    std::string err;
    EXPECT_FALSE(NodeId::parse("05.01.01.01.2\x1B.00", &err));
    EXPECT_NE(err.find("'\\x1B' is not a hex digit"), std::string::npos) << err;
    EXPECT_EQ(err.find('\x1B'), std::string::npos) << err;  // a terminal never gets the escape
    EXPECT_FALSE(NodeId::parse("05.01.01.01.22.0\t", &err));
    EXPECT_NE(err.find("'\\x09' is not a hex digit"), std::string::npos) << err;
    EXPECT_FALSE(NodeId::parse(std::string(65, '0'), &err));
    EXPECT_EQ(err, "node ID text too long (65 characters; expected 17 like 05.01.01.01.22.00)");
    EXPECT_FALSE(NodeId::parse("0x050101012200", &err));
    EXPECT_NE(err.find("'x' is not a hex digit"), std::string::npos) << err;
}

TEST(IdText, OneCodecForEverySize) {
    EXPECT_EQ(format_id(0x050101012200, 6), "05.01.01.01.22.00");
    EXPECT_EQ(format_id(0xFFFF'0501'0101'2200, 6), "05.01.01.01.22.00");
    EXPECT_EQ(format_id(0x0A0B, 2), "0A.0B");
    EXPECT_EQ(parse_id("0a.0B", 2, "alias pair"), 0x0A0Bu);
    EXPECT_EQ(parse_id("0A0b", 2, "alias pair"), 0x0A0Bu);
    std::string err;
    EXPECT_FALSE(parse_id("0A.B", 2, "alias pair", &err));
    EXPECT_EQ(err, "byte 2 of alias pair '0A.B' has 1 hex digit; expected exactly 2");
    EXPECT_FALSE(parse_id("0A.0B.0C", 2, "alias pair", &err));
    EXPECT_EQ(err, "alias pair '0A.0B.0C' has 3 groups; expected 2 like 05.01");
}

TEST(NodeId, HashableAndOrdered) {
    std::unordered_set<NodeId> set{NodeId(1), NodeId(2), NodeId(1)};
    EXPECT_EQ(set.size(), 2u);
    EXPECT_LT(NodeId(1), NodeId(2));
}

TEST(EventId, BytesTextAndComposition) {
    const EventId e(NodeId(0x050101012200), 0x0001);
    EXPECT_EQ(e.value(), 0x0501010122000001u);
    EXPECT_EQ(e.to_string(), "05.01.01.01.22.00.00.01");
    const auto bytes = e.to_bytes();
    EXPECT_EQ(bytes[0], 0x05);
    EXPECT_EQ(bytes[7], 0x01);
    EXPECT_EQ(EventId::from_bytes(bytes), e);
    EXPECT_EQ(EventId::parse("05.01.01.01.22.00.00.01"), e);
    EXPECT_EQ(EventId::parse("0501010122000001"), e);
    std::string err;
    EXPECT_FALSE(EventId::parse("05.01.01.01.22.00", &err));
    EXPECT_NE(err.find("event ID '05.01.01.01.22.00' has 6 groups; expected 8"), std::string::npos)
        << err;
    EXPECT_FALSE(EventId::parse("05.01.01.01.22.00.00.1", &err));
    EXPECT_NE(err.find("byte 8 of event ID"), std::string::npos) << err;
    EXPECT_FALSE(EventId::from_bytes(std::vector<std::uint8_t>(7, 0)));
    EXPECT_EQ(kDuplicateNodeIdEvent.to_string(), "01.01.00.00.00.00.02.01");
}

}  // namespace
}  // namespace olcb::base
