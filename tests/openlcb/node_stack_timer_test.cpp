// NodeStack owner timers (schedule / now).
#include <gtest/gtest.h>

#include "openlcb/node_stack.hpp"
#include "openlcb/node_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;

class NodeStackTimerTest : public test::StackFixture {
protected:
    using StackFixture::StackFixture;
};

TEST_F(NodeStackTimerTest, RunsAtItsTimeWithThatTime) {
    boot();
    const TimePoint t0 = net_.now();
    EXPECT_EQ(stack_.now(), t0);
    std::vector<TimePoint> calls;
    stack_.schedule(t0 + 500ms, [&](TimePoint now) { calls.push_back(now); });
    EXPECT_EQ(stack_.next_deadline(), t0 + 500ms);
    net_.run_for(499ms);
    EXPECT_TRUE(calls.empty());
    net_.run_for(1ms);
    ASSERT_EQ(calls.size(), 1u);
    EXPECT_EQ(calls[0], t0 + 500ms);
    EXPECT_EQ(stack_.next_deadline(), std::nullopt);
}

TEST_F(NodeStackTimerTest, TimersRunInTimeOrderAndMayRearm) {
    boot();
    const TimePoint t0 = net_.now();
    std::vector<int> order;
    stack_.schedule(t0 + 30ms, [&](TimePoint) { order.push_back(3); });
    stack_.schedule(t0 + 10ms, [&](TimePoint) { order.push_back(1); });
    stack_.schedule(t0 + 10ms, [&](TimePoint) { order.push_back(2); });  // same time: FIFO
    int ticks = 0;
    std::function<void(TimePoint)> tick = [&](TimePoint now) {
        if (++ticks < 3) stack_.schedule(now + 100ms, tick);
    };
    stack_.schedule(t0 + 100ms, tick);
    net_.run_for(1s);
    EXPECT_EQ(order, (std::vector<int>{1, 2, 3}));
    EXPECT_EQ(ticks, 3);
}

TEST_F(NodeStackTimerTest, TimerCanSendAndSurvivesRestart) {
    boot();
    stack_.schedule(net_.now() + 1s, [&](TimePoint) {
        stack_.send_message(Message{Mti::kVerifyNodeIdGlobal, {}, {}, {}});
    });
    stack_.restart(net_.now());
    net_.run_for(2s);
    const Strings frames = take();
    ASSERT_FALSE(frames.empty());
    EXPECT_EQ(frames.back(), ":X19490343N;");
}

TEST_F(NodeStackTimerTest, NowFollowsFramesAndPolls) {
    boot();
    net_.run_for(5s);  // nothing due: the stack is not polled
    const TimePoint before = stack_.now();
    inject(":X19490AAAN;");
    EXPECT_GE(stack_.now(), before);
    EXPECT_EQ(stack_.now(), net_.now());
}

}  // namespace
}  // namespace olcb
