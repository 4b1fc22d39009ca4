// Restart faults: nodes that crash, restart or refuse Reset/Lock, as real firmware does.
#include "openlcb/can_defs.hpp"
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

// Decided before the server sees the command: it would clear or take the lock.
template <typename Command>
void refuse(RequestTurn& turn, FaultValue) {
    if (turn.asked.ok() && std::holds_alternative<Command>(turn.asked.message)) {
        turn.answer = memory::Decision::reject(memory::ErrorCode::kSubcommandUnknown);
    }
}

void next_alias_on_restart(NodeStackConfig& config, FaultValue) {
    config.new_alias_on_restart = true;
}

// Like OpenLcbCLib: Reset/Reboot restarts the node at once, before its Datagram Received OK.
void reset_without_ack(ReplyTurn& turn, FaultValue) {
    if (turn.decision.accepted && turn.asked.ok() &&
        std::holds_alternative<memory::ResetReboot>(turn.asked.message)) {
        turn.unacknowledged = true;
    }
}

// True for a frame of a request to the stack's alias: a datagram or an addressed message other
// than the answers to the node's own datagrams (what is known to be lost, docs/faults.md).
bool request_to(const NodeStack& stack, const CanFrame& frame) {
    if (!can::is_openlcb_frame(frame) || !can::is_message(frame.id)) return false;
    const can::FrameFormat format = can::frame_format(frame.id);
    if (can::is_datagram_format(format)) return can::dest_alias(frame.id) == stack.alias();
    const std::uint16_t cmti = can::can_mti(frame.id);
    const bool datagram_answer = cmti == (to_u16(Mti::kDatagramReceivedOk) & 0xFFF) ||
                                 cmti == (to_u16(Mti::kDatagramRejected) & 0xFFF);
    if (format != can::FrameFormat::kGlobalAddressed || !is_addressed(static_cast<Mti>(cmti)) ||
        frame.len < 2 || datagram_answer)
        return false;
    return can::addressed_dest(frame.data[0], frame.data[1]) == stack.alias();
}

// Like OpenLcbCLib after a Reset: right after its Initialization Complete the node takes no
// request addressed to it yet.
void deaf_after_init(StackHooks& hooks, FaultValue v) {
    const Duration deaf = std::chrono::milliseconds(v.value);
    hooks.add_inbound([deaf](NodeStack& stack, const CanFrame& frame, TimePoint now) {
        FrameRoute route;
        if (stack.initialized() && now - stack.logged_in_at() < deaf && request_to(stack, frame))
            route.messages = false;
        return route;
    });
}

// The firmware trips over the value while building its SNIP reply.
bool crash_on_snip(NodeLife& life, const Message& message, FaultValue v) {
    if (message.mti != Mti::kSnipRequest || !life.watched_changed()) return false;
    life.abort(std::chrono::milliseconds(v.value));
    return true;
}

// Like OpenMRN: a stored config version other than the firmware's wipes the configuration.
void reset_on_other_version(NodeLife& life, FaultValue) {
    if (life.watched_changed()) life.factory_reset();
}

// Crashes and restarts.
std::vector<FaultDecl> restarts() {
    return {
        {
            .name = "abort-on-value",
            .order = 230,
            .param = {ParamKind::kNumber, "MS", 3000, 1, kMaxDelayMs},
            .summary = "a SNIP request while the first 253 int was changed: silent MS ms, then a "
                       "restart",
            .doc_parameter = "`MS`, default 3000 (1..600000)",
            .rule_broken = "SNIP + MsgNet timing: a SNIP request is answered within 750 ms (fact "
                           "sheet 3.3, 6); a node does not crash on a value it accepted in a "
                           "write. Model of OpenMRN's assertion in its SNIP code "
                           "(`real-world.md` §1)",
            .client_sees = "a SNIP request while the watched variable (below) differs from its "
                           "value when the node was created: nothing at all for MS (no SNIP "
                           "reply, no Verified Node ID, no alias defence, no datagram acks), "
                           "then CID..RID, AMD, Initialization Complete as after power-up, "
                           "memory kept; again at every SNIP request until the value is put "
                           "back. A node bug that a careful client (one that restores each test "
                           "value at once, before anything else) never triggers: it sees nothing "
                           "wrong",
            .verdict = Verdict::kNone,
            .hooks = {.message = crash_on_snip},
            .watches = true,
        },
        {
            .name = "factory-reset-on-version-change",
            .order = 270,
            .summary = "a restart while the first 253 int was changed factory-resets the "
                       "configuration",
            .rule_broken = "none broken by itself: what a node does at start-up is its own "
                           "business. Model of OpenMRN, which compares its stored config version "
                           "with its own at start-up and factory-resets on a difference "
                           "(`real-world.md` §1)",
            .client_sees = "at every restart (Reset/Reboot, Factory Reset, the restarts of "
                           "`abort-on-value` and `reboot-on-write`) while the watched variable "
                           "(below) differs from its value when the node was created, every "
                           "writable space (253, 251 with the user name, …) is reset to its "
                           "factory content first. A careful client never restarts the node with "
                           "a test value in place and sees nothing wrong",
            .verdict = Verdict::kNone,
            .hooks = {.powering_up = reset_on_other_version},
            .watches = true,
        },
        {
            .name = "new-alias-on-reboot",
            .order = 280,
            .summary = "every restart reserves a different alias",
            .rule_broken = "none broken: CAN: an alias is reserved afresh at every start-up and "
                           "any free alias may be taken (fact sheet 1.4, 1.5); OpenLcbCLib comes "
                           "back on another alias (`real-world.md` §5)",
            .client_sees = "every restart reserves the next alias of the generator sequence, "
                           "never the one it had (the first start-up is as usual, 0x343 for the "
                           "default node). A client that keeps the old alias talks to nobody; a "
                           "careful one follows the node ID (AMD, Initialization Complete, "
                           "Verified Node ID) and sees nothing wrong",
            .verdict = Verdict::kNone,
            .hooks = {.stack_config = next_alias_on_restart},
        },
        {
            .name = "reset-unacknowledged",
            .order = 285,
            .summary = "Reset/Reboot performed at once, without Datagram Received OK",
            .rule_broken = "none broken: the acknowledgement of Reset/Reboot may be lost when the "
                           "node restarts at once (fact sheet 5.4); OpenLcbCLib does this "
                           "(`real-world.md` §7)",
            .client_sees = "`20 A9` gets no Datagram Received OK: the node restarts at once and "
                           "announces itself (CID..RID, AMD, Initialization Complete). A careful "
                           "client follows the Initialization Complete instead of waiting out the "
                           "acknowledgement timeout, and sees nothing wrong",
            .verdict = Verdict::kNone,
            .hooks = {.reply = reset_without_ack},
        },
    };
}

