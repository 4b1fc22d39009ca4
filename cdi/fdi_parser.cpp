#include "cdi/fdi_parser.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "cdi/decimal.hpp"
#include "cdi/line_counter.hpp"
#include "cdi/parser.hpp"

namespace olcb::cdi {
namespace {

// Enough to report every problem of a real FDI; bounds memory on hostile input.
constexpr std::size_t kMaxDiagnostics = 1000;

bool named(pugi::xml_node node, const char* name) {
    return std::strcmp(node.name(), name) == 0;
}

pugi::xml_node element_from(pugi::xml_node node) {
    while (node && node.type() != pugi::node_element) node = node.next_sibling();
    return node;
}

pugi::xml_node first_element(pugi::xml_node parent) {
    return element_from(parent.first_child());
}

pugi::xml_node next_element(pugi::xml_node node) {
    return element_from(node.next_sibling());
}

// An element's text as the model keeps it: XML whitespace around it dropped.
std::string text_of(pugi::xml_node element) {
    return std::string(trim_xml_space(element.child_value()));
}

std::string quoted(std::string_view text) {
    return quoted_excerpt(text);
}

/// Builds the model from pugixml's tree in one pass in document order (lines are counted
/// incrementally); groups are walked with an explicit stack, so nesting costs heap, not stack.
class FdiReader {
public:
    FdiReader(std::string_view text, Diagnostics& out) : lines_(text), out_(out) {}

    std::optional<FdiDocument> run(const LoadedXml& loaded);

private:
    std::uint32_t line(pugi::xml_node node) { return lines_.line_of(source_offset(node)); }
    void error(std::uint32_t line, std::string message);
    void error(pugi::xml_node node, std::string message) { error(line(node), std::move(message)); }

    pugi::xml_node root_of(const LoadedXml& loaded);
    void read_segment(pugi::xml_node segment, FdiDocument& doc);
    void read_function(pugi::xml_node node, std::optional<std::size_t> group, FdiDocument& doc);
    void read_kind(pugi::xml_node node, FdiFunction& function);
    std::optional<std::int32_t> read_int(pugi::xml_node element);

