// The CAN alias rules of the client audit (alias.unreserved, alias.rid-too-early) and the
// message layer's start (message.before-init-complete): follows every client alias through
// CID7-CID4, RID, AMD and AMR, the Initialization Complete of the node it maps to, and the
// aliases simnode's own nodes hold (which also end any client's claim on them).
#pragma once

#include <cstdint>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"
#include "simnode/audit/audit_context.hpp"

namespace olcb::simnode::audit {

/// Judges the alias each client frame comes from.
class AliasWatch {
public:
    /// A watch reporting to ctx.
    explicit AliasWatch(AuditContext& ctx) : ctx_(ctx) {}

    /// A frame a client sent on connection; dest_node is the node alias it addresses, if any.
    void on_client_frame(const CanFrame& frame, std::uint64_t connection,
                         std::optional<std::uint16_t> dest_node, TimePoint now);
    /// A frame one of simnode's nodes sent: its alias mapping, and the end of any client's
    /// claim on that alias. True when the node (re)started or gave up the alias: its exchanges
    /// are over.
    bool on_node_frame(const CanFrame& frame);
    /// Forgets a client alias whose connection ended (the alias is free again; the node it
    /// mapped starts Uninitialized when it comes back).
    void forget(std::uint16_t alias);

private:
    enum class Phase : std::uint8_t { kNone, kChecking, kReserved, kPermitted, kReleased };
    struct State {
        Phase phase = Phase::kNone;
        TimePoint last_cid{};
        std::uint64_t cid_bits = 0;      // node-ID bits the CID frames carried
        std::uint8_t cids_seen = 0;      // bit n-4 set once CIDn came
        std::optional<NodeId> mapped{};  // the node ID of its AMD, once the audit saw it map
    };

    State& state_of(std::uint16_t alias, std::uint64_t connection, const CanFrame& frame);
    void on_control(State& s, const CanFrame& frame, std::optional<std::uint16_t> dest,
                    TimePoint now);
    void on_cid(State& s, const CanFrame& frame, TimePoint now);
    void require_permitted(const State& s, const CanFrame& frame, std::optional<std::uint16_t> dest,
                           TimePoint now);
    void learn_node_id(std::uint16_t alias, const CanFrame& frame);
    void judge_initialized(const State& s, const CanFrame& frame, std::optional<std::uint16_t> dest,
                           TimePoint now);

    AuditContext& ctx_;
    std::unordered_map<std::uint16_t, State> states_;
    // The client nodes that sent Initialization Complete: Initialized for good (a new alias
    // after a collision does not make a node Uninitialized again, MessageNetworkS §3.2).
    std::unordered_set<std::uint64_t> initialized_;
};

}  // namespace olcb::simnode::audit
