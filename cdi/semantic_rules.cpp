#include "cdi/semantic_rules.hpp"

#include "cdi/decimal.hpp"
#include "cdi/event_id_text.hpp"

#include <charconv>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace olcb::cdi {
namespace {

std::string float_text(double value) {
    if (value == 0.0) value = 0.0;  // folds -0.0 so equal values print equally
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
    return std::string(buffer, result.ptr);
}

// Dotted hex ("05.01.01.01.22.00.00.FF") is the usual spelling; plain decimal is accepted as
// well because the standard makes decimal the one numeric format (section 5.1).
std::optional<EventIdValue> parse_event_id_text(std::string_view text) {
    text = trim_xml_space(text);
    if (const auto id = parse_event_id(text)) return *id;
    if (text.empty() || text.find_first_not_of("0123456789") != std::string_view::npos) {
        return std::nullopt;
    }
    const auto value = parse_decimal_int(text);
    if (!value || *value > static_cast<WideInt>(UINT64_MAX)) return std::nullopt;
    return static_cast<EventIdValue>(*value);
}

bool valid_int_size(std::uint64_t size) {
    return size == 1 || size == 2 || size == 4 || size == 8;
}

bool valid_float_size(std::uint64_t size) {
    return size == 2 || size == 4 || size == 8;
}

/// The values an <int> of `size` bytes can store (standard 5.1.4.2: unsigned unless min < 0).
struct IntRange {
    WideInt low = 0;
    WideInt high = 0;
    bool is_signed = false;
    std::uint64_t size = 0;

    bool contains(WideInt value) const { return value >= low && value <= high; }
    std::string describe() const {
        return std::to_string(size) + "-byte " + (is_signed ? "signed" : "unsigned") + " (" +
               to_string(low) + ".." + to_string(high) + ")";
    }
};

IntRange int_range(std::uint64_t size, bool is_signed) {
    const WideInt span = WideInt{1} << (8 * size);
    if (is_signed) return {-(span / 2), span / 2 - 1, true, size};
    return {0, span - 1, false, size};
}

std::string element_label(const Element& e) {
    const std::string tag =
        e.kind == ElementKind::kUnknown && !e.tag.empty() ? e.tag : kind_name(e.kind);
    std::string label = "<" + tag + ">";
    if (!e.name.empty()) label += " \"" + e.name + "\"";
    return label;
}

/// Walks a document once, collecting findings in document order.
class Checker {
public:
    Diagnostics run(const Document& doc) {
        if (doc.identification) check_identification(*doc.identification);
        if (doc.acdi) check_acdi(*doc.acdi);
        for (const Segment& segment : doc.segments) check_segment(segment);
        return std::move(out_);
    }

private:
    void add(Severity severity, std::uint32_t line, std::string message) {
        out_.push_back({severity, line, std::move(message)});
    }
    void error(const Element& e, const std::string& message) {
        add(Severity::kError, e.pos.line, element_label(e) + ": " + message);
    }
    void warning(const Element& e, const std::string& message) {
        add(Severity::kWarning, e.pos.line, element_label(e) + ": " + message);
    }

    void check_identification(const Identification& id) {
        const auto check_length = [&](const std::string& value, const char* field,
                                      std::size_t limit) {
            if (value.size() <= limit) return;
            add(Severity::kWarning, id.pos.line,
                "<identification>: " + std::string(field) + " is " + std::to_string(value.size()) +
                    " bytes; SNIP and ACDI carry at most " + std::to_string(limit));
        };
        check_length(id.manufacturer, "manufacturer", kMaxManufacturerBytes);
        check_length(id.model, "model", kMaxModelBytes);
        check_length(id.hardware_version, "hardwareVersion", kMaxHardwareVersionBytes);
        check_length(id.software_version, "softwareVersion", kMaxSoftwareVersionBytes);
        if (id.map) {
            std::set<std::string> seen;
            for (const MapEntry& entry : id.map->entries) {
                if (!seen.insert(entry.property).second) {
                    add(Severity::kWarning, id.pos.line,
                        "<identification>: map property \"" + entry.property +
                            "\" appears more than once");
                }
            }
        }
    }

    void check_acdi(const Acdi& acdi) {
        if (acdi.fixed != kAcdiFixedVersion) {
            add(Severity::kWarning, acdi.pos.line,
                "<acdi>: fixed=\"" + std::to_string(acdi.fixed) + "\" is not " +
                    std::to_string(kAcdiFixedVersion) +
                    "; tools read space 252 with the version 4 layout");
        }
        if (acdi.var != kAcdiVarVersion) {
            add(Severity::kWarning, acdi.pos.line,
                "<acdi>: var=\"" + std::to_string(acdi.var) + "\" is not " +
                    std::to_string(kAcdiVarVersion) +
                    "; tools read space 251 with the version 2 layout");
        }
    }

