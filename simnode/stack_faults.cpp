#include "simnode/stack_faults.hpp"

#include "openlcb/can_defs.hpp"
#include "openlcb/stream_defs.hpp"

namespace olcb::simnode {

StackFaults::StackFaults(const FaultSet& faults)
    : undefended_(faults.alias_conflict_ignored),
      burst_drops_(faults.burst_drops),
      answers_standard_(faults.answers_standard_frames),
      wrong_count_(faults.stream_wrong_count),
      no_complete_(faults.stream_no_complete),
      ignore_proceed_(faults.stream_ignore_proceed),
      exceed_buffer_(faults.stream_exceed_buffer) {}

void StackFaults::attach(NodeStack& stack) {
    if (undefended_ || burst_drops_ || answers_standard_) {
        stack.set_inbound_filter(
            [this, &stack](const CanFrame& f, TimePoint now) { return route(stack, f, now); });
    }
    if (wrong_count_ || no_complete_) {
        stack.set_outbound_filter([this](Message& m) { return outbound(m); });
    }
    if (ignore_proceed_) {
        stack.streams().set_window_policy(
            [](std::uint16_t) { return StreamTransport::kUnlimitedWindow; });
    } else if (exceed_buffer_) {
        stack.streams().set_window_policy([](std::uint16_t buffer) { return 2ull * buffer; });
    }
}

FrameRoute StackFaults::route(NodeStack& stack, const CanFrame& frame, TimePoint now) {
    if (answers_standard_ && !frame.extended && !frame.remote) {
        if (stack.initialized()) {
            const Mti verified = stack.protocols().has(Protocol::kSimpleProtocol)
                                     ? Mti::kVerifiedNodeIdSimple
                                     : Mti::kVerifiedNodeId;
            const auto id = stack.node_id().to_bytes();
            stack.send_message(Message{verified, {}, std::nullopt, {id.begin(), id.end()}});
        }
        return {false, false};
    }
    FrameRoute route;
    if (!can::is_openlcb_frame(frame) || frame.len > 8) return route;
    const std::uint16_t source = can::source_alias(frame.id);
    // Without defence a frame using the node's active alias is taken as if the alias were not
    // its own: no RID on a CID, no AMR on a conflict.
    if (undefended_ && stack.alias_allocator().permitted() && source == stack.alias()) {
        route.alias = false;
    }
    // Every frame counts towards a burst, so the window is updated before anything is skipped.
    if (burst_drops_ && in_burst(now, source) && !can::is_control(frame.id) &&
        can::frame_format(frame.id) == can::FrameFormat::kGlobalAddressed &&
        is_addressed(static_cast<Mti>(can::can_mti(frame.id))) && frame.len >= 2 &&
        can::addressed_dest(frame.data[0], frame.data[1]) == stack.alias()) {
        route.messages = false;  // a receive buffer overrun by third-party traffic
    }
    return route;
}

// More than kBurstFrames frames from other sources within kBurstWindow: the requester's own
// quick exchanges do not count.
bool StackFaults::in_burst(TimePoint now, std::uint16_t source) {
    arrivals_[arrivals_seen_++ % arrivals_.size()] = {now, source};
    std::size_t others = 0;
    for (const Arrival& a : arrivals_) {
        if (a.source != source && a.at != TimePoint{} && now - a.at < kBurstWindow) ++others;
    }
    return others > kBurstFrames;
}

bool StackFaults::outbound(Message& msg) const {
    if (msg.mti != Mti::kStreamDataComplete) return true;
    if (no_complete_) return false;
    auto complete = stream::decode_data_complete(msg.payload);
    if (!complete || !complete->total_bytes) return true;
    ++*complete->total_bytes;  // one byte more than was sent
    msg.payload = stream::encode(*complete);
    return true;
}

}  // namespace olcb::simnode
