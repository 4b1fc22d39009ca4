#include "cdi/float_codec.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "base/half_float.hpp"

namespace olcb::cdi {
namespace {

using Bytes = std::vector<std::uint8_t>;

constexpr double kInf = std::numeric_limits<double>::infinity();

Bytes encoded(double value, std::uint64_t size, CodecMode mode = CodecMode::kStrict) {
    auto r = encode_float(value, size, mode);
    EXPECT_TRUE(r.ok()) << r.error().message;
    return r.ok() ? r.value() : Bytes{};
}

double decoded(const Bytes& bytes) {
    auto r = decode_float(bytes);
    EXPECT_TRUE(r.ok()) << r.error().message;
    return r.ok() ? r.value() : -12345.0;
}

TEST(FloatCodec, BigEndianIeeeBytes) {
    EXPECT_EQ(encoded(1.0, 2), (Bytes{0x3C, 0x00}));
    EXPECT_EQ(encoded(-2.0, 2), (Bytes{0xC0, 0x00}));
    EXPECT_EQ(encoded(1.0, 4), (Bytes{0x3F, 0x80, 0x00, 0x00}));
    EXPECT_EQ(encoded(-2.5, 4), (Bytes{0xC0, 0x20, 0x00, 0x00}));
    EXPECT_EQ(encoded(1.0, 8), (Bytes{0x3F, 0xF0, 0, 0, 0, 0, 0, 0}));
    EXPECT_EQ(encoded(0.1, 8), (Bytes{0x3F, 0xB9, 0x99, 0x99, 0x99, 0x99, 0x99, 0x9A}));
    EXPECT_EQ(encoded(-0.0, 4), (Bytes{0x80, 0, 0, 0}));
    EXPECT_EQ(encoded(kInf, 4), (Bytes{0x7F, 0x80, 0, 0}));

    EXPECT_EQ(decoded({0x3C, 0x00}), 1.0);
    EXPECT_EQ(decoded({0x7B, 0xFF}), 65504.0);
    EXPECT_EQ(decoded({0xC0, 0x20, 0x00, 0x00}), -2.5);
    EXPECT_EQ(decoded({0x3F, 0xB9, 0x99, 0x99, 0x99, 0x99, 0x99, 0x9A}), 0.1);
    EXPECT_EQ(decoded({0x3D, 0xCC, 0xCC, 0xCD}), static_cast<double>(0.1f));
}

TEST(FloatCodec, InvalidSizesAreErrors) {
    for (std::uint64_t size : {0u, 1u, 3u, 16u}) {
        EXPECT_FALSE(is_valid_float_size(size));
        const auto r = encode_float(1.0, size);
        ASSERT_FALSE(r.ok());
        EXPECT_NE(r.error().message.find("invalid float size"), std::string::npos);
        EXPECT_FALSE(decode_float(Bytes(size, 0)).ok());
    }
}

TEST(FloatCodec, StrictOverflowIsAnErrorNotInfinity) {
    auto half = encode_float(70000.0, 2);
    ASSERT_FALSE(half.ok());
    EXPECT_NE(half.error().message.find("overflows a 2-byte float (largest 65504)"),
              std::string::npos)
        << half.error().message;
    EXPECT_FALSE(encode_float(-1e39, 4).ok());
    EXPECT_EQ(encoded(65519.0, 2), (Bytes{0x7B, 0xFF}));  // rounds down to the largest
    // Just above FLT_MAX but nearer to it than to infinity.
    const double flt_max = std::numeric_limits<float>::max();
    EXPECT_EQ(encoded(flt_max + 0x1p102, 4), (Bytes{0x7F, 0x7F, 0xFF, 0xFF}));
    EXPECT_FALSE(encode_float(flt_max + 0x1p103, 4).ok());
    EXPECT_EQ(encoded(std::numeric_limits<double>::max(), 8),
              (Bytes{0x7F, 0xEF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF, 0xFF}));
}

TEST(FloatCodec, LenientOverflowSaturatesToInfinity) {
    EXPECT_EQ(encoded(70000.0, 2, CodecMode::kLenient), (Bytes{0x7C, 0x00}));
    EXPECT_EQ(encoded(-1e39, 4, CodecMode::kLenient), (Bytes{0xFF, 0x80, 0, 0}));
}

TEST(FloatCodec, NanKeepsSignAndPayload) {
    const double qnan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(encoded(qnan, 2), (Bytes{0x7E, 0x00}));
    EXPECT_EQ(encoded(-qnan, 4), (Bytes{0xFF, 0xC0, 0, 0}));
    // Signalling single-precision NaNs survive decode and encode bit for bit.
    for (std::uint32_t bits : {0x7F800001u, 0xFFA00000u, 0x7FBFFFFFu}) {
        const Bytes in{static_cast<std::uint8_t>(bits >> 24), static_cast<std::uint8_t>(bits >> 16),
                       static_cast<std::uint8_t>(bits >> 8), static_cast<std::uint8_t>(bits)};
        const double d = decoded(in);
        EXPECT_TRUE(std::isnan(d));
        EXPECT_EQ(encoded(d, 4), in);
    }
}

TEST(FloatCodec, RoundToSize) {
    EXPECT_EQ(round_to_float_size(0.1, 8), 0.1);
    EXPECT_EQ(round_to_float_size(0.1, 4), static_cast<double>(0.1f));
    EXPECT_EQ(round_to_float_size(0.1, 2), 0.0999755859375);
    EXPECT_EQ(round_to_float_size(1e39, 4), kInf);
    EXPECT_EQ(float_highest(2), 65504.0);
    EXPECT_EQ(float_highest(4), std::numeric_limits<float>::max());
    EXPECT_EQ(float_highest(8), std::numeric_limits<double>::max());
}

TEST(FloatCodec, FormatsShortestForTheSize) {
    EXPECT_EQ(format_float(0.1, 8), "0.1");
    EXPECT_EQ(format_float(static_cast<double>(0.1f), 4), "0.1");
    EXPECT_EQ(format_float(1.0 / 3, 4), "0.33333334");
    EXPECT_EQ(format_float(0.0999755859375, 2), "0.1");
    EXPECT_EQ(format_float(65504.0, 2), "65504");
    EXPECT_EQ(format_float(1.0, 2), "1");
    EXPECT_EQ(format_float(1000.5, 2), "1000.5");
    EXPECT_EQ(format_float(2050.0, 2), "2050");
    EXPECT_EQ(format_float(-32768.0, 2), "-32768");
    EXPECT_EQ(format_float(-0.0, 2), "-0");
    EXPECT_EQ(format_float(std::ldexp(1.0, -24), 2), "6e-08");
    EXPECT_EQ(format_float(kInf, 4), "inf");
    EXPECT_EQ(format_float(-kInf, 2), "-inf");
    EXPECT_EQ(format_float(std::numeric_limits<double>::quiet_NaN(), 8), "nan");
}

TEST(FloatCodec, EveryHalfFormatsAndParsesBackToTheSamePattern) {
    for (std::uint32_t h = 0; h <= 0xFFFF; ++h) {
        const double v = base::half_to_double(static_cast<std::uint16_t>(h));
        if (std::isnan(v)) continue;
        const std::string text = format_float(v, 2);
        const auto parsed = parse_float_text(text, 2);
        ASSERT_TRUE(parsed.ok()) << text;
        ASSERT_EQ(base::half_from_double(parsed.value()), h) << std::hex << h << " " << text;
    }
}

TEST(FloatCodec, RandomFloatsAndDoublesFormatAndParseBack) {
    std::mt19937_64 rng(99);
    for (int i = 0; i < 20000; ++i) {
        const double d = std::bit_cast<double>(rng());
        const double f =
            static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(rng())));
        if (!std::isnan(d)) {
            const auto back = parse_float_text(format_float(d, 8), 8);
            ASSERT_TRUE(back.ok());
            ASSERT_EQ(back.value(), d);
        }
        if (!std::isnan(f)) {
            const auto back = parse_float_text(format_float(f, 4), 4);
            ASSERT_TRUE(back.ok());
            ASSERT_EQ(back.value(), f);
        }
    }
}

