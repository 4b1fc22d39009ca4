// ActiveFaults: only the hooks of the faults that are on are called, with their values; with no
// fault on, every hook point leaves what the node would do unchanged.
#include "simnode/faults/fault_hooks.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "memory/snip.hpp"
#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode {
namespace {

std::vector<std::uint8_t> bytes(const std::string& s) {
    return std::vector<std::uint8_t>(s.begin(), s.end());
}

TEST(FaultHooksTest, NoFaultOnChangesNothing) {
    const ActiveFaults none(FaultSet{});
    auto expected = bytes("<cdi/>");
    expected.push_back(0);
    EXPECT_EQ(none.served_cdi("<cdi/>"), expected);
    EXPECT_EQ(none.served_cdi(std::string_view("<cdi/>\0junk", 11)), expected)
        << "the text ends at its first NUL";
    AcdiVersions versions{4, 2};
    none.acdi(versions);
    EXPECT_EQ(versions.fixed, 4);
    EXPECT_EQ(versions.user, 2);
    EXPECT_FALSE(none.stores());
    EXPECT_FALSE(none.watches());
    EXPECT_EQ(none.latency().latency.count(), 0);
    memory::Snip snip;
    snip.model = "model";
    none.snip(snip);
    EXPECT_EQ(snip.model, "model");
}

TEST(FaultHooksTest, OnlyTheFaultsOnAreCalled) {
    const ActiveFaults acdi(test::faults_of({"acdi-version"}));
    AcdiVersions versions{4, 2};
    acdi.acdi(versions);
    EXPECT_EQ(versions.fixed, 5);
    EXPECT_EQ(versions.user, 3);
    auto expected = bytes("<cdi/>");
    expected.push_back(0);
    EXPECT_EQ(acdi.served_cdi("<cdi/>"), expected) << "acdi-version has no cdi hook";
    EXPECT_FALSE(acdi.stores());

    EXPECT_EQ(ActiveFaults(test::faults_of({"cdi-unterminated"})).served_cdi("<cdi/>"),
              bytes("<cdi/>"));
    EXPECT_TRUE(ActiveFaults(test::faults_of({"int-byte-order"})).stores());
}

TEST(FaultHooksTest, HooksGetTheFaultsValue) {
    const AnswerLatency held = ActiveFaults(test::faults_of({"latency=120:30"})).latency();
    EXPECT_EQ(held.latency.count(), 120);
    EXPECT_EQ(held.jitter.count(), 30);
}

TEST(FaultHooksTest, EveryFaultOnHasItsTurn) {
    const ActiveFaults both(test::faults_of({"cdi-padding", "acdi-version"}));
    const auto served = both.served_cdi("<cdi/>");
    ASSERT_GT(served.size(), 7u);
    EXPECT_EQ(served[6], 0) << "padding follows the NUL";
    AcdiVersions versions{4, 2};
    both.acdi(versions);
    EXPECT_EQ(versions.fixed, 5);
}

}  // namespace
}  // namespace olcb::simnode
