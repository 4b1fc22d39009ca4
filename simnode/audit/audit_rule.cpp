#include "simnode/audit/audit_rule.hpp"

#include <algorithm>
#include <array>
#include <chrono>

#include "simnode/audit/audit_limits.hpp"

namespace olcb::simnode::audit {
namespace {

// Kept in RuleId order (a static_assert below checks the count; rule() checks each entry). The
// level follows the cited clause's words: "shall"/"must" an error, "should" a warning, none a note.
constexpr std::array kRules = {
    Rule{RuleId::kAliasUnreserved, "alias.unreserved", "CanFrameTransferS §5, §6.2.1, §6.2.2",
         Level::kError,
         "a frame other than CID/RID/AMD from an alias the client did not reserve (CID7-CID4, "
         "RID) and map (AMD) on this connection, or used after its AMR"},
    Rule{RuleId::kAliasRidTooEarly, "alias.rid-too-early", "CanFrameTransferS §6.2.1",
         Level::kError, "RID less than 200 ms after the alias's last CID frame"},
    Rule{RuleId::kMessageBeforeInitComplete, "message.before-init-complete",
         "MessageNetworkS §3.2, §3.4.1", Level::kError,
         "an OpenLCB message (Verify Node ID Global, a datagram, ...) from a client's alias it "
         "reserved and mapped on this segment before the client's Initialization Complete"},
    Rule{RuleId::kMessageUnknownMti, "message.unknown-mti", "MessageNetworkS §3.1.1, §7.3.1.2",
         Level::kNote,
         "a message with an MTI no standard allocates, or in a reserved CAN frame format (no "
         "clause forbids sending one; nodes reject or ignore it)"},
    Rule{RuleId::kDatagramFrameSequence, "datagram.frame-sequence",
         "DatagramTransportS §4.1, §7.3.1; MessageNetworkS §7.3.7", Level::kError,
         "datagram frames out of sequence: a middle or last frame without a first, a first "
         "before the last of the previous one, an empty middle frame, more than 72 bytes"},
    Rule{RuleId::kDatagramOverlap, "datagram.overlap", "DatagramTransportS §6.1", Level::kError,
         "a datagram to a node before its previous one was answered (Datagram Received OK or "
         "Rejected) and before 3 s had passed"},
    Rule{RuleId::kDatagramResendWithoutReject, "datagram.resend-without-reject",
         "DatagramTransportS §6.1, §6.2", Level::kError,
         "the same datagram again before the node answered it: only a temporary reject allows "
         "a resend"},
    Rule{RuleId::kDatagramResendAfterOk, "datagram.resend-after-ok",
         "MessageNetworkS §3.7; MemoryConfigurationS §4.4, §4.8", Level::kError,
         "the same datagram again after Datagram Received OK with Reply Pending stating no "
         "timeout, before the reply came and before 3 s had passed"},
    Rule{RuleId::kDatagramResendBeforeTimeout, "datagram.resend-before-timeout",
         "DatagramTransportS §4.2; MessageNetworkS §3.7; MemoryConfigurationS §4.4, §4.8",
         Level::kError,
         "the same datagram again after Datagram Received OK with Reply Pending promising the "
         "reply within 2^N s, before the reply came and before 2^N s (at most 3 s) had passed"},
    Rule{RuleId::kDatagramResendAfterPermanent, "datagram.resend-after-permanent",
         "DatagramTransportS §6.2", Level::kError,
         "the same datagram again right after the node rejected it with a permanent error"},
    Rule{RuleId::kDatagramRetryStorm, "datagram.retry-storm", "DatagramTransportS §6.2",
         Level::kNote,
         "more than 5 resends of one datagram within 1 s after temporary rejects: no pause "
         "for a busy node"},
    Rule{RuleId::kDatagramReplyUnacknowledged, "datagram.reply-unacknowledged",
         "DatagramTransportS §6; MessageNetworkS §3.7", Level::kError,
         "a datagram from the node (a reply) got neither Datagram Received OK nor Rejected "
         "within 3 s"},
    Rule{RuleId::kDatagramReplyAckLate, "datagram.reply-ack-late",
         "DatagramTransportS §6; MessageNetworkS §3.7", Level::kError,
         "a datagram from the node acknowledged more than 750 ms after its last frame"},
    Rule{RuleId::kMemoryRequestBeforeReply, "memory.request-before-reply",
         "DatagramTransportS §6.1; MemoryConfigurationS §4.4, §4.8", Level::kNote,
         "another datagram to the node after Datagram Received OK with Reply Pending, before "
         "the reply came and before the announced time (else 3 s): allowed once the OK came, "
         "but a node that holds one reply at a time may have to reject it"},
    Rule{RuleId::kSnipRequestBeforeReply, "snip.request-before-reply",
         "SimpleNodeInformationS §6.2", Level::kError,
         "a SNIP request to a node before its whole reply to the previous one had come (within "
         "3 s)"},
    Rule{RuleId::kMemoryReadPastEnd, "memory.read-past-end", "MemoryConfigurationS §4.5",
         Level::kNote,
         "a read starting at or after the end of the space (the node can only fail it)"},
    Rule{RuleId::kMemoryWriteReadOnly, "memory.write-read-only", "MemoryConfigurationS §4.1, §4.2",
         Level::kNote,
         "a write or write under mask to a read-only space (0xFF, 0xFC, ...): the node refuses "
         "it"},
    Rule{RuleId::kMemoryWritePastEnd, "memory.write-past-end", "MemoryConfigurationS §4.3",
         Level::kNote,
         "a write or write under mask running past the end of the space: the node refuses it"},
    Rule{RuleId::kMemoryWriteStraddles, "memory.write-straddles", "CDI §5.1.4.2-§5.1.4.5",
         Level::kError,
         "a write (consecutive writes continuing each other count as one) that starts or ends "
         "inside a variable, leaving it partly written; a string written from its first byte "
         "up to a NUL is whole"},
    Rule{RuleId::kMemoryWriteUncovered, "memory.write-uncovered", "CDI §5.1.4", Level::kNote,
         "a write of bytes no variable of the CDI covers"},
    Rule{RuleId::kCdiIntOutOfRange, "cdi.int-out-of-range", "CDI §5.1.4.2", Level::kError,
         "an <int> written with a value below its min or above its max"},
    Rule{RuleId::kCdiFloatOutOfRange, "cdi.float-out-of-range", "CDI §5.1.4.5", Level::kError,
         "a <float> written with a value below its min, above its max, or NaN"},
    Rule{RuleId::kCdiStringInvalid, "cdi.string-invalid", "CDI §5.1.4.3", Level::kError,
         "a <string> written without a NUL within its size, or not valid UTF-8"},
    Rule{RuleId::kCdiNotInMap, "cdi.not-in-map", "CDI §5.1.4.2-§5.1.4.5", Level::kError,
         "a variable with a <map> written with a value none of its properties has"},
    Rule{RuleId::kCdiActionValue, "cdi.action-value", "CDI §5.1.4.6", Level::kError,
         "an <action> written with another value than its <value>"},
    Rule{RuleId::kMemoryNoUpdateComplete, "memory.no-update-complete", "MemoryConfigurationS §4.23",
         Level::kWarning,
         "writes to a node with no Update Complete after them before the client left, the run "
         "ended or 10 s passed without a datagram from the client to the node"},
};

static_assert(kRules.size() == static_cast<std::size_t>(RuleId::kMemoryNoUpdateComplete) + 1);
// The descriptions are compile-time text and name the limits in words; these keep the words true
// to the limits the watches judge by.
static_assert(kAnswerDue == std::chrono::milliseconds(750), "descriptions say 750 ms");
static_assert(kReservationWait == std::chrono::milliseconds(200), "descriptions say 200 ms");
static_assert(kRequesterTimeout == std::chrono::seconds(3), "descriptions say 3 s");

}  // namespace

std::string_view level_name(Level level) {
    switch (level) {
        case Level::kError:
            return "error";
        case Level::kWarning:
            return "warning";
        case Level::kNote:
            return "note";
    }
    return "error";
}

std::span<const Rule> rules() {
    return kRules;
}

const Rule& rule(RuleId id) {
    return kRules[static_cast<std::size_t>(id)];
}

const Rule* find_rule(std::string_view name) {
    const auto it =
        std::find_if(kRules.begin(), kRules.end(), [&](const Rule& r) { return r.name == name; });
    return it == kRules.end() ? nullptr : &*it;
}

}  // namespace olcb::simnode::audit
