// Frame faults: CAN frames and alias handling.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

std::vector<FaultDecl> frame_faults() {
    return {
        {
            .name = "alias-conflict-ignored",
            .access = flag_field<&FaultSet::alias_conflict_ignored>(),
            .summary = "alias not defended: no RID on CID, no AMR on conflict",
            .rule_broken = "CAN 6.2/6.3: answer CID with RID; on a frame using our alias send "
                           "AMR and stop using it (fact sheet 1.6)",
            .client_sees = "no RID on CID for its alias, no AMR when another node uses it: it "
                           "keeps transmitting with the duplicated alias",
            .verdict = Verdict::kFail,
            .category = "frame",
            .checks = {"frame.cid-defended", "frame.collision"},
        },
        {
            .name = "burst-drops",
            .access = flag_field<&FaultSet::burst_drops>(),
            .summary = "addressed messages dropped while more than 16 frames arrived in the last "
                       "10 ms",
            .rule_broken = "CAN / MsgNet: a node takes every frame of a busy bus; OlcbChecker "
                           "fr50 sends 300 frames back to back around an addressed Verify Node ID",
            .client_sees = "while more than 16 extended frames from sources other than the "
                           "message's own (of any kind; standard and remote frames do not count) "
                           "arrived within the last 10 ms, every addressed message to the node "
                           "(format 1 frames, e.g. Verify Node ID addressed, Protocol Support "
                           "Inquiry, SNIP request) is dropped without answer; global messages "
                           "and datagrams are handled as usual; after 10 ms with at most 16 such "
                           "frames it answers again; the requester's own quick exchanges (a tool "
                           "reading over TCP) never count",
            .verdict = Verdict::kWarn,
            .category = "frame",
            .checks = {"frame.capacity"},
        },
        {
            .name = "answers-standard-frames",
            .access = flag_field<&FaultSet::answers_standard_frames>(),
            .summary = "every standard (11-bit) frame answered with a Verified Node ID",
            .rule_broken = "CAN: standard (11-bit) frames are not OpenLCB frames and are ignored "
                           "(fact sheet 1; OlcbChecker fr60)",
            .client_sees = "every standard data frame (any ID, any data) makes the node send one "
                           "Verified Node ID (`0x19170sss` + node ID); remote frames stay ignored",
            .verdict = Verdict::kFail,
            .category = "frame",
            .checks = {"frame.standard-frames-ignored"},
        },
    };
}

}  // namespace olcb::simnode
