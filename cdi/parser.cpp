#include "cdi/parser.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

namespace olcb::cdi {
namespace {

constexpr WideInt kTwoPow31 = WideInt{1} << 31;
constexpr WideInt kTwoPow32 = WideInt{1} << 32;
// Enough to report every problem of a real CDI; bounds memory on hostile input.
constexpr std::size_t kMaxDiagnostics = 1000;

// Maps a byte offset to a 1-based line. Elements are visited in document order, so lines are
// counted incrementally from the previous offset; a backwards step recounts from the start.
class LineCounter {
public:
    explicit LineCounter(std::string_view text) : text_(text) {}

    std::uint32_t line_of(std::size_t offset) {
        offset = std::min(offset, text_.size());
        if (offset < offset_) {
            offset_ = 0;
            line_ = 1;
        }
        line_ += static_cast<std::uint32_t>(
            std::count(text_.data() + offset_, text_.data() + offset, '\n'));
        offset_ = offset;
        return line_;
    }

private:
    std::string_view text_;
    std::size_t offset_ = 0;
    std::uint32_t line_ = 1;
};

// Compares a NUL-terminated name with a literal without strlen; stops at the first mismatch, so
// it never reads past the name's terminator.
template <std::size_t N>
bool is(const char* name, const char (&literal)[N]) {
    for (std::size_t i = 0; i < N; ++i) {
        if (name[i] != literal[i]) return false;
    }
    return true;
}

// A CDI needs about kMaxGroupDepth + 8 levels; anything far deeper is hostile.
constexpr std::size_t kMaxXmlDepth = 2 * kMaxGroupDepth + 16;

// Offset of the first start tag deeper than kMaxXmlDepth, by a scan of the (already
// well-formed) text: no recursion, and far cheaper than walking pugixml's tree node by node.
std::optional<std::size_t> first_too_deep(std::string_view text) {
    const char* const begin = text.data();
    const char* const end = begin + text.size();
    auto skip_past = [&](const char* from, std::string_view terminator) {
        std::string_view rest(from, static_cast<std::size_t>(end - from));
        const std::size_t at = rest.find(terminator);
        return at == std::string_view::npos ? end : from + at + terminator.size();
    };
    std::size_t depth = 0;
    const char* p = begin;
    while (p < end) {
        const void* hit = std::memchr(p, '<', static_cast<std::size_t>(end - p));
        if (hit == nullptr) break;
        const char* tag = static_cast<const char*>(hit);
        if (tag + 1 >= end) break;
        const char next = tag[1];
        if (next == '/') {
            if (depth > 0) --depth;
            p = tag + 2;
        } else if (next == '?') {
            p = skip_past(tag + 2, "?>");
        } else if (next == '!') {
            const std::string_view rest(tag, static_cast<std::size_t>(end - tag));
            if (rest.substr(0, 4) == "<!--") {
                p = skip_past(tag + 4, "-->");
            } else if (rest.substr(0, 9) == "<![CDATA[") {
                p = skip_past(tag + 9, "]]>");
            } else {
                p = skip_past(tag + 2, ">");
            }
        } else {
            if (++depth > kMaxXmlDepth) return static_cast<std::size_t>(tag - begin);
            // Find the end of the tag; attribute values may hold '>'.
            const char* q = tag + 1;
            char quote = 0;
            for (; q < end; ++q) {
                if (quote != 0) {
                    if (*q == quote) quote = 0;
                } else if (*q == '"' || *q == '\'') {
                    quote = *q;
                } else if (*q == '>') {
                    break;
                }
            }
            if (q < end && q[-1] == '/') --depth;
            p = q + 1;
        }
    }
    return std::nullopt;
}

bool is_xml_space(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

bool name_is(pugi::xml_node node, std::string_view name) {
    return node.name() == name;
}

std::string quoted(std::string_view text) {
    constexpr std::size_t kMaxShown = 40;
    std::string out = "'";
    out += text.substr(0, kMaxShown);
    if (text.size() > kMaxShown) out += "...";
    out += "'";
    return out;
}

// Attributes that are namespace plumbing (xmlns, xsi:...) are never reported as unknown.
bool is_namespace_attribute(std::string_view name) {
    return name.substr(0, 5) == "xmlns" || name.find(':') != std::string_view::npos;
}

std::optional<ElementKind> known_kind(const char* tag) {
    switch (tag[0]) {
        case 'g':
            if (is(tag, "group")) return ElementKind::kGroup;
            break;
        case 'i':
            if (is(tag, "int")) return ElementKind::kInt;
            break;
        case 's':
            if (is(tag, "string")) return ElementKind::kString;
            break;
        case 'e':
            if (is(tag, "eventid")) return ElementKind::kEventId;
            break;
        case 'f':
            if (is(tag, "float")) return ElementKind::kFloat;
            break;
        case 'a':
            if (is(tag, "action")) return ElementKind::kAction;
            break;
        case 'b':
            if (is(tag, "blob")) return ElementKind::kBlob;
            if (is(tag, "bit")) return ElementKind::kBit;
            break;
        default:
            break;
    }
    return std::nullopt;
}

// The data element kind of a child of <segment>/<group>, or nullopt for the container's own
// children (name, description, ...) and for unknown elements without a size.
std::optional<ElementKind> data_kind(pugi::xml_node child, const char* tag, bool in_group) {
    if (std::optional<ElementKind> kind = known_kind(tag)) return kind;
    if (is(tag, "name") || is(tag, "description") || is(tag, "link")) return std::nullopt;
    if (in_group && (is(tag, "repname") || is(tag, "hints"))) return std::nullopt;
    if (!child.attribute("size")) return std::nullopt;
    return ElementKind::kUnknown;
}

class Parser {
public:
    explicit Parser(Diagnostics& diagnostics) : diagnostics_(diagnostics) {}

    std::optional<Document> run(std::string_view bytes);

private:
    void report(Severity severity, std::uint32_t line, std::string message) {
        if (diagnostics_.size() >= kMaxDiagnostics) {
            if (!truncated_) {
                truncated_ = true;
                diagnostics_.push_back({Severity::kError, 0, "too many diagnostics; stopped"});
            }
            return;
        }
        diagnostics_.push_back({severity, line, std::move(message)});
    }
    void error(pugi::xml_node node, std::string message) {
        report(Severity::kError, line(node), std::move(message));
    }
    void warning(pugi::xml_node node, std::string message) {
        report(Severity::kWarning, line(node), std::move(message));
    }
    std::uint32_t line(pugi::xml_node node) {
        const std::ptrdiff_t offset = node.offset_debug();
        return offset < 0 ? 0 : lines_->line_of(static_cast<std::size_t>(offset));
    }

    std::optional<WideInt> int_attribute(pugi::xml_node node, const char* name, WideInt lo,
                                         WideInt hi, bool* bad);
    std::optional<WideInt> int_value(pugi::xml_node node, pugi::xml_attribute attr, WideInt lo,
                                     WideInt hi, bool* bad);
    bool bool_attribute(pugi::xml_node node, const char* name);
    std::optional<WideInt> int_text(pugi::xml_node node, pugi::xml_node parent);
    std::optional<double> float_text(pugi::xml_node node, pugi::xml_node parent);

    void read_declaration(std::string_view text, Document& doc);
    void parse_identification(pugi::xml_node node, Document& doc);
    void parse_acdi(pugi::xml_node node, Document& doc);
    void parse_segment(pugi::xml_node node, Document& doc);
    Link parse_link(pugi::xml_node node);
    Map parse_map(pugi::xml_node node);
    void parse_hints(pugi::xml_node node, Element& element);
    void parse_data_children(pugi::xml_node parent, std::vector<Element>& out, std::size_t depth);
    bool parse_data_element(pugi::xml_node node, const char* tag, ElementKind kind,
                            std::size_t depth, Element& element);
    void parse_group_body(pugi::xml_node node, Element& group, std::size_t depth);
    void parse_variable_body(pugi::xml_node node, Element& element);
    bool read_size(pugi::xml_node node, std::optional<WideInt> size, Element& element);

    Diagnostics& diagnostics_;
    LineCounter* lines_ = nullptr;
    bool truncated_ = false;
};

std::optional<WideInt> Parser::int_attribute(pugi::xml_node node, const char* name, WideInt lo,
                                             WideInt hi, bool* bad) {
    pugi::xml_attribute attr = node.attribute(name);
    if (!attr) return std::nullopt;
    return int_value(node, attr, lo, hi, bad);
}

std::optional<WideInt> Parser::int_value(pugi::xml_node node, pugi::xml_attribute attr, WideInt lo,
                                         WideInt hi, bool* bad) {
    std::optional<WideInt> value = parse_decimal_int(attr.value());
    if (!value) {
        error(node, std::string("attribute ") + attr.name() + "=" + quoted(attr.value()) + " of <" +
                        node.name() + "> is not a decimal integer");
        *bad = true;
        return std::nullopt;
    }
    if (*value < lo || *value > hi) {
        error(node, std::string("attribute ") + attr.name() + "=" + quoted(attr.value()) + " of <" +
                        node.name() + "> is out of range " + to_string(lo) + ".." + to_string(hi));
        *bad = true;
        return std::nullopt;
    }
    return value;
}

bool Parser::bool_attribute(pugi::xml_node node, const char* name) {
    pugi::xml_attribute attr = node.attribute(name);
    if (!attr) return false;
    std::string_view text = trim_xml_space(attr.value());
    if (text == "yes" || text == "true" || text == "1") return true;
    if (text == "no" || text == "false" || text == "0") return false;
    warning(node, std::string("attribute ") + name + "=" + quoted(attr.value()) + " of <" +
                      node.name() + "> is not yes/no/true/false/1/0; taken as false");
    return false;
}

std::optional<WideInt> Parser::int_text(pugi::xml_node node, pugi::xml_node parent) {
    std::optional<WideInt> value = parse_decimal_int(node.child_value());
    if (!value) {
        error(node, std::string("<") + node.name() + "> of <" + parent.name() +
                        "> is not a decimal integer: " + quoted(node.child_value()));
    }
    return value;
}

std::optional<double> Parser::float_text(pugi::xml_node node, pugi::xml_node parent) {
    std::optional<double> value = parse_decimal_float(node.child_value());
    if (!value) {
        error(node, std::string("<") + node.name() + "> of <" + parent.name() +
                        "> is not a decimal number: " + quoted(node.child_value()));
    }
    return value;
}

void Parser::read_declaration(std::string_view text, Document& doc) {
    std::size_t start = 0;
    while (start < text.size() && is_xml_space(text[start])) ++start;
    std::string_view rest = text.substr(start);
    if (rest.size() < 6 || rest.substr(0, 5) != "<?xml" ||
        !(is_xml_space(rest[5]) || rest[5] == '?'))
        return;
    const std::size_t end = rest.find("?>");
    if (end == std::string_view::npos) return;
    doc.has_xml_declaration = true;
    doc.xml_declaration = std::string(rest.substr(0, end + 2));
}

Link Parser::parse_link(pugi::xml_node node) {
    Link link;
    link.ref = node.attribute("ref").value();
    link.text = node.child_value();
    if (!node.attribute("ref")) warning(node, "<link> without a ref attribute");
    return link;
}

Map Parser::parse_map(pugi::xml_node node) {
    Map map;
    for (pugi::xml_node child : node.children()) {
        if (child.type() != pugi::node_element) continue;
        if (name_is(child, "name")) {
            map.name = child.child_value();
        } else if (name_is(child, "description")) {
            map.description = child.child_value();
        } else if (name_is(child, "relation")) {
            MapEntry entry;
            pugi::xml_node property = child.child("property");
            pugi::xml_node value = child.child("value");
            if (!property || !value) {
                warning(child, "<relation> without <property> and <value>");
            }
            entry.property = property.child_value();
            entry.value = value.child_value();
            map.entries.push_back(std::move(entry));
        } else {
            warning(child, std::string("unknown element <") + child.name() + "> in <map> ignored");
        }
    }
    return map;
}

void Parser::parse_hints(pugi::xml_node node, Element& element) {
    const bool group = element.kind == ElementKind::kGroup;
    for (pugi::xml_node child : node.children()) {
        if (child.type() != pugi::node_element) continue;
        if (!group && name_is(child, "slider")) {
            SliderHint slider;
            bool bad = false;
            // tickSpacing is xs:integer; anything beyond 64 bits is nonsense for a slider.
            if (auto v = int_attribute(child, "tickSpacing", INT64_MIN, INT64_MAX, &bad)) {
                slider.tick_spacing = static_cast<std::int64_t>(*v);
            }
            slider.immediate = bool_attribute(child, "immediate");
            slider.show_value = bool_attribute(child, "showValue");
            element.hints.slider = slider;
        } else if (!group && name_is(child, "radiobutton")) {
            element.hints.radiobutton = true;
        } else if (!group && name_is(child, "checkbox")) {
            element.hints.checkbox = true;
        } else if (group && name_is(child, "visibility")) {
            element.hints.visibility = true;
            element.hints.hideable = bool_attribute(child, "hideable");
            element.hints.hidden = bool_attribute(child, "hidden");
        } else if (group && name_is(child, "readOnly")) {
            element.hints.read_only = true;
        } else {
            warning(child, std::string("hint <") + child.name() + "> is not defined for <" +
                               element.tag + ">; ignored");
        }
    }
}

void Parser::parse_identification(pugi::xml_node node, Document& doc) {
    if (doc.identification) {
        warning(node, "duplicate <identification> ignored");
        return;
    }
    Identification id;
    id.pos.line = line(node);
    for (pugi::xml_node child : node.children()) {
        if (child.type() != pugi::node_element) continue;
        if (name_is(child, "manufacturer")) {
            id.manufacturer = child.child_value();
        } else if (name_is(child, "model")) {
            id.model = child.child_value();
        } else if (name_is(child, "hardwareVersion")) {
            id.hardware_version = child.child_value();
        } else if (name_is(child, "softwareVersion")) {
            id.software_version = child.child_value();
        } else if (name_is(child, "link")) {
            id.link = parse_link(child);
        } else if (name_is(child, "map")) {
            id.map = parse_map(child);
        } else {
            warning(child, std::string("unknown element <") + child.name() +
                               "> in <identification> ignored");
        }
    }
    doc.identification = std::move(id);
}

void Parser::parse_acdi(pugi::xml_node node, Document& doc) {
    if (doc.acdi) {
        warning(node, "duplicate <acdi> ignored");
        return;
    }
    Acdi acdi;
    acdi.pos.line = line(node);
    bool bad = false;
    if (auto v = int_attribute(node, "fixed", 0, kTwoPow32 - 1, &bad)) {
        acdi.fixed = static_cast<std::uint32_t>(*v);
    }
    if (auto v = int_attribute(node, "var", 0, kTwoPow32 - 1, &bad)) {
        acdi.var = static_cast<std::uint32_t>(*v);
    }
    doc.acdi = acdi;
}

void Parser::parse_segment(pugi::xml_node node, Document& doc) {
    Segment segment;
    segment.pos.line = line(node);
    bool bad = false;
    if (!node.attribute("space")) {
        error(node, "<segment> without the required space attribute");
    } else if (auto v = int_attribute(node, "space", 0, 255, &bad)) {
        segment.space = static_cast<std::uint32_t>(*v);
    }
    // origin is xs:int; unsigned 32-bit renderings are accepted, the layout checks addresses.
    if (auto v = int_attribute(node, "origin", -kTwoPow31, kTwoPow32 - 1, &bad)) {
        segment.origin = static_cast<std::int64_t>(*v);
    }
    for (pugi::xml_attribute attr : node.attributes()) {
        const char* name = attr.name();
        if (std::strcmp(name, "space") != 0 && std::strcmp(name, "origin") != 0 &&
            !is_namespace_attribute(name)) {
            warning(node, std::string("attribute '") + name + "' of <segment> ignored");
        }
    }
    for (pugi::xml_node child : node.children()) {
        if (child.type() != pugi::node_element) continue;
        if (name_is(child, "name")) {
            segment.name = child.child_value();
        } else if (name_is(child, "description")) {
            segment.description = child.child_value();
        } else if (name_is(child, "link")) {
            segment.link = parse_link(child);
        }
    }
    parse_data_children(node, segment.children, 1);
    doc.segments.push_back(std::move(segment));
}

// Reads the data elements among the children of a <segment> or <group>; other children are
// the caller's (name, description, ...) or unknown elements without size, skipped with a warning.
// Elements are built in place: an Element is large and moving it costs.
void Parser::parse_data_children(pugi::xml_node parent, std::vector<Element>& out,
                                 std::size_t depth) {
    const bool in_group = name_is(parent, "group");
    std::size_t count = 0;
    for (pugi::xml_node child = parent.first_child(); child; child = child.next_sibling()) {
        const char* tag = child.name();
        if (*tag != '\0' && data_kind(child, tag, in_group)) ++count;
    }
    out.reserve(out.size() + count);
    for (pugi::xml_node child = parent.first_child(); child; child = child.next_sibling()) {
        const char* tag = child.name();
        if (*tag == '\0') continue;  // text nodes; comments and PIs are not kept
        std::optional<ElementKind> kind = data_kind(child, tag, in_group);
        if (!kind) {
            if (!known_kind(tag) && !is(tag, "name") && !is(tag, "description") &&
                !is(tag, "link") && !(in_group && (is(tag, "repname") || is(tag, "hints")))) {
                warning(child, std::string("unknown element <") + child.name() + "> in <" +
                                   parent.name() + "> has no size attribute; skipped");
            }
            continue;
        }
        Element& element = out.emplace_back();
        if (!parse_data_element(child, tag, *kind, depth, element)) out.pop_back();
    }
}

bool Parser::read_size(pugi::xml_node node, std::optional<WideInt> size, Element& element) {
    switch (element.kind) {
        case ElementKind::kInt:
            element.size = size ? static_cast<std::uint64_t>(*size) : 1;
            return true;
        case ElementKind::kFloat:
            // CDI 1.2 defaulted float size to 4; 1.3+ require it.
            element.size = size ? static_cast<std::uint64_t>(*size) : 4;
            return true;
        case ElementKind::kBit:
            // CDI 1.0 gives <bit> size in bits (default 1); the variable spans whole bytes.
            element.size = size ? static_cast<std::uint64_t>((*size + 7) / 8) : 1;
            return true;
        case ElementKind::kEventId:
            if (size && *size != 8) {
                warning(node, "size=" + quoted(node.attribute("size").value()) +
                                  " of <eventid> ignored; an event ID is 8 bytes");
            }
            element.size = 8;
            return true;
        default:
            break;
    }
    if (!size) {
        error(node, std::string("<") + node.name() + "> requires a size attribute");
        return false;
    }
    element.size = static_cast<std::uint64_t>(*size);
    return true;
}

bool Parser::parse_data_element(pugi::xml_node node, const char* tag, ElementKind kind,
                                std::size_t depth, Element& element) {
    element.kind = kind;
    element.tag.assign(tag);
    element.pos.line = line(node);
    const bool group = kind == ElementKind::kGroup;
    bool bad = false;
    bool bad_size = false;
    std::optional<WideInt> size;
    // One pass over the attributes; offset is xs:int, but [2^31, 2^32) is OpenMRN's unsigned
    // rendering of a negative value and is kept verbatim for the layout to judge.
    for (pugi::xml_attribute attr = node.first_attribute(); attr; attr = attr.next_attribute()) {
        const char* name = attr.name();
        if (is(name, "offset")) {
            if (auto v = int_value(node, attr, -kTwoPow31, kTwoPow32 - 1, &bad)) {
                element.offset = static_cast<std::int64_t>(*v);
            }
        } else if (!group && is(name, "size")) {
            size = int_value(node, attr, 1, kTwoPow32, &bad_size);
        } else if (group && is(name, "replication")) {
            if (auto v = int_value(node, attr, 1, kTwoPow31 - 1, &bad)) {
                element.replication = static_cast<std::uint64_t>(*v);
            }
        } else if (kind == ElementKind::kFloat && is(name, "formatting")) {
            element.formatting = attr.value();
        } else if (kind == ElementKind::kBlob && is(name, "mode")) {
            element.blob_mode = attr.value();
        } else if (kind != ElementKind::kUnknown && !is_namespace_attribute(name)) {
            warning(node, std::string("attribute '") + attr.name() + "' of <" + node.name() +
                              "> is not in the CDI schema; ignored");
        }
    }
    if (group) {
        if (depth > kMaxGroupDepth) {
            error(node, "groups nested deeper than " + std::to_string(kMaxGroupDepth) +
                            " levels; refused");
            return false;
        }
        parse_group_body(node, element, depth);
    } else {
        if (bad_size || !read_size(node, size, element)) bad = true;
        parse_variable_body(node, element);
    }
    return !bad;
}

void Parser::parse_group_body(pugi::xml_node node, Element& group, std::size_t depth) {
    for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
        const char* tag = child.name();
        if (*tag == '\0') continue;  // text nodes; comments and PIs are not kept
        if (is(tag, "name")) {
            group.name = child.child_value();
        } else if (is(tag, "description")) {
            group.description = child.child_value();
        } else if (is(tag, "link")) {
            group.link = parse_link(child);
        } else if (is(tag, "repname")) {
            group.repnames.emplace_back(child.child_value());
        } else if (is(tag, "hints")) {
            parse_hints(child, group);
        }
    }
    parse_data_children(node, group.children, depth + 1);
}

void Parser::parse_variable_body(pugi::xml_node node, Element& element) {
    const ElementKind kind = element.kind;
    const bool integer = kind == ElementKind::kInt || kind == ElementKind::kBit;
    const bool floating = kind == ElementKind::kFloat;
    const bool text = kind == ElementKind::kString || kind == ElementKind::kEventId;
    const bool action = kind == ElementKind::kAction;
    for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
        const char* tag = child.name();
        if (*tag == '\0') continue;  // text nodes; comments and PIs are not kept
        if (is(tag, "name")) {
            element.name = child.child_value();
        } else if (is(tag, "description")) {
            element.description = child.child_value();
        } else if (kind == ElementKind::kUnknown) {
            continue;  // a future element: only its name, description and size matter here
        } else if (is(tag, "link")) {
            element.link = parse_link(child);
        } else if (is(tag, "hints")) {
            parse_hints(child, element);
        } else if (is(tag, "map") && !action && kind != ElementKind::kBlob) {
            element.map = parse_map(child);
        } else if (integer && is(tag, "min")) {
            element.int_min = int_text(child, node);
        } else if (integer && is(tag, "max")) {
            element.int_max = int_text(child, node);
        } else if (integer && is(tag, "default")) {
            element.int_default = int_text(child, node);
        } else if (floating && is(tag, "min")) {
            element.float_min = float_text(child, node);
        } else if (floating && is(tag, "max")) {
            element.float_max = float_text(child, node);
        } else if (floating && is(tag, "default")) {
            element.float_default = float_text(child, node);
        } else if (text && is(tag, "default")) {
            element.text_default = child.child_value();
        } else if (action && is(tag, "buttonText")) {
            element.button_text = child.child_value();
        } else if (action && is(tag, "dialogText")) {
            element.dialog_text = child.child_value();
        } else if (action && is(tag, "value")) {
            element.action_value = int_text(child, node);
        } else {
            warning(child, std::string("unknown element <") + child.name() + "> in <" +
                               node.name() + "> ignored");
        }
    }
}

std::optional<Document> Parser::run(std::string_view bytes) {
    if (bytes.size() >= 3 && static_cast<unsigned char>(bytes[0]) == 0xEF &&
        static_cast<unsigned char>(bytes[1]) == 0xBB &&
        static_cast<unsigned char>(bytes[2]) == 0xBF) {
        report(Severity::kError, 1,
               "the CDI starts with a UTF-8 byte-order mark; the standard forbids a BOM");
        return std::nullopt;
    }
    // A node serves the CDI with a NUL terminator (sometimes several); it is not XML.
    while (!bytes.empty() && bytes.back() == '\0') bytes.remove_suffix(1);
    LineCounter lines(bytes);
    lines_ = &lines;
    if (const void* nul = std::memchr(bytes.data(), '\0', bytes.size())) {
        const auto offset = static_cast<std::size_t>(static_cast<const char*>(nul) - bytes.data());
        report(Severity::kError, lines.line_of(offset),
               "NUL byte inside the CDI text (only trailing NUL terminators are allowed)");
        return std::nullopt;
    }
    if (trim_xml_space(bytes).empty()) {
        report(Severity::kError, 0, "the CDI is empty");
        return std::nullopt;
    }

    pugi::xml_document xml;
    // parse_doctype keeps a DOCTYPE as a node so it can be refused; pugixml never expands
    // entities it does not know, so a billion-laughs DTD costs one linear scan.
    const unsigned options = pugi::parse_default | pugi::parse_doctype;
    pugi::xml_parse_result parsed =
        xml.load_buffer(bytes.data(), bytes.size(), options, pugi::encoding_utf8);
    if (!parsed) {
        const std::size_t offset = parsed.offset < 0 ? 0 : static_cast<std::size_t>(parsed.offset);
        report(Severity::kError, lines.line_of(std::min(offset, bytes.size())),
               std::string("malformed XML: ") + parsed.description());
        return std::nullopt;
    }
    for (pugi::xml_node child : xml.children()) {
        if (child.type() == pugi::node_doctype) {
            report(Severity::kError, line(child),
                   "DOCTYPE/DTD (and entity declarations) are not allowed in a CDI");
            return std::nullopt;
        }
    }
    pugi::xml_node root = xml.document_element();
    if (!root) {
        report(Severity::kError, 0, "no root element");
        return std::nullopt;
    }
    if (!name_is(root, "cdi")) {
        error(root, std::string("root element is <") + root.name() + ">, expected <cdi>");
        return std::nullopt;
    }
    if (std::optional<std::size_t> deep = first_too_deep(bytes)) {
        report(
            Severity::kError, lines.line_of(*deep),
            "XML elements nested deeper than " + std::to_string(kMaxXmlDepth) + " levels; refused");
        return std::nullopt;
    }

    Document doc;
    read_declaration(bytes, doc);
    for (pugi::xml_attribute attr : root.attributes()) {
        const char* colon = std::strchr(attr.name(), ':');
        const char* local = colon ? colon + 1 : attr.name();
        if (std::strcmp(local, "noNamespaceSchemaLocation") == 0)
            doc.schema_location = attr.value();
    }
    for (pugi::xml_node child : root.children()) {
        if (child.type() != pugi::node_element) continue;
        if (name_is(child, "identification")) {
            parse_identification(child, doc);
        } else if (name_is(child, "acdi")) {
            parse_acdi(child, doc);
        } else if (name_is(child, "segment")) {
            parse_segment(child, doc);
        } else {
            warning(child, std::string("unknown element <") + child.name() + "> in <cdi> ignored");
        }
    }
    return doc;
}

}  // namespace

ParseResult parse(std::string_view bytes) {
    ParseResult result;
    Parser parser(result.diagnostics);
    result.document = parser.run(bytes);
    if (has_errors(result.diagnostics)) result.document.reset();
    return result;
}

}  // namespace olcb::cdi
