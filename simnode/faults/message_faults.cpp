// Message faults: messages sent unasked, or optional ones left out.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

void no_duplicate_pcer(NodeStackConfig& config, FaultValue) {
    config.builtins.duplicate_id_pcer = false;
}

void verify_every(NodeLife& life, TimePoint at, std::chrono::milliseconds period) {
    life.schedule(at, [&life, period](TimePoint now) {
        if (life.initialized()) life.send(Message{Mti::kVerifyNodeIdGlobal, {}, {}, {}});
        verify_every(life, now + period, period);
    });
}

// From the first start-up on, through restarts.
void verify_periodically(NodeLife& life, FaultValue v) {
    const std::chrono::milliseconds period(v.value);
    verify_every(life, life.now() + period, period);
}

}  // namespace

std::vector<FaultDecl> message_faults() {
    return {
        {
            .name = "unsolicited-traffic",
            .order = 220,
            .param = {ParamKind::kNumber, "MS", 1000, 10, kMaxDelayMs},
            .summary = "a Verify Node ID Global every MS milliseconds",
            .doc_parameter = "`MS`, default 1000",
            .rule_broken = "architecture \"interop facts\": no traffic after start-up other than "
                           "what standards require",
            .client_sees = "a Verify Node ID Global every MS (which makes every node answer)",
            .verdict = Verdict::kWarn,
            .category = "message",
            .checks = {"message.no-unsolicited"},
            .hooks = {.started = verify_periodically},
        },
        {
            .name = "duplicate-id-silent",
            .order = 400,
            .summary = "no duplicate-node-ID PCER on a duplicate node ID",
            .rule_broken = "none required: CAN 6 lets a node indicate a duplicate node ID with "
                           "the PCER `01.01.00.00.00.00.02.01`, optionally (fact sheet 1.6); "
                           "OlcbChecker me50 asks for it",
            .client_sees = "no PCER when another alias sends a Verified Node ID or AMD with the "
                           "node's ID; the node goes on as usual",
            .verdict = Verdict::kWarn,
            .category = "message",
            .checks = {"message.duplicate-node-id"},
            .hooks = {.stack_config = no_duplicate_pcer},
        },
    };
}

}  // namespace olcb::simnode
