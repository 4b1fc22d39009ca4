// Event faults: which event IDs the node identifies.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

void frozen(EventPolicy& policy, FaultValue) {
    policy.frozen_at_start = true;
}

void odd_slots_hidden(EventPolicy& policy, FaultValue) {
    policy.hidden = [](std::size_t slot) { return slot % 2 == 1; };
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
    };
}

}  // namespace olcb::simnode
