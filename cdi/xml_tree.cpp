#include "cdi/xml_tree.hpp"

namespace olcb::cdi {

XmlElement XmlTree::root() const {
    if (nodes_.empty()) return {};
    return XmlElement(this, 0, nodes_[0].end);
}

std::string_view XmlTree::keep(std::string text) {
    return kept_.emplace_back(std::move(text));
}

void XmlTree::clear() {
    nodes_.clear();
    attributes_.clear();
    kept_.clear();
}

void XmlTree::reserve(std::size_t elements, std::size_t attributes) {
    nodes_.reserve(elements);
    attributes_.reserve(attributes);
}

const XmlAttribute* XmlElement::attribute(std::string_view name) const {
    for (const XmlAttribute& attribute : attributes()) {
        if (attribute.name == name) return &attribute;
    }
    return nullptr;
}

}  // namespace olcb::cdi
