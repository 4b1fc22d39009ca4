// The timing faults: slow-reply, and latency (every answer MS (+ 0..JITTER) ms after its request,
// in request order; the CAN login and alias defence never held back). Simulated clock only.
#include <gtest/gtest.h>

#include "openlcb/can_defs.hpp"
#include "simnode/faults/fault_test_util.hpp"

namespace olcb::simnode::test {
namespace {

using std::chrono::milliseconds;

TEST_F(FaultTest, SlowReply) {
    start_with({"slow-reply"});
    const Answer a = exchange(read_cmd(0xFD, 15, 1), 5s);
    ASSERT_TRUE(a.ok);
    ASSERT_TRUE(a.reply);
    EXPECT_GE(a.reply_at - a.ok_at, std::chrono::milliseconds(1200));
    EXPECT_GT(a.reply_at - a.ok_at, std::chrono::milliseconds(750));
}

TEST_F(FaultTest, SlowReplyHoldsBackEveryThirtySecondReply) {
    constexpr std::uint64_t kSlowReplyEvery = 32;  // as docs/faults.md says
    start_with({"slow-reply"});
    for (std::uint64_t i = 0; i <= kSlowReplyEvery; ++i) {
        const Answer a = exchange(read_cmd(0xFD, 15, 1), 5s);
        ASSERT_TRUE(a.reply) << i;
        const bool slow = a.reply_at - a.ok_at >= std::chrono::milliseconds(1200);
        EXPECT_EQ(slow, i % kSlowReplyEvery == 0) << "reply " << i;
    }
}

TEST_F(FaultTest, SlowReplyDroppedByReboot) {
    start_with({"slow-reply=2000"});
    const Answer probe = exchange(read_cmd(0xFD, 15, 1), 100ms);
    EXPECT_TRUE(probe.ok);
    EXPECT_FALSE(probe.reply);
    EXPECT_TRUE(exchange({0x20, 0xA9}).ok);
    take();
    net_.run_for(3s);
    EXPECT_EQ(count_prefix(take(), ":X1A12C343N"), 0u);
}

TEST(LatencyFault, ParsesAndPrintsBack) {
    std::string error;
    auto f = parse_faults({"latency=120"}, error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("latency"), (FaultValue{120, 0}));
    EXPECT_EQ(to_names(*f), std::vector<std::string>{"latency=120"});
    f = parse_faults({"latency=120:30"}, error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("latency"), (FaultValue{120, 30}));
    EXPECT_EQ(to_names(*f), std::vector<std::string>{"latency=120:30"});
    EXPECT_EQ(parse_faults(to_names(*f), error), f);
    EXPECT_TRUE(parse_faults({"latency=0:5"}, error));
    f = parse_faults({"latency"}, error);
    ASSERT_TRUE(f) << error;
    EXPECT_EQ(f->value("latency"), (FaultValue{200, 0}));
    for (const char* bad : {"latency=0", "latency=x", "latency=5:", "latency=:5", "latency=700000",
                            "latency=1:2:3"}) {
        EXPECT_FALSE(parse_faults({bad}, error)) << bad;
        EXPECT_NE(error.find("latency"), std::string::npos) << error;
    }
}

class LatencyTest : public SimNodeTest {
protected:
    // Every frame the node sends from now on, with its time.
    void watch() {
        net_.add_endpoint([this](const CanFrame& f, TimePoint t) {
            if (node_ && can::source_alias(f.id) == alias()) seen_.push_back({t, f});
        });
    }
    // The time of the first frame seen whose CAN-MTI is cmti, from index first on.
    std::optional<TimePoint> first(std::uint16_t cmti, std::size_t from = 0) const {
        for (std::size_t i = from; i < seen_.size(); ++i) {
            if (can::is_message(seen_[i].frame.id) &&
                !can::is_datagram_format(can::frame_format(seen_[i].frame.id)) &&
                can::can_mti(seen_[i].frame.id) == cmti)
                return seen_[i].at;
        }
        return std::nullopt;
    }
    std::vector<LoggedFrame> seen_;
};

TEST_F(LatencyTest, VerifyPipSnipAndOirAreLate) {
    start_with({"latency=100"});
    watch();
    const TimePoint sent = net_.now();
    send_global(0x490);     // Verify Node ID Global
    send_addressed(0x828);  // Protocol Support Inquiry
    send_addressed(0xDE8);  // SNIP request
    send_addressed(0x5EB);  // Traction Control Command: not served, so OIR
    net_.run_for(milliseconds(99));
    EXPECT_TRUE(seen_.empty()) << gridconnect::format(seen_.front().frame);
    net_.run_for(milliseconds(5));
    const auto verified = first(0x170), psr = first(0x668), snip = first(0xA08), oir = first(0x068);
    ASSERT_TRUE(verified && psr && snip && oir);
    EXPECT_EQ(*verified - sent, milliseconds(100));
    EXPECT_EQ(*psr - sent, milliseconds(100));
    EXPECT_EQ(*oir - sent, milliseconds(100));
    // Same frames as the stack's own answers, in request order.
    std::vector<std::string> texts;
    texts.reserve(seen_.size());
    for (const auto& f : seen_) texts.push_back(gridconnect::format(f.frame));
    EXPECT_EQ(texts.front(), ":X19170343N050101012200;");
    EXPECT_EQ(texts[1], ":X19668343N012C745800000000;");
    EXPECT_EQ(texts.back(), ":X19068343N012C104305EB;");
}

TEST_F(LatencyTest, DatagramOkAndReplyAreLate) {
    start_with({"latency=250"});
    const TimePoint sent = net_.now();
    const Answer a = exchange(read_cmd(0xFF, 0, 16));
    ASSERT_TRUE(a.ok);
    ASSERT_TRUE(a.reply);
    EXPECT_GE(a.ok_at - sent, milliseconds(250));
    EXPECT_LT(a.ok_at - sent, milliseconds(260));
    EXPECT_LT(a.ok_index, a.reply_index);
    EXPECT_EQ(std::string(a.reply->begin() + 6, a.reply->begin() + 11), "<?xml");
}

TEST_F(LatencyTest, JitterIsSeededByTheNodeAndKeepsOrder) {
    start_with({"latency=40:30"});
    watch();
    AnswerDelay expected(milliseconds(40), milliseconds(30), kNodeId.value());
    std::vector<TimePoint> want;
    for (int i = 0; i < 12; ++i) {
        want.push_back(expected.answer_at(net_.now()));
        send_addressed(0x488);  // Verify Node ID Addressed
        net_.run_for(milliseconds(2));
    }
    net_.run_for(milliseconds(200));
    std::vector<TimePoint> got;
    got.reserve(seen_.size());
    for (const auto& f : seen_) got.push_back(f.at);
    EXPECT_EQ(got, want);
}

TEST_F(LatencyTest, LoginAndAliasDefenceAreNotDelayed) {
    start_with({"latency=2000"});  // start() needs the node initialized within 1 s
    watch();
    send_text(":X1070212CN;");  // AME: the AMD answer is link level, at once
    net_.run_for(milliseconds(1));
    ASSERT_EQ(seen_.size(), 1u);
    EXPECT_EQ(gridconnect::format(seen_[0].frame), ":X10701343N050101012200;");
}

TEST_F(LatencyTest, ARestartDropsHeldAnswers) {
    start_with({"latency=300"});
    watch();
    send_global(0x490);
    net_.run_for(milliseconds(100));
    node_->relogin(net_.now());
    ASSERT_TRUE(net_.run_until([this] { return node_->stack().initialized(); }, 1s));
    net_.run_for(milliseconds(400));
    EXPECT_FALSE(first(0x170)) << "a Verified Node ID of the old boot went out";
    EXPECT_TRUE(first(0x100)) << "no Initialization Complete after relogin";
}

}  // namespace
}  // namespace olcb::simnode::test
