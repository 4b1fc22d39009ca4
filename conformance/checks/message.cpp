// Verify Node ID, unknown MTIs, the Protocol Support Inquiry and the run-long silence check.
#include "conformance/checks/checks.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform::checks {
void oir_unknown_mti(CheckRun& run) {
    run.out().judge(run.frame_probe().oir,
                    "unknown addressed MTI 0x04F9 answered with OIR (permanent error, MTI echoed)",
                    "OIR 0x1xxx 04F9", "no such OIR");
}

void verify_addressed(CheckRun& run) {
    run.out().judge(run.frame_probe().verified,
                    "Verify Node ID addressed answered with Verified Node ID", "Verified Node ID",
                    "no answer");
}

void verify_global(CheckRun& run) {
    auto found = run.session().find_node(run.node().id, run.options().answer_window);
    run.out().judge(found.has_value(), "Verify Node ID global with the node ID answered",
                    "Verified Node ID", "no answer");
}

void unknown_global_ignored(CheckRun& run) {
    // An answer is a message to us (OIR, anything addressed): a global message from the node in
    // the window may answer another tool on the segment.
    const SilenceAnswers& a = silence_probe(run);
    run.out().judge(a.to_us.empty(), "unknown global MTI 0x0930 ignored silently", "silence",
                    a.to_us.empty() ? "" : a.to_us + " addressed to lcc-conform");
}

void pip_answered(CheckRun& run) {
    run.out().judge(run.pip().has_value(), "Protocol Support Inquiry answered",
                    "Protocol Support Reply", "no reply");
}

void no_unsolicited(CheckRun& run) {
    Session& s = run.session();
    // The run itself is the quiet window; top it up so periodic chatter cannot slip through.
    const Duration elapsed = s.link().now() - run.started();
    if (elapsed < run.options().quiet_window) s.wait(run.options().quiet_window - elapsed);
    // Frames, not messages: our stack answers some (Verify Node ID) without passing them on.
    static constexpr Mti kNeverUnasked[] = {
        Mti::kVerifyNodeIdGlobal,   Mti::kVerifyNodeIdAddressed,
        Mti::kIdentifyEventsGlobal, Mti::kIdentifyEventsAddressed,
        Mti::kIdentifyConsumer,     Mti::kIdentifyProducer,
        Mti::kEventReport,          Mti::kProtocolSupportInquiry,
        Mti::kSnipRequest,          Mti::kLearnEvent};
    std::string seen;
    for (const CanFrame& f : s.frames_since(run.start_frame())) {
        if (!run.from_node(f) || !can::is_message(f.id) ||
            can::frame_format(f.id) != can::FrameFormat::kGlobalAddressed)
            continue;
        for (Mti m : kNeverUnasked) {
            if (can::can_mti(f.id) == (to_u16(m) & 0x0FFF) && seen.empty())
                seen = std::string(mti_name(m));
        }
    }
    run.out().judge(seen.empty(), "no unsolicited traffic from the node during the run", "silence",
                    seen);
}

}  // namespace olcb::conform::checks
