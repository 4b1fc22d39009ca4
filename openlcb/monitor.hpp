// A decoded, human-readable view of OpenLCB-CAN traffic: one line per frame or per message.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "openlcb/can_frame.hpp"

namespace olcb {

/// Turns frames into lines such as `343 -> 12C Datagram Received OK flags 80`.
///
/// Per-frame mode prefixes every line with the frame's GridConnect text and shows each frame;
/// when a datagram's last frame arrives its line also carries the whole datagram. Per-message
/// mode prints nothing for first/middle frames and one line for the completed message
/// (datagrams and multi-frame addressed messages such as SNIP replies). Aliases are shown as
/// 3 hex digits, node and event IDs dotted. Reassembly state is bounded: at most kMaxPartials
/// messages in progress (the oldest is forgotten) and at most 72 (datagram) or kMaxMessageBytes
/// (other) bytes each.
class Monitor {
public:
    /// One line per frame, or one per completed message.
    enum class Mode : std::uint8_t { kPerFrame, kPerMessage };

    /// Display choices.
    struct Options {
        Mode mode = Mode::kPerFrame;
        bool show_node_ids = false;  ///< append the node ID learned from AMD to known aliases
    };

    /// Renders a complete datagram (content type byte included) as text.
    using DatagramDecoder = std::function<std::string(std::span<const std::uint8_t>)>;

    /// Messages in progress kept at most.
    static constexpr std::size_t kMaxPartials = 256;
    /// Longest non-datagram addressed message reassembled.
    static constexpr std::size_t kMaxMessageBytes = 256;

    /// A per-frame monitor.
    Monitor();
    /// A monitor with the given options.
    explicit Monitor(Options options);

    /// Lets `decoder` describe datagrams whose first byte is `content_type` (replaces any).
    void register_datagram_decoder(std::uint8_t content_type, DatagramDecoder decoder);

    /// Decodes one frame; the line it completes, or nullopt when it only adds to a message.
    std::optional<std::string> decode(const CanFrame& frame);

private:
    struct Partial {
        std::vector<std::uint8_t> bytes;
        std::uint64_t serial = 0;
    };
    using Key = std::tuple<std::uint16_t, std::uint16_t, std::uint16_t>;  // src, dst, mti

    std::string alias_text(std::uint16_t alias) const;
    std::string decode_control(const CanFrame& frame) const;
    std::optional<std::string> decode_datagram(const CanFrame& frame);
    std::optional<std::string> decode_message(const CanFrame& frame);
    std::string describe_datagram(std::span<const std::uint8_t> bytes) const;
    Partial& partial(const Key& key);
    void learn_alias(const CanFrame& frame);

    Options options_;
    std::map<std::uint8_t, DatagramDecoder> decoders_;
    std::map<Key, Partial> partials_;
    std::map<std::uint16_t, std::uint64_t> node_ids_;
    std::uint64_t serial_ = 0;
};

}  // namespace olcb
