// The CDI's rules a restored value must keep (CDI standard 5.1.4.2-5.1.4.5): values outside
// <min>/<max>, not in a <map>, strings without room for their NUL or not UTF-8 "shall not be
// written". A restore judges each value of a backup file before writing it, as JMRI disables
// writing such values; `restore --force` writes those that have bytes anyway.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/document.hpp"

namespace olcb::conform {

/// The rule a value of a backup file breaks.
enum class ValueRule : std::uint8_t {
    kOutOfRange,  ///< an int or float below its <min> or above its <max> (or its size's range)
    kNotInMap,    ///< a variable with a <map> given a value none of its properties has
    kTooLong,     ///< a string with no room left for its NUL in its size
    kNotUtf8,     ///< a string that is not UTF-8 (a character cut short, a stray byte)
    kMalformed,   ///< no value of the variable's type at all ("abc" for an int, a bad event ID)
};

/// "out-of-range", "not-in-map", "too-long", "not-utf-8" or "malformed".
std::string_view rule_name(ValueRule rule);

/// What the CDI says of one value text for one variable.
struct ValueVerdict {
    /// The bytes a write stores; nullopt when the text is no value of the variable's type and
    /// size at all (then not even --force can write it).
    std::optional<std::vector<std::uint8_t>> bytes;
    std::optional<ValueRule> broken;  ///< the rule broken; nullopt when the value may be written
    std::string why;                  ///< e.g. "value 2000 above max 1000 of 'Trim'" (CDI text)
    std::string clause;  ///< "CDI §5.1.4.2: invalid values shall not be written" (empty if allowed)

    /// True when the value may be written.
    bool allowed() const { return !broken; }
    /// True when the value breaks a rule but has bytes --force could write.
    bool forcible() const { return broken && bytes; }
};

/// Judges a value text of a backup line (strings unescaped) for the element: the bytes it
/// stores (an int in either form, signed or unsigned, as long as it fits the size), then the
/// value those bytes hold under cdi::check_value: <min>/<max>, the <map>, a string's length and
/// UTF-8. A value's rule is the map's when only the map refuses it, as simnode's audit judges.
ValueVerdict judge_backup_value(const cdi::Element& element, std::string_view text);

}  // namespace olcb::conform
