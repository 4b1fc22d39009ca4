// Event ID ranges as Producer/Consumer Range Identified carry them (EventTransportS §4.5, fact
// sheet §9): the trailing run of bits equal to bit 0 is the mask of "don't care" bits. Also which
// Identified messages name a single event.
#pragma once

#include <cstdint>

#include "base/node_id.hpp"
#include "openlcb/mti.hpp"

namespace olcb {

/// Producer Identified Valid/Invalid/Reserved/Unknown: one event, produced.
constexpr bool is_producer_identified(Mti m) {
    return to_u16(m) >= to_u16(Mti::kProducerIdentifiedValid) &&
           to_u16(m) <= to_u16(Mti::kProducerIdentifiedUnknown);
}

/// Consumer Identified Valid/Invalid/Reserved/Unknown: one event, consumed.
constexpr bool is_consumer_identified(Mti m) {
    return to_u16(m) >= to_u16(Mti::kConsumerIdentifiedValid) &&
           to_u16(m) <= to_u16(Mti::kConsumerIdentifiedUnknown);
}

/// The don't-care bits of a range event ID: the trailing run of bits equal to bit 0.
constexpr std::uint64_t range_mask(EventId range) {
    const std::uint64_t r = range.value();
    return ((r & 1) ? (r ^ (r + 1)) : (r ^ (r - 1))) >> 1;
}

/// True when id lies in the range.
constexpr bool in_range(EventId id, EventId range) {
    const std::uint64_t keep = ~range_mask(range);
    return (id.value() & keep) == (range.value() & keep);
}

/// The first event ID of the range.
constexpr EventId range_first(EventId range) {
    return EventId(range.value() & ~range_mask(range));
}

/// The last event ID of the range.
constexpr EventId range_last(EventId range) {
    return EventId(range.value() | range_mask(range));
}

/// The range ID of the aligned block of 2^bits event IDs (bits 1..63) holding first: its
/// don't-care bits are the complement of the next bit up, so the run ends there.
constexpr EventId make_range(EventId first, unsigned bits) {
    const std::uint64_t low = (std::uint64_t{1} << bits) - 1;
    const std::uint64_t base = first.value() & ~low;
    return EventId(((base >> bits) & 1) != 0 ? base : base | low);
}

}  // namespace olcb
