// The message_addressing_checks() and final_checks() entries against the simulated node: every
// one passes on the default node, and each fails on a node that misbehaves its way.
#include <gtest/gtest.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "conformance/checks/check_run.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/sim_bench.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform {
namespace {

using namespace std::chrono_literals;
using testing::dump;
using testing::fake_config;
using testing::FakeBench;
using testing::SimBench;

std::vector<CheckResult> run_list(Session& s, const NodeInfo& node,
                                  const std::vector<CheckSpec>& list, std::string_view only = {}) {
    CheckRun run(s, node, ProtocolOptions{});
    for (const CheckSpec& spec : list)
        if (only.empty() || spec.id == only) run.run(spec);
    return run.take();
}

CheckResult one(Session& s, const NodeInfo& node, const std::vector<CheckSpec>& list,
                std::string_view id) {
    auto r = run_list(s, node, list, id);
    EXPECT_EQ(r.size(), 1u) << dump(r);
    return r.empty() ? CheckResult{} : r.front();
}

// Answers, in the node's name, messages addressed to any other alias: a node that does not look
// at the destination.
void answer_for_everyone(SimNetwork& net, std::uint16_t node_alias) {
    auto port = std::make_shared<Transport*>(nullptr);
    *port = &net.add_endpoint([port, node_alias](const CanFrame& f, TimePoint) {
        if (!f.extended || !can::is_message(f.id) || f.len < 2 ||
            can::frame_format(f.id) != can::FrameFormat::kGlobalAddressed)
            return;
        const std::uint16_t dst = can::addressed_dest(f.data[0], f.data[1]);
        const std::uint16_t src = can::source_alias(f.id);
        if (dst == node_alias || src == node_alias) return;
        const auto hi = static_cast<std::uint8_t>(src >> 8), lo = static_cast<std::uint8_t>(src);
        switch (can::can_mti(f.id)) {
            case 0x488:
                (*port)->send(
                    can::make_node_id_frame(can::message_header(0x170, node_alias), kDut));
                break;
            case 0x828:
                (*port)->send(can::make_frame(can::message_header(0x668, node_alias),
                                              std::array<std::uint8_t, 8>{hi, lo, 0x40}));
                break;
            case 0x4F9:
                (*port)->send(
                    can::make_frame(can::message_header(0x068, node_alias),
                                    std::array<std::uint8_t, 6>{hi, lo, 0x10, 0x43, 0x04, 0xF9}));
                break;
            default:
                break;
        }
    });
}

TEST(MessageAddressingChecksTest, DefaultNodePassesQuickly) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    const TimePoint t0 = b.net.now();
    auto results = run_list(*b.session, *node, checks::message_addressing_checks());
    const Duration took = b.net.now() - t0;
    ASSERT_EQ(results.size(), checks::message_addressing_checks().size());
    for (const auto& r : results) {
        EXPECT_EQ(r.status, Status::kPass) << dump(results);
        EXPECT_EQ(r.category, Category::kMessage) << r.id;
    }
    // Three silence windows of 250 ms; the rest is answered at once.
    EXPECT_LE(took, 800ms);
}

// No clause forbids answering messages addressed to another node: noted as a WARN.
TEST(MessageAddressingChecksTest, MessagesToAnotherNodeAnsweredWarn) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    // The fake answers in the node's name: the node must not take that for a collision.
    NodeStack& dut = b.dut->stack();
    dut.set_inbound_filter([&dut](const CanFrame& f, TimePoint) {
        return FrameRoute{can::source_alias(f.id) != dut.alias(), true};
    });
    answer_for_everyone(b.net, node->alias);
    auto results = run_list(*b.session, *node, checks::message_addressing_checks());
    for (const char* id :
         {"message.verify-other-silent", "message.pip-other-silent", "message.oir-other-silent"}) {
        const CheckResult* r = testing::find_check(results, id);
        ASSERT_NE(r, nullptr) << id;
        EXPECT_EQ(r->status, Status::kWarn) << id << ": " << r->message;
        EXPECT_NE(r->seen.find("from the node"), std::string::npos) << r->seen;
        EXPECT_NE(r->message.find("not a FAIL"), std::string::npos) << r->message;
    }
    EXPECT_EQ(testing::find_check(results, "message.verify-other-silent")->seen,
              "Verified Node ID from the node");
}

