// The memory-configuration checks: both read forms, the reply form, unknown spaces' error codes,
// unknown commands.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "conformance/checks/check_registry.hpp"
#include "conformance/checks/check_run.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/checks_test_util.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

using testing::expect_status;
using testing::FakeBench;

// memory.unknown-command alone against a bare node whose datagram handler the test sets.
CheckResult unknown_command(FakeBench& f) {
    auto node = f.start();
    EXPECT_TRUE(node);
    if (!node) return {};
    CheckRun run(*f.session, *node, ProtocolOptions{});
    for (const CheckSpec& spec : checks::memory_checks())
        if (spec.id == "memory.unknown-command") run.run(spec);
    auto results = run.take();
    EXPECT_EQ(results.size(), 1u) << testing::dump(results);
    return results.empty() ? CheckResult{} : results.front();
}

FakeBench memory_node() {
    return FakeBench(
        testing::fake_config(ProtocolSet{Protocol::kDatagram, Protocol::kMemoryConfiguration}));
}

TEST(MemoryChecksTest, DefaultNodePassesEach) {
    const auto results = testing::protocol_results();
    testing::expect_each(
        results,
        {"memory.read-short-form", "memory.read-byte6-form", "memory.reply-form",
         "memory.unknown-space", "memory.config-options", "memory.unknown-command"},
        Status::kPass);
}

TEST(MemoryChecksTest, AnotherCodeForAnUnknownSpaceWarnsQuotingIt) {
    const auto results = testing::protocol_results({"unknown-space-0x1041"});
    const CheckResult& c = expect_status(results, "memory.unknown-space", Status::kWarn);
    EXPECT_NE((c.message + c.seen).find("1041"), std::string::npos) << c.message << " " << c.seen;
}

TEST(MemoryChecksTest, AWrongReplyFormWarns) {
    const auto results = testing::protocol_results({"reply-form"});
    expect_status(results, "memory.reply-form", Status::kWarn);
}

// A node whose PIP claims no Memory Configuration (OpenMRN's train node) gets no verdict on the
// read forms: CheckSpec::needs, not the node's name, decides.
TEST(MemoryChecksTest, TheReadFormsSkipOnANodeThatClaimsNoMemoryConfiguration) {
    simnode::NodeConfig c;
    c.node_id = NodeId{0x05'01'01'01'22'70ull};
    c.cdi = read_text(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios/train.xml");
    c.memory_config = false;
    std::string error;
    auto bench = testing::SimBench::serve(c, error);
    ASSERT_TRUE(bench) << error;
    auto node = bench->start();
    ASSERT_TRUE(node);
    ProtocolOptions o;
    o.selection.only = {"memory.read-*-form"};
    CheckContext ctx;
    const auto results = run_protocol_checks(*bench->session, *node, o, ctx);
    for (const char* id : {"memory.read-byte6-form", "memory.read-short-form"}) {
        const CheckResult& r = expect_status(results, id, Status::kSkip);
        EXPECT_EQ(r.message, "not run: the node's PIP does not claim Memory Configuration") << id;
    }
}

// MemoryConfigurationS §4.3: an unknown command shall be answered with Datagram Rejected.
TEST(MemoryChecksTest, AnUnknownCommandAcceptedFails) {
    FakeBench f = memory_node();
    f.node.set_datagram_handler(
        [&](const ReceivedDatagram& d) { f.node.accept_datagram(d.source_alias); });
    const CheckResult r = unknown_command(f);
    EXPECT_EQ(r.status, Status::kFail) << r.message;
    EXPECT_EQ(r.seen, "Datagram Received OK") << r.message;
    EXPECT_EQ(r.expected, "Datagram Rejected");
    EXPECT_EQ(r.section, "MemoryConfigurationS §4.3");
}

TEST(MemoryChecksTest, AnUnknownCommandUnansweredFails) {
    FakeBench f = memory_node();
    f.node.set_datagram_handler([](const ReceivedDatagram&) {});
    const CheckResult r = unknown_command(f);
    EXPECT_EQ(r.status, Status::kFail) << r.message;
    EXPECT_EQ(r.seen, "no answer") << r.message;
}

// The error code is free; another one passes and the message names the suggested one.
TEST(MemoryChecksTest, AnUnknownCommandRejectedWithAnyCodePasses) {
    for (const std::uint16_t code : {0x1041, 0x1000}) {
        FakeBench f = memory_node();
        f.node.set_datagram_handler(
            [&](const ReceivedDatagram& d) { f.node.reject_datagram(d.source_alias, code); });
        const CheckResult r = unknown_command(f);
        EXPECT_EQ(r.status, Status::kPass) << r.message;
        EXPECT_EQ(r.message.find("suggested") != std::string::npos, code != 0x1041) << r.message;
    }
}

}  // namespace
}  // namespace olcb::conform
