// NodeStack: the duplicate-node-ID PCER (NodeBuiltins::duplicate_id_pcer), the reserved bit 28
// ignored on receive, and the frame-level faults (NodeStackFaults) simnode injects.
#include <gtest/gtest.h>

#include "openlcb/node/node_test_util.hpp"
#include "openlcb/node_stack.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using Strings = std::vector<std::string>;

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
    NodeStack node(with([](NodeStackConfig& c) {
        c.builtins.duplicate_id_pcer = true;
        c.alias.halt_on_duplicate = true;
    }));
    SimNetwork net;
    Strings seen;
    Transport& port = net.add_endpoint(
        [&](const CanFrame& f, TimePoint) { seen.push_back(gridconnect::format(f)); });
    net.add_stack(node);
    net.start_all();
    net.run_for(300ms);
    seen.clear();
    port.send(test::gc(":X19170456N050101012200;"));
    net.run_for(0ms);
    EXPECT_EQ(seen, Strings{kPcer});
    EXPECT_TRUE(node.halted());
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

class BurstDropTest : public test::StackFixture {
protected:
    BurstDropTest()
        : StackFixture(with([](NodeStackConfig& c) { c.faults.drop_addressed_in_bursts = true; })) {
    }
};

TEST_F(BurstDropTest, AddressedMessagesDroppedWhileMoreThan16OtherFramesIn10Ms) {
    boot();
    net_.run_for(20ms);
    for (int i = 0; i < 16; ++i) port_.send(test::gc(":X198F4456N0909090909090909;"));
    inject(":X1948812CN0343;");
    EXPECT_EQ(take(), Strings{kVerified}) << "16 frames of another source: no burst";
    port_.send(test::gc(":X198F4456N0909090909090909;"));
    inject(":X1948812CN0343;");
    EXPECT_TRUE(take().empty()) << "17 frames of another source within 10 ms";
    inject(":X19490456N;");
    EXPECT_EQ(take(), Strings{kVerified}) << "global messages still answered";
    net_.run_for(10ms);
    inject(":X1948812CN0343;");
    EXPECT_EQ(take(), Strings{kVerified}) << "10 ms later the burst is over";
}

TEST_F(BurstDropTest, TheRequestersOwnQuickTrafficIsNoBurst) {
    boot();
    net_.run_for(20ms);
    for (int i = 0; i < 40; ++i) port_.send(test::gc(":X198F412CN0909090909090909;"));
    inject(":X1948812CN0343;");
    EXPECT_EQ(take(), Strings{kVerified});
}

class StandardFramesTest : public test::StackFixture {
protected:
    StandardFramesTest()
        : StackFixture(with([](NodeStackConfig& c) { c.faults.answer_standard_frames = true; })) {}
};

TEST_F(StandardFramesTest, EveryStandardFrameAnsweredWithVerifiedNodeId) {
    boot();
    inject(":S123N0102;");
    inject(":S7FFN;");
    EXPECT_EQ(take(), (Strings{kVerified, kVerified}));
    inject(":S123R;");
    EXPECT_TRUE(take().empty()) << "remote frames stay ignored";
}

}  // namespace
}  // namespace olcb
