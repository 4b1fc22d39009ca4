#include "simnode/event_roles.hpp"

#include <algorithm>
#include <cctype>
#include <string>

namespace olcb::simnode {
namespace {

bool contains_folded(std::string_view text, std::string_view needle) {
    const auto it = std::search(
        text.begin(), text.end(), needle.begin(), needle.end(),
        [](char a, char b) { return std::tolower(static_cast<unsigned char>(a)) == b; });
    return it != text.end();
}

}  // namespace

std::uint8_t role_bits_of(std::string_view text) {
    std::uint8_t bits = 0;
    if (contains_folded(text, "produc")) bits |= static_cast<std::uint8_t>(EventRole::kProducer);
    if (contains_folded(text, "consum")) bits |= static_cast<std::uint8_t>(EventRole::kConsumer);
    return bits;
}

EventRole event_role(const cdi::Cursor& cursor, const cdi::Document& doc) {
    const auto decide = [](const std::string& name, const std::string& description) {
        const std::uint8_t bits = role_bits_of(name);
        return bits != 0 ? bits : role_bits_of(description);
    };
    const cdi::Element& var = cursor.element();
    if (auto bits = decide(var.name, var.description)) return static_cast<EventRole>(bits);
    for (std::size_t level = cursor.group_depth(); level-- > 0;) {
        const cdi::Element& g = cursor.group(level);
        if (auto bits = decide(g.name, g.description)) return static_cast<EventRole>(bits);
    }
    if (cursor.segment_index() < doc.segments.size()) {
        const cdi::Segment& seg = doc.segments[cursor.segment_index()];
        if (auto bits = decide(seg.name, seg.description)) return static_cast<EventRole>(bits);
    }
    return EventRole::kConsumer;
}

std::vector<EventSlot> event_slots(const cdi::Layout& layout, std::size_t max_slots) {
    std::vector<EventSlot> slots;
    layout.visit([&](const cdi::Cursor& c) {
        if (slots.size() >= max_slots) return false;
        if (c.element().kind == cdi::ElementKind::kEventId && c.size() == 8) {
            slots.push_back(EventSlot{c.space(), c.address(), event_role(c, layout.document())});
        }
        return true;
    });
    return slots;
}

}  // namespace olcb::simnode
