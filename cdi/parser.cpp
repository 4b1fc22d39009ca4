#include "cdi/parser.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cdi/content_index.hpp"
#include "cdi/line_counter.hpp"
#include "cdi/loaded_xml.hpp"

namespace olcb::cdi {
namespace {

/// One attribute: its name and its value (entities decoded, whitespace normalised).
struct XmlAttribute {
    std::string_view name;
    std::string_view value;
};

// An element name as pugixml keeps it (NUL-terminated), compared with literals byte by byte up
// to the first difference: no strlen is paid to look at it, and nothing past its NUL is read.
class Tag {
public:
    explicit Tag(const char* name) : name_(name) {}
    char first() const { return name_[0]; }
    std::string_view view() const { return name_; }
    template <std::size_t N>
    bool is(const char (&literal)[N]) const {
        for (std::size_t i = 0; i < N; ++i) {
            if (name_[i] != literal[i]) return false;
        }
        return true;
    }

private:
    const char* name_;
};

// The attributes of an element in document order (duplicates kept), as XmlAttribute values.
class XmlAttributes {
public:
    explicit XmlAttributes(pugi::xml_attribute first) : first_(first) {}

    class Iterator {
    public:
        explicit Iterator(pugi::xml_attribute at) : at_(at) {}
        XmlAttribute operator*() const { return {at_.name(), at_.value()}; }
        Iterator& operator++() {
            at_ = at_.next_attribute();
            return *this;
        }
        bool operator!=(const Iterator& other) const { return at_ != other.at_; }

    private:
        pugi::xml_attribute at_;
    };
    Iterator begin() const { return Iterator(first_); }
    static Iterator end() { return Iterator(pugi::xml_attribute()); }

private:
    pugi::xml_attribute first_;
};

// An element of the pugixml document as the parser reads it: element children only (text,
// comments and PIs are skipped), names and texts as views into the document's buffer, source
// offsets of names. Cheap to copy.
class XmlElement {
public:
    XmlElement() = default;
    explicit XmlElement(pugi::xml_node node) : node_(node) {}

    explicit operator bool() const { return static_cast<bool>(node_); }
    std::string_view name() const { return node_.name(); }
    const char* c_name() const { return node_.name(); }
    Tag tag() const { return Tag(node_.name()); }
    pugi::xml_node node() const { return node_; }
    // The first text directly inside the element ("" when none).
    std::string_view text() const { return node_.child_value(); }
    // Byte offset of the name in the source: pugixml parses in place and never moves a name.
    std::size_t offset() const { return source_offset(node_); }
    XmlElement first_child() const { return forward(node_.first_child()); }
    XmlElement next_sibling() const { return forward(node_.next_sibling()); }
    XmlAttributes attributes() const { return XmlAttributes(node_.first_attribute()); }
    // The first attribute with this name.
    std::optional<XmlAttribute> attribute(std::string_view name) const {
        for (pugi::xml_attribute a = node_.first_attribute(); a; a = a.next_attribute()) {
            const char* candidate = a.name();
            if (std::strncmp(candidate, name.data(), name.size()) == 0 &&
                candidate[name.size()] == '\0') {
                return XmlAttribute{{candidate, name.size()}, a.value()};
            }
        }
        return std::nullopt;
    }

private:
    static XmlElement forward(pugi::xml_node n) {
        while (n && n.type() != pugi::node_element) n = n.next_sibling();
        return XmlElement(n);
    }

