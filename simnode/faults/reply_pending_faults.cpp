// Reply Pending faults: what a Datagram Received OK promises about the reply it announces.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

// The largest N the flags' low nibble holds.
constexpr std::uint32_t kMaxTimeoutExponent = 15;

// Only an OK that announces a reply states when it comes.
void state_timeout(ReplyTurn& turn, FaultValue v) {
    if (turn.decision.accepted && turn.decision.reply_pending)
        turn.decision.reply_timeout_exponent = static_cast<std::uint8_t>(v.value);
}

}  // namespace

std::vector<FaultDecl> reply_pending_faults() {
    return {
        {
            .name = "reply-pending-timeout",
            .order = 470,
            .param = {ParamKind::kNumber, "N", 1, 1, kMaxTimeoutExponent},
            .summary = "every Datagram Received OK with Reply Pending promises the reply within "
                       "2^N seconds",
            .doc_parameter = "`N`, default 1 (1..15)",
            .rule_broken = "none broken: a Datagram Received OK may state in its low nibble that "
                           "the pending reply comes within 2^N s (fact sheet 4.3). OpenLCB_Java "
                           "computes that wait as `1 << N*1000` (`real-world.md` §7)",
            .client_sees = "every Datagram Received OK that announces a reply carries flags "
                           "`0x80 | N` (`0x81` for N = 1) and the reply follows as usual. A "
                           "client that waits up to 2^N s sees nothing wrong; one that reads the "
                           "nibble as OpenLCB_Java does gives up after ~270 ms (N = 1) on a reply "
                           "that takes longer (add `slow-reply` or `latency` to see it)",
            .verdict = Verdict::kNone,
            .category = "memory",
            .hooks = {.reply = state_timeout},
        },
    };
}

}  // namespace olcb::simnode
