// NodeStack::go_silent (a crashed node: deaf and mute until restart) and
// NodeStackConfig::new_alias_on_restart (a node that comes back on another alias).
#include <gtest/gtest.h>

#include <cstdio>
#include <set>

#include "openlcb/alias_generator.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/node_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;

class SilentTest : public test::StackFixture {
protected:
    using StackFixture::StackFixture;
};

TEST_F(SilentTest, SilentNodeAnswersNothingAndSendsNothing) {
    boot();
    int datagrams = 0;
    stack_.set_datagram_handler([&](const ReceivedDatagram&) { ++datagrams; });
    stack_.go_silent(net_.now());
    EXPECT_TRUE(stack_.silent());
    EXPECT_FALSE(stack_.initialized());
    EXPECT_EQ(stack_.alias(), 0);
    for (const char* frame : {
             ":X1949012CN;",                  // Verify Node ID Global
             ":X1948812CN0343;",              // Verify Node ID addressed
             ":X1982812CN0343;",              // Protocol Support Inquiry
             ":X17050343N;",                  // CID for the alias it had
             ":X19170343N020000000001;",      // someone uses that alias
             ":X1070212CN;",                  // AME
             ":X1A34312CN2043000000000010;",  // a datagram
         }) {
        inject(frame, 10ms);
    }
    EXPECT_TRUE(take().empty()) << "a crashed node is deaf and mute";
    EXPECT_EQ(datagrams, 0);
    Message m;
    m.mti = Mti::kIdentifyEventsGlobal;
    EXPECT_EQ(stack_.send_message(m), SendStatus::kSilent);
    EXPECT_FALSE(stack_.send_datagram(0x12C, std::vector<std::uint8_t>{0x20}, net_.now()));
    stack_.start(net_.now());
    net_.run_for(1s);
    EXPECT_TRUE(take().empty()) << "start() does not end silence, restart() does";
    EXPECT_TRUE(stack_.silent());
}

TEST_F(SilentTest, OwnerTimerRestartsTheNodeAsAfterPowerUp) {
    boot();
    stack_.go_silent(net_.now());
    const TimePoint crash = net_.now();
    stack_.schedule(crash + 3s, [&](TimePoint now) { stack_.restart(now); });
    net_.run_for(2999ms);
    EXPECT_TRUE(take().empty());
    net_.run_for(300ms);
    EXPECT_EQ(take(),
              (Strings{":X17050343N;", ":X16101343N;", ":X15012343N;", ":X14200343N;",
                       ":X10700343N;", ":X10701343N050101012200;", ":X19100343N050101012200;"}));
    EXPECT_FALSE(stack_.silent());
    EXPECT_TRUE(stack_.initialized());
    EXPECT_EQ(stack_.initializations(), 2u);
    inject(":X1949012CN;");
    EXPECT_EQ(take(), (Strings{":X19170343N050101012200;"}));
}

TEST_F(SilentTest, PendingMessagesAreDroppedNotSentAfterRestart) {
    stack_.start(net_.now());
    Message m;
    m.mti = Mti::kIdentifyEventsGlobal;
    EXPECT_EQ(stack_.send_message(m), SendStatus::kQueued);
    stack_.go_silent(net_.now());
    stack_.restart(net_.now());
    net_.run_for(300ms);
    EXPECT_EQ(take().back(), ":X19100343N050101012200;") << "nothing after Init Complete";
}

NodeStackConfig new_alias_config() {
    NodeStackConfig c = test::stack_config();
    c.new_alias_on_restart = true;
    return c;
}

class NewAliasTest : public test::StackFixture {
protected:
    NewAliasTest() : StackFixture(new_alias_config()) {}
};

TEST_F(NewAliasTest, EachRestartContinuesTheGeneratorSequence) {
    AliasGenerator expected(kNodeId);
    boot();
    EXPECT_EQ(stack_.alias(), expected.next());
    std::set<std::uint16_t> seen{stack_.alias()};
    for (int i = 0; i < 3; ++i) {
        const std::uint16_t before = stack_.alias();
        stack_.restart(net_.now());
        ASSERT_TRUE(net_.run_until([&] { return stack_.initialized(); }, 1s));
        EXPECT_NE(stack_.alias(), before);
        EXPECT_EQ(stack_.alias(), expected.next());
        seen.insert(stack_.alias());
    }
    EXPECT_EQ(seen.size(), 4u);
    net_.run_for(10ms);
    const Strings frames = take();
    ASSERT_FALSE(frames.empty());
    char expected_init[32];
    std::snprintf(expected_init, sizeof expected_init, ":X19100%03XN050101012200;", stack_.alias());
    EXPECT_EQ(frames.back(), expected_init);
}

TEST_F(NewAliasTest, RestartAfterSilenceTakesANewAliasToo) {
    boot();
    const std::uint16_t before = stack_.alias();
    stack_.go_silent(net_.now());
    stack_.restart(net_.now());
    ASSERT_TRUE(net_.run_until([&] { return stack_.initialized(); }, 1s));
    EXPECT_NE(stack_.alias(), before);
}

TEST_F(SilentTest, DefaultRestartKeepsTheFirstAlias) {
    boot();
    stack_.restart(net_.now());
    ASSERT_TRUE(net_.run_until([&] { return stack_.initialized(); }, 1s));
    EXPECT_EQ(stack_.alias(), 0x343);
}

TEST_F(SilentTest, ReleaseSendsAmrAndLeavesTheSegment) {
    boot();
    stack_.release(net_.now());
    EXPECT_TRUE(stack_.silent());
    EXPECT_EQ(stack_.alias(), 0);
    net_.run_for(10ms);
    EXPECT_EQ(take(), (Strings{":X10703343N050101012200;"}));
    inject(":X1949012CN;");
    EXPECT_TRUE(take().empty()) << "a released node answers nothing";
}

TEST_F(SilentTest, ReleaseBeforeTheAliasIsPermittedSendsNoAmr) {
    stack_.start(net_.now());
    stack_.release(net_.now());
    net_.run_for(1s);
    for (const auto& frame : take()) {
        EXPECT_EQ(frame.find(":X10703"), std::string::npos) << frame;
    }
    EXPECT_FALSE(stack_.initialized());
}

}  // namespace
}  // namespace olcb
