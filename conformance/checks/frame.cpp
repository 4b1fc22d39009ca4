// The alias checks every run makes: AME answered, CID defended (one injected probe, shared with
// the first message checks).
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

void ame_answered(CheckRun& run, const CheckSpec& spec) {
    const FrameProbe& p = run.probe<FrameProbe>();
    const std::string seen = std::to_string(p.amd) + " AMD frame(s)";
    run.out(spec).judge(p.amd >= 2,
                        p.amd >= 2 ? "AME (global and with the node ID) answered with AMD"
                                   : "2 AMEs (global and with the node ID) answered with " + seen,
                        "2 AMD frames", seen);
}

void cid_defended(CheckRun& run, const CheckSpec& spec) {
    const FrameProbe& p = run.probe<FrameProbe>();
    run.out(spec).judge(p.rid >= 1,
                        p.rid >= 1 ? "CID carrying the node's alias answered with RID"
                                   : "CID carrying the node's alias: no RID within the answer "
                                     "window",
                        "RID", "no RID within the answer window");
}

}  // namespace

std::vector<CheckSpec> frame_checks() {
    return {
        {"frame.ame-answered", 10, Category::kFrame, "CanFrameTransferS §6.2.3", Strength::kShall,
         "a permitted node answers an AME that is empty or carries its node ID with an AMD "
         "carrying "
         "its node ID",
         "fr20",
         "AME without data and AME with the node ID: 2 AMD frames from the node's alias with its "
         "node ID",
         ame_answered},
        {"frame.cid-defended", 20, Category::kFrame, "CanFrameTransferS §6.2.5", Strength::kShall,
         "a node receiving a CID frame with an alias it holds answers with RID", "fr30",
         "CID7 with the node's alias (foreign node ID bits): RID from the node", cid_defended},
    };
}

}  // namespace olcb::conform::checks
