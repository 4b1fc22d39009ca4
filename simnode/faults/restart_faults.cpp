// Restart faults: nodes that crash, restart or refuse Reset/Lock, as real firmware does.
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
    for (FaultDecl& d : refusals()) all.push_back(std::move(d));
    return all;
}

}  // namespace olcb::simnode
