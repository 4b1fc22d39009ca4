// Which stacks of one interface a frame concerns (openlcb/stack_routes.cpp): by source alias,
// destination, carried node ID, global message taken, filter and datagrams waiting; and the
// alias cache the stacks share.
#include "openlcb/stack_routes.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "openlcb/can_defs.hpp"
#include "openlcb/node_test_util.hpp"

namespace olcb {
namespace {

using namespace test;
using namespace std::chrono_literals;
using Slots = std::vector<std::size_t>;

constexpr NodeId kOutsider{0x02'01'0D'00'00'99ull};
constexpr std::uint16_t kOutsideAlias = 0x0AB;
constexpr NodeId kFirst{0x05'01'01'01'30'00ull};

// A message frame from alias src with the CAN-MTI of mti.
CanFrame message(Mti mti, std::uint16_t src, std::span<const std::uint8_t> data = {}) {
    return can::make_frame(can::message_header(to_u16(mti) & 0xFFF, src), data);
}

// An addressed message frame from src to dst.
CanFrame addressed(Mti mti, std::uint16_t src, std::uint16_t dst) {
    const std::uint8_t data[] = {static_cast<std::uint8_t>(dst >> 8),
                                 static_cast<std::uint8_t>(dst & 0xFF)};
    return message(mti, src, data);
}

// A frame carrying a node ID (Verified Node ID, Initialization Complete).
CanFrame with_id(Mti mti, std::uint16_t src, NodeId id) {
    return can::make_node_id_frame(can::message_header(to_u16(mti) & 0xFFF, src), id);
}

// Three stacks started (tentative aliases held), taking no global message unless a test says.
class StackRoutesTest : public ::testing::Test {
protected:
    void make(bool share) {
        routes_.emplace(share);
        for (std::uint64_t k = 0; k < 3; ++k) {
            stacks_.push_back(
                std::make_unique<NodeStack>(stack_config(NodeId(kFirst.value() + k))));
            NodeStack& s = *stacks_.back();
            s.set_global_messages(std::vector<Mti>{});
            s.start(t0);
            routes_->add(s);
        }
    }
    std::uint16_t alias(std::size_t k) const { return stacks_[k]->alias(); }
    NodeId id(std::size_t k) const { return stacks_[k]->node_id(); }
    Slots route(const CanFrame& f, std::size_t sender = StackRoutes::kNoSender) {
        return routes_->route(f, sender);
    }
    // Runs stack k past its reservation, so it is Initialized.
    void initialize(std::size_t k) {
        stacks_[k]->poll(t0 + 200ms);
        ASSERT_TRUE(stacks_[k]->initialized());
        routes_->refresh(k);
    }

    std::vector<std::unique_ptr<NodeStack>> stacks_;
    std::optional<StackRoutes> routes_;
};

TEST_F(StackRoutesTest, ControlFramesReachTheHolderOfTheirSourceAlias) {
    make(true);
    EXPECT_EQ(route(can::make_cid(7, kOutsider, alias(1))), Slots{1});
    EXPECT_EQ(route(can::make_rid(alias(2))), Slots{2});
    EXPECT_EQ(route(can::make_cid(7, kOutsider, kOutsideAlias)), Slots{});
    // A stack's own frames never come back to it.
    EXPECT_EQ(route(can::make_cid(7, id(1), alias(1)), 1), Slots{});
}

TEST_F(StackRoutesTest, AddressedFramesReachTheirDestinationOnly) {
    make(true);
    EXPECT_EQ(route(addressed(Mti::kVerifyNodeIdAddressed, kOutsideAlias, alias(2))), Slots{2});
    EXPECT_EQ(route(addressed(Mti::kSnipRequest, alias(1), alias(2)), 1), Slots{2});
    const std::uint8_t data[] = {0x20, 0x43, 0, 0, 0, 0, 8};
    EXPECT_EQ(
        route(can::make_frame(
            can::addressed_header(can::FrameFormat::kDatagramOnly, alias(0), kOutsideAlias), data)),
        Slots{0});
    EXPECT_EQ(
        route(can::make_frame(
            can::addressed_header(can::FrameFormat::kStreamData, alias(1), kOutsideAlias), data)),
        Slots{1});
}

TEST_F(StackRoutesTest, AnnouncementsReachOnlyTheStacksTheyConcern) {
    make(true);
    EXPECT_EQ(route(can::make_amd(kOutsideAlias, kOutsider)), Slots{});
    EXPECT_EQ(route(with_id(Mti::kInitializationComplete, kOutsideAlias, kOutsider)), Slots{});
    EXPECT_EQ(route(can::make_amr(kOutsideAlias, kOutsider)), Slots{});
    // Another node with a stack's node ID: a duplicate only that stack can tell.
    EXPECT_EQ(route(can::make_amd(kOutsideAlias, id(1))), Slots{1});
    EXPECT_EQ(route(with_id(Mti::kVerifiedNodeId, kOutsideAlias, id(2))), Slots{2});
}

TEST_F(StackRoutesTest, WithoutASharedCacheEveryStackLearnsTheAnnouncements) {
    make(false);
    EXPECT_EQ(routes_->shared_cache(), nullptr);
    EXPECT_EQ(route(can::make_amd(kOutsideAlias, kOutsider)), (Slots{0, 1, 2}));
    EXPECT_EQ(route(can::make_amr(kOutsideAlias, kOutsider)), (Slots{0, 1, 2}));
    EXPECT_EQ(route(with_id(Mti::kVerifiedNodeId, kOutsideAlias, kOutsider), 0), (Slots{1, 2}));
    EXPECT_EQ(route(can::make_cid(7, kOutsider, kOutsideAlias)), Slots{});
}

TEST_F(StackRoutesTest, QueriesEveryNodeAnswersReachEveryStack) {
    make(true);
    EXPECT_EQ(route(message(Mti::kVerifyNodeIdGlobal, kOutsideAlias)), (Slots{0, 1, 2}));
    EXPECT_EQ(route(message(Mti::kVerifyNodeIdGlobal, alias(1)), 1), (Slots{0, 2}));
    EXPECT_EQ(route(can::make_ame(kOutsideAlias)), (Slots{0, 1, 2}));
    // An AME for one node: the others note its time (AMDs right after it answer it).
    EXPECT_EQ(route(can::make_ame(kOutsideAlias, kOutsider)), (Slots{0, 1, 2}));
}

TEST_F(StackRoutesTest, GlobalMessagesReachTheStacksTakingThem) {
    make(true);
    stacks_[0]->set_global_messages(std::vector<Mti>{Mti::kIdentifyProducer});
    stacks_[1]->set_global_messages(std::nullopt);  // every one
    stacks_[2]->set_global_messages(std::vector<Mti>{Mti::kEventReportWithPayload});
    for (std::size_t k = 0; k < 3; ++k) routes_->refresh(k);
    const auto event = EventId(0x0501010130000001ull).to_bytes();
    EXPECT_EQ(route(message(Mti::kIdentifyProducer, kOutsideAlias, event)), (Slots{0, 1}));
    EXPECT_EQ(route(message(Mti::kProducerIdentifiedValid, kOutsideAlias, event)), Slots{1});
    const CanFrame first =
        can::make_frame(can::message_header(can::kCanMtiPcerPayloadFirst, kOutsideAlias), event);
    EXPECT_EQ(route(first), (Slots{1, 2}));
    stacks_[1]->set_global_messages(std::vector<Mti>{});
    routes_->refresh(1);
    EXPECT_EQ(route(message(Mti::kProducerIdentifiedValid, kOutsideAlias, event)), Slots{});
}

TEST_F(StackRoutesTest, AStackWithAnInboundFilterSeesEveryFrame) {
    make(true);
    stacks_[1]->set_inbound_filter([](const CanFrame&, TimePoint) { return FrameRoute{}; });
    routes_->refresh(1);
    CanFrame standard;
    standard.extended = false;
    standard.id = 0x123;
    EXPECT_EQ(route(standard), Slots{1});
    EXPECT_EQ(route(can::make_cid(7, kOutsider, kOutsideAlias)), Slots{1});
    EXPECT_EQ(route(can::make_rid(alias(2))), (Slots{1, 2}));
    stacks_[1]->set_inbound_filter({});
    routes_->refresh(1);
    EXPECT_EQ(route(standard), Slots{});
}

TEST_F(StackRoutesTest, AStackSendingDatagramsSeesEveryReinitialization) {
    make(true);
    initialize(0);
    const std::uint8_t payload[] = {0x20, 0x43, 0, 0, 0, 0, 8};
    ASSERT_TRUE(stacks_[0]->send_datagram(kOutsideAlias, payload, t0 + 200ms));
    routes_->refresh(0);
    EXPECT_EQ(route(can::make_amd(kOutsideAlias, kOutsider)), Slots{0});
    EXPECT_EQ(route(with_id(Mti::kInitializationComplete, kOutsideAlias, kOutsider)), Slots{0});
    EXPECT_EQ(route(with_id(Mti::kVerifiedNodeId, kOutsideAlias, kOutsider)), Slots{});
}

TEST_F(StackRoutesTest, RefreshFollowsAnAliasChange) {
    make(true);
    const std::uint16_t before = alias(1);
    // Another node's CID for the tentative alias: the stack moves on to its next alias.
    stacks_[1]->on_frame(can::make_cid(7, kOutsider, before), t0 + 1ms);
    ASSERT_NE(alias(1), before);
    EXPECT_EQ(route(can::make_rid(before)), Slots{1}) << "the old alias until refresh()";
    routes_->refresh(1);
    EXPECT_EQ(route(can::make_rid(before)), Slots{});
    EXPECT_EQ(route(can::make_rid(alias(1))), Slots{1});
}

TEST_F(StackRoutesTest, TheSharedCacheLearnsEveryFrameRouted) {
    make(true);
    const AliasCache* cache = routes_->shared_cache();
    ASSERT_NE(cache, nullptr);
    EXPECT_EQ(&stacks_[2]->alias_cache(), cache);
    route(can::make_amd(kOutsideAlias, kOutsider));
    EXPECT_EQ(stacks_[0]->alias_cache().node_of(kOutsideAlias), kOutsider);
    route(can::make_amr(kOutsideAlias, kOutsider));
    EXPECT_FALSE(cache->node_of(kOutsideAlias));
    route(with_id(Mti::kVerifiedNodeId, 0x0CD, kOutsider));
    route(can::make_amd(alias(1), id(1)), 1);  // a stack's own announcement too
    EXPECT_EQ(cache->alias_of(kOutsider), 0x0CD);
    EXPECT_EQ(cache->node_of(alias(1)), id(1));
    route(can::make_ame(kOutsideAlias, kOutsider));
    EXPECT_EQ(cache->size(), 2u) << "an AME for one node voids nothing";
    route(can::make_ame(kOutsideAlias));
    EXPECT_EQ(cache->size(), 0u);
}

TEST_F(StackRoutesTest, ARemovedStackGetsNothingAndACacheOfItsOwn) {
    make(true);
    const std::uint16_t gone = alias(1);
    routes_->remove(1);
    EXPECT_EQ(routes_->stack(1), nullptr);
    EXPECT_EQ(routes_->slots(), 3u);
    EXPECT_NE(&stacks_[1]->alias_cache(), routes_->shared_cache());
    EXPECT_EQ(route(can::make_rid(gone)), Slots{});
    EXPECT_EQ(route(message(Mti::kVerifyNodeIdGlobal, kOutsideAlias)), (Slots{0, 2}));
    EXPECT_EQ(route(can::make_amd(kOutsideAlias, id(1))), Slots{});
}

}  // namespace
}  // namespace olcb
