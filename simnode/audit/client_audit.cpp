#include "simnode/audit/client_audit.hpp"

#include <algorithm>
#include <string>

#include "base/hex.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/mti.hpp"
#include "simnode/audit/audit_limits.hpp"

namespace olcb::simnode::audit {
namespace {

// The alias a message frame is addressed to: datagram and stream frames in the header, format-1
// addressed messages in their first two data bytes.
std::optional<std::uint16_t> destination(const CanFrame& frame) {
    if (!can::is_message(frame.id)) return std::nullopt;
    const auto format = can::frame_format(frame.id);
    if (can::is_datagram_format(format) || format == can::FrameFormat::kStreamData)
        return can::dest_alias(frame.id);
    if (format != can::FrameFormat::kGlobalAddressed || frame.len < 2) return std::nullopt;
    if (!is_addressed(static_cast<Mti>(can::can_mti(frame.id)))) return std::nullopt;
    return can::addressed_dest(frame.data[0], frame.data[1]);
}

bool is_allocated(std::uint16_t can_mti_value) {
    // Event Report With Payload's first and middle frames carry CAN-MTIs of their own.
    return !mti_name(can_mti_value).empty() || can_mti_value == can::kCanMtiPcerPayloadFirst ||
           can_mti_value == can::kCanMtiPcerPayloadMiddle;
}

}  // namespace

ClientAudit::ClientAudit(TimePoint start)
    : ctx_(start),
      aliases_(ctx_),
      memory_(ctx_),
      datagrams_(ctx_, [this](std::uint16_t client, std::uint16_t node,
                              std::span<const std::uint8_t> payload,
                              std::span<const CanFrame> frames, TimePoint now) {
          memory_.on_datagram(client, node, payload, frames, now);
      }) {}

void ClientAudit::on_frame(const CanFrame& frame, Direction direction, std::uint64_t connection,
                           TimePoint now) {
    // Standard and remote frames are not OpenLCB's: nodes ignore them, so does the audit.
    if (finished_ || !can::is_openlcb_frame(frame)) return;
    if (direction == Direction::kFromNode) {
        on_node_frame(frame, now);
    } else {
        on_client_frame(frame, connection, now);
    }
}

void ClientAudit::on_client_frame(const CanFrame& frame, std::uint64_t connection, TimePoint now) {
    end_reused_alias(can::source_alias(frame.id), connection, now);
    std::optional<std::uint16_t> node = destination(frame);
    if (node && ctx_.node_at(*node) == nullptr) node.reset();
    aliases_.on_client_frame(frame, connection, node, now);
    judge_mti(frame, node, now);
    if (node) datagrams_.on_client_frame(frame, *node, now);
}

void ClientAudit::on_node_frame(const CanFrame& frame, TimePoint now) {
    const std::uint16_t alias = can::source_alias(frame.id);
    if (aliases_.on_node_frame(frame)) {
        datagrams_.node_restarted(alias);
        memory_.node_restarted(alias, now);
    }
    // Only a node the audit knows has its client's answers routed back to its exchanges: one it
    // did not know would leave every reply unacknowledged.
    const auto client = destination(frame);
    if (client && ctx_.node_at(alias) != nullptr && ctx_.node_at(*client) == nullptr)
        datagrams_.on_node_frame(frame, *client, now);
}

void ClientAudit::judge_mti(const CanFrame& frame, std::optional<std::uint16_t> node,
                            TimePoint now) {
    if (!can::is_message(frame.id)) return;
    const auto format = can::frame_format(frame.id);
    std::string what;
    if (format == can::FrameFormat::kReserved0 || format == can::FrameFormat::kReserved6) {
        what = "a frame in the reserved CAN frame format " +
               std::to_string(static_cast<unsigned>(format));
    } else if (format == can::FrameFormat::kGlobalAddressed &&
               !is_allocated(can::can_mti(frame.id))) {
        what = "a message with MTI " + base::hex(can::can_mti(frame.id), 4);
    } else {
        return;
    }
    ctx_.report(RuleId::kMessageUnknownMti, can::source_alias(frame.id), node,
                what + ", which no standard allocates", std::span(&frame, 1), what, now);
}

void ClientAudit::on_disconnect(std::uint64_t connection, TimePoint now) {
    if (!finished_) closing_.emplace_back(connection, now + kDisconnectGrace);
}

void ClientAudit::close_connection(std::uint64_t connection, TimePoint now) {
    for (const std::uint16_t alias : ctx_.clients_of(connection)) close_client(alias, now);
}

void ClientAudit::close_client(std::uint16_t alias, TimePoint now) {
    datagrams_.client_gone(alias, now);
    memory_.client_gone(alias, now);
    aliases_.forget(alias);
    ctx_.forget_client(alias);
}

void ClientAudit::end_reused_alias(std::uint16_t alias, std::uint64_t connection, TimePoint now) {
    // Tools that always derive the same alias (OpenLCB_Java's 0xC22) take it up again on a new
    // connection within the grace: that is another client, so what the ended one left open is
    // judged now and under its own connection, and the new one starts Uninitialized.
    const auto previous = ctx_.connection_of(alias);
    if (!previous || *previous == connection) return;
    const bool ended = std::any_of(closing_.begin(), closing_.end(),
                                   [&](const auto& c) { return c.first == *previous; });
    if (ended) close_client(alias, now);
}

void ClientAudit::poll(TimePoint now) {
    if (finished_) return;
    const auto due = std::stable_partition(closing_.begin(), closing_.end(),
                                           [now](const auto& c) { return c.second > now; });
    std::vector<std::pair<std::uint64_t, TimePoint>> ended(due, closing_.end());
    closing_.erase(due, closing_.end());
    for (const auto& [connection, at] : ended) close_connection(connection, now);
    datagrams_.poll(now);
    memory_.poll(now);
}

std::optional<TimePoint> ClientAudit::next_deadline() const {
    std::optional<TimePoint> next = datagrams_.next_deadline();
    const auto consider = [&next](std::optional<TimePoint> t) {
        if (t && (!next || *t < *next)) next = t;
    };
    consider(memory_.next_deadline());
    for (const auto& c : closing_) consider(c.second);
    return next;
}

void ClientAudit::finish(TimePoint now) {
    if (finished_) return;
    for (const auto& [connection, at] : closing_) close_connection(connection, now);
    closing_.clear();
    datagrams_.poll(now);
    memory_.finish(now);
    finished_ = true;
}

}  // namespace olcb::simnode::audit
