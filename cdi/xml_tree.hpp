// A compact, read-only tree of the elements of an XML document: exactly what the CDI parser
// reads (names, attributes, each element's first text, source offsets) and nothing else.
//
// Text and comment nodes are not kept; each element carries its first text instead (what
// pugixml's child_value() returns). Elements are stored in document order with the index past
// their last descendant, so walking children needs no pointers and no calls into a library.
// Strings are views into the source text, or into the tree's own storage when they had to be
// decoded; the source must outlive the tree. An element name is stored as its offset in the
// source: names are never rewritten by decoding.
#pragma once

#include <cstdint>
#include <deque>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace olcb::cdi {

/// One attribute: its name and its value (entities decoded, whitespace normalised).
struct XmlAttribute {
    std::string_view name;
    std::string_view value;
};

class XmlTree;

/// A handle on one element of an XmlTree, or on none (false); cheap to copy.
class XmlElement {
public:
    /// No element.
    XmlElement() = default;

    /// True when the handle refers to an element.
    explicit operator bool() const { return tree_ != nullptr; }
    /// The element name.
    std::string_view name() const;
    /// The first text directly inside the element ("" when none), as pugixml's child_value().
    std::string_view text() const;
    /// Byte offset of the element name in the source (just after the '<').
    std::size_t offset() const;
    /// The first child element, or none.
    XmlElement first_child() const;
    /// The next sibling element, or none.
    XmlElement next_sibling() const;
    /// The attributes in document order (duplicates kept).
    std::span<const XmlAttribute> attributes() const;
    /// The first attribute with this name, or nullptr.
    const XmlAttribute* attribute(std::string_view name) const;

private:
    friend class XmlTree;
    XmlElement(const XmlTree* tree, std::uint32_t index, std::uint32_t limit)
        : tree_(tree), index_(index), limit_(limit) {}

    const XmlTree* tree_ = nullptr;
    std::uint32_t index_ = 0;
    std::uint32_t limit_ = 0;  // end of the parent's descendants: where siblings stop
};

/// The element tree of one document; built by open()/close() calls in document order.
class XmlTree {
public:
    /// An empty tree over this source text.
    explicit XmlTree(std::string_view source) : source_(source) {}
    XmlTree(const XmlTree&) = delete;
    XmlTree& operator=(const XmlTree&) = delete;

    /// The root element, or none when the tree is empty.
    XmlElement root() const;
    /// Number of elements.
    std::size_t size() const { return nodes_.size(); }

    /// Starts an element (a child of the innermost open one) whose name is the name_size bytes
    /// of the source at offset; returns its index.
    std::uint32_t open(std::size_t offset, std::size_t name_size);
    /// Adds an attribute to the element opened last (before any child is opened).
    void add_attribute(std::string_view name, std::string_view value);
    /// Sets an element's first text.
    void set_text(std::uint32_t index, std::string_view text);
    /// True once an element's first text is set (a first text is never empty).
    bool has_text(std::uint32_t index) const { return !nodes_[index].text.empty(); }
    /// An element's name.
    std::string_view name(std::uint32_t index) const {
        return {source_.data() + nodes_[index].offset, nodes_[index].name_size};
    }
    /// Ends an element: everything opened since open() returned index is its descendants.
    void close(std::uint32_t index);
    /// Keeps a decoded string alive as long as the tree; returns a view of the kept copy.
    std::string_view keep(std::string text);
    /// Removes every element (to read the source again another way).
    void clear();
    /// Reserves room for about this many elements and attributes.
    void reserve(std::size_t elements, std::size_t attributes);

private:
    friend class XmlElement;
    struct Node {
        std::string_view text;
        std::size_t offset = 0;  // of the name in the source
        // 32-bit sizes and indices: a name or 2^32 elements that large cannot fit in memory.
        std::uint32_t name_size = 0;
        std::uint32_t end = 0;              // index past the last descendant
        std::uint32_t first_attribute = 0;  // this node's attributes run to the next node's
    };
    std::uint32_t attribute_end(std::uint32_t index) const {
        return index + 1 < nodes_.size() ? nodes_[index + 1].first_attribute
                                         : static_cast<std::uint32_t>(attributes_.size());
    }

    std::string_view source_;
    std::vector<Node> nodes_;
    std::vector<XmlAttribute> attributes_;
    std::deque<std::string> kept_;  // a deque never moves its elements: views stay valid
};

inline std::uint32_t XmlTree::open(std::size_t offset, std::size_t name_size) {
    const auto index = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({{},
                      offset,
                      static_cast<std::uint32_t>(name_size),
                      index + 1,
                      static_cast<std::uint32_t>(attributes_.size())});
    return index;
}
inline void XmlTree::add_attribute(std::string_view name, std::string_view value) {
    attributes_.push_back({name, value});
}
inline void XmlTree::set_text(std::uint32_t index, std::string_view text) {
    nodes_[index].text = text;
}
inline void XmlTree::close(std::uint32_t index) {
    nodes_[index].end = static_cast<std::uint32_t>(nodes_.size());
}

inline std::string_view XmlElement::name() const {
    return tree_->name(index_);
}
inline std::string_view XmlElement::text() const {
    return tree_->nodes_[index_].text;
}
inline std::size_t XmlElement::offset() const {
    return tree_->nodes_[index_].offset;
}
inline XmlElement XmlElement::first_child() const {
    const std::uint32_t end = tree_->nodes_[index_].end;
    return index_ + 1 < end ? XmlElement(tree_, index_ + 1, end) : XmlElement();
}
inline XmlElement XmlElement::next_sibling() const {
    const std::uint32_t next = tree_->nodes_[index_].end;
    return next < limit_ ? XmlElement(tree_, next, limit_) : XmlElement();
}
inline std::span<const XmlAttribute> XmlElement::attributes() const {
    const std::uint32_t begin = tree_->nodes_[index_].first_attribute;
    return {tree_->attributes_.data() + begin, tree_->attribute_end(index_) - begin};
}

}  // namespace olcb::cdi
