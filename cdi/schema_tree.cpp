#include "cdi/schema_tree.hpp"

#include <libxml/uri.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "cdi/content_index.hpp"
#include "cdi/decimal.hpp"

namespace olcb::cdi {
namespace {

constexpr std::string_view kXsiNamespace = "http://www.w3.org/2001/XMLSchema-instance";

const xmlChar* xml_chars(const char* text) {
    return reinterpret_cast<const xmlChar*>(text);
}

bool is_name_start(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}

// An ASCII name (or the local part of one) without a colon: pugixml keeps ASCII names to XML's
// name characters, so the rest is to see. In an all-ASCII text only the colon is.
bool is_plain_name(const char* name, bool ascii) {
    if (!is_name_start(*name)) return false;
    if (ascii) {
        for (; *name != '\0'; ++name) {  // names are short: a loop beats strchr's setup
            if (*name == ':') return false;
        }
        return true;
    }
    for (; *name != '\0'; ++name) {
        if (static_cast<unsigned char>(*name) >= 0x80 || *name == ':') return false;
    }
    return true;
}

// The end of an attribute value, or null when it holds a '<' (refused: see feed_tree).
const char* value_end(const char* value) {
    for (; *value != '\0'; ++value) {
        if (*value == '<') return nullptr;
    }
    return value;
}

// A namespace name libxml2's parser takes without a word: one its own URI parser reads, with a
// scheme, and neither the xml nor the xmlns namespace (which only their own prefixes may bind).
bool is_plain_uri(const char* uri) {
    const std::string_view name = uri;
    if (name == "http://www.w3.org/XML/1998/namespace" || name == "http://www.w3.org/2000/xmlns/")
        return false;
    xmlURIPtr parsed = xmlParseURI(uri);
    const bool absolute = parsed != nullptr && parsed->scheme != nullptr;
    xmlFreeURI(parsed);
    return absolute;
}

struct Binding {
    std::string_view prefix;
    const char* uri = nullptr;  // NUL-terminated, in the document
};

// The root's xmlns:p declarations; false for a default namespace or a doubtful declaration.
bool read_bindings(pugi::xml_node root, std::vector<Binding>& out) {
    for (pugi::xml_attribute a = root.first_attribute(); a; a = a.next_attribute()) {
        const std::string_view name = a.name();
        if (name == "xmlns") return false;
        if (!name.starts_with("xmlns:")) continue;
        const std::string_view prefix = name.substr(6);
        if (!is_plain_name(name.data() + 6, false) || prefix.starts_with("xml") ||
            !is_plain_uri(a.value()))
            return false;
        out.push_back({prefix, a.value()});
    }
    return true;
}

const char* uri_of(const std::vector<Binding>& bindings, std::string_view prefix) {
    for (const Binding& b : bindings) {
        if (b.prefix == prefix) return b.uri;
    }
    return nullptr;
}

// Builds libxml2's start-tag arrays for one element and feeds it.
class StartTag {
public:
    StartTag(const xmlSAXHandler& sax, void* user, const std::vector<Binding>& bindings, bool ascii)
        : sax_(sax), user_(user), bindings_(bindings), ascii_(ascii) {}

    // Feeds the start tag of element, whose name is `name`.
    bool feed(pugi::xml_node element, const char* name, bool root);

private:
    bool add_attribute(pugi::xml_attribute a, bool root);

    const xmlSAXHandler& sax_;
    void* user_;
    const std::vector<Binding>& bindings_;
    bool ascii_;
    std::vector<const xmlChar*> attributes_;  // five per attribute, as libxml2 passes them
    std::vector<const xmlChar*> namespaces_;  // two per declaration
};

bool StartTag::add_attribute(pugi::xml_attribute a, bool root) {
    const char* name = a.name();
    const char* local = name;
    const char* uri = nullptr;
    if (const char* colon = std::strchr(name, ':'); colon != nullptr) {
        const std::string_view prefix(name, static_cast<std::size_t>(colon - name));
        if (prefix == "xmlns") {
            if (!root) return false;  // the root's are read_bindings' to judge
            namespaces_.push_back(xml_chars(colon + 1));
            namespaces_.push_back(xml_chars(a.value()));
            return true;
        }
        local = colon + 1;
        uri = uri_of(bindings_, prefix);
        if (uri == nullptr || !is_plain_name(local, ascii_)) return false;
    } else if (!is_plain_name(name, ascii_) || std::strcmp(name, "xmlns") == 0) {
        return false;
    }
    const char* value = a.value();
    const char* end = value_end(value);
    if (end == nullptr) return false;
    for (std::size_t i = 0; i < attributes_.size(); i += 5) {
        if (std::strcmp(reinterpret_cast<const char*>(attributes_[i]), local) == 0) return false;
    }
    for (const char* part : {local, static_cast<const char*>(nullptr), uri, value, end}) {
        attributes_.push_back(xml_chars(part));
    }
    return true;
}

bool StartTag::feed(pugi::xml_node element, const char* name, bool root) {
    if (!is_plain_name(name, ascii_)) return false;
    attributes_.clear();
    namespaces_.clear();
    for (pugi::xml_attribute a = element.first_attribute(); a; a = a.next_attribute()) {
        if (!add_attribute(a, root)) return false;
    }
    if (sax_.startElementNs == nullptr) return true;
    sax_.startElementNs(user_, xml_chars(name), nullptr, nullptr,
                        static_cast<int>(namespaces_.size() / 2), namespaces_.data(),
                        static_cast<int>(attributes_.size() / 5), 0, attributes_.data());
    return true;
}

/// Stretches of the source ([begin, end) offsets) to feed as text, in document order. Only the
/// first `count` are set: zeroing all of them would cost a memset per element.
struct Runs {
    static constexpr std::size_t kMax = 8;
    std::size_t at[kMax][2];  // NOLINT(cppcoreguidelines-pro-type-member-init)
    std::size_t count = 0;

