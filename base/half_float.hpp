// IEEE 754 binary16 (half precision) <-> double, by hand: the CDI's <float size="2"> (CDI standard
// 5.1.4.5) and Train Control's speeds (TrainControlS §4.3), so it lives below both libraries.
#pragma once

#include <cstdint>

namespace olcb::base {

/// The exact double of a binary16 bit pattern; NaN payload and sign are kept (payload in the top
/// mantissa bits), so half_from_double(half_to_double(h)) == h for all 65536 patterns.
double half_to_double(std::uint16_t half);

/// The binary16 bit pattern of `value`, rounded to nearest, ties to even; too large -> infinity,
/// too small -> signed zero or subnormal. A NaN keeps its sign and top 10 payload bits; a NaN whose
/// top payload bits are all zero becomes the quiet NaN of that sign (0x7E00 / 0xFE00).
std::uint16_t half_from_double(double value);

/// Largest finite binary16 value, 65504.
inline constexpr double kHalfMax = 65504.0;

}  // namespace olcb::base
