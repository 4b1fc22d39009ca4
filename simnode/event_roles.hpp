// Which <eventid> variables of a CDI a simulated node produces and which it consumes. The rule
// (docs/faults.md, "Events"): the nearest text that names a role decides, searching the
// variable's name and description, then each enclosing group's name and description from the
// innermost outward, then the segment's name and description. A text containing "produc"
// (any case) means producer, "consum" consumer, both means both; with no such text anywhere the
// event is consumed (a consumer never reports events, the safer guess for a simulated node).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "cdi/layout.hpp"

namespace olcb::simnode {

/// Producer, consumer or both; a bit set.
enum class EventRole : std::uint8_t { kProducer = 1, kConsumer = 2, kBoth = 3 };

/// True when role includes producing.
constexpr bool produces(EventRole role) {
    return (static_cast<std::uint8_t>(role) & 1) != 0;
}
/// True when role includes consuming.
constexpr bool consumes(EventRole role) {
    return (static_cast<std::uint8_t>(role) & 2) != 0;
}

/// One <eventid> variable after replication.
struct EventSlot {
    std::uint32_t space = 0;
    std::uint64_t address = 0;
    EventRole role = EventRole::kConsumer;
};

/// The role bits (EventRole values) a text names; 0 when it names none.
std::uint8_t role_bits_of(std::string_view text);

/// The role of the eventid variable under the cursor (a cursor of a layout of doc), by the rule
/// above.
EventRole event_role(const cdi::Cursor& cursor, const cdi::Document& doc);

/// Every eventid variable of the layout in document order, at most max_slots of them.
std::vector<EventSlot> event_slots(const cdi::Layout& layout, std::size_t max_slots);

}  // namespace olcb::simnode