    void add(std::size_t begin, std::size_t end) {
        at[count][0] = begin;
        at[count][1] = end;
        ++count;
    }
};

// pugixml drops whitespace-only text, which an element of empty content may not hold either:
// the raw content of an element with no nodes in the tree is fed as it stands, from the end of
// its start tag to the next '<'. False when a comment sits inside (libxml2 then reads the text).
bool dropped_whitespace(std::string_view text, pugi::xml_node element, Runs& runs) {
    const std::size_t close = end_of_start_tag(text, source_offset(element));
    if (close < 2) return false;
    if (text[close - 2] == '/') return true;  // <x/>: no content at all
    const std::size_t next = text.find('<', close);
    if (next == std::string_view::npos || text.substr(next, 2) != "</") return false;
    if (close < next) runs.add(close, next);
    return true;
}

// The whitespace runs pugixml dropped before an element's first child element, split by comments
// as libxml2 feeds them. They matter to an element of empty or simple content, which then reports
// character content before the element content. Found backwards from the child's '<': runs, and
// comments jumped over, back to the '>' of the parent's start tag. False for a text or an
// instruction in that stretch, or a parent named "...-" (its '>' would look like a comment's
// end): the text is then libxml2's to read.
bool leading_whitespace(std::string_view text, pugi::xml_node element, pugi::xml_node first,
                        Runs& runs) {
    if (std::string_view(element.name()).ends_with('-')) return false;
    Runs backwards;
    std::size_t end = source_offset(first) - 1;  // the child's '<'
    for (;;) {
        std::size_t begin = end;
        while (begin > 0 && is_xml_space(text[begin - 1])) --begin;
        if (begin < end) {
            if (backwards.count == Runs::kMax) return false;
            backwards.add(begin, end);
        }
        if (begin == 0 || text[begin - 1] != '>') return false;
        if (begin < 3 || text.substr(begin - 3, 3) != "-->") {
            if (begin >= 2 && text[begin - 2] == '?') return false;
            break;  // the parent's start tag
        }
        end = text.rfind("<!--", begin - 3);
        if (end == std::string_view::npos) return false;
    }
    for (std::size_t i = backwards.count; i-- > 0;)
        runs.add(backwards.at[i][0], backwards.at[i][1]);
    return true;
}

// True when some child of element is an element.
bool has_element_child(pugi::xml_node element) {
    for (pugi::xml_node c = element.first_child(); c; c = c.next_sibling()) {
        if (c.type() == pugi::node_element) return true;
    }
    return false;
}

// The walk: the open elements, outermost first, each with the child to feed next.
class TreeFeeder {
public:
    TreeFeeder(const LoadedXml& xml, StartTag& start, const xmlSAXHandler& sax, void* user,
               TreePosition& position)
        : xml_(xml), start_(start), sax_(sax), user_(user), position_(position) {}

    // Feeds root and its subtree; false where the text is left to libxml2.
    bool run(pugi::xml_node root);

private:
    struct Open {
        pugi::xml_node element;
        const char* name;
        pugi::xml_node next;
    };

    bool enter(pugi::xml_node element);
    bool content_start(pugi::xml_node element, pugi::xml_node first);
    void text(const char* begin, std::size_t size, std::size_t offset);
    void leave();