    pugi::xml_node node_;
};

constexpr WideInt kTwoPow31 = WideInt{1} << 31;
constexpr WideInt kTwoPow32 = WideInt{1} << 32;
// Enough to report every problem of a real CDI; bounds memory on hostile input.
constexpr std::size_t kMaxDiagnostics = 1000;

template <std::size_t N>
bool is(std::string_view name, const char (&literal)[N]) {
    return name == std::string_view(literal, N - 1);
}

template <std::size_t N>
bool is(Tag tag, const char (&literal)[N]) {
    return tag.is(literal);
}

std::string str(std::string_view text) {
    return std::string(text);
}

std::string str(Tag tag) {
    return std::string(tag.view());
}

// A literal's length is known at compile time; a view of it through const char* costs a strlen.
template <std::size_t N>
std::string_view part(const char (&literal)[N]) {
    return {literal, N - 1};
}
inline std::string_view part(std::string_view text) {
    return text;
}
inline std::string_view part(Tag tag) {
    return tag.view();
}

// A message from its parts with one allocation (a CDI may earn hundreds of warnings).
template <typename... Parts>
std::string cat(const Parts&... parts) {
    std::string out;
    out.reserve((part(parts).size() + ...));
    (out.append(part(parts)), ...);
    return out;
}

// A CDI needs about kMaxGroupDepth + 8 levels (cdi, segment, the groups, a variable, its map,
// relation, value); anything deeper is refused before the model is built.
constexpr std::size_t kMaxXmlDepth = kMaxGroupDepth + 16;

// Finds the first element (document order) nested deeper than kMaxXmlDepth. pugixml's own
// traversal is iterative and stays inside the library, so it costs a few instructions a node.
class DepthWalker : public pugi::xml_tree_walker {
public:
    bool for_each(pugi::xml_node& node) override {
        // depth() is 0 for the root element, which is at XML depth 1.
        if (static_cast<std::size_t>(depth()) < kMaxXmlDepth || node.type() != pugi::node_element)
            return true;
        too_deep_ = node;
        return false;
    }
    pugi::xml_node too_deep() const { return too_deep_; }

private:
    pugi::xml_node too_deep_;
};

// Number of children named name; a reservation hint.
template <std::size_t N>
std::size_t count_children(XmlElement node, const char (&name)[N]) {
    std::size_t n = 0;
    for (XmlElement child = node.first_child(); child; child = child.next_sibling()) {
        if (is(child.tag(), name)) ++n;
    }
    return n;
}

// Stores a rarely present text; an empty one is the same as none.
void set_text(Boxed<std::string>& box, std::string_view text) {
    if (!text.empty()) {
        box = std::string(text);
    } else {
        box.reset();
    }
}

// strcmp stops at the first difference; a string_view of the name would measure it first.
template <std::size_t N>
bool name_is(XmlElement node, const char (&name)[N]) {
    return std::strcmp(node.c_name(), name) == 0;
}

// Attributes that are namespace plumbing (xmlns, xsi:...) are never reported as unknown.
bool is_namespace_attribute(std::string_view name) {
    return name.substr(0, 5) == "xmlns" || name.find(':') != std::string_view::npos;
}

std::optional<ElementKind> known_kind(Tag tag) {
    switch (tag.first()) {
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

// The container's own children of a <segment>/<group>, read by its caller (name, ...).
bool is_own_child(Tag tag, bool in_group) {
    if (is(tag, "name") || is(tag, "description") || is(tag, "link")) return true;
    return in_group && (is(tag, "repname") || is(tag, "hints"));
}

// A child of a <segment>/<group> that parse_data_children acts on, in document order.
struct PendingChild {
    XmlElement node;
    std::optional<ElementKind> kind;  // nullopt: an unknown element without size (warned)
    std::uint32_t content_index = 0;
};

// Numbers the element children of one parent, visited in order, by their index among all the
// parent's content nodes (content_index.hpp): only the tags and end tags between one child's
// last descendant and the next child are read, not the children's insides.
class ContentCounter {
public:
    ContentCounter(std::string_view text, XmlElement parent) : text_(text), parent_(parent) {}

    // The index of child, the parent's next element child.
    std::uint32_t index_of(XmlElement child) {
        const auto [from, depth] = last_ ? last_descendant(last_) : std::pair{parent_, -1};
        next_ += non_element_nodes_between(text_, from.offset(), depth, child.offset());
        last_ = child;
        return next_++;
    }

private:
    // The last element of e's subtree in document order, and how deep below e's parent it is.
    static std::pair<XmlElement, int> last_descendant(XmlElement e) {
        const auto [last, depth] = last_element(e.node());
        return {XmlElement(last), depth + 1};
    }

    std::string_view text_;
    XmlElement parent_;
    XmlElement last_;
    std::uint32_t next_ = 0;
};

// A <segment> or <group> whose data children parse_data_tree is reading.
struct OpenContainer {
    XmlElement parent;
    std::vector<Element>* out = nullptr;  // where its data elements go
    std::size_t first = 0;                // its slice of pending_ is [first, end)
    std::size_t next = 0;
    std::size_t end = 0;
    std::size_t depth = 0;    // group depth of its children
    bool drop_owner = false;  // the group itself is refused: drop it once its children are read
};

class Parser {
public:
    explicit Parser(Diagnostics& diagnostics) : diagnostics_(diagnostics) {}

    std::optional<Document> run(const LoadedXml& xml);

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
    void error(XmlElement node, std::string message) {
        report(Severity::kError, line(node), std::move(message));
    }
    void warning(XmlElement node, std::string message) {
        report(Severity::kWarning, line(node), std::move(message));
    }
    std::uint32_t line(XmlElement node) { return lines_->line_of(node.offset()); }

    std::optional<WideInt> int_attribute(XmlElement node, std::string_view name, WideInt lo,
                                         WideInt hi, bool* bad);
    std::optional<WideInt> int_value(XmlElement node, const XmlAttribute& attr, WideInt lo,
                                     WideInt hi, bool* bad);
    bool bool_attribute(XmlElement node, std::string_view name);
    std::optional<WideInt> int_text(XmlElement node, XmlElement parent);
    std::optional<double> float_text(XmlElement node, XmlElement parent);

    XmlElement read_xml(const LoadedXml& loaded);
    void read_declaration(std::string_view text, Document& doc);
    void parse_identification(XmlElement node, Document& doc);
    void parse_acdi(XmlElement node, Document& doc);
    void parse_segment(XmlElement node, std::uint32_t content_index, Document& doc);
    Link parse_link(XmlElement node);
    void parse_map(XmlElement node, Map& map);
    void parse_relation(XmlElement node, MapEntry& entry);
    void parse_hints(XmlElement node, Element& element);
    void open_container(XmlElement parent, std::vector<Element>& out, std::size_t depth,
                        bool drop_owner);
    void parse_data_tree(XmlElement segment, std::vector<Element>& out);
    bool read_data_attributes(XmlElement node, Element& element, std::optional<WideInt>* size,
                              bool* bad_size);
    bool parse_data_element(XmlElement node, ElementKind kind, std::size_t depth, Element& element);
    void parse_group_body(XmlElement node, Element& group);
    void parse_variable_body(XmlElement node, Element& element);
    bool parse_value_child(XmlElement node, XmlElement child, Tag tag, Element& element);
    bool parse_action_child(XmlElement node, XmlElement child, Tag tag, Element& element);
    bool read_size(XmlElement node, std::optional<WideInt> size, Element& element);

    Diagnostics& diagnostics_;
    LineCounter* lines_ = nullptr;
    std::string_view text_;              // the source, for the nodes between elements
    std::vector<PendingChild> pending_;  // the open containers' children, one slice each
    std::vector<OpenContainer> open_;    // parse_data_tree's stack, outermost first
    bool truncated_ = false;
};

std::optional<WideInt> Parser::int_attribute(XmlElement node, std::string_view name, WideInt lo,
                                             WideInt hi, bool* bad) {
    const std::optional<XmlAttribute> attr = node.attribute(name);
    if (!attr) return std::nullopt;
    return int_value(node, *attr, lo, hi, bad);
}

std::optional<WideInt> Parser::int_value(XmlElement node, const XmlAttribute& attr, WideInt lo,
                                         WideInt hi, bool* bad) {
    std::optional<WideInt> value = parse_decimal_int(attr.value);
    if (!value) {
        error(node, "attribute " + str(attr.name) + "=" + quoted_excerpt(attr.value) + " of <" +
                        str(node.name()) + "> is not a decimal integer");
        *bad = true;
        return std::nullopt;
    }
    if (*value < lo || *value > hi) {
        error(node, "attribute " + str(attr.name) + "=" + quoted_excerpt(attr.value) + " of <" +
                        str(node.name()) + "> is out of range " + to_string(lo) + ".." +
                        to_string(hi));
        *bad = true;
        return std::nullopt;
    }
    return value;
}

bool Parser::bool_attribute(XmlElement node, std::string_view name) {
    const std::optional<XmlAttribute> attr = node.attribute(name);
    if (!attr) return false;
    std::string_view text = trim_xml_space(attr->value);
    if (text == "yes" || text == "true" || text == "1") return true;
    if (text == "no" || text == "false" || text == "0") return false;
    warning(node, "attribute " + str(name) + "=" + quoted_excerpt(attr->value) + " of <" +
                      str(node.name()) + "> is not yes/no/true/false/1/0; taken as false");
    return false;
}

std::optional<WideInt> Parser::int_text(XmlElement node, XmlElement parent) {
    std::optional<WideInt> value = parse_decimal_int(node.text());
    if (!value) {
        error(node, "<" + str(node.name()) + "> of <" + str(parent.name()) +
                        "> is not a decimal integer: " + quoted_excerpt(node.text()));
    }
    return value;
}

std::optional<double> Parser::float_text(XmlElement node, XmlElement parent) {
    std::optional<double> value = parse_decimal_float(node.text());
    if (!value) {
        error(node, "<" + str(node.name()) + "> of <" + str(parent.name()) +
                        "> is not a decimal number: " + quoted_excerpt(node.text()));
    }
    return value;
}

// The <cdi> root of the loaded text, or none with a report of what makes the document
// unusable (malformed XML, a DTD, no root, another root, nesting too deep) and returns none.
XmlElement Parser::read_xml(const LoadedXml& loaded) {
    const auto line = [this](pugi::xml_node node) -> std::uint32_t {
        return lines_->line_of(XmlElement(node).offset());
    };
    const pugi::xml_parse_result& parsed = loaded.result();
    if (!parsed) {
        const std::size_t offset = parsed.offset < 0 ? 0 : static_cast<std::size_t>(parsed.offset);
        report(Severity::kError, lines_->line_of(std::min(offset, loaded.text().size())),
               std::string("malformed XML: ") + parsed.description());
        return {};
    }
    const pugi::xml_document& xml = loaded.document();
    for (pugi::xml_node child : xml.children()) {
        if (child.type() == pugi::node_doctype) {
            report(Severity::kError, line(child),
                   "DOCTYPE/DTD (and entity declarations) are not allowed in a CDI");
            return {};
        }
    }
    const XmlElement root(xml.document_element());
    if (!root) {
        report(Severity::kError, 0, "no root element");
        return {};
    }
    if (!name_is(root, "cdi")) {
        error(root, "root element is <" + str(root.name()) + ">, expected <cdi>");
        return {};
    }
    if (const auto bound = loaded.depth_bound(); bound && *bound <= kMaxXmlDepth) return root;
    DepthWalker walker;
    pugi::xml_node(xml).traverse(walker);  // a handle: traverse() is not const
    if (pugi::xml_node deep = walker.too_deep()) {
        report(
            Severity::kError, line(deep),
            "XML elements nested deeper than " + std::to_string(kMaxXmlDepth) + " levels; refused");
        return {};
    }
    return root;
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

Link Parser::parse_link(XmlElement node) {
    Link link;
    const std::optional<XmlAttribute> ref = node.attribute("ref");
    if (ref) link.ref = ref->value;
    link.text = node.text();
    if (!ref) warning(node, "<link> without a ref attribute");
    return link;
}

// The first <property> and the first <value> of a <relation>, in one pass over it.
void Parser::parse_relation(XmlElement node, MapEntry& entry) {
    XmlElement property;
    XmlElement value;
    for (XmlElement part = node.first_child(); part; part = part.next_sibling()) {
        const Tag part_tag = part.tag();
        if (!property && is(part_tag, "property")) {
            property = part;
        } else if (!value && is(part_tag, "value")) {
            value = part;
        }
    }
    if (!property || !value) warning(node, "<relation> without <property> and <value>");
    if (property) entry.property = property.text();
    if (value) entry.value = value.text();
}

void Parser::parse_map(XmlElement node, Map& map) {
    for (XmlElement child = node.first_child(); child; child = child.next_sibling()) {
        const Tag tag = child.tag();
        if (is(tag, "name")) {
            map.name = child.text();
        } else if (is(tag, "description")) {
            map.description = child.text();
        } else if (is(tag, "relation")) {
            if (map.entries.empty()) map.entries.reserve(count_children(node, "relation"));
            parse_relation(child, map.entries.emplace_back());
        } else {
            warning(child, "unknown element <" + str(tag) + "> in <map> ignored");
        }
    }
}

void Parser::parse_hints(XmlElement node, Element& element) {
    const bool group = element.kind == ElementKind::kGroup;
    for (XmlElement child = node.first_child(); child; child = child.next_sibling()) {
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
            warning(child, "hint <" + str(child.name()) + "> is not defined for <" + element.tag +
                               ">; ignored");
        }
    }
}

void Parser::parse_identification(XmlElement node, Document& doc) {
    if (doc.identification) {
        warning(node, "duplicate <identification> ignored");
        return;
    }
    Identification id;
    id.pos.line = line(node);
    for (XmlElement child = node.first_child(); child; child = child.next_sibling()) {
        if (name_is(child, "manufacturer")) {
            id.manufacturer = child.text();
        } else if (name_is(child, "model")) {
            id.model = child.text();
        } else if (name_is(child, "hardwareVersion")) {
            id.hardware_version = child.text();
        } else if (name_is(child, "softwareVersion")) {
            id.software_version = child.text();
        } else if (name_is(child, "link")) {
            id.link = parse_link(child);
        } else if (name_is(child, "map")) {
            parse_map(child, id.map.emplace());
        } else {
            warning(child,
                    "unknown element <" + str(child.name()) + "> in <identification> ignored");
        }
    }
    doc.identification = std::move(id);
}

void Parser::parse_acdi(XmlElement node, Document& doc) {
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

void Parser::parse_segment(XmlElement node, std::uint32_t content_index, Document& doc) {
    Segment segment;
    segment.pos.line = line(node);
    segment.content_index = content_index;
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
    for (const XmlAttribute attr : node.attributes()) {
        if (attr.name != "space" && attr.name != "origin" && !is_namespace_attribute(attr.name)) {
            warning(node, cat("attribute '", attr.name, "' of <segment> ignored"));
        }
    }
    for (XmlElement child = node.first_child(); child; child = child.next_sibling()) {
        if (name_is(child, "name")) {
            segment.name = child.text();
        } else if (name_is(child, "description")) {
            segment.description = child.text();
        } else if (name_is(child, "link")) {
            segment.link = parse_link(child);
        }
    }
    parse_data_tree(node, segment.children);
    doc.segments.push_back(std::move(segment));
}

// Classifies the data elements among the children of a <segment> or <group> (depth: that of
// the children) onto pending_ and opens it on the stack; other children are the caller's (name,
// description, ...) or unknown elements without size, warned about when their turn comes. out
// is reserved exactly, so Elements are built in place (moving one costs) and never move while
// their own children are read.
void Parser::open_container(XmlElement parent, std::vector<Element>& out, std::size_t depth,
                            bool drop_owner) {
    const bool in_group = name_is(parent, "group");
    const std::size_t first = pending_.size();
    std::size_t count = 0;
    ContentCounter counter(text_, parent);
    for (XmlElement child = parent.first_child(); child; child = child.next_sibling()) {
        const std::uint32_t content_index = counter.index_of(child);
        const Tag tag = child.tag();
        if (is_own_child(tag, in_group)) continue;  // the caller's
        std::optional<ElementKind> kind = known_kind(tag);
        if (!kind && child.attribute("size")) kind = ElementKind::kUnknown;
        if (kind) ++count;
        pending_.push_back({child, kind, content_index});
    }
    out.reserve(out.size() + count);
    open_.push_back({parent, &out, first, first, pending_.size(), depth, drop_owner});
}

// Reads every data element below a <segment> in document order, depth first, with an explicit
// stack instead of recursion: nesting costs heap in proportion to the input, never the call
// stack. A group refused for its attributes is still read through (its children's findings are
// reported), then dropped.
void Parser::parse_data_tree(XmlElement segment, std::vector<Element>& out) {
    open_container(segment, out, 1, false);
    while (!open_.empty()) {
        OpenContainer& top = open_.back();
        if (top.next == top.end) {
            pending_.resize(top.first);
            const bool drop = top.drop_owner;
            open_.pop_back();
            if (drop) open_.back().out->pop_back();
            continue;
        }
        const PendingChild child = pending_[top.next++];  // a copy: open_container grows pending_
        const XmlElement parent = top.parent;
        const std::size_t depth = top.depth;
        std::vector<Element>& siblings = *top.out;
        if (!child.kind) {
            warning(child.node, cat("unknown element <", child.node.name(), "> in <", parent.name(),
                                    "> has no size attribute; skipped"));
            continue;
        }
        Element& element = siblings.emplace_back();
        element.content_index = child.content_index;
        const bool ok = parse_data_element(child.node, *child.kind, depth, element);
        if (element.kind == ElementKind::kGroup && depth <= kMaxGroupDepth) {
            open_container(child.node, element.children, depth + 1, !ok);
        } else if (!ok) {
            siblings.pop_back();
        }
    }
}

bool Parser::read_size(XmlElement node, std::optional<WideInt> size, Element& element) {
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
                warning(node, "size=" + quoted_excerpt(node.attribute("size")->value) +
                                  " of <eventid> ignored; an event ID is 8 bytes");
            }
            element.size = 8;
            return true;
        default:
            break;
    }
    if (!size) {
        error(node, "<" + str(node.name()) + "> requires a size attribute");
        return false;
    }
    element.size = static_cast<std::uint64_t>(*size);
    return true;
}

// One pass over a data element's attributes; offset is xs:int, but [2^31, 2^32) is OpenMRN's
// unsigned rendering of a negative value and is kept verbatim for the layout to judge. Returns
// false when an attribute other than size is bad; size goes to *size (*bad_size when bad).
bool Parser::read_data_attributes(XmlElement node, Element& element, std::optional<WideInt>* size,
                                  bool* bad_size) {
    const ElementKind kind = element.kind;
    const bool group = kind == ElementKind::kGroup;
    bool bad = false;
    for (const XmlAttribute attr : node.attributes()) {
        const std::string_view name = attr.name;
        if (is(name, "offset")) {
            if (auto v = int_value(node, attr, -kTwoPow31, kTwoPow32 - 1, &bad)) {
                element.offset = static_cast<std::int64_t>(*v);
            }
        } else if (!group && is(name, "size")) {
            *size = int_value(node, attr, 1, kTwoPow32, bad_size);
        } else if (group && is(name, "replication")) {
            if (auto v = int_value(node, attr, 1, kTwoPow31 - 1, &bad)) {
                element.replication = static_cast<std::uint64_t>(*v);
            }
        } else if (kind == ElementKind::kFloat && is(name, "formatting")) {
            set_text(element.formatting, attr.value);
        } else if (kind == ElementKind::kBlob && is(name, "mode")) {
            set_text(element.blob_mode, attr.value);
        } else if (kind != ElementKind::kUnknown && !is_namespace_attribute(name)) {
            warning(node, cat("attribute '", name, "' of <", node.name(),
                              "> is not in the CDI schema; ignored"));
        }
    }
    return !bad;
}

// Reads a data element's attributes and own children; a group's data children are
// parse_data_tree's. False when the element is refused.
bool Parser::parse_data_element(XmlElement node, ElementKind kind, std::size_t depth,
                                Element& element) {
    element.kind = kind;
    element.tag = node.name();
    element.pos.line = line(node);
    bool bad_size = false;
    std::optional<WideInt> size;
    bool ok = read_data_attributes(node, element, &size, &bad_size);
    if (kind == ElementKind::kGroup) {
        if (depth > kMaxGroupDepth) {
            error(node, "groups nested deeper than " + std::to_string(kMaxGroupDepth) +
                            " levels; refused");
            return false;
        }
        parse_group_body(node, element);
    } else {
        if (bad_size || !read_size(node, size, element)) ok = false;
        parse_variable_body(node, element);
    }
    return ok;
}

void Parser::parse_group_body(XmlElement node, Element& group) {
    for (XmlElement child = node.first_child(); child; child = child.next_sibling()) {
        const Tag tag = child.tag();
        if (is(tag, "name")) {
            group.name = child.text();
        } else if (is(tag, "description")) {
            group.description = child.text();
        } else if (is(tag, "link")) {
            group.link = parse_link(child);
        } else if (is(tag, "repname")) {
            group.repnames.emplace_back(child.text());
        } else if (is(tag, "hints")) {
            parse_hints(child, group);
        }
    }
}

// The children of a variable that hold a value (<min>, <max>, <default>, the action's
// texts): false when tag is none of those this kind has.
bool Parser::parse_value_child(XmlElement node, XmlElement child, Tag tag, Element& element) {
    const ElementKind kind = element.kind;
    const bool integer = kind == ElementKind::kInt || kind == ElementKind::kBit;
    if (integer && is(tag, "min")) {
        element.int_min = int_text(child, node);
    } else if (integer && is(tag, "max")) {
        element.int_max = int_text(child, node);
    } else if (integer && is(tag, "default")) {
        element.int_default = int_text(child, node);
    } else if (kind == ElementKind::kFloat && is(tag, "min")) {
        element.float_min = float_text(child, node);
    } else if (kind == ElementKind::kFloat && is(tag, "max")) {
        element.float_max = float_text(child, node);
    } else if (kind == ElementKind::kFloat && is(tag, "default")) {
        element.float_default = float_text(child, node);
    } else if ((kind == ElementKind::kString || kind == ElementKind::kEventId) &&
               is(tag, "default")) {
        element.text_default = std::string(child.text());
    } else if (kind == ElementKind::kAction) {
        return parse_action_child(node, child, tag, element);
    } else {
        return false;
    }
    return true;
}

bool Parser::parse_action_child(XmlElement node, XmlElement child, Tag tag, Element& element) {
    if (is(tag, "buttonText")) {
        set_text(element.button_text, child.text());
    } else if (is(tag, "dialogText")) {
        set_text(element.dialog_text, child.text());
    } else if (is(tag, "value")) {
        element.action_value = int_text(child, node);
    } else {
        return false;
    }
    return true;
}

void Parser::parse_variable_body(XmlElement node, Element& element) {
    const ElementKind kind = element.kind;
    const bool mappable = kind != ElementKind::kAction && kind != ElementKind::kBlob;
    for (XmlElement child = node.first_child(); child; child = child.next_sibling()) {
        const Tag tag = child.tag();
        if (is(tag, "name")) {
            element.name = child.text();
        } else if (is(tag, "description")) {
            element.description = child.text();
        } else if (kind == ElementKind::kUnknown) {
            continue;  // a future element: only its name, description and size matter here
        } else if (is(tag, "link")) {
            element.link = parse_link(child);
        } else if (is(tag, "hints")) {
            parse_hints(child, element);
        } else if (is(tag, "map") && mappable) {
            parse_map(child, element.map.emplace());
        } else if (!parse_value_child(node, child, tag, element)) {
            warning(child, cat("unknown element <", tag, "> in <", node.name(), "> ignored"));
        }
    }
}

std::optional<Document> Parser::run(const LoadedXml& loaded) {
    std::string_view bytes = loaded.text();
    if (bytes.size() >= 3 && static_cast<unsigned char>(bytes[0]) == 0xEF &&
        static_cast<unsigned char>(bytes[1]) == 0xBB &&
        static_cast<unsigned char>(bytes[2]) == 0xBF) {
        report(Severity::kError, 1,
               "the CDI starts with a UTF-8 byte-order mark; the standard forbids a BOM");
        return std::nullopt;
    }
    // A node serves the CDI with a NUL terminator (sometimes several): LoadedXml dropped them.
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

    // pugixml parsed a copy in place (it rewrites texts as it decodes them); the nodes between
    // elements are counted in the original.
    const XmlElement root = read_xml(loaded);
    if (!root) return std::nullopt;
    text_ = bytes;

    Document doc;
    read_declaration(bytes, doc);
    for (const XmlAttribute attr : root.attributes()) {
        const std::size_t colon = attr.name.find(':');
        const std::string_view local =
            colon == std::string_view::npos ? attr.name : attr.name.substr(colon + 1);
        if (local == "noNamespaceSchemaLocation") doc.schema_location = attr.value;
    }
    ContentCounter counter(text_, root);
    for (XmlElement child = root.first_child(); child; child = child.next_sibling()) {
        const std::uint32_t content_index = counter.index_of(child);
        if (name_is(child, "identification")) {
            parse_identification(child, doc);
        } else if (name_is(child, "acdi")) {
            parse_acdi(child, doc);
        } else if (name_is(child, "segment")) {
            parse_segment(child, content_index, doc);
        } else {
            warning(child, "unknown element <" + str(child.name()) + "> in <cdi> ignored");
        }
    }
    return doc;
}

}  // namespace

ParseResult parse(std::string_view bytes) {
    const LoadedXml loaded(bytes);
    return parse(loaded);
}

ParseResult parse(const LoadedXml& loaded) {
    ParseResult result;
    Parser parser(result.diagnostics);
    result.document = parser.run(loaded);
    if (has_errors(result.diagnostics)) result.document.reset();
    return result;
}

}  // namespace olcb::cdi
