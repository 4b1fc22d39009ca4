// One protocol violation the client audit recorded, and the log that keeps them (bounded,
// repeats of the same violation counted on its first finding).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "openlcb/clock.hpp"
#include "openlcb/node_id.hpp"
#include "simnode/audit/audit_rule.hpp"

namespace olcb::simnode::audit {

/// The client a finding is about.
struct ClientRef {
    std::uint64_t connection = 0;   ///< the hub connection its frames came on (0: not a client)
    std::string remote;             ///< that connection's "HOST:PORT" ("" when not known)
    std::uint16_t alias = 0;        ///< its CAN alias
    std::optional<NodeId> node_id;  ///< its node ID, when its frames told it
};

/// The simnode node a finding is about.
struct NodeRef {
    NodeId node_id;           ///< the node's ID
    std::uint16_t alias = 0;  ///< its alias at the time
};

/// One violation (and how often the same one happened).
struct Finding {
    RuleId rule = RuleId::kAliasUnreserved;  ///< which rule
    std::string message;                     ///< one line: what the client did
    ClientRef client;                        ///< who did it
    std::optional<NodeRef> node;             ///< to which of simnode's nodes (none: the bus)
    std::vector<std::string> frames;         ///< the frames involved, GridConnect text
    double time = 0;                         ///< seconds since the audit started (first time)
    double last_time = 0;                    ///< seconds since the audit started (last time)
    std::uint64_t count = 1;                 ///< times it happened
};

/// Findings in the order they first happened; the same violation again (same rule, client,
/// node and key) only counts. At most kMaxFindings are kept, the rest counted as dropped.
class FindingLog {
public:
    /// A log whose times count from start.
    explicit FindingLog(TimePoint start) : start_(start) {}

    /// Records finding (its time is set from now), or counts it on an earlier one with the
    /// same rule, client, node and key.
    void add(Finding finding, std::string_view key, TimePoint now);
    /// Every finding kept, oldest first.
    const std::vector<Finding>& findings() const { return findings_; }
    /// Findings not kept because the log was full.
    std::uint64_t dropped() const { return dropped_; }
    /// Changes whenever a finding is added or counted (a writer compares it to its last).
    std::uint64_t revision() const { return revision_; }
    /// Seconds from the start to now.
    double seconds(TimePoint now) const;

private:
    TimePoint start_;
    std::vector<Finding> findings_;
    std::unordered_map<std::string, std::size_t> index_;  // dedup key -> findings_ index
    std::uint64_t dropped_ = 0;
    std::uint64_t revision_ = 0;
};

}  // namespace olcb::simnode::audit
