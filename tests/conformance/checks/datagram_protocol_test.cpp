// The datagram_protocol_checks() entries against the simulated node: both pass on the default
// node, and each fails (or warns) on a node that answers otherwise.
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

std::vector<CheckResult> run_list(Session& s, const NodeInfo& node, std::string_view only = {}) {
    CheckRun run(s, node, ProtocolOptions{});
    for (const CheckSpec& spec : checks::datagram_protocol_checks())
        if (only.empty() || spec.id == only) run.run(spec);
    return run.take();
}

const CheckResult& get(const std::vector<CheckResult>& results, const char* id) {
    static const CheckResult kNone;
    const CheckResult* r = testing::find_check(results, id);
    EXPECT_NE(r, nullptr) << id << "\n" << dump(results);
    return r ? *r : kNone;
}

TEST(DatagramProtocolChecksTest, DefaultNodePassesQuickly) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    const TimePoint t0 = b.net.now();
    auto results = run_list(*b.session, *node);
    const Duration took = b.net.now() - t0;
    ASSERT_EQ(results.size(), 2u) << dump(results);
    for (const auto& r : results) {
        EXPECT_EQ(r.status, Status::kPass) << dump(results);
        EXPECT_EQ(r.category, Category::kDatagram) << r.id;
    }
    EXPECT_NE(get(results, "datagram.unknown-protocol").message.find("rejected with 0x1042"),
              std::string::npos);
    EXPECT_LE(took, 200ms);  // answered at once; 3 x 50 ms for second answers
    // Our own stack's transport is undisturbed: a read still works afterwards.
    EXPECT_TRUE(b.session->read(*node, memory::Space::kCdi, 0, 8).ok);
}

TEST(DatagramProtocolChecksTest, SilentNodeFailsBoth) {
    SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    b.dut->stack().go_silent(b.net.now());
    auto results = run_list(*b.session, *node);
    EXPECT_EQ(get(results, "datagram.unknown-protocol").status, Status::kFail) << dump(results);
    EXPECT_NE(get(results, "datagram.unknown-protocol").message.find("1 byte: no answer"),
              std::string::npos);
    EXPECT_EQ(get(results, "datagram.out-of-order").status, Status::kFail) << dump(results);
    EXPECT_NE(get(results, "datagram.out-of-order").message.find("a last frame alone: no answer"),
              std::string::npos);
}

TEST(DatagramProtocolChecksTest, NoDatagramsInPipSkips) {
    FakeBench f(fake_config(ProtocolSet{}));
    auto node = f.start();
    ASSERT_TRUE(node);
    for (const auto& r : run_list(*f.session, *node)) EXPECT_EQ(r.status, Status::kSkip) << r.id;
}

TEST(DatagramProtocolChecksTest, AcceptingUnknownProtocolWarns) {
    FakeBench f(fake_config(ProtocolSet{Protocol::kDatagram}));
    f.node.set_datagram_handler(
        [&](const ReceivedDatagram& d) { f.node.accept_datagram(d.source_alias); });
    auto node = f.start();
    ASSERT_TRUE(node);
    auto results = run_list(*f.session, *node);
    const CheckResult& r = get(results, "datagram.unknown-protocol");
    EXPECT_EQ(r.status, Status::kWarn) << r.message;
    EXPECT_NE(r.message.find("Datagram Received OK"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("0x1042 is the recommended answer"), std::string::npos) << r.message;
    // The stack's reassembly answers the broken sequences whatever the handler does.
    EXPECT_EQ(get(results, "datagram.out-of-order").status, Status::kPass) << dump(results);
}

TEST(DatagramProtocolChecksTest, AnotherPermanentCodePassesNoted) {
    FakeBench f(fake_config(ProtocolSet{Protocol::kDatagram}));
    f.node.set_datagram_handler(
        [&](const ReceivedDatagram& d) { f.node.reject_datagram(d.source_alias, 0x1041); });
    auto node = f.start();
    ASSERT_TRUE(node);
    const CheckResult& r = get(run_list(*f.session, *node), "datagram.unknown-protocol");
    EXPECT_EQ(r.status, Status::kPass) << r.message;
    EXPECT_NE(r.message.find("rejected 0x1041"), std::string::npos) << r.message;
    EXPECT_NE(r.message.find("the standard gives 0x1042"), std::string::npos) << r.message;
}

TEST(DatagramProtocolChecksTest, TemporaryRejectsAreResent) {
    SimBench b({"reject-temporary=3"});
    auto node = b.start();
    ASSERT_TRUE(node);
    const CheckResult& r = get(run_list(*b.session, *node), "datagram.unknown-protocol");
    EXPECT_EQ(r.status, Status::kPass) << r.message;
}

// A node made of raw frames whose reassembly takes anything: it answers Verify Node ID and
// acknowledges every frame that could end a datagram, lone ones included.
TEST(DatagramProtocolChecksTest, AcceptingLoneFramesFails) {
    SimNetwork net;
    net.set_logging(false);
    constexpr std::uint16_t kAlias = 0x5E5;
    auto port = std::make_shared<Transport*>(nullptr);
    *port = &net.add_endpoint([port](const CanFrame& f, TimePoint) {
        if (!f.extended || !can::is_message(f.id)) return;
        const auto fmt = can::frame_format(f.id);
        const std::uint16_t src = can::source_alias(f.id);
        if (fmt == can::FrameFormat::kGlobalAddressed && can::can_mti(f.id) == 0x490) {
            (*port)->send(can::make_node_id_frame(can::message_header(0x170, kAlias), kDut));
        } else if ((fmt == can::FrameFormat::kDatagramLast ||
                    fmt == can::FrameFormat::kDatagramOnly) &&
                   can::dest_alias(f.id) == kAlias) {
            const std::array<std::uint8_t, 3> ok = {static_cast<std::uint8_t>(src >> 8),
                                                    static_cast<std::uint8_t>(src), 0};
            (*port)->send(can::make_frame(can::message_header(0xA28, kAlias), ok));
        }
    });
    auto link = make_sim_link(net, kTool);
    Session s(*link);
    ASSERT_TRUE(s.start());
    auto node = s.find_node(kDut);
    ASSERT_TRUE(node);
    auto results = run_list(s, *node);
    const CheckResult& r = get(results, "datagram.out-of-order");
    EXPECT_EQ(r.status, Status::kFail) << r.message;
    EXPECT_NE(r.message.find("a last frame alone: Datagram Received OK"), std::string::npos)
        << r.message;
    EXPECT_NE(r.message.find("a middle frame alone: no answer"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace olcb::conform
