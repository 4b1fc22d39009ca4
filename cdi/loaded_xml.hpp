// One pugixml parse of a CDI text kept with the text it was made from, so the model parser can
// find in the source what the tree drops (lines, the content index).
#pragma once

#include <pugixml.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace olcb::cdi {

/// A CDI text (trailing NUL terminators dropped) and pugixml's in-place parse of a copy of it.
/// Element names keep their byte offsets, so the original text tells what the tree drops.
class LoadedXml {
public:
    /// Parses a copy of `bytes`; `text()` stays a view of `bytes`, which must outlive this.
    explicit LoadedXml(std::string_view bytes);
    LoadedXml(const LoadedXml&) = delete;
    LoadedXml& operator=(const LoadedXml&) = delete;

    /// The source text, without trailing NUL bytes.
    std::string_view text() const { return text_; }
    /// pugixml's verdict (an error status and its offset when the text is not XML to it).
    const pugi::xml_parse_result& result() const { return result_; }
    /// The parsed document; meaningful only when result() is a success.
    const pugi::xml_document& document() const { return document_; }

    /// Records that no element lies deeper than `depth` (1: the root alone), as a walk over the
    /// whole tree found; a later walk that only checks depth can then be skipped.
    void note_depth_bound(std::size_t depth) const { depth_bound_ = depth; }
    /// The bound noted, if a walk noted one.
    std::optional<std::size_t> depth_bound() const { return depth_bound_; }

private:
    mutable std::optional<std::size_t> depth_bound_;  // a finding about the tree, not state
    std::string_view text_;
    std::string buffer_;  // pugixml rewrites texts in place as it decodes them
    pugi::xml_document document_;
    pugi::xml_parse_result result_;
};

/// `bytes` without the NUL terminators a node serves after the CDI text.
std::string_view without_trailing_nuls(std::string_view bytes);

/// The byte offset of an element's name in the source (pugixml parses in place and never moves a
/// name); 0 for a null node.
std::size_t source_offset(pugi::xml_node node);

/// The last element of e's subtree in document order and its depth below e (-1: e itself), as
/// content_index.hpp's scans take them.
std::pair<pugi::xml_node, int> last_element(pugi::xml_node e);

}  // namespace olcb::cdi
