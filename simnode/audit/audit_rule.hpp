// The rules of simnode's client audit: every protocol violation it records about the tools that
// talk to its nodes is one entry of this registry (stable ID, standard and section, level).
// docs/audit.md documents each entry; a test keeps the two in step.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace olcb::simnode::audit {

/// How bad a finding is, by the standard's words: an error breaks a "shall" (or "must"), a
/// warning a "should"; a note is advice where no clause forbids what the client did.
enum class Level : std::uint8_t { kError, kWarning, kNote };

/// "error", "warning" or "note".
std::string_view level_name(Level level);

/// Every rule, in the registry's order (the order docs/audit.md lists them).
enum class RuleId : std::uint8_t {
    kAliasUnreserved,
    kAliasRidTooEarly,
    kMessageBeforeInitComplete,
    kMessageUnknownMti,
    kDatagramFrameSequence,
    kDatagramOverlap,
    kDatagramResendWithoutReject,
    kDatagramResendAfterOk,
    kDatagramResendBeforeTimeout,
    kDatagramResendAfterPermanent,
    kDatagramRetryStorm,
    kDatagramReplyUnacknowledged,
    kDatagramReplyAckLate,
    kMemoryRequestBeforeReply,
    kSnipRequestBeforeReply,
    kMemoryReadPastEnd,
    kMemoryWriteReadOnly,
    kMemoryWritePastEnd,
    kMemoryWriteStraddles,
    kMemoryWriteUncovered,
    kCdiIntOutOfRange,
    kCdiFloatOutOfRange,
    kCdiStringInvalid,
    kCdiNotInMap,
    kCdiActionValue,
    kMemoryNoUpdateComplete,
};

/// One rule of the audit.
struct Rule {
    RuleId id;                  ///< its place in the registry
    std::string_view name;      ///< stable ID, e.g. "datagram.reply-unacknowledged"
    std::string_view standard;  ///< standard and section, e.g. "DatagramTransportS §6"
    Level level;                ///< the level of its findings
    std::string_view summary;   ///< one line: what the client did
};

/// Every rule, in RuleId order.
std::span<const Rule> rules();

/// The registry entry of id.
const Rule& rule(RuleId id);

/// The rule with this stable ID, or null.
const Rule* find_rule(std::string_view name);

}  // namespace olcb::simnode::audit
