#include "base/half_float.hpp"

#include <bit>

namespace olcb::base {

namespace {

constexpr int kDoubleMantissaBits = 52;
constexpr int kHalfMantissaBits = 10;
constexpr int kDropBits = kDoubleMantissaBits - kHalfMantissaBits;  // 42
constexpr std::uint64_t kDoubleMantissaMask = (std::uint64_t{1} << kDoubleMantissaBits) - 1;
constexpr int kDoubleBias = 1023;
constexpr int kHalfBias = 15;
constexpr std::uint16_t kHalfInfinity = 0x7C00;
constexpr std::uint16_t kHalfQuietBit = 0x0200;

// Shifts `significand` right by `shift` bits, rounding to nearest with ties to even.
std::uint64_t shift_round_even(std::uint64_t significand, int shift) {
    if (shift >= 64) return 0;  // every significand here is below 2^53, far under half of 2^64
    const std::uint64_t kept = significand >> shift;
    const std::uint64_t rest = significand & ((std::uint64_t{1} << shift) - 1);
    const std::uint64_t halfway = std::uint64_t{1} << (shift - 1);
    if (rest > halfway || (rest == halfway && (kept & 1) != 0)) return kept + 1;
    return kept;
}

}  // namespace

double half_to_double(std::uint16_t half) {
    const std::uint64_t sign = static_cast<std::uint64_t>(half >> 15) << 63;
    const int exponent = (half >> kHalfMantissaBits) & 0x1F;
    const std::uint64_t mantissa = half & 0x3FF;
    if (exponent == 0x1F) {
        // Infinity (mantissa 0) or NaN; the payload moves to the top of the double mantissa.
        return std::bit_cast<double>(sign | (std::uint64_t{0x7FF} << kDoubleMantissaBits) |
                                     (mantissa << kDropBits));
    }
    if (exponent == 0) {
        if (mantissa == 0) return std::bit_cast<double>(sign);
        // Subnormal: mantissa * 2^-24. Normalise so the leading 1 becomes the implicit bit.
        int shift = 0;
        std::uint64_t m = mantissa;
        while ((m & 0x400) == 0) {
            m <<= 1;
            ++shift;
        }
        const int double_exponent = 1 - kHalfBias - shift + kDoubleBias;
        return std::bit_cast<double>(
            sign | (static_cast<std::uint64_t>(double_exponent) << kDoubleMantissaBits) |
            ((m & 0x3FF) << kDropBits));
    }
    const int double_exponent = exponent - kHalfBias + kDoubleBias;
    return std::bit_cast<double>(
        sign | (static_cast<std::uint64_t>(double_exponent) << kDoubleMantissaBits) |
        (mantissa << kDropBits));
}

std::uint16_t half_from_double(double value) {
    const auto bits = std::bit_cast<std::uint64_t>(value);
    const auto sign = static_cast<std::uint16_t>((bits >> 48) & 0x8000);
    const int exponent = static_cast<int>((bits >> kDoubleMantissaBits) & 0x7FF);
    const std::uint64_t mantissa = bits & kDoubleMantissaMask;

    if (exponent == 0x7FF) {
        if (mantissa == 0) return sign | kHalfInfinity;
        auto payload = static_cast<std::uint16_t>(mantissa >> kDropBits);
        if (payload == 0) payload = kHalfQuietBit;  // keep it a NaN, not an infinity
        return sign | kHalfInfinity | payload;
    }
    // Double subnormals (and zero) are far below half the smallest half subnormal.
    if (exponent == 0) return sign;

    const int unbiased = exponent - kDoubleBias;
    if (unbiased > kHalfBias) return sign | kHalfInfinity;
    const std::uint64_t significand = mantissa | (std::uint64_t{1} << kDoubleMantissaBits);
    if (unbiased >= 1 - kHalfBias) {
        // Normal range: the carry of rounding may bump the exponent, up to infinity, which is
        // exactly the IEEE result.
        const int half_exponent = unbiased + kHalfBias;
        const std::uint64_t rounded =
            (static_cast<std::uint64_t>(half_exponent) << kHalfMantissaBits) +
            shift_round_even(mantissa, kDropBits);
        return static_cast<std::uint16_t>(sign | rounded);
    }
    // Subnormal range: value = significand * 2^(unbiased - 52), unit 2^-24.
    const int shift = kDoubleMantissaBits - 24 - unbiased;
    return static_cast<std::uint16_t>(sign | shift_round_even(significand, shift));
}

}  // namespace olcb::base
