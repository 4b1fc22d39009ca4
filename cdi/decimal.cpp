#include "cdi/decimal.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <string>

namespace olcb::cdi {
namespace {

bool is_digit(char c) {
    return c >= '0' && c <= '9';
}

// Advances i past a '+' or '-' at text[i], if there is one.
void skip_sign(std::string_view text, std::size_t& i) {
    if (i < text.size() && (text[i] == '-' || text[i] == '+')) ++i;
}

// Advances i past the decimal digits from text[i]; returns how many there were.
std::size_t skip_digits(std::string_view text, std::size_t& i) {
    const std::size_t start = i;
    while (i < text.size() && is_digit(text[i])) ++i;
    return i - start;
}

// 38 significant digits always fit in a signed 128-bit integer (10^38 < 2^127).
constexpr std::size_t kMaxSignificantDigits = 38;

}  // namespace

std::string_view trim_xml_space(std::string_view text) {
    while (!text.empty() && is_xml_space(text.front())) text.remove_prefix(1);
    while (!text.empty() && is_xml_space(text.back())) text.remove_suffix(1);
    return text;
}

std::optional<WideInt> parse_decimal_int(std::string_view text) {
    text = trim_xml_space(text);
    bool negative = false;
    if (!text.empty() && (text.front() == '-' || text.front() == '+')) {
        negative = text.front() == '-';
        text.remove_prefix(1);
    }
    if (text.empty()) return std::nullopt;
    for (char c : text) {
        if (!is_digit(c)) return std::nullopt;
    }
    while (text.size() > 1 && text.front() == '0') text.remove_prefix(1);
    if (text.size() > kMaxSignificantDigits) return std::nullopt;
    // 18 digits fit in 64 bits; 128-bit arithmetic is only needed beyond.
    std::uint64_t low = 0;
    const std::size_t fast = std::min<std::size_t>(text.size(), 18);
    for (std::size_t i = 0; i < fast; ++i)
        low = low * 10 + static_cast<std::uint64_t>(text[i] - '0');
    WideInt value = low;
    for (char c : text.substr(fast)) value = value * 10 + (c - '0');
    return negative ? -value : value;
}

std::optional<double> parse_decimal_float(std::string_view text) {
    text = trim_xml_space(text);
    std::size_t i = 0;
    skip_sign(text, i);
    const std::size_t mantissa_start = i;
    std::size_t digits = skip_digits(text, i);
    if (i < text.size() && text[i] == '.') {
        ++i;
        digits += skip_digits(text, i);
    }
    if (digits == 0) return std::nullopt;
    if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
        ++i;
        skip_sign(text, i);
        if (skip_digits(text, i) == 0) return std::nullopt;
    }
    if (i != text.size()) return std::nullopt;
    // from_chars takes no leading '+'; the sign is re-applied below.
    const bool negative = text.front() == '-';
    std::string_view body = text.substr(mantissa_start);
    double value = 0;
    auto [end, ec] =
        std::from_chars(body.data(), body.data() + body.size(), value, std::chars_format::general);
    if (ec != std::errc() || end != body.data() + body.size()) return std::nullopt;
    return negative ? -value : value;
}

}  // namespace olcb::cdi
