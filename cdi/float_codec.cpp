#include "cdi/float_codec.hpp"

#include <bit>
#include <charconv>
#include <cmath>
#include <limits>

#include "base/half_float.hpp"

namespace olcb::cdi {

namespace {

constexpr double kFloatMax = std::numeric_limits<float>::max();
// FLT_MAX plus half its ulp (2^104): from here on round-to-nearest-even gives infinity.
constexpr double kFloatRoundsToInfinity = kFloatMax + 0x1p103;
constexpr std::uint32_t kFloatExponentMask = 0x7F800000;
constexpr std::uint32_t kFloatQuietBit = 0x00400000;
constexpr int kFloatDropBits = 52 - 23;

// Converting an out-of-range double to float is undefined behaviour in C++, and a hardware
// conversion may quiet a signalling NaN, so both cases are done on the bits.
std::uint32_t float_bits_from_double(double value) {
    const auto bits = std::bit_cast<std::uint64_t>(value);
    const auto sign = static_cast<std::uint32_t>(bits >> 32) & 0x80000000u;
    if (std::isnan(value)) {
        auto payload =
            static_cast<std::uint32_t>((bits & ((std::uint64_t{1} << 52) - 1)) >> kFloatDropBits);
        if (payload == 0) payload = kFloatQuietBit;
        return sign | kFloatExponentMask | payload;
    }
    const double magnitude = std::fabs(value);
    if (magnitude >= kFloatRoundsToInfinity) return sign | kFloatExponentMask;
    if (magnitude > kFloatMax) {
        return sign | std::bit_cast<std::uint32_t>(std::numeric_limits<float>::max());
    }
    return std::bit_cast<std::uint32_t>(static_cast<float>(value));
}

double double_from_float_bits(std::uint32_t bits) {
    if ((bits & kFloatExponentMask) == kFloatExponentMask && (bits & 0x007FFFFF) != 0) {
        const std::uint64_t sign = static_cast<std::uint64_t>(bits & 0x80000000u) << 32;
        const std::uint64_t payload = static_cast<std::uint64_t>(bits & 0x007FFFFF)
                                      << kFloatDropBits;
        return std::bit_cast<double>(sign | (std::uint64_t{0x7FF} << 52) | payload);
    }
    return static_cast<double>(std::bit_cast<float>(bits));
}

std::string size_error(std::uint64_t size) {
    return "invalid float size " + std::to_string(size) + " (valid sizes: 2, 4, 8)";
}

std::string shortest_double(double value) {
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, value);
    return std::string(buf, res.ptr);
}

std::string shortest_half(double value) {
    const std::uint16_t target = base::half_from_double(value);
    // Halves from 1024 up are whole numbers of at most 5 digits: print them exactly rather than
    // as a shorter neighbour ("65504", not "65500").
    const double stored = base::half_to_double(target);
    if (std::isfinite(stored) && std::fabs(stored) >= 1024) return shortest_double(stored);
    char buf[64];
    for (int precision = 1; precision <= 17; ++precision) {
        const auto res =
            std::to_chars(buf, buf + sizeof buf, value, std::chars_format::general, precision);
        double parsed = 0;
        std::from_chars(buf, res.ptr, parsed);
        // Re-printing the parsed double drops the exponent padding of the general format.
        if (base::half_from_double(parsed) == target) return shortest_double(parsed);
    }
    return shortest_double(value);
}

}  // namespace

bool is_valid_float_size(std::uint64_t size) {
    return size == 2 || size == 4 || size == 8;
}

double float_highest(std::uint64_t size) {
    switch (size) {
        case 2:
            return base::kHalfMax;
        case 4:
            return kFloatMax;
        case 8:
            return std::numeric_limits<double>::max();
        default:
            return 0;
    }
}

double round_to_float_size(double value, std::uint64_t size) {
    if (size == 2) return base::half_to_double(base::half_from_double(value));
    if (size == 4) return double_from_float_bits(float_bits_from_double(value));
    return value;
}

CodecResult<std::vector<std::uint8_t>> encode_float(double value, std::uint64_t size,
                                                    CodecMode mode) {
    if (!is_valid_float_size(size)) return CodecError{size_error(size)};
    std::uint64_t bits = 0;
    if (size == 2) {
        bits = base::half_from_double(value);
    } else if (size == 4) {
        bits = float_bits_from_double(value);
    } else {
        bits = std::bit_cast<std::uint64_t>(value);
    }
    if (mode == CodecMode::kStrict && std::isfinite(value) &&
        !std::isfinite(round_to_float_size(value, size))) {
        return CodecError{"value " + shortest_double(value) + " overflows a " +
                          std::to_string(size) + "-byte float (largest " +
                          format_float(float_highest(size), size) + ")"};
    }
    std::vector<std::uint8_t> out(size);
    for (std::size_t i = size; i-- > 0;) {
        out[i] = static_cast<std::uint8_t>(bits & 0xFF);
        bits >>= 8;
    }
    return out;
}

CodecResult<double> decode_float(std::span<const std::uint8_t> bytes) {
    if (!is_valid_float_size(bytes.size())) return CodecError{size_error(bytes.size())};
    std::uint64_t bits = 0;
    for (std::uint8_t b : bytes) bits = (bits << 8) | b;
    if (bytes.size() == 2) return base::half_to_double(static_cast<std::uint16_t>(bits));
    if (bytes.size() == 4) return double_from_float_bits(static_cast<std::uint32_t>(bits));
    return std::bit_cast<double>(bits);
}

std::string format_float(double value, std::uint64_t size) {
    if (!std::isfinite(value)) return shortest_double(value);
    if (size == 2) return shortest_half(value);
    if (size == 4) {
        char buf[64];
        const float stored = std::bit_cast<float>(float_bits_from_double(value));
        const auto res = std::to_chars(buf, buf + sizeof buf, stored);
        return std::string(buf, res.ptr);
    }
    return shortest_double(value);
}

CodecResult<double> parse_float_text(std::string_view text, std::uint64_t size) {
    std::string_view body = text;
    // from_chars takes '-' but not '+'.
    if (body.size() > 1 && body.front() == '+' && body[1] != '-' && body[1] != '+') {
        body.remove_prefix(1);
    }
    const char* first = body.data();
    const char* last = body.data() + body.size();
    if (size == 4) {
        float f = 0;
        const auto res = std::from_chars(first, last, f);
        if (res.ec == std::errc() && res.ptr == last) return static_cast<double>(f);
        // Out of float range falls through: the double is kept so encode can report overflow.
    }
    double d = 0;
    const auto res = std::from_chars(first, last, d);
    if (res.ec == std::errc::result_out_of_range && res.ptr == last) {
        return CodecError{"'" + std::string(text.substr(0, 40)) + "' is out of the float range"};
    }
    if (res.ec != std::errc() || res.ptr != last || body.empty()) {
        return CodecError{"'" + std::string(text.substr(0, 40)) + "' is not a decimal number"};
    }
    return d;
}

}  // namespace olcb::cdi
