// The probes the checks share: the CDI download judges the NUL (cdi.nul-terminated,
// cdi.nul-at-highest) and reads the CDI once, by stream when the node offers streams.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

#include "conformance/checks/check_registry.hpp"
#include "conformance/checks/check_run.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/checks/probes.hpp"
#include "conformance/checks_test_util.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

using testing::expect_status;
using testing::SimBench;

// Read commands the tool sent for space 0xFF, from the bus log: datagram reads (0x20 0x43, one
// frame each) and stream reads (0x20 0x63, the first of two frames).
struct CdiReads {
    std::size_t datagram = 0;
    std::size_t stream = 0;
};

CdiReads cdi_reads(const SimBench& b) {
    CdiReads n;
    for (const LoggedFrame& f : b.net.log()) {
        const std::uint32_t type = (f.frame.id >> 24) & 0x7;  // 2: only frame, 3: first frame
        if ((type != 2 && type != 3) || f.frame.len < 2 || f.frame.data[0] != 0x20) continue;
        if (f.frame.data[1] == 0x43) ++n.datagram;
        if (f.frame.data[1] == 0x63) ++n.stream;
    }
    return n;
}

// The CdiDownload probe of a run with options against the default node.
CdiReads download(SimBench& b, const ProtocolOptions& options, std::string& how) {
    b.net.set_logging(true);
    auto node = b.start();
    if (!node) return {};
    CheckRun run(*b.session, *node, options);
    const CdiDownload& d = run.probe<CdiDownload>();
    how = (d.by_stream ? "stream " : "datagrams ") + std::to_string(d.result.data.size()) + " " +
          d.sampled;
    return cdi_reads(b);
}

TEST(ProbesTest, TheCdiDownloadFindsTheNulAtTheHighestAddress) {
    const auto results = testing::protocol_results();
    expect_status(results, "cdi.nul-terminated", Status::kPass);
    expect_status(results, "cdi.nul-at-highest", Status::kPass);
}

TEST(ProbesTest, AnUnterminatedCdiFailsNulTerminated) {
    const auto results = testing::protocol_results({"cdi-unterminated"});
    expect_status(results, "cdi.nul-terminated", Status::kFail);
}

TEST(ProbesTest, WithStreamsTheCdiIsReadOnceAndSampledByTwoDatagramReads) {
    SimBench b;
    std::string how;
    const CdiReads n = download(b, {}, how);
    EXPECT_EQ(how, "stream 2562 0x00000000-0x0000003F, 0x000009C2-0x00000A01");
    EXPECT_EQ(n.stream, 1u);
    EXPECT_EQ(n.datagram, 2u);
}

TEST(ProbesTest, WithoutStreamsTheCdiIsReadByDatagramsOnly) {
    SimBench b;
    ProtocolOptions o;
    o.no_stream = true;
    std::string how;
    const CdiReads n = download(b, o, how);
    EXPECT_EQ(how, "datagrams 2562 ");
    EXPECT_EQ(n.stream, 0u);
    EXPECT_EQ(n.datagram, (2562u + 63) / 64);
}

TEST(ProbesTest, AStreamPastTheCdiLimitIsCutAndTheCdiReadByDatagrams) {
    SimBench b;
    ProtocolOptions o;
    o.max_cdi_bytes = 1000;
    std::string how;
    const CdiReads n = download(b, o, how);
    EXPECT_EQ(how, "datagrams 1000 ");
    EXPECT_EQ(n.stream, 1u);
    EXPECT_EQ(n.datagram, (1000u + 63) / 64);
}

TEST(ProbesTest, StreamAndDatagramReadsOfTheCdiAreJudgedApart) {
    // A node whose stream never ends: the CDI is read by datagrams and stream.cdi-read fails.
    const auto results = testing::protocol_results({"stream-no-complete"});
    expect_status(results, "cdi.read", Status::kPass);
    expect_status(results, "stream.cdi-read", Status::kFail);
}

}  // namespace
}  // namespace olcb::conform
