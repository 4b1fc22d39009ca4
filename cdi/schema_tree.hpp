// Feeds a loaded document to a schema validator as libxml2's parser would feed it SAX events, so
// a text pugixml has read (and xml_screen.hpp has passed) is validated without a second parse.
#pragma once

#include <libxml/parser.h>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "cdi/line_counter.hpp"
#include "cdi/loaded_xml.hpp"

namespace olcb::cdi {

/// Deeper documents are left to libxml2's own parse: the end-tag lines below are found by
/// scanning, which deep nesting would make quadratic.
inline constexpr int kMaxTreeDepth = 256;

/// Which event the walk fed last, so that the validator's findings get the line libxml2's parser
/// would have been on: the '>' of a start tag, the end of a text, the '>' of an end tag.
class TreePosition {
public:
    /// Positions in `text`, the source of the loaded document.
    explicit TreePosition(std::string_view text) : text_(text), lines_(text) {}

    /// The walk fed the start tag of element, its text (at `text_offset`), or its end tag.
    void at_start(pugi::xml_node element);
    void at_text(std::size_t text_offset);
    void at_end(pugi::xml_node element);

    /// The line of the event fed last (computed only when asked: the validator asks on errors).
    std::uint32_t line();

    /// False when the event fed last is a text libxml2's parser would have fed in pieces (it
    /// splits at a CR, a reference, a non-ASCII character, or 300 bytes): a finding about it
    /// may then come at another line, or once per piece, so the tree cannot stand in for it.
    bool finding_fits() const;

private:
    enum class Event : std::uint8_t { kStart, kText, kEnd };
    std::string_view text_;
    LineCounter lines_;
    Event event_ = Event::kStart;
    pugi::xml_node element_;
    std::size_t text_offset_ = 0;
};

/// The root's xsi:noNamespaceSchemaLocation ("" when absent), through the prefixes it declares.
std::string root_schema_location(pugi::xml_node root);

/// Feeds the document's root element and everything in it to `sax` (start tags with their
/// attributes namespace-resolved, texts, end tags), telling `position` each event first; `ascii`
/// says the text has no byte above 0x7F (the screen's finding), so names need less looking at.
/// Stops and returns false at what the walk does not resolve as libxml2 would (a prefixed or
/// non-ASCII name, a default namespace, a namespace declared below the root or to a doubtful
/// URI, an undeclared or reserved prefix, two attributes of one local name, '<' in an attribute
/// value, nesting deeper than kMaxTreeDepth): the caller then parses the text with libxml2.
bool feed_tree(const LoadedXml& xml, bool ascii, const xmlSAXHandler& sax, void* user,
               TreePosition& position);

}  // namespace olcb::cdi
