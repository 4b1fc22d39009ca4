#include "openlcb/gridconnect.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace olcb::gridconnect {
namespace {

CanFrame make(std::uint32_t id, std::vector<std::uint8_t> bytes) {
    CanFrame f;
    f.id = id;
    f.len = static_cast<std::uint8_t>(bytes.size());
    for (std::size_t i = 0; i < bytes.size(); ++i) f.data[i] = bytes[i];
    return f;
}

std::vector<CanFrame> feed_all(Parser& p, std::string_view text) {
    std::vector<CanFrame> out;
    p.feed(text, [&](const CanFrame& f) { out.push_back(f); });
    return out;
}

TEST(GridConnectFormat, ExtendedUppercaseEightDigits) {
    EXPECT_EQ(format(make(0x19490343, {})), ":X19490343N;");
    EXPECT_EQ(format(make(0x19170343, {0x05, 0x01, 0x01, 0x01, 0x22, 0x00})),
              ":X19170343N050101012200;");
    EXPECT_EQ(format(make(0x00000ABC, {0xab, 0xcd})), ":X00000ABCNABCD;");
}

TEST(GridConnectFormat, StandardAndRemote) {
    CanFrame f = make(0x12, {0x01});
    f.extended = false;
    EXPECT_EQ(format(f), ":S012N01;");
    f.remote = true;
    EXPECT_EQ(format(f), ":S012R01;");
}

TEST(GridConnectFormat, FormatToAppendsWithoutReallocating) {
    std::string out;
    out.reserve(100);
    const char* data = out.data();
    format_to(make(0x19490343, {}), out);
    format_to(make(0x19490343, {1, 2, 3, 4, 5, 6, 7, 8}), out);
    EXPECT_EQ(out, ":X19490343N;:X19490343N0102030405060708;");
    EXPECT_EQ(out.data(), data);
}

TEST(GridConnectParse, LowercaseAndShortIds) {
    auto f = parse_frame(":x19490343n;");
    ASSERT_TRUE(f);
    EXPECT_EQ(f->id, 0x19490343u);
    EXPECT_TRUE(f->extended);
    EXPECT_FALSE(f->remote);
    EXPECT_EQ(f->len, 0);

    auto g = parse_frame(":X1N0aFf;");
    ASSERT_TRUE(g);
    EXPECT_EQ(g->id, 1u);
    ASSERT_EQ(g->len, 2);
    EXPECT_EQ(g->data[0], 0x0A);
    EXPECT_EQ(g->data[1], 0xFF);
}

TEST(GridConnectParse, StandardAndRemoteFlags) {
    auto s = parse_frame(":S123N01;");
    ASSERT_TRUE(s);
    EXPECT_FALSE(s->extended);
    EXPECT_EQ(s->id, 0x123u);
    auto r = parse_frame(":X19490343R;");
    ASSERT_TRUE(r);
    EXPECT_TRUE(r->remote);
    EXPECT_TRUE(r->extended);
}

TEST(GridConnectParse, SurroundingWhitespaceAccepted) {
    EXPECT_TRUE(parse_frame("  :X19490343N;\r\n"));
}

TEST(GridConnectParse, InvalidTextsRejected) {
    for (const char* bad :
         {"", ":", ";", ":X;", ":XN;", ":X123456789N;", ":X20000000N;", ":S800N;", ":X1N0;",
          ":X1N001122334455667788;", ":X1Q;", ":Y1N;", ":X1NZZ;", "X1N;", ":X1N", ":X1N;x"}) {
        EXPECT_FALSE(parse_frame(bad)) << bad;
    }
}

TEST(GridConnectParse, RoundTrip) {
    const CanFrame f = make(0x1A34312C, {0x20, 0x43, 0, 0, 0, 0, 0x40});
    auto back = parse_frame(format(f));
    ASSERT_TRUE(back);
    EXPECT_EQ(*back, f);
}

TEST(GridConnectParser, SplitChunksAndNewlines) {
    Parser p;
    std::vector<CanFrame> got;
    auto sink = [&](const CanFrame& f) { got.push_back(f); };
    p.feed(":X1949", sink);
    EXPECT_TRUE(got.empty());
    p.feed("0343N;\n:X19170343N0501", sink);
    p.feed("01012200;\r\n", sink);
    ASSERT_EQ(got.size(), 2u);
    EXPECT_EQ(got[0].id, 0x19490343u);
    EXPECT_EQ(got[1], make(0x19170343, {0x05, 0x01, 0x01, 0x01, 0x22, 0x00}));
    EXPECT_EQ(p.frames(), 2u);
    EXPECT_EQ(p.errors(), 0u);
}

TEST(GridConnectParser, GarbagePrefixResynchronised) {
    Parser p;
    auto got = feed_all(p, "garbage;;xx:X1N;");
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].id, 1u);
    // A frame interrupted by ':' is dropped and the next one still parses.
    got = feed_all(p, ":X19490343N01:X2N;");
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].id, 2u);
    EXPECT_EQ(p.errors(), 1u);
}

TEST(GridConnectParser, WhitespaceInsideFrameSkipped) {
    Parser p;
    auto got = feed_all(p, " \t:X19490343N 01 02;\n");
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0], make(0x19490343, {1, 2}));
}

TEST(GridConnectParser, OverlongFrameDropped) {
    Parser p;
    std::string longtext = ":X19490343N" + std::string(1000, '0') + ";";
    auto got = feed_all(p, longtext + ":X3N;");
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].id, 3u);
    EXPECT_EQ(p.errors(), 1u);
    EXPECT_EQ(p.frames(), 1u);
}

TEST(GridConnectParser, InvalidFrameCountedAsError) {
    Parser p;
    auto got = feed_all(p, ":X1NZZ;:S7FFN;");
    ASSERT_EQ(got.size(), 1u);
    EXPECT_FALSE(got[0].extended);
    EXPECT_EQ(p.errors(), 1u);
}

TEST(GridConnectParser, MaxLengthInvalidFrameCountedOnce) {
    Parser p;
    // 64 chars including ':' and ';' is within bounds even if invalid as a frame; it counts as an
    // error for syntax, not silently vanishing.
    std::string t = ":X1N" + std::string(Parser::kMaxFrameText - 5, '0') + ";";
    ASSERT_EQ(t.size(), Parser::kMaxFrameText);
    feed_all(p, t);
    EXPECT_EQ(p.errors(), 1u);
    EXPECT_EQ(p.frames(), 0u);
}

TEST(GridConnectParser, WholeAndByteByByteFeedsAgree) {
    const std::string stream = "junk:X19490343N;\n:x1n0a;: X2N01;\r\n:X3N01:X4N02;;;:S7FFR;" +
                               std::string(80, 'F') + ":X5N;";
    Parser whole;
    const auto a = feed_all(whole, stream);
    Parser bytewise;
    std::vector<CanFrame> b;
    for (char c : stream) {
        bytewise.feed(std::string_view(&c, 1), [&](const CanFrame& f) { b.push_back(f); });
    }
    ASSERT_EQ(a.size(), 6u);
    EXPECT_EQ(a, b);
    EXPECT_EQ(whole.frames(), bytewise.frames());
    EXPECT_EQ(whole.errors(), bytewise.errors());
    EXPECT_EQ(whole.errors(), 1u);  // ":X3N01" cut short by ':'
}

}  // namespace
}  // namespace olcb::gridconnect
