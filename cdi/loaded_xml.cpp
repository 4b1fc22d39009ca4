#include "cdi/loaded_xml.hpp"

namespace olcb::cdi {
namespace {

// parse_doctype keeps a DOCTYPE as a node so it can be refused; pugixml never expands entities
// it does not know, so a billion-laughs DTD costs one linear scan. parse_embed_pcdata stores an
// element's first text in the element: fewer nodes.
constexpr unsigned kPugixmlOptions =
    pugi::parse_default | pugi::parse_doctype | pugi::parse_embed_pcdata;

}  // namespace

std::string_view without_trailing_nuls(std::string_view bytes) {
    while (!bytes.empty() && bytes.back() == '\0') bytes.remove_suffix(1);
    return bytes;
}

LoadedXml::LoadedXml(std::string_view bytes) : text_(without_trailing_nuls(bytes)), buffer_(text_) {
    result_ = document_.load_buffer_inplace(buffer_.data(), buffer_.size(), kPugixmlOptions,
                                            pugi::encoding_utf8);
}

std::size_t source_offset(pugi::xml_node node) {
    const std::ptrdiff_t offset = node.offset_debug();
    return offset < 0 ? 0 : static_cast<std::size_t>(offset);
}

std::pair<pugi::xml_node, int> last_element(pugi::xml_node e) {
    int depth = -1;
    for (;;) {
        pugi::xml_node c = e.last_child();
        while (c && c.type() != pugi::node_element) c = c.previous_sibling();
        if (!c) return {e, depth};
        e = c;
        ++depth;
    }
}

}  // namespace olcb::cdi
