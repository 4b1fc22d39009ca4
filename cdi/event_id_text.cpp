#include "cdi/event_id_text.hpp"

#include <string>

#include "base/node_id.hpp"

namespace olcb::cdi {

std::string format_event_id(EventIdValue id) {
    return base::EventId(id).to_string();
}

CodecResult<EventIdValue> parse_event_id(std::string_view text) {
    std::string error;
    if (const auto id = base::EventId::parse(text, &error)) return id->value();
    return CodecError{error};
}

std::array<std::uint8_t, kEventIdSize> encode_event_id(EventIdValue id) {
    return base::EventId(id).to_bytes();
}

CodecResult<EventIdValue> decode_event_id(std::span<const std::uint8_t> bytes) {
    if (bytes.size() != kEventIdSize) {
        return CodecError{"an event ID has 8 bytes, not " + std::to_string(bytes.size())};
    }
    return base::EventId::from_bytes(bytes)->value();
}

}  // namespace olcb::cdi
