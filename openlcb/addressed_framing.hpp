// Messages <-> CAN frames (fact sheet 2.2, 2.3, 4.1): format-1 global and addressed messages with
// the framing nibble, datagram formats 2-5, stream format 7, Event Report With Payload.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "base/timings.hpp"
#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/message.hpp"

namespace olcb {

/// Why a message could not be framed.
enum class FramingError : std::uint8_t {
    kNone,
    kMissingSourceAlias,       ///< source alias 0
    kMissingDestinationAlias,  ///< addressed, datagram or stream message without dest alias
    kBadPayloadLength,         ///< too long for its kind (global > 8, datagram > 72, ...)
};

/// Sentence describing a FramingError.
std::string_view framing_error_text(FramingError error);

/// Payload bytes an addressed format-1 frame carries after `fddd`.
inline constexpr std::size_t kAddressedBytesPerFrame = 6;
/// Largest payload of an Event Report With Payload (8-byte event ID + 256 bytes).
inline constexpr std::size_t kMaxPcerPayload = 8 + 256;

/// Appends the CAN frames of msg to out (nothing is appended on error).
FramingError encode_message(const Message& msg, std::vector<CanFrame>& out);

/// Tunables of MessageAssembler; every limit bounds memory against hostile input.
struct MessageAssemblerConfig {
    /// Multi-frame messages reassembled at once; the oldest is dropped beyond this.
    std::size_t max_in_progress = 32;
    /// Largest reassembled payload (addressed messages, PCER with payload); longer are dropped.
    std::size_t max_payload = kMaxPcerPayload;
    /// A partial message idle this long is dropped: by then its requester may have given up.
    Duration timeout = base::kRequesterTimeout;
    /// Also reassemble datagram frames (formats 2-5) without answering them (for monitors).
    bool datagrams = false;
};

/// Reassembles messages from CAN frames per (source alias, destination alias, MTI). It never
/// answers on the wire; datagram accept/reject is DatagramReceiver's job.
class MessageAssembler {
public:
    /// Assembler with the given limits.
    explicit MessageAssembler(MessageAssemblerConfig config = {}) : config_(config) {}

    /// Feeds one frame; returns the message it completes, if any. Control frames, standard and
    /// remote frames are ignored.
    std::optional<Message> on_frame(const CanFrame& frame, TimePoint now);
    /// Drops partial messages idle for longer than the timeout.
    void poll(TimePoint now);
    /// When poll() next has something to drop.
    std::optional<TimePoint> next_deadline() const;
    /// Forgets all partial messages.
    void clear() { partials_.clear(); }

    /// Partial messages held now.
    std::size_t in_progress() const { return partials_.size(); }
    /// Frames or partial messages dropped as malformed, out of order, too long or stale.
    std::uint64_t errors() const { return errors_; }

private:
    struct Partial {
        std::uint16_t src;
        std::uint16_t dst;
        Mti mti;
        TimePoint last;
        std::vector<std::uint8_t> data;
    };

    std::optional<Message> on_addressed(const CanFrame& frame, TimePoint now);
    std::optional<Message> on_pcer_payload(const CanFrame& frame, TimePoint now);
    std::optional<Message> on_datagram(const CanFrame& frame, TimePoint now);
    // Shared first/middle/last logic; limit is the largest payload for this kind.
    std::optional<Message> step(std::uint16_t src, std::uint16_t dst, Mti mti, bool first,
                                bool last, const std::uint8_t* bytes, std::size_t count,
                                std::size_t limit, TimePoint now);
    Partial* find(std::uint16_t src, std::uint16_t dst, Mti mti);
    void erase(Partial* p);

    MessageAssemblerConfig config_;
    std::vector<Partial> partials_;
    std::uint64_t errors_ = 0;
};

}  // namespace olcb
