// The alias checks every run makes: AME answered, CID defended (one injected probe, shared with
// the first message checks).
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {

void ame_answered(CheckRun& run) {
    const FrameProbe& p = run.frame_probe();
    run.out().judge(p.amd >= 2, "AME (global and with the node ID) answered with AMD",
                    "2 AMD frames", std::to_string(p.amd) + " AMD frame(s)");
}

void cid_defended(CheckRun& run) {
    const FrameProbe& p = run.frame_probe();
    run.out().judge(p.rid >= 1, "CID carrying the node's alias answered with RID", "RID",
                    "no RID within the answer window");
}

}  // namespace olcb::conform::checks
