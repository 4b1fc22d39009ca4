// NodeProfile and profile_of: the spaces a node serves and the variables its CDI lays out in
// them, with the ACDI user strings where the CDI lays out none of space 251.
#include "simnode/audit/node_profile.hpp"

#include <gtest/gtest.h>

#include <string>

#include "audit_script.hpp"
#include "simnode/node_memory.hpp"

namespace olcb::simnode::audit::test {
namespace {

// <acdi/> and one segment of space 253: space 251 has no layout of the CDI's.
constexpr const char* kAcdiOnlyCdi = R"(<?xml version="1.0"?>
<cdi><acdi/>
<segment space="253" origin="4"><int size="2"><name>Speed</name></int></segment>
</cdi>)";

NodeProfile profile_with(const char* cdi_text) {
    std::string error;
    auto model = load_cdi_model(cdi_text, error);
    EXPECT_TRUE(model) << error;
    return NodeProfile(kNodeId, model, {{0xFD, SpaceShape{6, false}}});
}

TEST(NodeProfile, ProfileOfASimNodeHasItsIdAndTheSpacesItServes) {
    const NodeProfile& p = default_profile();
    EXPECT_EQ(p.node_id(), kNodeId);
    ASSERT_TRUE(p.space(0xFD));
    EXPECT_EQ(p.space(0xFD)->size, 179u);
    EXPECT_FALSE(p.space(0xFD)->read_only);
    ASSERT_TRUE(p.space(0xFF)) << "the CDI space";
    EXPECT_TRUE(p.space(0xFF)->read_only);
    EXPECT_FALSE(p.space(0x50)) << "a space the node does not serve";
}

TEST(NodeProfile, EveryByteOfAVariableFindsItWithItsPath) {
    const NodeProfile& p = default_profile();
    for (const std::uint64_t address : {1u, 2u}) {
        const auto v = p.variable_at(0xFD, address);
        ASSERT_TRUE(v) << address;
        EXPECT_EQ(v->address, 1u);
        EXPECT_EQ(v->size, 2u);
        EXPECT_EQ(v->end(), 3u);
        EXPECT_EQ(v->name, "Settings.Trim");
        ASSERT_NE(v->element, nullptr);
    }
    EXPECT_FALSE(p.variable_at(0xFD, 179)) << "past the segment";
    EXPECT_FALSE(p.variable_at(0x50, 0));
}

TEST(NodeProfile, WithAcdiTheUserStringsAreVariablesWhereTheCdiLaysOutNone) {
    const NodeProfile p = profile_with(kAcdiOnlyCdi);
    const auto name = p.variable_at(0xFB, 10);
    ASSERT_TRUE(name);
    EXPECT_EQ(name->address, 1u);
    EXPECT_EQ(name->size, 63u);
    EXPECT_EQ(name->name, "ACDI.User Name");
    const auto description = p.variable_at(0xFB, 127);
    ASSERT_TRUE(description);
    EXPECT_EQ(description->address, 64u);
    EXPECT_EQ(description->name, "ACDI.User Description");
    EXPECT_FALSE(p.variable_at(0xFB, 0)) << "the version byte is the firmware's";
    EXPECT_FALSE(p.variable_at(0xFB, 128));
    const auto speed = p.variable_at(0xFD, 5);
    ASSERT_TRUE(speed);
    EXPECT_EQ(speed->address, 4u);
    EXPECT_FALSE(p.variable_at(0xFD, 3)) << "before the segment's origin";
}

TEST(NodeProfile, WithoutACdiThereAreSpacesButNoVariables) {
    const NodeProfile p(kNodeId, nullptr, {{0xFB, SpaceShape{128, false}}});
    EXPECT_EQ(p.space(0xFB)->size, 128u);
    EXPECT_FALSE(p.variable_at(0xFB, 1));
}

}  // namespace
}  // namespace olcb::simnode::audit::test
