// Reply Pending faults: what a Datagram Received OK promises about the reply it announces, and
// a reply that takes its time within that promise.
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

// reply-pending's MS (its parser keeps it below the 2^N s the OK states).
void hold_within_promise(AnswerPlan& plan, FaultValue v) {
    plan.delay = std::chrono::milliseconds(v.jitter);
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
                           "`0x80 | N` (`0x81` for N = 1) and the reply follows at once (as "
                           "`reply-pending=N:0`). A client that waits up to 2^N s sees nothing "
                           "wrong; one that reads the nibble as OpenLCB_Java does gives up after "
                           "~270 ms (N = 1) on a reply that takes longer: `reply-pending` makes "
                           "the reply take its time",
            .verdict = Verdict::kNone,
            .category = "memory",
            .hooks = {.reply = state_timeout},
        },
        {
            .name = "reply-pending",
            .order = 475,
            .param = {ParamKind::kExponentMs, "N[:MS]", 1, 1, kMaxTimeoutExponent},
            .summary = "every Datagram Received OK with Reply Pending promises the reply within "
                       "2^N seconds, and the reply comes MS ms later (default half of 2^N s)",
            .doc_parameter = "`N[:MS]`, N default 1 (1..15); MS 0..2^N s - 1 ms (at most "
                             "600000), default half of 2^N s (at most 600000)",
            .rule_broken = "none broken: the reply keeps the promise of the OK's low nibble, "
                           "2^N s (DatagramTransportS §4.2); a requester may repeat the request "
                           "once that time has passed (MemoryConfigurationS §4.4, §4.8) and times "
                           "out no sooner than 3 s (MessageNetworkS §3.7). OpenLCB_Java computes "
                           "the wait as `1 << N*1000` and resends after ~270 ms (`real-world.md` "
                           "§7)",
            .client_sees = "every Datagram Received OK that announces a reply carries flags "
                           "`0x80 | N` (`0x81` for N = 1), and the reply datagram follows MS ms "
                           "after it (1000 ms for N = 1 by default); a reply still held at "
                           "Reset/Reboot is dropped. A client that waits as promised sees nothing "
                           "wrong; one that resends earlier gets a second OK and a second reply, "
                           "and simnode's client audit names the resend "
                           "(`datagram.resend-before-timeout`, `docs/audit.md`)",
            .verdict = Verdict::kNone,
            .category = "memory",
            .hooks = {.reply = state_timeout, .answer = hold_within_promise},
        },
    };
}

}  // namespace olcb::simnode