TEST(MessageAddressingChecksTest, ReservedPipByteSetFails) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    const auto bits = b.dut->stack().protocols().bits() | std::uint64_t{0x01} << 16;  // byte 4
    b.dut->stack().set_protocols(ProtocolSet::from_bits(bits));
    const CheckResult r =
        one(*b.session, *node, checks::message_addressing_checks(), "message.pip-fourth-byte");
    EXPECT_EQ(r.status, Status::kFail);
    EXPECT_EQ(r.seen, "byte 4 is 0x01");
}

// MessageNetworkS §4 is informative: a simple bit that disagrees is a WARN.
TEST(MessageAddressingChecksTest, SimpleBitDisagreeingWithVerifiedWarns) {
    NodeStackConfig c = fake_config();
    c.builtins.protocol_support = false;  // the test answers the inquiry
    FakeBench f(c);
    f.node.set_message_handler([&](const Message& m) {
        if (m.mti != Mti::kProtocolSupportInquiry) return false;
        Message psr;
        psr.mti = Mti::kProtocolSupportReply;
        psr.destination = m.source;
        psr.payload = {0xC0, 0, 0, 0, 0, 0};  // simple + datagram, yet Verified is 0x0170
        f.node.send_message(psr);
        return true;
    });
    auto node = f.start();
    ASSERT_TRUE(node);
    const CheckResult r =
        one(*f.session, *node, checks::message_addressing_checks(), "message.pip-simple-bit");
    EXPECT_EQ(r.status, Status::kWarn) << r.message;
    EXPECT_EQ(r.seen, "Verified Node ID (0x0170)");
}

TEST(MessageAddressingChecksTest, SimpleNodeAgreeingPasses) {
    NodeStackConfig c = fake_config();
    c.protocols.set(Protocol::kSimpleProtocol);
    FakeBench f(c);
    auto node = f.start();
    ASSERT_TRUE(node);
    const CheckResult r =
        one(*f.session, *node, checks::message_addressing_checks(), "message.pip-simple-bit");
    EXPECT_EQ(r.status, Status::kPass) << r.message;
    EXPECT_NE(r.message.find("bit set"), std::string::npos) << r.message;
}

TEST(DuplicateNodeIdCheckTest, IsThoroughOnly) {
    ASSERT_EQ(checks::final_checks().size(), 1u);
    EXPECT_EQ(checks::final_checks()[0].id, "message.duplicate-node-id");
    EXPECT_TRUE(checks::final_checks()[0].thorough);
}

TEST(DuplicateNodeIdCheckTest, PcerPasses) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    const CheckResult r =
        one(*b.session, *node, checks::final_checks(), "message.duplicate-node-id");
    EXPECT_EQ(r.status, Status::kPass) << r.message;
    // The node kept its alias: the injected Verified Node ID did not move it to ours.
    EXPECT_EQ(b.session->alias_of(*node), node->alias);
}

TEST(DuplicateNodeIdCheckTest, NoPcerWarns) {
    SimBench b({"duplicate-id-silent"});
    auto node = b.start();
    ASSERT_TRUE(node);
    const CheckResult r =
        one(*b.session, *node, checks::final_checks(), "message.duplicate-node-id");
    EXPECT_EQ(r.status, Status::kWarn) << r.message;
    EXPECT_NE(r.message.find("partial pass"), std::string::npos) << r.message;
}

TEST(DuplicateNodeIdCheckTest, PcerThenSilenceWarns) {
    NodeStackConfig c = fake_config();
    c.alias.halt_on_duplicate = true;  // CanFrameTransferS 6.2.6: silent after the report
    FakeBench f(c);
    auto node = f.start();
    ASSERT_TRUE(node);
    const CheckResult r =
        one(*f.session, *node, checks::final_checks(), "message.duplicate-node-id");
    EXPECT_EQ(r.status, Status::kWarn) << r.message;
    EXPECT_NE(r.message.find("then no answer"), std::string::npos) << r.message;
}

// MessageNetworkS §3.5.4 asks for an indication by whatever means the node has: going silent
// is allowed, so a WARN.
TEST(DuplicateNodeIdCheckTest, SilenceWithoutReportWarns) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    b.dut->stack().go_silent(b.net.now());
    const CheckResult r =
        one(*b.session, *node, checks::final_checks(), "message.duplicate-node-id");
    EXPECT_EQ(r.status, Status::kWarn) << r.message;
}

}  // namespace
}  // namespace olcb::conform
