// Strict decimal number parsing: the CDI standard (section 5) requires decimal numbers in
// attributes and element text, so hex, octal-looking prefixes and exponents are refused for ints.
#pragma once

#include <optional>
#include <string_view>

#include "cdi/document.hpp"

namespace olcb::cdi {

/// Strict decimal integer (optional leading '-' or '+', digits only, surrounding XML whitespace
/// ok).
std::optional<WideInt> parse_decimal_int(std::string_view text);

/// Decimal floating point: [sign] digits [. digits] [e|E [sign] digits], surrounding XML whitespace
/// ok; refuses hex floats, "inf", "nan" and values outside the double range.
std::optional<double> parse_decimal_float(std::string_view text);

/// XML whitespace (the S production): space, tab, CR, LF.
inline bool is_xml_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

/// The text without leading and trailing XML whitespace (space, tab, CR, LF).
std::string_view trim_xml_space(std::string_view text);

}  // namespace olcb::cdi