    void check_segment(const Segment& segment) {
        if (segment.space > 255) {
            std::string label = "<segment>";
            if (!segment.name.empty()) label += " \"" + segment.name + "\"";
            add(Severity::kError, segment.pos.line,
                label + ": space " + std::to_string(segment.space) +
                    " is not a valid memory space (0 to 255)");
        }
        check_tree(segment.children);
    }

    // Every element under a segment in document order (cdi::walk_elements: no recursion).
    void check_tree(const std::vector<Element>& top) {
        walk_elements(top, [this](const Element& e, std::size_t) { check_element(e); });
    }

    // One element's own rules; a group's children are check_tree's.
    void check_element(const Element& e) {
        check_hints(e);
        switch (e.kind) {
            case ElementKind::kGroup:
                // §5.1.3 repeats the group N times and sets no lower bound: 0 is odd, not wrong.
                if (e.replication < 1)
                    warning(e, "replication " + std::to_string(e.replication) +
                                   " repeats the group no time at all");
                break;
            case ElementKind::kInt:
                check_int(e);
                break;
            case ElementKind::kString:
                check_string(e);
                break;
            case ElementKind::kEventId:
                check_event_id(e);
                break;
            case ElementKind::kFloat:
                check_float(e);
                break;
            case ElementKind::kAction:
                check_action(e);
                break;
            case ElementKind::kUnknown:
                warning(e, "unknown element read as a " + std::to_string(e.size) +
                               "-byte variable (CDI standard section 6)");
                break;
            case ElementKind::kBlob:
            case ElementKind::kBit:
                break;
        }
    }

    void check_hints(const Element& e) {
        const std::size_t entries = e.map ? e.map->entries.size() : 0;
        if (e.hints.checkbox && (!e.map || entries != 2)) {
            error(e, "a checkbox hint needs a <map> with exactly two entries, found " +
                         (e.map ? std::to_string(entries) : std::string("no map")));
        }
        if (e.hints.radiobutton && !e.map) {
            error(e, "a radiobutton hint needs a <map>, found none");
        }
    }

    /// Checks each map property with `key_of` (nullopt + reason when invalid), warns on
    /// duplicates, then checks that a default (given as its key) is one of the properties.
    template <typename KeyOf>
    void check_map(const Element& e, KeyOf key_of, const std::optional<std::string>& default_key,
                   const std::string& default_text) {
        if (!e.map) return;
        std::set<std::string> keys;
        for (const MapEntry& entry : e.map->entries) {
            std::string why;
            const std::optional<std::string> key = key_of(entry.property, why);
            if (!key) {
                error(e, "map property \"" + entry.property + "\" " + why);
                continue;
            }
            if (!keys.insert(*key).second) {
                warning(e, "map property \"" + entry.property + "\" appears more than once");
            }
        }
        if (default_key && !e.map->entries.empty() && !keys.contains(*default_key)) {
            // No clause ties a default to the map (values outside min/max are §5.1.4.2's).
            warning(e, "default " + default_text + " is not one of the map's properties");
        }
    }

    void check_int(const Element& e) {
        const bool size_ok = valid_int_size(e.size);
        if (!size_ok) {
            error(e, "size " + std::to_string(e.size) +
                         " is not valid; int size must be 1, 2, 4, or 8");
        }
        if (e.int_min && e.int_max && *e.int_min > *e.int_max) {
            error(e,
                  "min " + to_string(*e.int_min) + " is greater than max " + to_string(*e.int_max));
        }
        std::optional<IntRange> range;
        if (size_ok) range = int_range(e.size, e.is_signed());
        const auto check_fits = [&](const std::optional<WideInt>& value, const char* what) {
            if (value && range && !range->contains(*value)) {
                error(e, std::string(what) + " " + to_string(*value) + " does not fit in a " +
                             range->describe() + " int");
            }
        };
        check_fits(e.int_min, "min");
        check_fits(e.int_max, "max");
        check_fits(e.int_default, "default");
        if (e.int_default) {
            if (e.int_min && *e.int_default < *e.int_min) {
                error(e, "default " + to_string(*e.int_default) + " is below min " +
                             to_string(*e.int_min));
            }
            if (e.int_max && *e.int_default > *e.int_max) {
                error(e, "default " + to_string(*e.int_default) + " is above max " +
                             to_string(*e.int_max));
            }
        }
        const auto key_of = [&](const std::string& text,
                                std::string& why) -> std::optional<std::string> {
            const auto value = parse_decimal_int(text);
            if (!value) {
                why = "is not a decimal integer";
                return std::nullopt;
            }
            if (range && !range->contains(*value)) {
                why = "does not fit in a " + range->describe() + " int";
                return std::nullopt;
            }
            if ((e.int_min && *value < *e.int_min) || (e.int_max && *value > *e.int_max)) {
                why = "is outside min/max";
                return std::nullopt;
            }
            return to_string(*value);
        };
        std::optional<std::string> default_key;
        if (e.int_default) default_key = to_string(*e.int_default);
        check_map(e, key_of, default_key, default_key.value_or(""));
    }

