// Frame faults: CAN frames and alias handling.
#include <array>
#include <memory>

#include "openlcb/can_defs.hpp"
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

/// A burst for burst-drops: more than this many frames from other sources than an addressed
/// message's ...
constexpr std::size_t kBurstFrames = 16;
/// ... within this long.
constexpr Duration kBurstWindow = std::chrono::milliseconds(10);

// Without defence a frame using the node's active alias is taken as if the alias were not its
// own: no RID on a CID, no AMR on a conflict.
void undefended(StackHooks& hooks, FaultValue) {
    hooks.add_inbound([](NodeStack& stack, const CanFrame& frame, TimePoint) {
        FrameRoute route;
        if (can::is_openlcb_frame(frame) && frame.len <= 8 && stack.alias_allocator().permitted() &&
            can::source_alias(frame.id) == stack.alias()) {
            route.alias = false;
        }
        return route;
    });
}

// Arrival times and sources of the last frames, a ring: more than kBurstFrames frames from other
// sources within kBurstWindow make a burst (the requester's own quick exchanges do not count).
class BurstWatch {
public:
    bool in_burst(TimePoint now, std::uint16_t source) {
        arrivals_[seen_++ % arrivals_.size()] = {now, source};
        std::size_t others = 0;
        for (const Arrival& a : arrivals_) {
            if (a.source != source && a.at != TimePoint{} && now - a.at < kBurstWindow) ++others;
        }
        return others > kBurstFrames;
    }

private:
    struct Arrival {
        TimePoint at{};
        std::uint16_t source = 0;
    };
    std::array<Arrival, 4 * kBurstFrames> arrivals_{};
    std::size_t seen_ = 0;
};

// A receive buffer overrun by third-party traffic: addressed messages to the node are lost.
void drop_in_bursts(StackHooks& hooks, FaultValue) {
    hooks.add_inbound([watch = std::make_shared<BurstWatch>()](
                          NodeStack& stack, const CanFrame& frame, TimePoint now) {
        FrameRoute route;
        if (!can::is_openlcb_frame(frame) || frame.len > 8) return route;
        // Every frame counts towards a burst, so the window is updated before anything is
        // skipped.
        if (watch->in_burst(now, can::source_alias(frame.id)) && !can::is_control(frame.id) &&
            can::frame_format(frame.id) == can::FrameFormat::kGlobalAddressed &&
            is_addressed(static_cast<Mti>(can::can_mti(frame.id))) && frame.len >= 2 &&
            can::addressed_dest(frame.data[0], frame.data[1]) == stack.alias()) {
            route.messages = false;
        }
        return route;
    });
}

void answer_standard_frames(StackHooks& hooks, FaultValue) {
    hooks.add_inbound([](NodeStack& stack, const CanFrame& frame, TimePoint) {
        if (frame.extended || frame.remote) return FrameRoute{};
        if (stack.initialized()) {
            const Mti verified = stack.protocols().has(Protocol::kSimpleProtocol)
                                     ? Mti::kVerifiedNodeIdSimple
                                     : Mti::kVerifiedNodeId;
            const auto id = stack.node_id().to_bytes();
            stack.send_message(Message{verified, {}, std::nullopt, {id.begin(), id.end()}});
        }
        return FrameRoute{false, false};
    });
}

}  // namespace

std::vector<FaultDecl> frame_faults() {
    return {
        {
            .name = "alias-conflict-ignored",
            .order = 210,
            .summary = "alias not defended: no RID on CID, no AMR on conflict",
            .rule_broken = "CAN 6.2/6.3: answer CID with RID; on a frame using our alias send "
                           "AMR and stop using it (fact sheet 1.6)",
            .client_sees = "no RID on CID for its alias, no AMR when another node uses it: it "
                           "keeps transmitting with the duplicated alias",
            .verdict = Verdict::kFail,
            .category = "frame",
            .checks = {"frame.cid-defended", "frame.collision"},
            .hooks = {.stack = undefended},
        },
        {
            .name = "burst-drops",
            .order = 410,
            .summary = "addressed messages dropped while more than 16 frames arrived in the last "
                       "10 ms",
            .rule_broken = "CAN / MsgNet: a node takes every frame of a busy bus; OlcbChecker "
                           "fr50 sends 300 frames back to back around an addressed Verify Node ID",
            .client_sees = "while more than 16 extended frames from sources other than the "
                           "message's own (of any kind; standard and remote frames do not count) "
                           "arrived within the last 10 ms, every addressed message to the node "
                           "(format 1 frames, e.g. Verify Node ID addressed, Protocol Support "
                           "Inquiry, SNIP request) is dropped without answer; global messages "
                           "and datagrams are handled as usual; after 10 ms with at most 16 such "
                           "frames it answers again; the requester's own quick exchanges (a tool "
                           "reading over TCP) never count",
            .verdict = Verdict::kWarn,
            .category = "frame",
            .checks = {"frame.capacity"},
            .hooks = {.stack = drop_in_bursts},
        },
        {
            .name = "answers-standard-frames",
            .order = 420,
            .summary = "every standard (11-bit) frame answered with a Verified Node ID",
            .rule_broken = "CAN: standard (11-bit) frames are not OpenLCB frames and are ignored "
                           "(fact sheet 1; OlcbChecker fr60)",
            .client_sees = "every standard data frame (any ID, any data) makes the node send one "
                           "Verified Node ID (`0x19170sss` + node ID); remote frames stay ignored",
            .verdict = Verdict::kFail,
            .category = "frame",
            .checks = {"frame.standard-frames-ignored"},
            .hooks = {.stack = answer_standard_frames},
        },
    };
}

}  // namespace olcb::simnode
