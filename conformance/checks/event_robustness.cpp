// Event messages a configurable node need not act on must not upset it: a PCER with payload
// (OlcbChecker ev60) and a Learn Event (ev70). The node passes when it neither restarts nor
// stops answering.
#include <array>

#include "conformance/checks/checks.hpp"
#include "conformance/checks/events.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform::checks {
namespace {

// Frames that carry an event ID of lcc-conform's own range (05.01.01.01.3F.xx), which no
// device produces or consumes.
std::array<std::uint8_t, 8> tool_event(Session& s, std::uint8_t tag) {
    const std::uint64_t id = s.tool_id().value();
    std::array<std::uint8_t, 8> e{};
    for (std::size_t i = 0; i < 6; ++i) e[i] = static_cast<std::uint8_t>(id >> (8 * (5 - i)));
    e[6] = 0xEE;
    e[7] = tag;
    return e;
}

// The verdict on a node sent frames it need not act on: it answered Verify Node ID after them
// (carried), shows no restart (a new alias reservation or Initialization Complete) within the
// silence window, and answered again after it.
void judge_unharmed(CheckRun& run, const CheckSpec& spec, bool carried, bool restarted,
                    bool still_answers, const std::string& what) {
    // A node that stops answering breaks MessageNetworkS §3.4.2; a restart breaks no clause.
    if (!carried || !still_answers)
        return run.out(spec).fail(what + ": the node no longer answers Verify Node ID",
                                  "still answering", "no answer");
    if (restarted)
        return run.out(spec).warn(what +
                                  ": the node restarted (Initialization Complete), then "
                                  "answered again");
    run.out(spec).pass(what);
}

}  // namespace

void inject_payload_pcers(Session& s) {
    const std::uint16_t me = s.tool_alias();
    const auto event = tool_event(s, 0x60);
    const std::array<std::uint8_t, 8> payload = {1, 2, 3, 4, 5, 6, 7, 8};
    // Payloads of 4, 8 and 12 bytes, and one of 255 middle frames (2,044 bytes).
    for (int middles : {0, 0, 1, 255}) {
        s.inject(can::make_frame(can::message_header(can::kCanMtiPcerPayloadFirst, me), event));
        for (int i = 0; i < middles; ++i)
            s.inject(
                can::make_frame(can::message_header(can::kCanMtiPcerPayloadMiddle, me), payload));
        s.inject(can::make_frame(can::message_header(can::kCanMtiPcerPayloadLast, me),
                                 std::span(payload).first(middles == 0 ? 4 : 8)));
    }
}

void pcer_payload_tolerated(CheckRun& run, const CheckSpec& spec) {
    // The PCERs go out in the window events.identify-producer-consumer waits anyway (probes.hpp).
    const EventWindow& w = run.probe<EventWindow>();
    judge_unharmed(run, spec, w.carried, w.restarted, w.still_answers,
                   "PCERs with payloads of 4 to 2,044 bytes leave the node running");
}

void learn_tolerated(CheckRun& run, const CheckSpec& spec) {
    Session& s = run.session();
    const NodeTrack before = s.track(run.node().id);
    s.inject(can::make_frame(can::message_header(to_u16(Mti::kLearnEvent) & 0x0FFF, s.tool_alias()),
                             tool_event(s, 0x70)));
    // The answer shows the frame was carried (the window then starts at once, not after its
    // modelled bus time); the second that the node still runs after the window.
    const bool carried = s.ping(run.node(), run.options().answer_window);
    if (carried) s.wait(run.options().window);
    const bool restarted = s.track(run.node().id).restarted_since(before);
    const bool answers = carried && s.ping(run.node(), run.options().answer_window);
    judge_unharmed(run, spec, carried, restarted, answers, "Learn Event leaves the node running");
}

std::vector<CheckSpec> event_robustness_checks() {
    return {
        {"events.pcer-payload-tolerated", 650, Category::kEvents,
         "MessageNetworkS §3.4.2; EventTransportS §4.1", Strength::kShall,
         "the node keeps answering Verify Node ID after PCERs with payload; a restart or a payload "
         "past 256 bytes WARNs",
         "ev60",
         "PCERs with payload (first/middle/last frames, 4 to 2,044 payload bytes) of an event in "
         "lcc-conform's own range, in the window of events.identify-producer-consumer once its "
         "owed answers came: no restart, the node still answers Verify Node ID",
         pcer_payload_tolerated},
        {"events.learn-tolerated", 660, Category::kEvents,
         "MessageNetworkS §3.4.2; EventTransportS §6.5", Strength::kShall,
         "the node keeps answering Verify Node ID after Learn Event; a restart WARNs", "ev70",
         "Learn Event with an event of lcc-conform's own range: no restart, the node still "
         "answers (only with --thorough: a node in learn mode would store the event)",
         learn_tolerated, true},
    };
}

}  // namespace olcb::conform::checks
