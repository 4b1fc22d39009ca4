// <int> and <action> storage (CDI standard 5.1.4.2, 5.1.4.6): 1, 2, 4 or 8 bytes, big-endian,
// unsigned or two's complement, every byte written. Also the decimal text form of integers.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/codec_result.hpp"
#include "cdi/document.hpp"

namespace olcb::cdi {

/// True for the sizes an <int> or <action> may have: 1, 2, 4, 8.
bool is_valid_int_size(std::uint64_t size);

/// Smallest value storable in `size` bytes (0 when unsigned); 0 for an invalid size.
WideInt int_lowest(std::uint64_t size, bool is_signed);

/// Largest value storable in `size` bytes; 0 for an invalid size.
WideInt int_highest(std::uint64_t size, bool is_signed);

/// The `size` big-endian bytes of `value`; an error for an invalid size or a value out of range.
CodecResult<std::vector<std::uint8_t>> encode_int(WideInt value, std::uint64_t size,
                                                  bool is_signed);

/// The integer stored in `bytes` (its length is the size); an error for an invalid size.
CodecResult<WideInt> decode_int(std::span<const std::uint8_t> bytes, bool is_signed);

/// Decimal text of an integer ("-128", "18446744073709551615").
std::string format_int(WideInt value);

/// Parses an optional sign followed by decimal digits (no spaces, no hex); an error for anything
/// else or a value beyond +-(2^127 - 1).
CodecResult<WideInt> parse_int_text(std::string_view text);

}  // namespace olcb::cdi
