// Datagram faults: how datagrams are acknowledged.
#include "base/error_codes.hpp"
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

void reply_before_ok(AnswerPlan& plan, FaultValue) {
    plan.reply_first = true;
}

void never_ok(AnswerPlan& plan, FaultValue) {
    plan.no_ok = true;
}

void busy_first(DatagramTurn& turn, FaultValue v) {
    if (turn.index < v.value) turn.reject = base::to_u16(base::ErrorCode::kBufferUnavailable);
}

}  // namespace

std::vector<FaultDecl> datagram_faults() {
    return {
        {
            .name = "no-datagram-ack",
            .order = 180,
            .summary = "reply datagram sent before the Datagram Received OK",
            .rule_broken = "Datagram: every datagram gets Datagram Received OK/Rejected; MemCfg: "
                           "the OK (Reply Pending) precedes the reply datagram (fact sheet 4, "
                           "5.2)",
            .client_sees = "the reply datagram arrives *before* the Datagram Received OK",
            .verdict = Verdict::kWarn,
            .category = "datagram",
            .checks = {"datagram.ok-before-reply"},
            .hooks = {.answer = reply_before_ok},
        },
        {
            .name = "reply-without-ack",
            .order = 185,
            .summary = "accepted datagrams never get a Datagram Received OK; replies still come",
            .rule_broken = "Datagram: every datagram is answered with Datagram Received OK or "
                           "Datagram Rejected (fact sheet 4)",
            .client_sees = "no Datagram Received OK for any accepted datagram (reads, writes, "
                           "commands, Read Stream); its reply datagram or stream comes as usual, "
                           "rejects still go. A client that waits for each OK before its next "
                           "datagram waits out its timeout every time; a careful one notes it "
                           "once and takes the replies as they come",
            .verdict = Verdict::kFail,
            .category = "datagram",
            .checks = {"datagram.ok-before-reply"},
            .hooks = {.answer = never_ok},
        },
        {
            .name = "reject-temporary",
            .order = 200,
            .param = {ParamKind::kNumber, "N", 3, 1, kMaxCount},
            .summary = "the first N datagrams are rejected with 0x2020, then it works",
            .doc_parameter = "`N`, default 3",
            .rule_broken = "none broken by itself: a busy node may reject with a temporary error "
                           "(fact sheet 4.2, 4.4)",
            .client_sees = "the first N datagrams are rejected `0x2020`; then it works. A good "
                           "client resends and copes; one that gives up fails",
            .verdict = Verdict::kNone,
            .category = "datagram",
            .checks = {"datagram.temporary-rejects"},
            .hooks = {.datagram = busy_first},
        },
    };
}

}  // namespace olcb::simnode