    void check_float(const Element& e) {
        if (!valid_float_size(e.size)) {
            error(e, "size " + std::to_string(e.size) +
                         " is not valid; float size must be 2, 4, or 8");
        }
        if (e.float_min && e.float_max && *e.float_min > *e.float_max) {
            error(e, "min " + float_text(*e.float_min) + " is greater than max " +
                         float_text(*e.float_max));
        }
        if (e.float_default) {
            if (e.float_min && *e.float_default < *e.float_min) {
                error(e, "default " + float_text(*e.float_default) + " is below min " +
                             float_text(*e.float_min));
            }
            if (e.float_max && *e.float_default > *e.float_max) {
                error(e, "default " + float_text(*e.float_default) + " is above max " +
                             float_text(*e.float_max));
            }
        }
        const auto key_of = [&](const std::string& text,
                                std::string& why) -> std::optional<std::string> {
            const auto value = parse_decimal_float(text);
            if (!value) {
                why = "is not a decimal number";
                return std::nullopt;
            }
            if ((e.float_min && *value < *e.float_min) || (e.float_max && *value > *e.float_max)) {
                why = "is outside min/max";
                return std::nullopt;
            }
            return float_text(*value);
        };
        std::optional<std::string> default_key;
        if (e.float_default) default_key = float_text(*e.float_default);
        check_map(e, key_of, default_key, default_key.value_or(""));
    }

    void check_string(const Element& e) {
        if (e.size < 1) {
            error(e, "size 0 is not valid; string size must be at least 1");
            return;
        }
        const std::uint64_t room = e.size - 1;  // one byte always holds the terminating NUL
        const auto fits = [room](const std::string& text) { return text.size() <= room; };
        if (e.text_default && !fits(*e.text_default)) {
            error(e, "default is " + std::to_string(e.text_default->size()) + " bytes; at most " +
                         std::to_string(room) + " fit before the NUL");
        }
        const auto key_of = [&](const std::string& text,
                                std::string& why) -> std::optional<std::string> {
            if (!fits(text)) {
                why = "is " + std::to_string(text.size()) + " bytes; at most " +
                      std::to_string(room) + " fit before the NUL";
                return std::nullopt;
            }
            return text;
        };
        const std::optional<std::string> default_key =
            e.text_default ? std::optional<std::string>(*e.text_default) : std::nullopt;
        check_map(e, key_of, default_key,
                  e.text_default ? "\"" + *e.text_default + "\"" : std::string());
    }

    void check_event_id(const Element& e) {
        if (e.size != 0 && e.size != 8) {
            error(e, "size " + std::to_string(e.size) + " is not valid; an eventid is 8 bytes");
        }
        std::optional<std::string> default_key;
        if (e.text_default) {
            if (const auto id = parse_event_id_text(*e.text_default)) {
                default_key = std::to_string(*id);
            } else {
                error(e, "default \"" + *e.text_default +
                             "\" is not an event ID (8 dotted hex bytes)");
            }
        }
        const auto key_of = [](const std::string& text,
                               std::string& why) -> std::optional<std::string> {
            const auto id = parse_event_id_text(text);
            if (!id) {
                why = "is not an event ID (8 dotted hex bytes, e.g. 05.01.01.01.22.00.00.FF)";
                return std::nullopt;
            }
            return std::to_string(*id);
        };
        check_map(e, key_of, default_key,
                  e.text_default ? "\"" + *e.text_default + "\"" : std::string());
    }

    void check_action(const Element& e) {
        if (!valid_int_size(e.size)) {
            error(e, "size " + std::to_string(e.size) +
                         " is not valid; action size must be 1, 2, 4, or 8");
            return;
        }
        if (e.action_value) {
            const IntRange range = int_range(e.size, *e.action_value < 0);
            if (!range.contains(*e.action_value)) {
                error(e, "value " + to_string(*e.action_value) + " does not fit in a " +
                             range.describe() + " action");
            }
        }
    }

    Diagnostics out_;
};

}  // namespace

Diagnostics check_semantics(const Document& doc) {
    return Checker{}.run(doc);
}

}  // namespace olcb::cdi
