// Event faults: which event IDs the node identifies, and when it stops identifying them.
#include <memory>

#include "openlcb/can_defs.hpp"
#include "openlcb/event_range.hpp"
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

void frozen(EventPolicy& policy, FaultValue) {
    policy.frozen_at_start = true;
}

void odd_slots_hidden(EventPolicy& policy, FaultValue) {
    policy.hidden = [](std::size_t slot) { return slot % 2 == 1; };
}

// Two Identify Events (either form) this close together: the second arrives while the node still
// answers the first.
constexpr Duration kOverlap = std::chrono::milliseconds(20);

struct IdentifyStall {
    TimePoint last{};
    bool seen = false;
    bool stalled = false;
    std::uint32_t since = 0;  ///< the stack's initializations when it stalled: a restart clears it
};

// OpenMRN's time_server: sent Identify Events addressed while it answered the global one, it
// identified no single event again (ranges still) and answered no Query, until restarted.
void stall_on_overlap(StackHooks& hooks, FaultValue) {
    auto state = std::make_shared<IdentifyStall>();
    hooks.add_inbound([state](NodeStack& stack, const CanFrame& frame, TimePoint now) {
        const FrameRoute route;
        if (state->stalled && stack.initializations() != state->since) state->stalled = false;
        if (!can::is_openlcb_frame(frame) || can::is_control(frame.id) ||
            can::frame_format(frame.id) != can::FrameFormat::kGlobalAddressed)
            return route;
        const std::uint16_t mti = can::can_mti(frame.id);
        const bool to_us = mti == 0x968 && frame.len >= 2 &&
                           can::addressed_dest(frame.data[0], frame.data[1]) == stack.alias();
        if (mti != 0x970 && !to_us) return route;
        if (state->seen && now - state->last < kOverlap) {
            state->stalled = true;
            state->since = stack.initializations();
        }
        state->seen = true;
        state->last = now;
        return route;
    });
    hooks.add_outbound([state](Message& m) {
        return !(state->stalled &&
                 (is_producer_identified(m.mti) || is_consumer_identified(m.mti)));
    });
}

}  // namespace

std::vector<FaultDecl> event_faults() {
    return {
        {
            .name = "events-stale-after-write",
            .order = 380,
            .summary = "events identified as at start-up: written event IDs not identified until "
                       "a restart",
            .rule_broken = "Events: a node identifies the event IDs it holds now; a written "
                           "`<eventid>` is the node's event from then on",
            .client_sees = "Identify Events (global, addressed), Identify Producer and Identify "
                           "Consumer are answered for the event IDs of the last start-up; a "
                           "write of an event ID advertises nothing, the new ID is never "
                           "identified and the old one still is, Update Complete changes "
                           "nothing; after a restart (Reset/Reboot, …) the stored IDs count",
            .verdict = Verdict::kWarn,
            .category = "events",
            .checks = {"events.follow-write"},
            .hooks = {.events = frozen},
        },
        {
            .name = "events-missing",
            .order = 390,
            .summary = "every second eventid of the CDI (slots 1, 3, 5...) never identified",
            .rule_broken = "Events: a node identifies every event it produces or consumes (fact "
                           "sheet 9)",
            .client_sees = "the `<eventid>` slots 1, 3, 5, … of the CDI (counted from 0 in "
                           "document order, after replication; in `scenarios/default.xml` every "
                           "\"Off event\") are never identified: not on Initialization Complete, "
                           "Identify Events, Identify Producer/Consumer or after a write; their "
                           "bytes are stored and read as usual",
            .verdict = Verdict::kWarn,
            .category = "events",
            .checks = {"events.cdi-events-identified"},
            .hooks = {.events = odd_slots_hidden},
        },
        {
            .name = "identify-overlap-stall",
            .order = 395,
            .summary = "Identify Events arriving while it answers another: no single event "
                       "identified again until a restart",
            .rule_broken = "none that a careful client provokes: it asks the second form after "
                           "the first one's answers (EventTransportS §6.2 then owes every event). "
                           "OpenMRN's time_server does this, and answers no Broadcast Time Query "
                           "either",
            .client_sees = "a second Identify Events (global, or addressed to the node) within "
                           "20 ms of another: from then on every answer holds the ranges only, "
                           "no Producer or Consumer Identified, until the node restarts",
            .verdict = Verdict::kNone,
            .category = "events",
            .checks = {"events.identify-addressed"},
            .hooks = {.stack = stall_on_overlap},
        },
    };
}

}  // namespace olcb::simnode
