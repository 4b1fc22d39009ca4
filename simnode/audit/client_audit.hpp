// simnode's client audit, sans-I/O: fed every frame of the segment with its direction (a
// client's, or one of simnode's nodes') and the client connection it came on, and the time; it
// records every protocol violation of the clients (the rules of audit_rule.hpp, docs/audit.md).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"
#include "simnode/audit/alias_watch.hpp"
#include "simnode/audit/audit_context.hpp"
#include "simnode/audit/datagram_watch.hpp"
#include "simnode/audit/finding.hpp"
#include "simnode/audit/memory_watch.hpp"
#include "simnode/audit/node_profile.hpp"

namespace olcb::simnode::audit {

/// Which way a frame went.
enum class Direction : std::uint8_t {
    kFromClient,  ///< sent by a client (anything on the segment that is not simnode's node)
    kFromNode,    ///< sent by one of simnode's nodes
};

/// The audit of every client of one simnode segment.
class ClientAudit {
public:
    /// An audit whose finding times count from start.
    explicit ClientAudit(TimePoint start);
    ClientAudit(const ClientAudit&) = delete;
    ClientAudit& operator=(const ClientAudit&) = delete;

    /// Adds one of simnode's nodes before its first frame: at start, or when live control adds
    /// it (`simnode ctl add`); one with the ID of an earlier node replaces that one.
    void add_node(NodeProfile profile) { ctx_.add_node(std::move(profile)); }
    /// Names a client connection; one never named is a bridge (see ConnectionKind).
    void name_connection(std::uint64_t connection, std::string remote, ConnectionKind kind) {
        ctx_.name_connection(connection, std::move(remote), kind);
    }
    /// One frame of the segment; connection is the client connection it came on (ignored for
    /// frames from nodes).
    void on_frame(const CanFrame& frame, Direction direction, std::uint64_t connection,
                  TimePoint now);
    /// A client connection ended; what its clients left open is judged kDisconnectGrace later.
    void on_disconnect(std::uint64_t connection, TimePoint now);
    /// Judges the time limits that have passed by now.
    void poll(TimePoint now);
    /// When poll() next has something to judge.
    std::optional<TimePoint> next_deadline() const;
    /// The end of the run: everything still open that can be judged is; later frames are
    /// ignored.
    void finish(TimePoint now);
    /// True once finish() ran.
    bool finished() const { return finished_; }
    /// The findings.
    const FindingLog& log() const { return ctx_.log(); }

private:
    void on_client_frame(const CanFrame& frame, std::uint64_t connection, TimePoint now);
    void on_node_frame(const CanFrame& frame, TimePoint now);
    void judge_mti(const CanFrame& frame, std::optional<std::uint16_t> node, TimePoint now);
    void close_connection(std::uint64_t connection, TimePoint now);
    void close_client(std::uint16_t alias, TimePoint now);
    void end_reused_alias(std::uint16_t alias, std::uint64_t connection, TimePoint now);

    AuditContext ctx_;
    AliasWatch aliases_;
    MemoryWatch memory_;
    DatagramWatch datagrams_;
    std::vector<std::pair<std::uint64_t, TimePoint>> closing_;  // ended connections, judged at
    bool finished_ = false;
};

}  // namespace olcb::simnode::audit
