// The producer/consumer rule of event_roles.hpp on small CDIs.
#include <gtest/gtest.h>

#include "cdi/layout.hpp"
#include "cdi/parser.hpp"
#include "simnode/event_roles.hpp"

namespace olcb::simnode {
namespace {

std::vector<EventSlot> slots_of(const std::string& segment_body,
                                const std::string& segment_name = "Seg") {
    const std::string xml = "<?xml version=\"1.0\"?><cdi><segment space=\"253\"><name>" +
                            segment_name + "</name>" + segment_body + "</segment></cdi>";
    static std::vector<std::unique_ptr<cdi::Document>> keep;  // layouts point into documents
    auto parsed = cdi::parse(xml);
    EXPECT_TRUE(parsed.document);
    keep.push_back(std::make_unique<cdi::Document>(std::move(*parsed.document)));
    auto laid = cdi::build_layout(*keep.back());
    EXPECT_TRUE(laid.layout);
    return event_slots(*laid.layout, 100);
}

TEST(EventRoles, TextRule) {
    EXPECT_EQ(role_bits_of("Producer events"), 1);
    EXPECT_EQ(role_bits_of("CONSUMED"), 2);
    EXPECT_EQ(role_bits_of("produces and consumes"), 3);
    EXPECT_EQ(role_bits_of("On event"), 0);
}

TEST(EventRoles, NearestNamingTextDecides) {
    const auto slots = slots_of(
        "<group><name>Consumers</name>"
        "<eventid><name>Produced here</name></eventid>"  // own name wins
        "<eventid><name>Plain</name></eventid>"          // group decides
        "</group>"
        "<eventid><name>x</name><description>it is consumed and produced</description></eventid>"
        "<eventid><name>y</name></eventid>",  // segment name says nothing: consumer
        "Seg");
    ASSERT_EQ(slots.size(), 4u);
    EXPECT_EQ(slots[0].role, EventRole::kProducer);
    EXPECT_EQ(slots[0].address, 0u);
    EXPECT_EQ(slots[1].role, EventRole::kConsumer);
    EXPECT_EQ(slots[1].address, 8u);
    EXPECT_EQ(slots[2].role, EventRole::kBoth);
    EXPECT_EQ(slots[3].role, EventRole::kConsumer);
}

TEST(EventRoles, SegmentNameAndReplication) {
    const auto slots =
        slots_of("<group replication=\"3\"><name>Line</name><eventid/><int size=\"1\"/></group>",
                 "Producer lines");
    ASSERT_EQ(slots.size(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(slots[i].role, EventRole::kProducer);
        EXPECT_EQ(slots[i].address, 9 * i);
    }
}

TEST(EventRoles, BoundedCount) {
    std::string body = "<group replication=\"5000\"><eventid/></group>";
    EXPECT_EQ(slots_of(body).size(), 100u);
}

}  // namespace
}  // namespace olcb::simnode