// Slow to listen after a start-up.
std::vector<FaultDecl> start_ups() {
    return {
        {
            .name = "deaf-after-init",
            .order = 287,
            .param = {ParamKind::kNumber, "MS", 250, 1, kMaxDelayMs},
            .summary = "datagrams and addressed requests ignored for MS ms after each start-up",
            .doc_parameter = "`MS`, default 250",
            .rule_broken = "none judged: every datagram is answered and an addressed Verify Node "
                           "ID gets Verified Node ID (fact sheet 3, 4), but no clause says how "
                           "soon after Initialization Complete a node listens. OpenLcbCLib after "
                           "a Reset: a Verify Node ID addressed and a Lock datagram sent within "
                           "1 ms of its Initialization Complete got no answer, a global Verify "
                           "0.5 s later did (docs/benchmarks.md)",
            .client_sees = "for MS ms after each start-up's Initialization Complete (the first "
                           "and every restart's, not a re-announcement on the same alias) every "
                           "datagram and addressed request to the node is dropped unanswered; "
                           "global messages and the answers to its own datagrams are taken. A "
                           "client that "
                           "sends its next request the moment the node is back waits out its "
                           "timeouts (lcc-conform's Lock after `--reboot`: 4 s); a careful one "
                           "first sees the node answer",
            .verdict = Verdict::kNone,
            .hooks = {.stack = deaf_after_init},
        },
    };
}

// Commands refused.
std::vector<FaultDecl> refusals() {
    return {
        {
            .name = "reset-rejected",
            .order = 250,
            .summary = "Reset/Reboot rejected with 0x1041; the node does not restart",
            .rule_broken = "none broken by itself: Reset/Reboot is an optional command, and an "
                           "unknown command is rejected `0x1041` (fact sheet 5.2, 5.4); OpenMRN "
                           "on Linux does this (`real-world.md` §1)",
            .client_sees = "`20 A9` gets Datagram Rejected `0x1041` and the node does not "
                           "restart (lock, images and alias untouched). A careful client quotes "
                           "the code, skips what needs a reboot and sees nothing wrong",
            .verdict = Verdict::kNone,
            .hooks = {.request = refuse<memory::ResetReboot>},
        },
        {
            .name = "lock-rejected",
            .order = 260,
            .summary = "Lock/Reserve rejected with 0x1041",
            .rule_broken = "none broken by itself: Lock/Reserve is advisory, and an unknown "
                           "command is rejected `0x1041` (fact sheet 5.4); OpenMRN on Linux does "
                           "this (`real-world.md` §1)",
            .client_sees = "`20 88 …` gets Datagram Rejected `0x1041`; the lock stays free. A "
                           "careful client reports the code and works without the lock: nothing "
                           "wrong",
            .verdict = Verdict::kNone,
            .hooks = {.request = refuse<memory::Lock>},
        },
    };
}

}  // namespace

std::vector<FaultDecl> restart_faults() {
    auto all = restarts();
    for (FaultDecl& d : start_ups()) all.push_back(std::move(d));
    for (FaultDecl& d : refusals()) all.push_back(std::move(d));
    return all;
}

}  // namespace olcb::simnode
