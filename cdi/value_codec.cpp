#include "cdi/value_codec.hpp"

#include <algorithm>
#include <cmath>

#include "base/utf8.hpp"
#include "cdi/event_id_text.hpp"
#include "cdi/float_codec.hpp"
#include "cdi/int_codec.hpp"
#include "cdi/string_codec.hpp"

namespace olcb::cdi {

namespace {

using Bytes = std::vector<std::uint8_t>;

// A map with hundreds of entries would drown the message; the first few make the point.
constexpr std::size_t kMaxListedProperties = 8;

const char* tag_of(const Element& e) {
    return e.tag.empty() ? kind_name(e.kind) : e.tag.c_str();
}

// How messages name an element: by its <name>, else by its tag and line.
std::string label(const Element& e) {
    if (!e.name.empty()) return "'" + e.name + "'";
    std::string out = std::string("unnamed <") + tag_of(e) + ">";
    if (e.pos.line != 0) out += " at line " + std::to_string(e.pos.line);
    return out;
}

CodecError about(const Element& e, const std::string& detail) {
    return CodecError{label(e) + ": " + detail};
}

std::string_view trim(std::string_view text) {
    constexpr std::string_view kSpace = " \t\r\n";
    const auto first = text.find_first_not_of(kSpace);
    if (first == std::string_view::npos) return {};
    const auto last = text.find_last_not_of(kSpace);
    return text.substr(first, last - first + 1);
}

bool action_is_signed(const Element& e) {
    return e.action_value && *e.action_value < 0;
}

bool int_is_signed(const Element& e) {
    return e.kind == ElementKind::kAction ? action_is_signed(e) : e.is_signed();
}

CodecError wrong_kind(const Element& e, ValueKind expected, const Value& value) {
    return CodecError{std::string("expected ") + value_kind_name(expected) + " value for <" +
                      tag_of(e) + "> " + label(e) + ", got " + value_kind_name(value.kind())};
}

std::string list_properties(const Map& map) {
    std::string out;
    for (std::size_t i = 0; i < map.entries.size() && i < kMaxListedProperties; ++i) {
        if (i != 0) out += ", ";
        out += map.entries[i].property;
    }
    if (map.entries.size() > kMaxListedProperties) out += ", ...";
    return out;
}

CodecError not_in_map(const Element& e, const std::string& shown) {
    return CodecError{"value " + shown + " is not one of the map properties (" +
                      list_properties(*e.map) + ") of " + label(e)};
}

// True when a map property, read by parse (as a value of the element's type is written), is v.
template <typename T, typename Parse>
bool map_has(const Map& map, const T& v, Parse parse) {
    return std::any_of(map.entries.begin(), map.entries.end(), [&](const MapEntry& entry) {
        const auto p = parse(trim(entry.property));
        return p.ok() && *p == v;
    });
}

CodecStatus check_int(const Element& e, WideInt v, std::uint64_t size) {
    const bool is_signed = e.is_signed();
    const WideInt lo = std::max(e.int_min.value_or(0), int_lowest(size, is_signed));
    const WideInt hi =
        std::min(e.int_max.value_or(int_highest(size, is_signed)), int_highest(size, is_signed));
    if (v < lo) {
        return CodecError{"value " + format_int(v) + " below min " + format_int(lo) + " of " +
                          label(e)};
    }
    if (v > hi) {
        return CodecError{"value " + format_int(v) + " above max " + format_int(hi) + " of " +
                          label(e)};
    }
    if (e.map && !map_has(*e.map, v, parse_int_text)) return not_in_map(e, format_int(v));
    return {};
}

CodecStatus check_float(const Element& e, double v, std::uint64_t size) {
    if (std::isnan(v)) return CodecError{"value nan (not a number) is invalid for " + label(e)};
    // Compare what will be stored with what the limits mean in the same precision, so min 0.1
    // accepts 0.1 on a half float although neither is exactly 0.1 there.
    const double stored = round_to_float_size(v, size);
    const double lo = round_to_float_size(e.float_min.value_or(0.0), size);
    const double hi = std::min(round_to_float_size(e.float_max.value_or(float_highest(size)), size),
                               float_highest(size));
    // A value too large for the size would print as "inf"; show it as given instead.
    const std::string shown = format_float(v, std::isfinite(stored) ? size : 8);
    if (stored < lo) {
        return CodecError{"value " + shown + " below min " + format_float(lo, size) + " of " +
                          label(e)};
    }
    if (stored > hi) {
        return CodecError{"value " + shown + " above max " + format_float(hi, size) + " of " +
                          label(e)};
    }
    const auto parse_stored = [size](std::string_view text) -> CodecResult<double> {
        auto p = parse_float_text(text, size);
        if (!p.ok()) return p;
        return round_to_float_size(*p, size);
    };
    if (e.map && !map_has(*e.map, stored, parse_stored)) return not_in_map(e, shown);
    return {};
}

CodecStatus check_string(const Element& e, const std::string& v, std::uint64_t size) {
    if (const auto nul = v.find('\0'); nul != std::string::npos) {
        return CodecError{"text contains a NUL byte at offset " + std::to_string(nul) + " for " +
                          label(e)};
    }
    if (const auto bad = base::find_invalid_utf8(v)) {
        return CodecError{"text is not valid UTF-8 (byte " + std::to_string(*bad) + ") for " +
                          label(e)};
    }
    if (v.size() > size - 1) {
        return CodecError{"text of " + std::to_string(v.size()) + " bytes is longer than max " +
                          std::to_string(size - 1) + " bytes of " + label(e)};
    }
    if (e.map) {
        const bool found = std::any_of(e.map->entries.begin(), e.map->entries.end(),
                                       [&](const MapEntry& entry) { return entry.property == v; });
        if (!found) return not_in_map(e, "'" + v + "'");
    }
    return {};
}

CodecStatus check_event_id(const Element& e, EventIdValue v) {
    if (e.map && !map_has(*e.map, v, parse_event_id)) return not_in_map(e, format_event_id(v));
    return {};
}

CodecStatus check_action(const Element& e, WideInt v, std::uint64_t size) {
    if (!e.action_value) return CodecError{"action " + label(e) + " has no <value>"};
    if (v != *e.action_value) {
        return CodecError{"value " + format_int(v) + " is not the action value " +
                          format_int(*e.action_value) + " of " + label(e)};
    }
    if (const auto bytes = encode_int(v, size, action_is_signed(e)); !bytes.ok()) {
        return about(e, bytes.error().message);
    }
    return {};
}

}  // namespace

std::optional<ValueKind> value_kind_of(const Element& element) {
    switch (element.kind) {
        case ElementKind::kInt:
        case ElementKind::kAction:
        case ElementKind::kBit:
            return ValueKind::kInt;
        case ElementKind::kFloat:
            return ValueKind::kFloat;
        case ElementKind::kString:
            return ValueKind::kString;
        case ElementKind::kEventId:
            return ValueKind::kEventId;
        case ElementKind::kGroup:
        case ElementKind::kBlob:
        case ElementKind::kUnknown:
            break;
    }
    return std::nullopt;
}

CodecResult<std::uint64_t> value_size(const Element& element) {
    const std::uint64_t size = element.size;
    switch (element.kind) {
        case ElementKind::kBit:
            if (size == 0) return std::uint64_t{1};
            [[fallthrough]];
        case ElementKind::kInt:
        case ElementKind::kAction:
            if (!is_valid_int_size(size)) {
                return about(element, "invalid size " + std::to_string(size) + " for <" +
                                          tag_of(element) + "> (valid sizes: 1, 2, 4, 8)");
            }
            return size;
        case ElementKind::kFloat:
            if (!is_valid_float_size(size)) {
                return about(element, "invalid size " + std::to_string(size) +
                                          " for <float> (valid sizes: 2, 4, 8)");
            }
            return size;
        case ElementKind::kString:
            if (size == 0 || size > kMaxStringSize) {
                return about(element, "unsupported <string> size " + std::to_string(size) +
                                          " (1 to " + std::to_string(kMaxStringSize) + ")");
            }
            return size;
        case ElementKind::kEventId:
            if (size != 0 && size != kEventIdSize) {
                return about(element, "an <eventid> has 8 bytes, not " + std::to_string(size));
            }
            return std::uint64_t{kEventIdSize};
        case ElementKind::kGroup:
        case ElementKind::kBlob:
        case ElementKind::kUnknown:
            break;
    }
    return about(element, std::string("a <") + tag_of(element) + "> has no value to encode");
}

CodecResult<Bytes> encode(const Element& element, const Value& value, CodecMode mode) {
    const auto size = value_size(element);
    if (!size.ok()) return size.error();
    const ValueKind expected = *value_kind_of(element);
    if (value.kind() != expected) return wrong_kind(element, expected, value);

    CodecResult<Bytes> bytes = CodecError{};
    switch (expected) {
        case ValueKind::kInt:
            bytes = encode_int(*value.as_int(), *size, int_is_signed(element));
            break;
        case ValueKind::kFloat:
            bytes = encode_float(*value.as_float(), *size, mode);
            break;
        case ValueKind::kString:
            bytes = encode_string(*value.as_string(), *size, mode);
            break;
        case ValueKind::kEventId: {
            const auto array = encode_event_id(*value.as_event_id());
            return Bytes(array.begin(), array.end());
        }
    }
    if (!bytes.ok()) return about(element, bytes.error().message);
    return bytes;
}

CodecResult<Bytes> encode_action(const Element& element) {
    if (element.kind != ElementKind::kAction) {
        return about(element, std::string("a <") + tag_of(element) + "> is not an <action>");
    }
    if (!element.action_value) return CodecError{"action " + label(element) + " has no <value>"};
    return encode(element, Value::integer(*element.action_value));
}

CodecResult<Value> decode(const Element& element, std::span<const std::uint8_t> bytes,
                          CodecMode mode) {
    const auto size = value_size(element);
    if (!size.ok()) return size.error();
    if (bytes.size() != *size) {
        return about(element, "got " + std::to_string(bytes.size()) + " bytes, expected " +
                                  std::to_string(*size));
    }
    switch (*value_kind_of(element)) {
        case ValueKind::kInt: {
            const auto v = decode_int(bytes, int_is_signed(element));
            if (!v.ok()) return about(element, v.error().message);
            return Value::integer(*v);
        }
        case ValueKind::kFloat: {
            const auto v = decode_float(bytes);
            if (!v.ok()) return about(element, v.error().message);
            return Value::real(*v);
        }
        case ValueKind::kString: {
            DecodedString s = decode_string(bytes);
            if (mode == CodecMode::kStrict) {
                if (!s.terminated) {
                    return about(element, "string has no NUL terminator within its " +
                                              std::to_string(*size) + " bytes");
                }
                if (const auto bad = base::find_invalid_utf8(s.text)) {
                    return about(element,
                                 "string is not valid UTF-8 (byte " + std::to_string(*bad) + ")");
                }
            }
            return Value::text(std::move(s.text));
        }
        case ValueKind::kEventId: {
            const auto v = decode_event_id(bytes);
            if (!v.ok()) return about(element, v.error().message);
            return Value::event_id(*v);
        }
    }
    return about(element, "has no value");
}

CodecStatus check_value(const Element& element, const Value& value) {
    const auto size = value_size(element);
    if (!size.ok()) return size.error();
    const ValueKind expected = *value_kind_of(element);
    if (value.kind() != expected) return wrong_kind(element, expected, value);
    switch (element.kind) {
        case ElementKind::kInt:
        case ElementKind::kBit:
            return check_int(element, *value.as_int(), *size);
        case ElementKind::kAction:
            return check_action(element, *value.as_int(), *size);
        case ElementKind::kFloat:
            return check_float(element, *value.as_float(), *size);
        case ElementKind::kString:
            return check_string(element, *value.as_string(), *size);
        case ElementKind::kEventId:
            return check_event_id(element, *value.as_event_id());
        case ElementKind::kGroup:
        case ElementKind::kBlob:
        case ElementKind::kUnknown:
            break;
    }
    return about(element, "has no value");
}

CodecResult<Value> parse_value_text(const Element& element, std::string_view text) {
    const auto kind = value_kind_of(element);
    if (!kind) {
        return about(element, std::string("a <") + tag_of(element) + "> has no value to parse");
    }
    switch (*kind) {
        case ValueKind::kInt: {
            const auto v = parse_int_text(trim(text));
            if (!v.ok()) return about(element, v.error().message);
            return Value::integer(*v);
        }
        case ValueKind::kFloat: {
            const auto v = parse_float_text(trim(text), element.size);
            if (!v.ok()) return about(element, v.error().message);
            return Value::real(*v);
        }
        case ValueKind::kString:
            return Value::text(std::string(text));
        case ValueKind::kEventId: {
            const auto v = parse_event_id(trim(text));
            if (!v.ok()) return about(element, v.error().message);
            return Value::event_id(*v);
        }
    }
    return about(element, "has no value");
}

std::string format_value(const Element& element, const Value& value) {
    switch (value.kind()) {
        case ValueKind::kInt:
            return format_int(*value.as_int());
        case ValueKind::kFloat:
            return format_float(*value.as_float(),
                                element.kind == ElementKind::kFloat ? element.size : 8);
        case ValueKind::kString:
            return *value.as_string();
        case ValueKind::kEventId:
            return format_event_id(*value.as_event_id());
    }
    return {};
}

}  // namespace olcb::cdi
