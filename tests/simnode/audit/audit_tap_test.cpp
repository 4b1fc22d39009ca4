// AuditTap: opens both files at once, audits the frames of an in-process segment through the
// port it wraps, or a hub's frames by the connection they came on, and marks the files complete
// when the run ends.
#include "simnode/audit/audit_tap.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "openlcb/gridconnect.hpp"
#include "openlcb/in_process_bus.hpp"
#include "openlcb/tcp_hub_server.hpp"
#include "support/temp_files.hpp"

namespace olcb::simnode::audit {
namespace {

using nlohmann::json;
using test_support::read_text;
using test_support::TempDir;

// Addressed MTI 0x04F9 from alias 0x12C to 0x343: allocated to nothing (message.unknown-mti),
// a finding whatever the audit assumes of the client's alias.
const CanFrame kUnknownMti = *gridconnect::parse_frame(":X194F912CN0343;");

class AuditTapTest : public ::testing::Test {
protected:
    std::unique_ptr<AuditTap> open_tap() {
        std::string error;
        auto tap = AuditTap::open(io_, AuditFiles{json_path_, junit_path_}, error);
        EXPECT_TRUE(tap) << error;
        return tap;
    }
    json audit_json() const { return json::parse(read_text(json_path_)); }

    boost::asio::io_context io_;
    TempDir dir_;
    std::filesystem::path json_path_ = dir_.path() / "audit.json";
    std::filesystem::path junit_path_ = dir_.path() / "audit.xml";
};

TEST_F(AuditTapTest, OpenWritesBothFilesAtOnceAndFinishMarksThemComplete) {
    auto tap = open_tap();
    ASSERT_TRUE(tap);
    EXPECT_EQ(audit_json()["complete"], false);
    EXPECT_TRUE(audit_json()["findings"].empty());
    EXPECT_NE(read_text(junit_path_).find("<testsuite"), std::string::npos);
    EXPECT_EQ(tap->finish(), "");
    EXPECT_EQ(audit_json()["complete"], true);
    std::filesystem::remove(json_path_);
    EXPECT_EQ(tap->finish(), "");
    EXPECT_FALSE(std::filesystem::exists(json_path_)) << "only the first finish writes";
}

TEST_F(AuditTapTest, APathThatCannotBeWrittenFailsOpen) {
    std::string error;
    auto tap = AuditTap::open(io_, AuditFiles{dir_.path() / "missing" / "audit.json", {}}, error);
    EXPECT_FALSE(tap);
    EXPECT_NE(error.find("missing"), std::string::npos) << error;
}

TEST_F(AuditTapTest, WithoutAHubTheWrappedPortAuditsWhatReachesTheNodes) {
    auto tap = open_tap();
    ASSERT_TRUE(tap);
    InProcessBus bus(io_);
    Transport& outside = bus.add_endpoint();
    Transport& port = tap->attach(bus.add_endpoint(), nullptr);
    int delivered = 0;
    port.set_handler([&](const CanFrame&) { ++delivered; });
    outside.send(kUnknownMti);
    io_.poll();
    EXPECT_EQ(delivered, 1) << "the wrapped port still delivers";
    EXPECT_EQ(tap->finish(), "");
    const json j = audit_json();
    ASSERT_EQ(j["findings"].size(), 1u);
    EXPECT_EQ(j["findings"][0]["rule"], "message.unknown-mti");
}

TEST_F(AuditTapTest, WithAHubFramesOfOtherEndpointsAreAuditedAndTheNodesPortIsReturned) {
    TcpHubServer hub(io_);  // before the tap: the tap, destroyed first, stops observing it
    auto tap = open_tap();
    ASSERT_TRUE(tap);
    Transport& nodes = hub.add_local_endpoint();
    Transport& bridge = hub.add_local_endpoint();
    EXPECT_EQ(&tap->attach(nodes, &hub), &nodes);
    nodes.send(kUnknownMti);  // the nodes' own frames are not judged as a client's
    bridge.send(kUnknownMti);
    io_.poll();
    EXPECT_EQ(tap->finish(), "");
    const json j = audit_json();
    ASSERT_EQ(j["findings"].size(), 1u);
    EXPECT_EQ(j["findings"][0]["rule"], "message.unknown-mti");
    EXPECT_TRUE(j["findings"][0]["client"]["remote"].is_null()) << "a bridge stays unnamed";
}

}  // namespace
}  // namespace olcb::simnode::audit
