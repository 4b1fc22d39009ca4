#include "openlcb/alias_allocator.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "openlcb/gc_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;

const Strings cid_343 = {":X17050343N;", ":X16101343N;", ":X15012343N;", ":X14200343N;"};
const Strings cid_bd9 = {":X17050BD9N;", ":X16101BD9N;", ":X15012BD9N;", ":X14200BD9N;"};

std::vector<AliasEvent> events(AliasAllocator& a) {
    std::vector<AliasEvent> out;
    while (auto e = a.pop_event()) out.push_back(*e);
    return out;
}

// A node that has completed reservation of 0x343 and drained its output.
AliasAllocator permitted_node(AliasAllocatorConfig config = {}) {
    AliasAllocator a(kNodeId, config);
    a.start(t0);
    a.poll(t0 + 200ms);
    drain(a);
    events(a);
    return a;
}

TEST(AliasAllocator, StartupSequenceOfWorkedExample) {
    AliasAllocator a(kNodeId);
    EXPECT_EQ(a.state(), AliasAllocator::State::kIdle);
    EXPECT_FALSE(a.next_deadline());
    a.start(t0);
    EXPECT_EQ(drain(a), cid_343);
    EXPECT_EQ(a.alias(), 0x343);
    EXPECT_EQ(a.state(), AliasAllocator::State::kChecking);
    EXPECT_EQ(a.next_deadline(), t0 + 200ms);

    a.poll(t0 + 199ms);
    EXPECT_TRUE(drain(a).empty()) << "RID must not come before 200 ms";
    EXPECT_FALSE(a.permitted());

    a.poll(t0 + 200ms);
    EXPECT_EQ(drain(a), (Strings{":X10700343N;", ":X10701343N050101012200;"}));
    EXPECT_TRUE(a.permitted());
    EXPECT_FALSE(a.next_deadline());
    EXPECT_EQ(events(a), (std::vector<AliasEvent>{{AliasEvent::Kind::kPermitted, 0x343}}));
    a.poll(t0 + 1s);
    EXPECT_TRUE(drain(a).empty());
}

TEST(AliasAllocator, DeferredPermitSendsAmdOnRequest) {
    AliasAllocator a(kNodeId, {.auto_permit = false});
    a.start(t0);
    drain(a);
    a.poll(t0 + 200ms);
    EXPECT_EQ(drain(a), (Strings{":X10700343N;"}));
    EXPECT_EQ(a.state(), AliasAllocator::State::kReserved);
    EXPECT_EQ(events(a), (std::vector<AliasEvent>{{AliasEvent::Kind::kReserved, 0x343}}));
    a.permit();
    EXPECT_EQ(drain(a), (Strings{":X10701343N050101012200;"}));
    EXPECT_TRUE(a.permitted());
}

TEST(AliasAllocator, CidHittingActiveAliasIsDefendedWithRid) {
    auto a = permitted_node();
    a.on_frame(gc(":X17020343N;"), t0 + 1s);
    EXPECT_EQ(drain(a), (Strings{":X10700343N;"}));
    EXPECT_TRUE(a.permitted());
    EXPECT_EQ(a.alias(), 0x343);
    EXPECT_TRUE(events(a).empty());
}

TEST(AliasAllocator, CidHittingReservedAliasIsDefendedWithRid) {
    AliasAllocator a(kNodeId, {.auto_permit = false});
    a.start(t0);
    a.poll(t0 + 200ms);
    drain(a);
    a.on_frame(gc(":X14999343N;"), t0 + 300ms);
    EXPECT_EQ(drain(a), (Strings{":X10700343N;"}));
    EXPECT_EQ(a.state(), AliasAllocator::State::kReserved);
}

TEST(AliasAllocator, NonCidHittingActiveAliasSendsAmrAndReallocates) {
    auto a = permitted_node();
    a.on_frame(gc(":X19490343N;"), t0 + 1s);
    Strings expected = {":X10703343N050101012200;"};
    expected.insert(expected.end(), cid_bd9.begin(), cid_bd9.end());
    EXPECT_EQ(drain(a), expected);
    EXPECT_FALSE(a.permitted());
    EXPECT_EQ(a.alias(), 0xBD9);
    EXPECT_EQ(events(a), (std::vector<AliasEvent>{{AliasEvent::Kind::kAliasLost, 0x343}}));
    a.poll(t0 + 1s + 200ms);
    EXPECT_EQ(drain(a), (Strings{":X10700BD9N;", ":X10701BD9N050101012200;"}));
    EXPECT_EQ(events(a), (std::vector<AliasEvent>{{AliasEvent::Kind::kPermitted, 0xBD9}}));
}