    LineCounter lines_;
    Diagnostics& out_;
    std::size_t suppressed_ = 0;
};

void FdiReader::error(std::uint32_t line, std::string message) {
    if (out_.size() >= kMaxDiagnostics) {
        ++suppressed_;
        return;
    }
    out_.push_back({Severity::kError, line, std::move(message)});
}

// The <fdi> root, or none with the reason (not XML, a DOCTYPE, another root).
pugi::xml_node FdiReader::root_of(const LoadedXml& loaded) {
    const std::string_view text = loaded.text();
    if (const void* nul = std::memchr(text.data(), '\0', text.size())) {
        const auto offset = static_cast<std::size_t>(static_cast<const char*>(nul) - text.data());
        error(lines_.line_of(offset),
              "NUL byte inside the FDI text (only trailing NUL terminators are allowed)");
        return {};
    }
    if (trim_xml_space(text).empty()) {
        error(0, "the FDI is empty");
        return {};
    }
    const pugi::xml_parse_result& parsed = loaded.result();
    if (!parsed) {
        const std::size_t offset = parsed.offset < 0 ? 0 : static_cast<std::size_t>(parsed.offset);
        error(lines_.line_of(std::min(offset, text.size())),
              std::string("malformed XML: ") + parsed.description());
        return {};
    }
    for (pugi::xml_node child : loaded.document().children()) {
        if (child.type() == pugi::node_doctype) {
            error(child, "DOCTYPE/DTD (and entity declarations) are not allowed in an FDI");
            return {};
        }
    }
    const pugi::xml_node root = loaded.document().document_element();
    if (!root) {
        error(0, "no root element");
        return {};
    }
    if (!named(root, "fdi")) {
        error(root, "root element is <" + std::string(root.name()) + ">, expected <fdi>");
        return {};
    }
    return root;
}

std::optional<FdiDocument> FdiReader::run(const LoadedXml& loaded) {
    const pugi::xml_node root = root_of(loaded);
    if (!root) return std::nullopt;
    FdiDocument doc;
    for (pugi::xml_attribute a = root.first_attribute(); a; a = a.next_attribute()) {
        const std::string_view name = a.name();
        const std::size_t colon = name.find(':');
        const std::string_view local =
            colon == std::string_view::npos ? name : name.substr(colon + 1);
        if (local == "noNamespaceSchemaLocation") doc.schema_location = a.value();
    }
    bool segment_seen = false;
    for (pugi::xml_node child = first_element(root); child; child = next_element(child)) {
        if (!named(child, "segment")) continue;  // the schema names unknown elements
        if (segment_seen) {
            error(child,
                  "a second <segment>, ignored: the <fdi> element contains exactly one (§5.1.1)");
            continue;
        }
        segment_seen = true;
        read_segment(child, doc);
    }
    if (!segment_seen) error(root, "<fdi> has no <segment>; it contains exactly one (§5.1.1)");
    if (suppressed_ != 0) {
        out_.push_back(
            {Severity::kError, 0, std::to_string(suppressed_) + " further errors suppressed"});
    }
    return doc;
}

void FdiReader::read_segment(pugi::xml_node segment, FdiDocument& doc) {
    doc.segment_line = line(segment);
    doc.space_given = static_cast<bool>(segment.attribute("space"));
    doc.origin_given = static_cast<bool>(segment.attribute("origin"));
    doc.name = text_of(segment.child("name"));
    doc.description = text_of(segment.child("description"));
    struct Frame {
        pugi::xml_node next;
        std::optional<std::size_t> group;
        std::size_t depth;
    };
    std::vector<Frame> open{{first_element(segment), std::nullopt, 0}};
    while (!open.empty()) {
        const pugi::xml_node node = open.back().next;
        if (!node) {
            open.pop_back();
            continue;
        }
        open.back().next = next_element(node);
        const std::optional<std::size_t> group = open.back().group;
        const std::size_t depth = open.back().depth;
        if (named(node, "function")) {
            read_function(node, group, doc);
        } else if (named(node, "group")) {
            if (depth >= kMaxGroupDepth) {
                error(node, "groups nested deeper than " + std::to_string(kMaxGroupDepth) +
                                " levels; the group is left out");
                continue;
            }
            FdiGroup g;
            g.name = text_of(node.child("name"));
            g.description = text_of(node.child("description"));
            g.parent = group;
            g.depth = depth + 1;
            g.first_function = doc.functions.size();
            g.line = line(node);
            doc.groups.push_back(std::move(g));
            open.push_back({first_element(node), doc.groups.size() - 1, depth + 1});
        }
    }
}

// §5.1.4: binary (the default), momentary or analog; xs:token, so surrounding blanks are allowed.
void FdiReader::read_kind(pugi::xml_node node, FdiFunction& function) {
    const pugi::xml_attribute kind = node.attribute("kind");
    if (!kind) return;
    const std::string_view value = trim_xml_space(kind.value());
    if (value == "binary") {
        function.kind = FunctionKind::kBinary;
    } else if (value == "momentary") {
        function.kind = FunctionKind::kMomentary;
    } else if (value == "analog") {
        function.kind = FunctionKind::kAnalog;
    } else {
        error(node, "<function> kind " + quoted(kind.value()) +
                        " is not binary, momentary or analog (§5.1.4); read as binary");
    }
}

// An xs:int element (<icon>, <min>, <max>), decimal as §5 requires; none with an error otherwise.
std::optional<std::int32_t> FdiReader::read_int(pugi::xml_node element) {
    const auto value = parse_decimal_int(element.child_value());
    if (value && *value >= std::numeric_limits<std::int32_t>::min() &&
        *value <= std::numeric_limits<std::int32_t>::max()) {
        return static_cast<std::int32_t>(*value);
    }
    error(element, "<" + std::string(element.name()) + "> " + quoted(element.child_value()) +
                       " is not a decimal integer of 32 bits (§5: decimal numbers; schema xs:int)"
                       "; ignored");
    return std::nullopt;
}

void FdiReader::read_function(pugi::xml_node node, std::optional<std::size_t> group,
                              FdiDocument& doc) {
    FdiFunction f;
    f.line = line(node);
    f.group = group;
    read_kind(node, f);
    if (const pugi::xml_attribute size = node.attribute("size")) {
        f.size_given = true;
        if (trim_xml_space(size.value()) != "1") {
            error(node, "<function> size " + quoted(size.value()) +
                            " is not 1 (§5.1.4: reserved; if given, it shall be 1)");
        }
    }
    pugi::xml_node number;
    for (pugi::xml_node child = first_element(node); child; child = next_element(child)) {
        if (named(child, "name")) {
            f.name = text_of(child);
        } else if (named(child, "number")) {
            if (!number) number = child;
        } else if (named(child, "icon")) {
            f.icon = read_int(child);
        } else if (named(child, "min")) {
            f.min = read_int(child);
        } else if (named(child, "max")) {
            f.max = read_int(child);
        }
    }
    if (!number) {
        error(node, "<function> has no <number>; it shall contain one (§5.1.4); left out");
        return;
    }
    const auto value = parse_decimal_int(number.child_value());
    if (!value || *value < 0 || *value > static_cast<WideInt>(kMaxFunctionNumber)) {
        error(number, "<number> " + quoted(number.child_value()) +
                          " is not a decimal integer in 0.." + std::to_string(kMaxFunctionNumber) +
                          " (§5.1.4); the function is left out");
        return;
    }
    f.number = static_cast<std::uint32_t>(*value);
    doc.functions.push_back(std::move(f));
}

// Skips what may precede the root: blanks, the declaration and other processing instructions,
// comments, a DOCTYPE (with its internal subset). False when the text ends first.
bool skip_prolog_item(std::string_view& t) {
    std::size_t blanks = 0;
    while (blanks < t.size() && is_xml_space(t[blanks])) ++blanks;
    t.remove_prefix(blanks);
    std::size_t end = std::string_view::npos;
    if (t.starts_with("<?")) {
        end = t.find("?>");
        if (end != std::string_view::npos) end += 2;
    } else if (t.starts_with("<!--")) {
        end = t.find("-->", 4);
        if (end != std::string_view::npos) end += 3;
    } else if (t.starts_with("<!")) {
        end = t.find_first_of("[>");
        if (end != std::string_view::npos && t[end] == '[') end = t.find(']', end);
        if (end != std::string_view::npos) end = t.find('>', end);
        if (end != std::string_view::npos) end += 1;
    } else {
        return blanks != 0;
    }
    if (end == std::string_view::npos) {
        t = {};
        return false;
    }
    t.remove_prefix(end);
    return true;
}

}  // namespace

FdiParseResult parse_fdi(std::string_view bytes) {
    const LoadedXml loaded(bytes);
    return parse_fdi(loaded);
}

FdiParseResult parse_fdi(const LoadedXml& loaded) {
    FdiParseResult result;
    FdiReader reader(loaded.text(), result.diagnostics);
    result.document = reader.run(loaded);
    return result;
}

bool is_fdi_text(std::string_view text) {
    constexpr std::string_view kBom = "\xEF\xBB\xBF";
    if (text.starts_with(kBom)) text.remove_prefix(kBom.size());
    while (skip_prolog_item(text)) {
    }
    if (!text.starts_with("<fdi")) return false;
    if (text.size() == 4) return true;
    const char after = text[4];
    return is_xml_space(after) || after == '>' || after == '/';
}

}  // namespace olcb::cdi
