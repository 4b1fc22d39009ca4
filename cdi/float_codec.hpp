// <float> storage (CDI standard 5.1.4.5): IEEE 754 binary16/32/64, big-endian, every byte
// written. Also the shortest round-trip decimal text of a stored float.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/codec_result.hpp"

namespace olcb::cdi {

/// True for the sizes a <float> may have: 2, 4, 8.
bool is_valid_float_size(std::uint64_t size);

/// Largest finite value of the format (65504, FLT_MAX, DBL_MAX); 0 for an invalid size.
double float_highest(std::uint64_t size);

/// `value` as it reads back after storing it in `size` bytes (rounded to nearest even; values too
/// large become infinity); `value` unchanged for size 8 or an invalid size.
double round_to_float_size(double value, std::uint64_t size);

/// The `size` big-endian bytes of `value`. Strict: a finite value that rounds to infinity is an
/// error. Lenient: it is stored as infinity. NaN stays NaN with its sign.
CodecResult<std::vector<std::uint8_t>> encode_float(double value, std::uint64_t size,
                                                    CodecMode mode = CodecMode::kStrict);

/// The value stored in `bytes` (its length is the size: 2, 4 or 8), exactly.
CodecResult<double> decode_float(std::span<const std::uint8_t> bytes);

/// The shortest decimal text that reads back to the same `size`-byte float ("0.1" for the half
/// nearest 0.1; halves of 1024 and more, all whole numbers, exactly: "65504"); "inf", "-inf",
/// "nan", "-nan" for the special values.
std::string format_float(double value, std::uint64_t size);

/// Parses decimal or scientific text ("1.5", "-2e3", "inf", "nan"); a 4-byte float is rounded
/// once, directly from the decimal. An error for other text or a value beyond a double's range.
CodecResult<double> parse_float_text(std::string_view text, std::uint64_t size);

}  // namespace olcb::cdi