TEST(FloatCodec, ParsesText) {
    EXPECT_EQ(parse_float_text("1.5", 8).value(), 1.5);
    EXPECT_EQ(parse_float_text("+2", 8).value(), 2.0);
    EXPECT_EQ(parse_float_text("-2e3", 8).value(), -2000.0);
    EXPECT_EQ(parse_float_text("0.1", 4).value(), static_cast<double>(0.1f));
    EXPECT_EQ(parse_float_text("1e39", 4).value(), 1e39);  // kept so encode can report overflow
    EXPECT_EQ(parse_float_text("inf", 4).value(), kInf);
    EXPECT_EQ(parse_float_text("-inf", 2).value(), -kInf);
    EXPECT_TRUE(std::isnan(parse_float_text("nan", 8).value()));
    EXPECT_TRUE(std::signbit(parse_float_text("-nan", 8).value()));
}

TEST(FloatCodec, RejectsBadText) {
    for (const char* bad : {"", "abc", "1.5x", " 1", "1,5", "0x10", "+", "+-1", "--1", "1e"}) {
        const auto r = parse_float_text(bad, 8);
        ASSERT_FALSE(r.ok()) << bad;
        EXPECT_NE(r.error().message.find("not a decimal number"), std::string::npos) << bad;
    }
    const auto huge = parse_float_text("1e400", 8);
    ASSERT_FALSE(huge.ok());
    EXPECT_NE(huge.error().message.find("out of the float range"), std::string::npos);
}

}  // namespace
}  // namespace olcb::cdi
