// Where an element stands among all the content nodes of its parent, as a DOM that keeps every
// node sees it: whitespace text runs, comments, CDATA sections, processing instructions and
// elements each count one. OpenLCB_Java (JMRI) numbers unnamed CDI elements by this index
// (JDOM's indexOf), so a backup key depends on the served file's formatting. The parser's tree
// keeps elements only; the nodes between them are counted here from the source text.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace olcb::cdi {

/// The content nodes other than elements (text runs, comments, CDATA sections, PIs) directly
/// inside an element E that lie in text between the element whose name starts at `from` and
/// offset `to` (the name of E's next child element; the scan stops at its '<'). `depth` is how
/// many elements below E are open just before the element at `from`: -1 when it is E itself
/// (the nodes before E's first child), 0 for a child of E, and so on; `from` should be the last
/// element before `to` in document order, so that only its tag and the end tags after it are
/// read. Counted as pugixml counts the children of a node parsed with parse_ws_pcdata |
/// parse_comments | parse_pi | parse_cdata; malformed text ends the count, never a crash.
std::uint32_t non_element_nodes_between(std::string_view text, std::size_t from, int depth,
                                        std::size_t to);

/// The offset just past the '>' that ends element E (its end tag, or the tag itself for <x/>),
/// scanning from the element whose name starts at `from` with `depth` as above (-1: E itself;
/// for a short scan, E's last element in document order). 0 when the text ends first.
std::size_t end_of_element(std::string_view text, std::size_t from, int depth);

/// The offset just past the '>' of the start tag whose name starts at `from`; 0 when none.
std::size_t end_of_start_tag(std::string_view text, std::size_t from);

}  // namespace olcb::cdi
