#include "conformance/backup/value_rules.hpp"

#include <charconv>
#include <system_error>
#include <utility>

#include "base/utf8.hpp"
#include "cdi/decimal.hpp"
#include "cdi/value_codec.hpp"
#include "conformance/backup/backup_values.hpp"

namespace olcb::conform {

namespace {

// The section of the CDI standard that gives a variable kind its rules.
std::string section_of(const cdi::Element& e) {
    switch (e.kind) {
        case cdi::ElementKind::kString:
            return "CDI §5.1.4.3";
        case cdi::ElementKind::kEventId:
            return "CDI §5.1.4.4";
        case cdi::ElementKind::kFloat:
            return "CDI §5.1.4.5";
        default:
            return "CDI §5.1.4.2";
    }
}

// The clause a rule judges, in our words ("shall" where the standard says it).
std::string clause_of(const cdi::Element& e, ValueRule rule) {
    switch (rule) {
        case ValueRule::kOutOfRange:
        case ValueRule::kNotInMap:
            return section_of(e) + ": invalid values shall not be written";
        case ValueRule::kTooLong:
            return section_of(e) + ": a string shall be written with a trailing NUL";
        case ValueRule::kNotUtf8:
            return section_of(e) + ": a string holds UTF-8";
        case ValueRule::kMalformed:
            break;
    }
    return section_of(e) + ": no value of this type";
}

// True when text is a decimal number, however large (1e999 is one; "abc" is not).
bool is_decimal_number(std::string_view text) {
    double d = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), d);
    return !text.empty() && end == text.data() + text.size() &&
           (ec == std::errc() || ec == std::errc::result_out_of_range);
}

// The rule a text breaks that has no bytes for the element at all.
ValueRule unwritable_rule(const cdi::Element& e, std::string_view text) {
    const std::string_view number = cdi::trim_xml_space(text);
    switch (e.kind) {
        case cdi::ElementKind::kInt:
            return e.size >= 1 && e.size <= 8 && cdi::parse_decimal_int(number)
                       ? ValueRule::kOutOfRange
                       : ValueRule::kMalformed;
        case cdi::ElementKind::kFloat:
            return is_decimal_number(number) ? ValueRule::kOutOfRange : ValueRule::kMalformed;
        case cdi::ElementKind::kString:
            return text.size() >= e.size ? ValueRule::kTooLong : ValueRule::kMalformed;
        default:
            return ValueRule::kMalformed;
    }
}

// Which rule a value check_value refused breaks: the map's when the value is within every other
// limit, else the kind's own (simnode's audit names them the same way).
ValueRule refused_rule(const cdi::Element& e, const cdi::Value& value) {
    if (e.map) {
        cdi::Element without_map = e;
        without_map.map.reset();
        if (cdi::check_value(without_map, value)) return ValueRule::kNotInMap;
    }
    if (e.kind != cdi::ElementKind::kString) return ValueRule::kOutOfRange;
    const std::string& text = *value.as_string();
    if (text.find('\0') != std::string::npos) return ValueRule::kMalformed;
    if (!base::is_valid_utf8(text)) return ValueRule::kNotUtf8;
    return ValueRule::kTooLong;
}

// True when the bytes from `bad` to the end are the start of one UTF-8 character cut short (a
// lead byte and fewer continuation bytes than it announces): what cutting a string by bytes, as
// OpenLCB_Java's StringEntry does, leaves.
bool ends_inside_a_character(std::string_view text, std::size_t bad) {
    const auto lead = static_cast<unsigned char>(text[bad]);
    const std::size_t length = lead >= 0xF0 && lead <= 0xF4   ? 4
                               : lead >= 0xE0 && lead <= 0xEF ? 3
                               : lead >= 0xC2 && lead <= 0xDF ? 2
                                                              : 0;
    if (length == 0 || text.size() - bad >= length) return false;
    for (std::size_t i = bad + 1; i < text.size(); ++i) {
        if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) return false;
    }
    return true;
}

std::string not_utf8_why(const cdi::Element& e, const std::string& text) {
    const std::size_t bad = base::find_invalid_utf8(text).value_or(0);
    const std::string name = e.name.empty() ? "the string" : "'" + e.name + "'";
    return name + ": " +
           (ends_inside_a_character(text, bad)
                ? "the text ends inside a UTF-8 character (byte " + std::to_string(bad) + ")"
                : "the text is not valid UTF-8 (byte " + std::to_string(bad) + ")");
}

}  // namespace

std::string_view rule_name(ValueRule rule) {
    switch (rule) {
        case ValueRule::kOutOfRange:
            return "out-of-range";
        case ValueRule::kNotInMap:
            return "not-in-map";
        case ValueRule::kTooLong:
            return "too-long";
        case ValueRule::kNotUtf8:
            return "not-utf-8";
        case ValueRule::kMalformed:
            return "malformed";
    }
    return "malformed";
}

ValueVerdict judge_backup_value(const cdi::Element& e, std::string_view text) {
    ValueVerdict v;
    std::string error;
    v.bytes = parse_backup_value(e, text, error);
    if (!v.bytes) {
        v.broken = unwritable_rule(e, text);
        v.why = std::move(error);
        v.clause = clause_of(e, *v.broken);
        return v;
    }
    // Judged on what the bytes hold, as the node will: "65531" in a signed 2-byte int is -5.
    cdi::CodecResult<cdi::Value> value = e.kind == cdi::ElementKind::kString
                                             ? cdi::Value::text(std::string(text))
                                             : cdi::decode(e, *v.bytes, cdi::CodecMode::kStrict);
    if (!value) {
        v.broken = ValueRule::kMalformed;
        v.why = value.error().message;
        v.clause = clause_of(e, *v.broken);
        return v;
    }
    const cdi::CodecStatus status = cdi::check_value(e, *value);
    if (status) return v;
    v.broken = refused_rule(e, *value);
    v.why = *v.broken == ValueRule::kNotUtf8 ? not_utf8_why(e, *value->as_string())
                                             : status.error().message;
    v.clause = clause_of(e, *v.broken);
    return v;
}

}  // namespace olcb::conform
