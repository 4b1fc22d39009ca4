// Recognises frames a GridConnect hub or adapter sends back to the port that sent them.
//
// Some hubs and USB adapters echo every frame to every connection, the sender's included. A node
// that took its own frames for another node's would see an alias conflict with itself. A frame
// that equals one this port sent within the window is taken for its echo and dropped, once per
// frame sent. Two different nodes never put identical frames on the bus (the source alias is
// part of the header) unless they share an alias, and that conflict still shows in every frame
// that is not a byte-exact copy of one of ours.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <unordered_map>

#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"

namespace olcb {

/// Remembers recently sent frames and recognises their echoes.
class EchoFilter {
public:
    /// Remembers at most `capacity` frames, each for `window` after it was sent.
    explicit EchoFilter(std::size_t capacity = 256, Duration window = std::chrono::seconds(2));

    /// Records a frame this port sent at `now`.
    void sent(const CanFrame& frame, TimePoint now);
    /// True (and the sent frame is forgotten) when `frame` is the echo of one sent within the
    /// window; false for every other frame.
    bool is_echo(const CanFrame& frame, TimePoint now);
    /// Forgets every sent frame (after a reconnect nothing sent before can come back).
    void clear() {
        sent_.clear();
        live_.clear();
    }
    /// Echoes recognised so far.
    std::uint64_t echoes() const { return echoes_; }

private:
    struct Sent {
        CanFrame frame;
        TimePoint at;
        std::uint64_t hash;
        bool consumed;  // its echo came: kept only until it reaches the front
    };
    void expire(TimePoint now);
    void pop_front();

    std::size_t capacity_;
    Duration window_;
    std::deque<Sent> sent_;  // oldest first
    // Unconsumed entries per frame hash: most received frames are no echo, and this answers
    // that without scanning sent_.
    std::unordered_map<std::uint64_t, std::uint32_t> live_;
    std::uint64_t echoes_ = 0;
};

}  // namespace olcb
