#include "simnode/audit/alias_watch.hpp"

#include <span>
#include <string>

#include "openlcb/can_defs.hpp"
#include "openlcb/mti.hpp"
#include "simnode/audit/audit_limits.hpp"

namespace olcb::simnode::audit {
namespace {

using can::ControlFrame;

// All four CID frames (CID7..CID4) of one reservation came.
constexpr std::uint8_t kAllCids = 0x0F;

std::optional<Mti> message_mti(const CanFrame& frame) {
    if (!can::is_message(frame.id) ||
        can::frame_format(frame.id) != can::FrameFormat::kGlobalAddressed) {
        return std::nullopt;
    }
    return static_cast<Mti>(can::can_mti(frame.id));
}

// What a frame is, for messages: "AMD", "Verify Node ID Global", "a datagram frame".
std::string what_frame(const CanFrame& frame) {
    if (can::is_control(frame.id)) return can::control_name(can::classify_control(frame.id));
    if (const auto mti = message_mti(frame)) {
        const std::string_view name = mti_name(*mti);
        if (!name.empty()) return std::string(name);
        return "a message";
    }
    return can::is_datagram_format(can::frame_format(frame.id)) ? "a datagram frame"
                                                                : "a stream frame";
}

// The frame that starts a message (a datagram's first or only frame, an addressed message's
// first or only frame): a message before Initialization Complete is counted once, not per frame.
bool starts_message(const CanFrame& frame) {
    switch (can::frame_format(frame.id)) {
        case can::FrameFormat::kDatagramOnly:
        case can::FrameFormat::kDatagramFirst:
        case can::FrameFormat::kStreamData:
            return true;
        case can::FrameFormat::kGlobalAddressed:
            break;
        default:
            return false;
    }
    if (frame.len < 2 || !is_addressed(static_cast<Mti>(can::can_mti(frame.id)))) return true;
    const auto framing = can::addressed_framing(frame.data[0]);
    return framing == can::AddressedFraming::kOnly || framing == can::AddressedFraming::kFirst;
}

bool is_initialization_complete(const CanFrame& frame) {
    const auto mti = message_mti(frame);
    return mti == Mti::kInitializationComplete || mti == Mti::kInitializationCompleteSimple;
}

bool carries_node_id(const CanFrame& frame) {
    if (frame.len < NodeId::kSize) return false;
    if (can::is_control(frame.id)) {
        const auto kind = can::classify_control(frame.id);
        return kind == ControlFrame::kAmd;
    }
    const auto mti = message_mti(frame);
    return mti == Mti::kInitializationComplete || mti == Mti::kInitializationCompleteSimple ||
           mti == Mti::kVerifiedNodeId || mti == Mti::kVerifiedNodeIdSimple;
}

}  // namespace

void AliasWatch::on_client_frame(const CanFrame& frame, std::uint64_t connection,
                                 std::optional<std::uint16_t> dest_node, TimePoint now) {
    const std::uint16_t alias = can::source_alias(frame.id);
    ctx_.note_client(alias, connection);
    learn_node_id(alias, frame);
    State& s = state_of(alias, connection, frame);
    if (can::is_control(frame.id)) {
        on_control(s, frame, dest_node, now);
    } else {
        require_permitted(s, frame, dest_node, now);
        judge_initialized(s, frame, dest_node, now);
    }
}

void AliasWatch::forget(std::uint16_t alias) {
    const auto it = states_.find(alias);
    if (it == states_.end()) return;
    if (it->second.mapped) initialized_.erase(it->second.mapped->value());
    states_.erase(it);
}

bool AliasWatch::on_node_frame(const CanFrame& frame) {
    const std::uint16_t alias = can::source_alias(frame.id);
    // A node only trying an alias (CID) does not hold it yet; anything else claims it.
    if (!can::is_cid(frame.id)) states_.erase(alias);
    const auto id = carries_node_id(frame)
                        ? NodeId::from_bytes(std::span<const std::uint8_t>(frame.data.data(), 6))
                        : std::nullopt;
    if (can::is_control(frame.id)) {
        const auto kind = can::classify_control(frame.id);
        if (kind == ControlFrame::kAmr) {
            ctx_.release_node_alias(alias);
            return true;
        }
        if (kind == ControlFrame::kAmd && id) {
            if (const auto index = ctx_.node_index(*id)) ctx_.set_node_alias(alias, *index);
        }
        return false;
    }
    const auto mti = message_mti(frame);
    if ((mti == Mti::kInitializationComplete || mti == Mti::kInitializationCompleteSimple) && id) {
        if (const auto index = ctx_.node_index(*id)) ctx_.set_node_alias(alias, *index);
        return true;
    }
    return false;
}

AliasWatch::State& AliasWatch::state_of(std::uint16_t alias, std::uint64_t connection,
                                        const CanFrame& frame) {
    auto [it, fresh] = states_.try_emplace(alias);
    // A bridged bus carries nodes that reserved their aliases before simnode joined it.
    if (fresh && ctx_.kind(connection) == ConnectionKind::kBridge && !can::is_cid(frame.id)) {
        it->second.phase = Phase::kPermitted;
    }
    return it->second;
}

void AliasWatch::on_control(State& s, const CanFrame& frame, std::optional<std::uint16_t> dest,
                            TimePoint now) {
    switch (can::classify_control(frame.id)) {
        case ControlFrame::kCid7:
        case ControlFrame::kCid6:
        case ControlFrame::kCid5:
        case ControlFrame::kCid4:
            on_cid(s, frame, now);
            return;
        case ControlFrame::kRid:
            // RID is also how a holder defends its alias; only after all four CIDs does it
            // complete a reservation.
            if (s.phase == Phase::kChecking && s.cids_seen == kAllCids) {
                if (now - s.last_cid < kReservationWait - kArrivalJitter) {
                    const auto waited =
                        std::chrono::duration_cast<std::chrono::milliseconds>(now - s.last_cid);
                    ctx_.report(RuleId::kAliasRidTooEarly, can::source_alias(frame.id), dest,
                                "RID for alias " + alias_text(can::source_alias(frame.id)) + " " +
                                    std::to_string(waited.count()) +
                                    " ms after its last CID frame (at least 200 ms)",
                                std::span(&frame, 1), "", now);
                }
                s.phase = Phase::kReserved;
            }
            return;
        case ControlFrame::kAmd:
            if (s.phase == Phase::kReserved) {
                s.phase = Phase::kPermitted;
                if (frame.len >= NodeId::kSize)
                    s.mapped = NodeId::from_bytes(
                        std::span<const std::uint8_t>(frame.data.data(), NodeId::kSize));
                return;
            }
            require_permitted(s, frame, dest, now);
            return;
        case ControlFrame::kAmr:
            require_permitted(s, frame, dest, now);
            s.phase = Phase::kReleased;
            return;
        default:
            require_permitted(s, frame, dest, now);
            return;
    }
}

void AliasWatch::on_cid(State& s, const CanFrame& frame, TimePoint now) {
    // A holder re-checking its own alias keeps it; anyone else starts a reservation.
    if (s.phase == Phase::kPermitted || s.phase == Phase::kReserved) return;
    const int n = static_cast<int>(can::content(frame.id) >> 12);
    if (s.phase != Phase::kChecking || n == 7) s = State{Phase::kChecking};
    s.cids_seen |= static_cast<std::uint8_t>(1u << (n - 4));
    s.cid_bits |= std::uint64_t{can::cid_node_id_bits(frame.id)} << (12 * (n - 4));
    s.last_cid = now;
    if (s.cids_seen == kAllCids)
        ctx_.set_client_node_id(can::source_alias(frame.id), NodeId(s.cid_bits));
}

void AliasWatch::require_permitted(const State& s, const CanFrame& frame,
                                   std::optional<std::uint16_t> dest, TimePoint now) {
    if (s.phase == Phase::kPermitted) return;
    const std::uint16_t alias = can::source_alias(frame.id);
    std::string why;
    switch (s.phase) {
        case Phase::kChecking:
            why = "before its reservation was complete (no RID after CID7-CID4)";
            break;
        case Phase::kReserved:
            why = "reserved but not mapped (no AMD yet: still Inhibited)";
            break;
        case Phase::kReleased:
            why = "after giving it up with AMR";
            break;
        default:
            why = "which it never reserved (CID7-CID4, RID) nor mapped (AMD) on this connection";
            break;
    }
    ctx_.report(RuleId::kAliasUnreserved, alias, dest,
                what_frame(frame) + " from alias " + alias_text(alias) + ", " + why,
                std::span(&frame, 1), "", now);
}

// Only aliases the audit saw reserved and mapped are judged: an alias that was never reserved
// is alias.unreserved's, and a bridged bus's nodes may have started before simnode joined it.
void AliasWatch::judge_initialized(const State& s, const CanFrame& frame,
                                   std::optional<std::uint16_t> dest, TimePoint now) {
    if (s.phase != Phase::kPermitted || !s.mapped) return;
    if (is_initialization_complete(frame)) {
        initialized_.insert(s.mapped->value());
        return;
    }
    if (initialized_.contains(s.mapped->value()) || !starts_message(frame)) return;
    const std::uint16_t alias = can::source_alias(frame.id);
    const std::string what =
        can::is_datagram_format(can::frame_format(frame.id)) ? "a datagram" : what_frame(frame);
    ctx_.report(RuleId::kMessageBeforeInitComplete, alias, dest,
                what + " from alias " + alias_text(alias) + " (node " + s.mapped->to_string() +
                    ") before its Initialization Complete",
                std::span(&frame, 1), "", now);
}

void AliasWatch::learn_node_id(std::uint16_t alias, const CanFrame& frame) {
    if (!carries_node_id(frame)) return;
    if (const auto id =
            NodeId::from_bytes(std::span<const std::uint8_t>(frame.data.data(), NodeId::kSize)))
        ctx_.set_client_node_id(alias, *id);
}

}  // namespace olcb::simnode::audit
