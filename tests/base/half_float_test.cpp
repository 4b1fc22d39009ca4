#include "base/half_float.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace olcb::base {
namespace {

TEST(HalfFloat, EveryBitPatternRoundTripsExactly) {
    int nans = 0;
    for (std::uint32_t h = 0; h <= 0xFFFF; ++h) {
        const auto half = static_cast<std::uint16_t>(h);
        const double d = half_to_double(half);
        const bool is_nan_pattern = (half & 0x7C00) == 0x7C00 && (half & 0x03FF) != 0;
        EXPECT_EQ(std::isnan(d), is_nan_pattern) << std::hex << h;
        EXPECT_EQ(std::signbit(d), (half & 0x8000) != 0) << std::hex << h;
        ASSERT_EQ(half_from_double(d), half) << std::hex << h;
        nans += is_nan_pattern ? 1 : 0;
    }
    EXPECT_EQ(nans, 2 * 1023);
}

TEST(HalfFloat, KnownValues) {
    EXPECT_EQ(half_from_double(1.0), 0x3C00);
    EXPECT_EQ(half_from_double(-2.0), 0xC000);
    EXPECT_EQ(half_from_double(0.5), 0x3800);
    EXPECT_EQ(half_from_double(65504.0), 0x7BFF);
    EXPECT_EQ(half_from_double(std::ldexp(1.0, -24)), 0x0001);         // smallest subnormal
    EXPECT_EQ(half_from_double(1023 * std::ldexp(1.0, -24)), 0x03FF);  // largest subnormal
    EXPECT_EQ(half_from_double(std::ldexp(1.0, -14)), 0x0400);         // smallest normal
    EXPECT_EQ(half_from_double(0.0), 0x0000);
    EXPECT_EQ(half_from_double(-0.0), 0x8000);
    EXPECT_EQ(half_from_double(std::numeric_limits<double>::infinity()), 0x7C00);
    EXPECT_EQ(half_from_double(-std::numeric_limits<double>::infinity()), 0xFC00);

    EXPECT_EQ(half_to_double(0x3C00), 1.0);
    EXPECT_EQ(half_to_double(0x7BFF), 65504.0);
    EXPECT_EQ(half_to_double(0x0001), std::ldexp(1.0, -24));
    EXPECT_EQ(half_to_double(0x3555), 0.333251953125);
    EXPECT_TRUE(std::signbit(half_to_double(0x8000)));
    EXPECT_EQ(half_to_double(0x8000), 0.0);
    EXPECT_EQ(half_to_double(0x7C00), std::numeric_limits<double>::infinity());
    EXPECT_EQ(half_to_double(0xFC00), -std::numeric_limits<double>::infinity());
    EXPECT_EQ(kHalfMax, half_to_double(0x7BFF));
}

TEST(HalfFloat, RoundsTiesToEven) {
    const double ulp_at_one = std::ldexp(1.0, -10);
    // Halfway between 3C00 (even) and 3C01: down to the even one.
    EXPECT_EQ(half_from_double(1.0 + ulp_at_one / 2), 0x3C00);
    // Halfway between 3C01 and 3C02 (even): up.
    EXPECT_EQ(half_from_double(1.0 + 1.5 * ulp_at_one), 0x3C02);
    // Just above and below a tie go to the nearer value.
    EXPECT_EQ(half_from_double(1.0 + ulp_at_one / 2 + std::ldexp(1.0, -40)), 0x3C01);
    EXPECT_EQ(half_from_double(1.0 + 1.5 * ulp_at_one - std::ldexp(1.0, -40)), 0x3C01);
    // Subnormal ties: half the smallest subnormal goes to zero, 1.5 of it to 2 units.
    EXPECT_EQ(half_from_double(std::ldexp(1.0, -25)), 0x0000);
    EXPECT_EQ(half_from_double(-std::ldexp(1.0, -25)), 0x8000);
    EXPECT_EQ(half_from_double(std::ldexp(1.0, -25) * (1 + 1e-9)), 0x0001);
    EXPECT_EQ(half_from_double(3 * std::ldexp(1.0, -25)), 0x0002);
    EXPECT_EQ(half_from_double(std::ldexp(1.0, -26)), 0x0000);
    EXPECT_EQ(half_from_double(std::numeric_limits<double>::denorm_min()), 0x0000);
    // The largest subnormal plus half a unit carries into the smallest normal.
    EXPECT_EQ(half_from_double(1023.5 * std::ldexp(1.0, -24)), 0x0400);
    // Carry out of the mantissa bumps the exponent.
    EXPECT_EQ(half_from_double(2.0 - std::ldexp(1.0, -12)), 0x4000);
}

TEST(HalfFloat, OverflowBecomesInfinity) {
    EXPECT_EQ(half_from_double(65519.99), 0x7BFF);
    EXPECT_EQ(half_from_double(65520.0), 0x7C00);  // tie with odd 7BFF goes up to infinity
    EXPECT_EQ(half_from_double(1e6), 0x7C00);
    EXPECT_EQ(half_from_double(-1e300), 0xFC00);
}

TEST(HalfFloat, NanStaysNanWithSign) {
    const double qnan = std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(half_from_double(qnan), 0x7E00);
    EXPECT_EQ(half_from_double(-qnan), 0xFE00);
    // A payload only in bits the half cannot hold still gives a NaN, not infinity.
    const double low_payload = std::bit_cast<double>(std::uint64_t{0x7FF0000000000001});
    ASSERT_TRUE(std::isnan(low_payload));
    EXPECT_EQ(half_from_double(low_payload), 0x7E00);
    // A signalling half NaN keeps its pattern through double.
    EXPECT_EQ(half_from_double(half_to_double(0x7C01)), 0x7C01);
    EXPECT_EQ(half_from_double(half_to_double(0xFD55)), 0xFD55);
}

// Independent oracle: the nearest of the sorted finite halves, ties to the even pattern.
std::uint16_t nearest_half_by_search(double x, const std::vector<double>& magnitudes) {
    const std::uint16_t sign = std::signbit(x) ? 0x8000 : 0;
    const double m = std::fabs(x);
    if (m >= 65520.0) return sign | 0x7C00;  // at or past the tie with the next power, 65536
    if (m >= magnitudes.back()) return sign | 0x7BFF;
    const auto upper = std::lower_bound(magnitudes.begin(), magnitudes.end(), m);
    const auto hi = static_cast<std::uint16_t>(upper - magnitudes.begin());
    if (*upper == m || hi == 0) return sign | hi;
    const auto lo = static_cast<std::uint16_t>(hi - 1);
    const double below = m - magnitudes[lo];
    const double above = magnitudes[hi] - m;
    if (below < above) return sign | lo;
    if (above < below) return sign | hi;
    return sign | ((lo & 1) == 0 ? lo : hi);
}

TEST(HalfFloat, MatchesNearestSearchOnRandomDoubles) {
    std::vector<double> magnitudes;
    for (std::uint16_t h = 0; h <= 0x7BFF; ++h) magnitudes.push_back(half_to_double(h));
    std::mt19937_64 rng(12345);
    std::uniform_real_distribution<double> exponent(-27, 16.5);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (int i = 0; i < 200000; ++i) {
        const double x = unit(rng) * std::exp2(exponent(rng));
        ASSERT_EQ(half_from_double(x), nearest_half_by_search(x, magnitudes)) << x;
    }
    // Exact midpoints between neighbours exercise every tie.
    for (std::size_t k = 0; k + 1 < magnitudes.size(); ++k) {
        const double mid = (magnitudes[k] + magnitudes[k + 1]) / 2;
        ASSERT_EQ(half_from_double(mid), nearest_half_by_search(mid, magnitudes)) << mid;
    }
}

#if defined(__FLT16_MAX__) && defined(__GNUC__) && !defined(__clang__)
TEST(HalfFloat, MatchesCompilerConversion) {
    std::mt19937_64 rng(777);
    std::uniform_real_distribution<double> exponent(-27, 16.5);
    std::uniform_real_distribution<double> unit(-1, 1);
    for (int i = 0; i < 100000; ++i) {
        // Random bit patterns reach every exponent; the scaled ones stay near the half range.
        const double x =
            i % 2 == 0 ? std::bit_cast<double>(rng()) : unit(rng) * std::exp2(exponent(rng));
        if (std::isnan(x)) continue;
        const auto expected = std::bit_cast<std::uint16_t>(static_cast<_Float16>(x));
        ASSERT_EQ(half_from_double(x), expected) << x;
    }
}
#endif

}  // namespace
}  // namespace olcb::base
