#include "cdi/pugixml_tree.hpp"

#include <cstring>
#include <utility>
#include <vector>

namespace olcb::cdi {

void copy_pugixml_elements(pugi::xml_node root, XmlTree& tree) {
    // Names are located in the source by offset_debug(): pugixml parses a copy of the source
    // in place and never rewrites the bytes of a name.
    const auto add = [&tree](pugi::xml_node node) {
        const std::uint32_t index =
            tree.open(static_cast<std::size_t>(node.offset_debug()), std::strlen(node.name()));
        for (pugi::xml_attribute attr : node.attributes()) {
            tree.add_attribute(attr.name(), attr.value());
        }
        tree.set_text(index, node.child_value());
        return index;
    };
    std::vector<std::pair<pugi::xml_node, std::uint32_t>> open;
    open.emplace_back(root, add(root));
    pugi::xml_node next = root.first_child();
    for (;;) {
        while (next && next.type() != pugi::node_element) next = next.next_sibling();
        if (next) {
            open.emplace_back(next, add(next));
            next = next.first_child();
            continue;
        }
        const auto [node, index] = open.back();
        open.pop_back();
        tree.close(index);
        if (open.empty()) return;
        next = node.next_sibling();
    }
}

}  // namespace olcb::cdi
