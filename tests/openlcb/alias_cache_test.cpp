// What a node knows of other nodes' alias <-> node ID mappings (openlcb/alias_cache.cpp): both
// directions kept consistent, 12-bit aliases, forgetting one mapping or all.
#include "openlcb/alias_cache.hpp"

#include <gtest/gtest.h>

#include "openlcb/gc_test_util.hpp"

namespace olcb {
namespace {

using test::gc;

constexpr NodeId kNode(0x050101012200);
constexpr NodeId kRunner(0x02010D000001);

TEST(AliasCache, ReplacesStaleMappings) {
    AliasCache c;
    c.add(0x100, NodeId(1));
    c.add(0x200, NodeId(1));  // node moved to a new alias
    EXPECT_FALSE(c.node_of(0x100));
    EXPECT_EQ(c.alias_of(NodeId(1)), 0x200);
    c.add(0x200, NodeId(2));  // alias reused by another node
    EXPECT_FALSE(c.alias_of(NodeId(1)));
    EXPECT_EQ(c.size(), 1u);
    c.add(0, NodeId(3));
    c.add(0x300, NodeId(0));
    EXPECT_EQ(c.size(), 1u);
}

TEST(AliasCache, LooksUpBothWays) {
    AliasCache c;
    EXPECT_EQ(c.size(), 0u);
    EXPECT_FALSE(c.node_of(0x343));
    EXPECT_FALSE(c.alias_of(kNode));
    c.add(0x343, kNode);
    c.add(0x12C, kRunner);
    EXPECT_EQ(c.size(), 2u);
    EXPECT_EQ(c.node_of(0x343), kNode);
    EXPECT_EQ(c.node_of(0x12C), kRunner);
    EXPECT_EQ(c.alias_of(kNode), 0x343);
    EXPECT_EQ(c.alias_of(kRunner), 0x12C);
    c.add(0x343, kNode);  // a re-announced mapping changes nothing
    EXPECT_EQ(c.size(), 2u);
    EXPECT_EQ(c.alias_of(kNode), 0x343);
}

TEST(AliasCache, AliasesAreTwelveBits) {
    AliasCache c;
    c.add(0x1343, kNode);  // the bits above the 12-bit alias are not part of it
    EXPECT_EQ(c.alias_of(kNode), 0x343);
    EXPECT_EQ(c.node_of(0x343), kNode);
    EXPECT_EQ(c.node_of(0xF343), kNode);
    c.add(0x1000, kRunner);  // alias 0 once masked: ignored
    EXPECT_FALSE(c.alias_of(kRunner));
    c.remove_alias(0x2343);
    EXPECT_FALSE(c.node_of(0x343));
    EXPECT_EQ(c.size(), 0u);
}

TEST(AliasCache, RemoveForgetsOneMappingAndClearForgetsAll) {
    AliasCache c;
    c.remove_alias(0x343);  // nothing known yet: no effect
    c.add(0x343, kNode);
    c.add(0x12C, kRunner);
    c.remove_alias(0x343);  // e.g. after its AMR
    EXPECT_FALSE(c.node_of(0x343));
    EXPECT_FALSE(c.alias_of(kNode));
    EXPECT_EQ(c.alias_of(kRunner), 0x12C);
    EXPECT_EQ(c.size(), 1u);
    c.remove_alias(0x343);  // twice: no effect
    EXPECT_EQ(c.size(), 1u);
    c.clear();  // global AME
    EXPECT_EQ(c.size(), 0u);
    EXPECT_FALSE(c.node_of(0x12C));
    EXPECT_FALSE(c.alias_of(kRunner));
    c.add(0x12C, kRunner);  // usable again after clear()
    EXPECT_EQ(c.node_of(0x12C), kRunner);
}

// An observer of the whole segment learns what every frame says, its own node's too.
TEST(AliasCache, LearnsWhatTheFramesOfTheSegmentSay) {
    AliasCache c;
    c.learn(gc(":X10701343N050101012200;"));  // AMD
    c.learn(gc(":X1917012CN02010D000001;"));  // Verified Node ID
    c.learn(gc(":X19100456N020000000002;"));  // Initialization Complete
    EXPECT_EQ(c.node_of(0x343), kNode);
    EXPECT_EQ(c.node_of(0x12C), kRunner);
    EXPECT_EQ(c.node_of(0x456), NodeId(0x020000000002));
    for (const char* nothing : {":X17050777N;", ":X10700777N;", ":X19490777N;", ":X19170458N0200;",
                                ":S343N050101012201;", ":X1070212CN02010D000001;"}) {
        c.learn(gc(nothing));  // CID, RID, Verify, truncated, standard, AME for one node
    }
    EXPECT_EQ(c.size(), 3u);
    c.learn(gc(":X10703343N050101012200;"));  // AMR
    EXPECT_FALSE(c.node_of(0x343));
    c.learn(gc(":X10702999N;"));  // global AME
    EXPECT_EQ(c.size(), 0u);
}

}  // namespace
}  // namespace olcb
