// NodeStack: the duplicate-node-ID PCER (NodeBuiltins::duplicate_id_pcer), the reserved bit 28
// ignored on receive, and the inbound and outbound filters an owner breaks rules through.
#include <gtest/gtest.h>

#include "openlcb/can_defs.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/node_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;

const std::string kPcer = ":X195B4343N0101000000000201;";
const std::string kVerified = ":X19170343N050101012200;";

NodeStackConfig with(void (*change)(NodeStackConfig&)) {
    NodeStackConfig c = test::stack_config();
    change(c);
    return c;
}

class DuplicatePcerTest : public test::StackFixture {
protected:
    DuplicatePcerTest()
        : StackFixture(with([](NodeStackConfig& c) { c.builtins.duplicate_id_pcer = true; })) {}
};

TEST_F(DuplicatePcerTest, VerifiedNodeIdOrAmdWithOurIdGivesOnePcerPerSecond) {
    boot();
    inject(":X19170456N050101012200;");
    EXPECT_EQ(take(), Strings{kPcer});
    inject(":X10701456N050101012200;", 999ms);
    inject(":X10701456N050101012200;", 1ms);  // 999 ms after the first: still quiet
    EXPECT_TRUE(take().empty());
    inject(":X10701456N050101012200;");  // 1 s after it
    EXPECT_EQ(take(), Strings{kPcer});
    EXPECT_TRUE(stack_.initialized());
    EXPECT_FALSE(stack_.halted());
    inject(":X1948812CN0343;");
    EXPECT_EQ(take(), Strings{kVerified}) << "keeps answering";
}

TEST_F(DuplicatePcerTest, AnotherIdOrInitializationCompleteIsNoDuplicate) {
    boot();
    inject(":X19170456N050101012201;");
    inject(":X19100456N050101012200;");  // Initialization Complete is not looked at
    EXPECT_TRUE(take().empty());
}

TEST_F(DuplicatePcerTest, HaltOnDuplicateSendsItsOwnPcerOnly) {
    LoneStack lone(with([](NodeStackConfig& c) {
        c.builtins.duplicate_id_pcer = true;
        c.alias.halt_on_duplicate = true;
    }));
    lone.start();
    lone.seen.clear();
    lone.inject(":X19170456N050101012200;");
    EXPECT_EQ(lone.seen, Strings{kPcer});
    EXPECT_TRUE(lone.stack.halted());
}

class StackFramesTest : public test::StackFixture {};

TEST_F(StackFramesTest, DuplicateReportedWithoutPcerByDefault) {
    std::vector<AliasEvent> events;
    stack_.set_alias_event_handler([&](const AliasEvent& e) { events.push_back(e); });
    boot();
    events.clear();
    inject(":X19170456N050101012200;");
    inject(":X10701456N050101012200;");
    EXPECT_TRUE(take().empty());
    EXPECT_EQ(events, (std::vector<AliasEvent>{{AliasEvent::Kind::kDuplicateNodeId, 0x343},
                                               {AliasEvent::Kind::kDuplicateNodeId, 0x343}}));
}

TEST_F(StackFramesTest, ReservedBit28IsIgnoredOnReceive) {
    boot();
    inject(":X0070212CN;");
    EXPECT_EQ(take(), Strings{":X10701343N050101012200;"});
    inject(":X0948812CN0343;");
    EXPECT_EQ(take(), Strings{kVerified});
}

// The inbound filter decides which layers take a frame in: an owner breaking a rule on purpose
// (simnode's faults, tests/simnode/stack_faults_test.cpp) does it here, not in the core.
TEST_F(StackFramesTest, InboundFilterHidesFramesFromTheAliasLayer) {
    stack_.set_inbound_filter([this](const CanFrame& f, TimePoint) {
        return FrameRoute{can::source_alias(f.id) != stack_.alias(), true};
    });
    boot();
    inject(":X17050343N;", 10ms);            // CID of our alias: no RID
    inject(":X19170343N020000000001;", 1s);  // a frame using our alias: no AMR, alias kept
    EXPECT_TRUE(take().empty());
    EXPECT_EQ(stack_.alias(), 0x343);
    inject(":X19490AAAN;");
    EXPECT_EQ(take(), Strings{kVerified}) << "the message layer still answers";
}

TEST_F(StackFramesTest, InboundFilterHidesFramesFromTheMessageLayerAndSeesStandardFrames) {
    int standard = 0;
    stack_.set_inbound_filter([&standard](const CanFrame& f, TimePoint) {
        if (!f.extended) ++standard;
        return FrameRoute{true, can::source_alias(f.id) != 0x12C};
    });
    boot();
    inject(":X1948812CN0343;");
    EXPECT_TRUE(take().empty()) << "hidden from the message layer";
    inject(":X17050343N;");
    EXPECT_EQ(take(), Strings{":X10700343N;"}) << "the alias layer still defends";
    inject(":X19488456N0343;");
    EXPECT_EQ(take(), Strings{kVerified});
    inject(":S123N0102;");
    EXPECT_EQ(standard, 1);
    EXPECT_TRUE(take().empty());
}

TEST_F(StackFramesTest, OutboundFilterChangesOrDropsMessages) {
    stack_.set_outbound_filter([](Message& m) {
        if (m.mti == Mti::kProtocolSupportReply) return false;
        if (m.mti == Mti::kVerifiedNodeId) m.payload.back() ^= 0xFF;
        return true;
    });
    boot();
    stack_.send_message(
        Message{Mti::kVerifiedNodeId, {}, std::nullopt, {0x05, 0x01, 0x01, 0x01, 0x22, 0x00}});
    stack_.send_message(
        Message{Mti::kProtocolSupportReply, {}, NodeHandle{NodeId{}, 0x12C}, {0, 0, 0, 0, 0, 0}});
    net_.run_for(0ms);
    EXPECT_EQ(take(), Strings{":X19170343N0501010122FF;"});
}

}  // namespace
}  // namespace olcb
