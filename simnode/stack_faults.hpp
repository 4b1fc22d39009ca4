// The faults that break rules below the node's answers, on the frames and the stream window:
// hooks on the node's NodeStack (its inbound frame filter, outbound message filter and stream
// window policy), so the sans-I/O core keeps no misbehaviour of its own.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "openlcb/node_stack.hpp"
#include "simnode/faults.hpp"

namespace olcb::simnode {

/// A burst for burst-drops: more than this many frames from other sources than an addressed
/// message's ...
inline constexpr std::size_t kBurstFrames = 16;
/// ... within this long.
inline constexpr Duration kBurstWindow = std::chrono::milliseconds(10);

/// alias-conflict-ignored, burst-drops, answers-standard-frames and the stream-* faults of one
/// node. Must outlive the stack it is attached to.
class StackFaults {
public:
    explicit StackFaults(const FaultSet& faults);
    StackFaults(const StackFaults&) = delete;
    StackFaults& operator=(const StackFaults&) = delete;

    /// Installs on stack the hooks the faults need (none when none of them is on).
    void attach(NodeStack& stack);

private:
    FrameRoute route(NodeStack& stack, const CanFrame& frame, TimePoint now);
    bool in_burst(TimePoint now, std::uint16_t source);
    bool outbound(Message& msg) const;

    bool undefended_;
    bool burst_drops_;
    bool answers_standard_;
    bool wrong_count_;
    bool no_complete_;
    bool ignore_proceed_;
    bool exceed_buffer_;
    // Arrival times and sources of the last frames (burst-drops), a ring.
    struct Arrival {
        TimePoint at{};
        std::uint16_t source = 0;
    };
    std::array<Arrival, 4 * kBurstFrames> arrivals_{};
    std::size_t arrivals_seen_ = 0;
};

}  // namespace olcb::simnode
