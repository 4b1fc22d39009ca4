// The event faults: events-stale-after-write, events-missing and identify-overlap-stall against
// the good node's event identification (sim_node_test.cpp).
#include <gtest/gtest.h>

#include "simnode/faults/fault_test_util.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(SimNodeRulesTest, EventsStaleAfterWrite) {
    start_with({"events-stale-after-write"});
    take();
    write_ok(0xFD, kPort0On, kNewEvent);
    EXPECT_EQ(count_prefix(take(), ":X194C7"), 0u) << "the write advertises nothing";
    EXPECT_TRUE(identify(kNewEvent).empty());
    EXPECT_EQ(identify(default_event(0)).size(), 1u) << "the old ID is still identified";
    auto frames = identify_events_global();
    EXPECT_EQ(count_prefix(frames, consumer_identified(default_event(0))), 1u);
    EXPECT_EQ(count_prefix(frames, consumer_identified(kNewEvent)), 0u);
    EXPECT_TRUE(exchange({0x20, 0xA8}).ok);
    EXPECT_TRUE(identify(kNewEvent).empty()) << "Update Complete does not help";
    reboot();
    EXPECT_EQ(identify(kNewEvent).size(), 1u);
    EXPECT_TRUE(identify(default_event(0)).empty());
}

TEST_F(SimNodeRulesTest, EventsMissing) {
    start_with({"events-missing"});
    auto frames = identify_events_global();
    EXPECT_EQ(frames, (std::vector<std::string>{
                          consumer_identified(default_event(0)),
                          consumer_identified(default_event(2)),
                          consumer_identified(default_event(4)),
                          consumer_identified(default_event(6)),
                      }));
    EXPECT_TRUE(identify(default_event(1)).empty());
    EXPECT_EQ(identify(default_event(2)).size(), 1u);
    take();
    write_ok(0xFD, kPort0Off, kNewEvent);  // slot 1
    EXPECT_EQ(count_prefix(take(), ":X194C7"), 0u);
    EXPECT_TRUE(identify(kNewEvent).empty());
    EXPECT_EQ(read(0xFD, kPort0Off, 8), kNewEvent) << "stored as usual";
}

// Asked once at a time, the node answers in full; the addressed form within 20 ms of the global
// one stalls it (ranges only, no single event) until it restarts.
TEST_F(SimNodeRulesTest, IdentifyOverlapStall) {
    start_with({"identify-overlap-stall"});
    EXPECT_EQ(count_prefix(identify_events_global(), ":X194C7"), 8u);
    net_.run_for(250ms);
    take();
    send_addressed(0x968);
    net_.run_for(10ms);
    EXPECT_EQ(count_prefix(take(), ":X194C7"), 8u) << "250 ms after the global one: no overlap";
    send_global(0x970);
    send_addressed(0x968);
    net_.run_for(10ms);
    take();
    EXPECT_EQ(count_prefix(identify_events_global(), ":X194C7"), 0u) << "stalled";
    EXPECT_TRUE(identify(default_event(0)).empty());
    reboot();
    EXPECT_EQ(count_prefix(identify_events_global(), ":X194C7"), 8u) << "a restart clears it";
}

}  // namespace
}  // namespace olcb::simnode::test
