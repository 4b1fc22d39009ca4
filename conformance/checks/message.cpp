// Verify Node ID, unknown MTIs, the Protocol Support Inquiry and the run-long silence check.
#include "conformance/checks/checks.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform::checks {
namespace {
void oir_unknown_mti(CheckRun& run, const CheckSpec& spec) {
    const std::optional<std::uint16_t> code = run.probe<FrameProbe>().oir;
    if (!code)
        return run.out(spec).fail(
            "unknown addressed MTI 0x04F9 not answered with an OIR echoing it", "OIR echoing 04F9",
            "no such OIR");
    const std::string what = "unknown addressed MTI 0x04F9 answered with OIR " + hex(*code);
    // MessageNetworkS §3.5.5 lets the code be 0; a temporary one says "try again", which an
    // unknown MTI never deserves.
    if (*code == 0 || (*code & 0xF000) == 0x1000) return run.out(spec).pass(what);
    run.out(spec).warn(what + ": not a permanent error code (0x1xxx), yet retrying cannot help");
}

void verify_addressed(CheckRun& run, const CheckSpec& spec) {
    const bool verified = run.probe<FrameProbe>().verified;
    run.out(spec).judge(verified,
                        verified ? "Verify Node ID addressed answered with Verified Node ID"
                                 : "Verify Node ID addressed: no Verified Node ID came",
                        "Verified Node ID", "no answer");
}

void verify_global(CheckRun& run, const CheckSpec& spec) {
    auto found = run.session().find_node(run.node().id, run.options().answer_window);
    run.out(spec).judge(found.has_value(),
                        found ? "Verify Node ID global with the node ID answered"
                              : "Verify Node ID global with the node ID: no Verified Node ID came",
                        "Verified Node ID", "no answer");
}

void unknown_global_ignored(CheckRun& run, const CheckSpec& spec) {
    // An answer is a message to us (OIR, anything addressed): a global message from the node in
    // the window may answer another tool on the segment.
    // MessageNetworkS §3.5.2: the node may drop it; an answer is allowed, only noted.
    const SilenceAnswers& a = run.probe<SilenceAnswers>();
    if (a.to_us.empty()) return run.out(spec).pass("unknown global MTI 0x0930 ignored silently");
    run.out(spec).warn(
        "unknown global MTI 0x0930 answered with " + a.to_us +
        " addressed to lcc-conform (allowed; dropping it silently is the usual way)");
}

void pip_answered(CheckRun& run, const CheckSpec& spec) {
    const bool answered = run.probe<PipProbe>().reply.has_value();
    run.out(spec).judge(answered,
                        answered ? "Protocol Support Inquiry answered"
                                 : "Protocol Support Inquiry: no Protocol Support Reply came",
                        "Protocol Support Reply", "no reply");
}

void no_unsolicited(CheckRun& run, const CheckSpec& spec) {
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
        // A clock generator's reports are required of it (BroadcastTimeS §6.2), a display's
        // Query is how it learns the time.
        if (can::can_mti(f.id) == (to_u16(Mti::kEventReport) & 0x0FFF) && is_clock_report(run, f))
            continue;
        for (Mti m : kNeverUnasked) {
            if (can::can_mti(f.id) == (to_u16(m) & 0x0FFF) && seen.empty())
                seen = std::string(mti_name(m));
        }
    }
    // No clause forbids it (a producer sends PCERs as it likes): a note for the developer.
    if (seen.empty())
        return run.out(spec).pass("no unsolicited traffic from the node during the run");
    run.out(spec).warn("the node sent " + seen +
                       " unasked during the run (allowed; noted because a "
                       "busy node slows every tool on the segment)");
}

}  // namespace

std::vector<CheckSpec> message_checks() {
    return {
        {"message.oir-unknown-mti", 30, Category::kMessage, "MessageNetworkS §3.5.1, §3.5.5",
         Strength::kShall,
         "an addressed message of an interaction the node does not take part in is answered with "
         "OIR "
         "carrying an error code and the rejected MTI; the code may be 0x0000",
         "me40",
         "addressed frame with unassigned MTI 0x04F9: OIR with a permanent code echoing 0x04F9",
         oir_unknown_mti},
        {"message.verify-addressed", 40, Category::kMessage, "MessageNetworkS §3.4.2",
         Strength::kShall,
         "a Verify Node ID addressed to the node is answered with Verified Node ID", "me20",
         "Verify Node ID addressed: Verified Node ID with the node's ID", verify_addressed},
        {"message.verify-global", 50, Category::kMessage, "MessageNetworkS §3.4.2",
         Strength::kShall,
         "a global Verify Node ID carrying the node's ID is answered with Verified Node ID", "me20",
         "Verify Node ID global with the node's ID: Verified Node ID", verify_global},
        {"message.unknown-global-ignored", 60, Category::kMessage, "MessageNetworkS §3.5.2",
         Strength::kMay,
         "a node may drop an unaddressed message of an interaction it does not take part in "
         "without a "
         "reply (answering is not forbidden)",
         "me40",
         "global frame with unassigned MTI 0x0930: nothing addressed to lcc-conform within the "
         "silence window",
         unknown_global_ignored},
        {"message.pip-answered", 70, Category::kMessage, "MessageNetworkS §3.4.3", Strength::kShall,
         "a Protocol Support Inquiry is answered with a Protocol Support Reply", "me30",
         "Protocol Support Inquiry: Protocol Support Reply", pip_answered},
        {"message.no-unsolicited", 760, Category::kMessage, "", Strength::kNone,
         "an initialized node may send any message; unprompted traffic is only noted (WARN)", "",
         "(observes the whole run, >= 1.2 s) no Verify/Identify/PCER/PSI/SNIP request/Learn frame "
         "originated by the node",
         no_unsolicited},
    };
}

}  // namespace olcb::conform::checks