    const LoadedXml& xml_;
    StartTag& start_;
    const xmlSAXHandler& sax_;
    void* user_;
    TreePosition& position_;
    std::vector<Open> open_;
};

void TreeFeeder::text(const char* begin, std::size_t size, std::size_t offset) {
    if (sax_.characters == nullptr) return;
    position_.at_text(offset);
    sax_.characters(user_, xml_chars(begin), static_cast<int>(size));
}

// What comes first inside an element: its embedded text, or the whitespace pugixml dropped.
bool TreeFeeder::content_start(pugi::xml_node element, pugi::xml_node first) {
    const char* value = element.value();
    if (*value != '\0') {
        if (first && has_element_child(element)) return false;  // text mixed with elements
        text(value, std::strlen(value), xml_.offset_of(value));
        return true;
    }
    // With no text embedded, a first child is an element (pugixml embeds a first text).
    Runs runs;
    const bool read = first ? leading_whitespace(xml_.text(), element, first, runs)
                            : dropped_whitespace(xml_.text(), element, runs);
    for (std::size_t i = 0; i < runs.count; ++i) {
        text(xml_.text().data() + runs.at[i][0], runs.at[i][1] - runs.at[i][0], runs.at[i][0]);
    }
    return read;
}

bool TreeFeeder::enter(pugi::xml_node element) {
    if (open_.size() >= static_cast<std::size_t>(kMaxTreeDepth)) return false;
    position_.at_start(element);
    const char* name = element.name();
    if (!start_.feed(element, name, open_.empty())) return false;
    const pugi::xml_node first = element.first_child();
    if (!content_start(element, first)) return false;
    open_.push_back({element, name, first});
    return true;
}

void TreeFeeder::leave() {
    const Open& top = open_.back();
    position_.at_end(top.element);
    if (sax_.endElementNs != nullptr)
        sax_.endElementNs(user_, xml_chars(top.name), nullptr, nullptr);
    open_.pop_back();
}

bool TreeFeeder::run(pugi::xml_node root) {
    if (!enter(root)) return false;
    std::size_t deepest = 1;
    while (!open_.empty()) {
        deepest = std::max(deepest, open_.size());
        Open& top = open_.back();
        const pugi::xml_node child = top.next;
        if (!child) {
            leave();
            continue;
        }
        top.next = child.next_sibling();
        const pugi::xml_node_type type = child.type();
        if (type == pugi::node_element) {
            if (!enter(child)) return false;
        } else if (type == pugi::node_pcdata || type == pugi::node_cdata) {
            const char* value = child.value();
            text(value, std::strlen(value), xml_.offset_of(value));
        }
    }
    xml_.note_depth_bound(deepest);
    return true;
}

}  // namespace

void TreePosition::at_start(pugi::xml_node element) {
    event_ = Event::kStart;
    element_ = element;
}

void TreePosition::at_text(std::size_t text_offset) {
    event_ = Event::kText;
    text_offset_ = text_offset;
}

void TreePosition::at_end(pugi::xml_node element) {
    event_ = Event::kEnd;
    element_ = element;
}

std::uint32_t TreePosition::line() {
    std::size_t offset = 0;
    switch (event_) {
        case Event::kStart:
            offset = end_of_start_tag(text_, source_offset(element_));
            break;
        case Event::kText:
            offset = text_.find('<', text_offset_) + 1;  // 0 when the text runs to the end
            break;
        case Event::kEnd: {
            const auto [last, depth] = last_element(element_);
            offset = end_of_element(text_, source_offset(last), depth);
            break;
        }
    }
    if (offset == 0) offset = source_offset(element_) + 1;
    return lines_.line_of(offset - 1);
}

bool TreePosition::finding_fits() const {
    if (event_ != Event::kText) return true;
    constexpr std::size_t kLibxml2Piece = 300;  // XML_PARSER_BIG_BUFFER_SIZE
    const std::size_t end = std::min(text_.find('<', text_offset_), text_.size());
    if (end - text_offset_ >= kLibxml2Piece) return false;
    for (std::size_t i = text_offset_; i < end; ++i) {
        const char c = text_[i];
        if (c == '\r' || c == '&' || static_cast<unsigned char>(c) >= 0x80) return false;
    }
    return true;
}

std::string root_schema_location(pugi::xml_node root) {
    std::vector<Binding> bindings;
    read_bindings(root, bindings);
    for (pugi::xml_attribute a = root.first_attribute(); a; a = a.next_attribute()) {
        const std::string_view name = a.name();
        const std::size_t colon = name.find(':');
        if (colon == std::string_view::npos ||
            name.substr(colon + 1) != "noNamespaceSchemaLocation")
            continue;
        const char* uri = uri_of(bindings, name.substr(0, colon));
        if (uri != nullptr && uri == kXsiNamespace) return a.value();
    }
    return {};
}

bool feed_tree(const LoadedXml& xml, bool ascii, const xmlSAXHandler& sax, void* user,
               TreePosition& position) {
    const pugi::xml_node root = xml.document().document_element();
    std::vector<Binding> bindings;
    if (!root || !read_bindings(root, bindings)) return false;
    StartTag start(sax, user, bindings, ascii);
    TreeFeeder feeder(xml, start, sax, user, position);
    return feeder.run(root);
}

}  // namespace olcb::cdi
