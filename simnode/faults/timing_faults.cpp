// Timing faults: answers held back on purpose.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

// slow-reply holds back the first reply datagram and then every this-many-th: like firmware
// that stalls now and then (a flash erase), and a client's run stays bounded in time.
constexpr std::uint64_t kSlowReplyEvery = 32;

void hold_reply(AnswerPlan& plan, FaultValue v) {
    if (plan.index % kSlowReplyEvery == 0) plan.delay = std::chrono::milliseconds(v.value);
}

void hold_answers(AnswerLatency& latency, FaultValue v) {
    latency.latency = std::chrono::milliseconds(v.value);
    latency.jitter = std::chrono::milliseconds(v.jitter);
}

// The stack would answer these at once; the node answers them itself, late.
void no_builtin_answers(NodeStackConfig& config, FaultValue) {
    config.builtins.verify_node_id = false;
    config.builtins.protocol_support = false;
    config.builtins.reject_unknown_addressed = false;
}

}  // namespace

std::vector<FaultDecl> timing_faults() {
    return {
        {
            .name = "slow-reply",
            .order = 190,
            .param = {ParamKind::kNumber, "MS", 1200, 1, kMaxDelayMs},
            .summary = "reply datagrams sent MS milliseconds late",
            .doc_parameter = "`MS`, default 1200",
            .rule_broken = "MsgNet timing: replies within 750 ms (fact sheet 3.3)",
            .client_sees = "OK with Reply Pending (no timeout stated) at once, the reply "
                           "datagram MS later, for the first reply and every 32nd after it (so a "
                           "client's run stays bounded); a reply still held at Reset/Reboot is "
                           "dropped",
            .verdict = Verdict::kFail,
            .category = "memory",
            .checks = {"memory.reply-latency"},
            .hooks = {.answer = hold_reply},
        },
        {
            .name = "latency",
            .order = 320,
            .param = {ParamKind::kMsJitter, "MS[:JITTER]", 200, 0, kMaxDelayMs},
            .summary = "every answer sent MS ms (plus 0..JITTER ms, random) after its request, "
                       "in order",
            .doc_parameter = "`MS[:JITTER]`, default 200 (each 0..600000, not both 0)",
            .rule_broken = "none broken by itself: MsgNet timing allows answers up to 750 ms "
                           "(fact sheet 3.3); real buses and busy nodes are slow. A test hook "
                           "(issue 11): loopback answers in microseconds hide a client's races "
                           "(python-openlcb loses one when a datagram is acknowledged in 20 µs, "
                           "`real-world.md` §3)",
            .client_sees = "every answer (Verified Node ID, Protocol Support Reply, SNIP reply, "
                           "Producer/Consumer Identified on Identify, Datagram Received "
                           "OK/Rejected and the reply datagram, OIR) leaves MS ms plus a "
                           "uniformly random 0..JITTER ms after its request arrived, in request "
                           "order; the jitter sequence is seeded by the node ID, so a run "
                           "repeats exactly. The CAN login, alias defence (RID, AMD on AME) and "
                           "the stack's own rejects of malformed datagrams are not delayed; a "
                           "restart drops answers still held. `--latency MS[:JITTER]` (key "
                           "`latency`) gives it to every node without its own",
            .verdict = Verdict::kNone,
            .category_note = "above 750 ms: message",
            .hooks = {.stack_config = no_builtin_answers, .latency = hold_answers},
        },
    };
}

}  // namespace olcb::simnode