TEST(AliasAllocator, NonCidHittingReservedAliasDropsItSilently) {
    AliasAllocator a(kNodeId, {.auto_permit = false});
    a.start(t0);
    a.poll(t0 + 200ms);
    drain(a);
    events(a);
    a.on_frame(gc(":X10701343N020000000001;"), t0 + 300ms);  // AMD from someone else
    EXPECT_EQ(drain(a), cid_bd9) << "no AMR for an alias that was never Permitted";
    EXPECT_EQ(events(a), (std::vector<AliasEvent>{{AliasEvent::Kind::kConflictRestart, 0x343}}));
    EXPECT_EQ(a.state(), AliasAllocator::State::kChecking);
}

class TentativeConflict : public ::testing::TestWithParam<const char*> {};

TEST_P(TentativeConflict, AnyFrameWithTentativeAliasRestartsWithNextAlias) {
    AliasAllocator a(kNodeId);
    a.start(t0);
    drain(a);
    a.on_frame(gc(GetParam()), t0 + 150ms);
    EXPECT_EQ(drain(a), cid_bd9);
    EXPECT_EQ(a.alias(), 0xBD9);
    EXPECT_EQ(a.attempts(), 2u);
    EXPECT_EQ(a.next_deadline(), t0 + 350ms);
    a.poll(t0 + 349ms);
    EXPECT_TRUE(drain(a).empty());
    a.poll(t0 + 350ms);
    EXPECT_EQ(drain(a), (Strings{":X10700BD9N;", ":X10701BD9N050101012200;"}));
}

INSTANTIATE_TEST_SUITE_P(Frames, TentativeConflict,
                         ::testing::Values(":X17020343N;", ":X10700343N;",
                                           ":X10701343N020000000001;", ":X19490343N;",
                                           ":X1A12C343N2043;"));

TEST(AliasAllocator, SecondConflictMovesToThirdAlias) {
    AliasAllocator a(kNodeId);
    a.start(t0);
    a.on_frame(gc(":X19490343N;"), t0 + 10ms);
    a.on_frame(gc(":X19490BD9N;"), t0 + 20ms);
    EXPECT_EQ(a.alias(), 0x60D);
    a.on_frame(gc(":X19490BD9N;"), t0 + 30ms);  // the abandoned alias no longer matters
    EXPECT_EQ(a.alias(), 0x60D);
}

TEST(AliasAllocator, TransmitErrorDuringCheckRestarts) {
    AliasAllocator a(kNodeId);
    a.start(t0);
    drain(a);
    a.on_transmit_error(t0 + 1ms);
    EXPECT_EQ(drain(a), cid_bd9);
}

TEST(AliasAllocator, FramesOfOtherAliasesAndNonOpenLcbFramesIgnored) {
    auto a = permitted_node();
    a.on_frame(gc(":X19490344N;"), t0 + 1s);
    a.on_frame(gc(":X19490343R;"), t0 + 1s);  // remote frame
    a.on_frame(gc(":S343N;"), t0 + 1s);       // standard frame
    EXPECT_TRUE(drain(a).empty());
    EXPECT_TRUE(a.permitted());
}

TEST(AliasAllocator, GlobalAmeAnsweredAndCacheCleared) {
    auto a = permitted_node();
    a.on_frame(gc(":X1070112CN02010D000001;"), t0 + 1s);
    EXPECT_EQ(a.cache().node_of(0x12C), kRunnerId);
    a.on_frame(gc(":X1070212CN;"), t0 + 2s);
    EXPECT_EQ(drain(a), (Strings{":X10701343N050101012200;"}));
    EXPECT_EQ(a.cache().size(), 0u);
}

TEST(AliasAllocator, AmeWithOurIdAnswered) {
    auto a = permitted_node();
    a.on_frame(gc(":X1070212CN050101012200;"), t0 + 1s);
    EXPECT_EQ(drain(a), (Strings{":X10701343N050101012200;"}));
}

TEST(AliasAllocator, AmeWithAnotherIdSilent) {
    auto a = permitted_node();
    a.on_frame(gc(":X1070112CN02010D000001;"), t0 + 1s);
    a.on_frame(gc(":X1070212CN02010D000001;"), t0 + 2s);
    EXPECT_TRUE(drain(a).empty());
    EXPECT_EQ(a.cache().node_of(0x12C), kRunnerId) << "only a global AME clears the cache";
}

TEST(AliasAllocator, InhibitedNeverAnswersAme) {
    AliasAllocator a(kNodeId);
    a.start(t0);
    drain(a);
    a.on_frame(gc(":X1070212CN;"), t0 + 10ms);
    a.on_frame(gc(":X1070212CN050101012200;"), t0 + 20ms);
    EXPECT_TRUE(drain(a).empty());

    AliasAllocator idle(kNodeId);
    idle.on_frame(gc(":X1070212CN;"), t0);
    EXPECT_TRUE(drain(idle).empty());
}

TEST(AliasAllocator, AmdWithOurNodeIdReportsDuplicate) {
    auto a = permitted_node();
    a.on_frame(gc(":X10701777N050101012200;"), t0 + 1s);
    EXPECT_EQ(events(a), (std::vector<AliasEvent>{{AliasEvent::Kind::kDuplicateNodeId, 0x343}}));
    EXPECT_TRUE(drain(a).empty()) << "report only by default";
    EXPECT_TRUE(a.permitted());
    EXPECT_FALSE(a.cache().node_of(0x777)) << "our own ID is never cached for another alias";
}

TEST(AliasAllocator, DuplicateWithHaltSendsPcerThenStaysSilent) {
    auto a = permitted_node({.halt_on_duplicate = true});
    a.on_frame(gc(":X10701777N050101012200;"), t0 + 1s);
    EXPECT_EQ(drain(a), (Strings{":X195B4343N0101000000000201;"}));
    EXPECT_EQ(a.state(), AliasAllocator::State::kHalted);
    a.on_frame(gc(":X1070212CN;"), t0 + 2s);
    a.on_frame(gc(":X17020343N;"), t0 + 2s);
    a.poll(t0 + 10s);
    EXPECT_TRUE(drain(a).empty());
    a.start(t0 + 20s);  // user reset
    EXPECT_EQ(drain(a).size(), 4u);
}

TEST(AliasAllocator, DuplicateWhileInhibitedHaltsWithoutPcer) {
    AliasAllocator a(kNodeId, {.halt_on_duplicate = true});
    a.start(t0);
    drain(a);
    a.on_frame(gc(":X10701777N050101012200;"), t0 + 10ms);
    EXPECT_TRUE(drain(a).empty());
    EXPECT_EQ(a.state(), AliasAllocator::State::kHalted);
}

TEST(AliasAllocator, CacheLearnsFromAmdVerifiedAndForgetsOnAmr) {
    auto a = permitted_node();
    a.on_frame(gc(":X1070112CN02010D000001;"), t0 + 1s);
    EXPECT_EQ(a.cache().alias_of(kRunnerId), 0x12C);
    a.on_frame(gc(":X1070312CN02010D000001;"), t0 + 2s);
    EXPECT_FALSE(a.cache().node_of(0x12C));
    a.on_frame(gc(":X19170456N020000000002;"), t0 + 3s);
    EXPECT_EQ(a.cache().node_of(0x456), NodeId(0x020000000002));
    a.on_frame(gc(":X19100457N020000000003;"), t0 + 3s);
    EXPECT_EQ(a.cache().node_of(0x457), NodeId(0x020000000003));
    a.on_frame(gc(":X19170458N0200;"), t0 + 3s);  // truncated: ignored
    EXPECT_FALSE(a.cache().node_of(0x458));
}

TEST(AliasAllocator, NextAliasSkipsAliasesKnownInUse) {
    AliasAllocator a(kNodeId);
    a.on_frame(gc(":X10701BD9N020000000009;"), t0);  // someone owns BD9
    a.start(t0);
    a.on_frame(gc(":X19490343N;"), t0 + 1ms);
    EXPECT_EQ(a.alias(), 0x60D);
}

// A cache several nodes share: looked up, never written, and this node's own mapping in it is
// no reason to skip an alias.
TEST(AliasAllocator, ASharedCacheIsLookedUpButKeptByItsOwner) {
    auto shared = std::make_shared<AliasCache>();
    shared->add(0x343, kNodeId);  // its own mapping, from an earlier run
    AliasAllocator a(kNodeId);
    a.share_cache(shared);
    a.start(t0);
    EXPECT_EQ(a.alias(), 0x343);
    a.on_frame(gc(":X1070112CN02010D000001;"), t0 + 1ms);
    EXPECT_EQ(shared->size(), 1u) << "its owner learns the segment's frames";
    EXPECT_EQ(&a.cache(), shared.get());

    AliasAllocator b(kNodeId);
    shared->add(0x343, kRunnerId);  // another node holds 0x343 now
    b.share_cache(shared);
    b.start(t0);
    EXPECT_EQ(b.alias(), 0xBD9);
    b.share_cache(nullptr);
    EXPECT_EQ(b.cache().size(), 0u) << "a cache of its own again";
}

TEST(AliasAllocator, ReleaseSendsAmrWhenPermitted) {
    auto a = permitted_node();
    a.release();
    EXPECT_EQ(drain(a), (Strings{":X10703343N050101012200;"}));
    EXPECT_EQ(a.state(), AliasAllocator::State::kIdle);
    EXPECT_EQ(a.alias(), 0);
    a.on_frame(gc(":X19490343N;"), t0 + 5s);
    EXPECT_TRUE(drain(a).empty());
}

}  // namespace
}  // namespace olcb
