// A node's memory map: the verdict of every listed variable from the run's evidence, every
// tested replica listed, and whole runs against the simulated node (a clean one and one that
// stores ints little-endian, where writing stops at the first int).
#include "conformance/run/memory_map.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "conformance/checks/protocol_checks.hpp"
#include "conformance/conform_test_util.hpp"
#include "conformance/link/link.hpp"
#include "conformance/link/session.hpp"
#include "conformance/run/encoding_checks.hpp"
#include "conformance/run/runner.hpp"
#include "openlcb/sim_network.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::conform {
namespace {

namespace fs = std::filesystem;

constexpr const char* kCdi = R"(<?xml version="1.0"?><cdi><segment space="253"><name>S</name>
<int><name>Plain</name></int>
<group><name>Internal data</name><description>Do not change these settings.</description>
<int><name>Version</name></int></group>
<action size="1"><name>Go</name><value>1</value></action>
<blob size="4" mode="readwrite"><name>Raw</name></blob>
<group replication="100"><name>Port</name><int><name>Mode</name></int></group>
</segment><segment space="255"><int><name>Fixed</name></int></segment></cdi>)";

const cdi::MapVariable* find(const MemoryMapSpace& s, const std::string& name) {
    for (const auto& v : s.map.variables) {
        if (v.name == name) return &v;
    }
    return nullptr;
}

const VariableVerdict* verdict_of(const MemoryMapSpace& s, const std::string& name) {
    for (std::size_t i = 0; i < s.map.variables.size(); ++i) {
        if (s.map.variables[i].name == name) return &s.verdicts[i];
    }
    return nullptr;
}

class NodeMemoryMap : public ::testing::Test {
protected:
    void SetUp() override { load_cdi(kCdi, doc_, layout_); }
    std::vector<MemoryMapSpace> map(const MapEvidence& evidence) {
        return node_memory_map(*layout_, evidence);
    }
    cdi::Document doc_;
    std::optional<cdi::Layout> layout_;
};

TEST_F(NodeMemoryMap, VerdictsFollowTheRulesThatKeptVariablesUnwritten) {
    MapEvidence evidence;
    evidence.sample = 3;
    const auto spaces = map(evidence);
    ASSERT_EQ(spaces.size(), 2u);
    const MemoryMapSpace& s = spaces[0];
    ASSERT_EQ(s.verdicts.size(), s.map.variables.size());
    EXPECT_EQ(verdict_of(s, "S.Internal data.Version")->verdict, MapVerdict::kProtected);
    EXPECT_EQ(verdict_of(s, "S.Go")->verdict, MapVerdict::kProtected);
    EXPECT_NE(verdict_of(s, "S.Raw")->reason.find("--blob"), std::string::npos);
    EXPECT_NE(verdict_of(s, "S.Port(1).Mode")->reason.find("not sampled"), std::string::npos);
    // Planned, but the checks never reached it.
    EXPECT_NE(verdict_of(s, "S.Plain")->reason.find("beyond"), std::string::npos);
    EXPECT_NE(verdict_of(spaces[1], "seg1.Fixed")->reason.find("read-only"), std::string::npos);
    evidence.planned = {find(s, "S.Plain")->ordinal};
    const auto planned = map(evidence);
    EXPECT_NE(verdict_of(planned[0], "S.Plain")->reason.find("not reached"), std::string::npos);
    evidence.protection.exclude = {"*Plain*"};
    const auto excluded = map(evidence);
    EXPECT_NE(verdict_of(excluded[0], "S.Plain")->reason.find("--exclude"), std::string::npos);
    evidence.not_written = "--read-only: no write";
    const auto read_only = map(evidence);
    EXPECT_EQ(verdict_of(read_only[0], "S.Plain")->reason, "--read-only: no write");
    EXPECT_EQ(verdict_of(read_only[0], "S.Internal data.Version")->verdict, MapVerdict::kProtected);
}

TEST_F(NodeMemoryMap, TestedVerdictsAreKeptUnlessTheLinkWentDown) {
    MapEvidence evidence;
    const auto first = map(evidence);
    const std::uint64_t plain = find(first[0], "S.Plain")->ordinal;
    VariableVerdict failed{MapVerdict::kFailed, "reads back as 00", "5", "05", {}};
    failed.values.push_back({"255", "FF", "00", "0", "", false});
    evidence.tested.push_back({plain, failed});
    const auto spaces = map(evidence);
    const VariableVerdict* v = verdict_of(spaces[0], "S.Plain");
    EXPECT_EQ(v->verdict, MapVerdict::kFailed);
    ASSERT_EQ(v->values.size(), 1u);
    EXPECT_EQ(v->values[0].read, "00");
    const nlohmann::json j = memory_map_json(spaces);
    EXPECT_EQ(j[0]["verdicts"]["failed"], 1);
    EXPECT_EQ(j[0]["verdicts"]["protected"], 2);
    const nlohmann::json& var = j[0]["variables"][0];
    EXPECT_EQ(var["verdict"], "failed");
    EXPECT_EQ(var["original"]["bytes"], "05");
    EXPECT_EQ(var["values"][0]["written"], "FF");
    EXPECT_FALSE(var["values"][0]["ok"].get<bool>());
    evidence.not_judged = "not judged: the link went down mid-run";
    const auto unjudged = map(evidence);
    const VariableVerdict* after = verdict_of(unjudged[0], "S.Plain");
    EXPECT_EQ(after->verdict, MapVerdict::kSkipped);
    EXPECT_EQ(after->reason, evidence.not_judged);
}

// The map lists every replica the encoding checks sample, however large the group.
TEST(NodeMemoryMapSampling, EveryTestedReplicaIsListed) {
    for (std::uint64_t count : {5u, 37u, 100u, 1000u, 65535u}) {
        const std::string cdi =
            "<?xml version=\"1.0\"?><cdi><segment space=\"253\"><group "
            "replication=\"" +
            std::to_string(count) + "\"><int/></group></segment></cdi>";
        cdi::Document doc;
        std::optional<cdi::Layout> layout;
        load_cdi(cdi.c_str(), doc, layout);
        for (std::size_t sample : {1u, 2u, 3u, 7u}) {
            MapEvidence evidence;
            evidence.sample = sample;
            const auto spaces = node_memory_map(*layout, evidence);
            std::set<std::uint64_t> listed;
            for (const auto& v : spaces.at(0).map.variables) listed.insert(v.address);
            for (std::uint64_t r = 0; r < count; ++r) {
                if (replica_sampled(r, count, sample)) {
                    EXPECT_TRUE(listed.count(r)) << r << " of " << count << ", sample " << sample;
                }
            }
            for (std::size_t i = 0; i < spaces[0].verdicts.size(); ++i) {
                const bool tested =
                    replica_sampled(spaces[0].map.variables[i].address, count, sample);
                EXPECT_EQ(spaces[0].verdicts[i].reason.find("not sampled") == std::string::npos,
                          tested);
            }
        }
    }
}

// Whole runs in-process against the simulated node.
class MemoryMapRun : public ::testing::Test {
protected:
    NodeReport run(const simnode::FaultSet& faults) {
        simnode::NodeConfig config;
        config.node_id = kDut;
        config.cdi = read_text(fs::path(OLCB_SOURCE_DIR) / "scenarios" / "default.xml");
        config.faults = faults;
        std::string error;
        dut_ = simnode::SimNode::create(config, error);
        EXPECT_TRUE(dut_) << error;
        if (!dut_) return {};
        net_.set_logging(false);
        net_.add_stack(dut_->stack());
        dut_->stack().start(net_.now());
        link_ = make_sim_link(net_, kTool);
        session_ = std::make_unique<Session>(*link_);
        EXPECT_TRUE(session_->start());
        auto node = session_->find_node(kDut);
        EXPECT_TRUE(node);
        if (!node) return {};
        RunOptions options;
        options.sample = 2;
        options.backup_path =
            (fs::temp_directory_path() / ("memory_map_test_" + std::to_string(::getpid())))
                .string();
        ProtocolChecks checks = [](Session& s, const NodeInfo& n, CheckContext& ctx) {
            return run_protocol_checks(s, n, ProtocolOptions{}, ctx);
        };
        return run_node(*session_, *node, options, checks, progress_);
    }

    SimNetwork net_;
    std::unique_ptr<simnode::SimNode> dut_;
    std::unique_ptr<Link> link_;
    std::unique_ptr<Session> session_;
    std::ostringstream progress_;
};

const MemoryMapSpace* space_of(const NodeReport& r, std::uint32_t space) {
    for (const auto& s : r.memory_map) {
        if (s.map.space == space) return &s;
    }
    return nullptr;
}

TEST_F(MemoryMapRun, CleanNodeVerifiesEveryTestedVariable) {
    const NodeReport r = run({});
    const MemoryMapSpace* settings = space_of(r, 253);
    ASSERT_NE(settings, nullptr);
    ASSERT_NE(space_of(r, 251), nullptr);
    std::size_t verified = 0;
    for (std::size_t i = 0; i < settings->verdicts.size(); ++i) {
        const VariableVerdict& v = settings->verdicts[i];
        EXPECT_NE(v.verdict, MapVerdict::kFailed) << settings->map.variables[i].name;
        if (v.verdict != MapVerdict::kVerified) continue;
        ++verified;
        EXPECT_FALSE(v.original_bytes.empty());
        ASSERT_FALSE(v.values.empty());
        for (const TestedValue& t : v.values) EXPECT_TRUE(t.ok) << t.value;
    }
    // 9 settings plus Ports 1 and 4 (4 variables each); the action is protected, 2 and 3 skipped.
    EXPECT_EQ(verified, 9u + 8u);
    EXPECT_EQ(verdict_of(*settings, "Settings.Flash LEDs")->verdict, MapVerdict::kProtected);
    EXPECT_EQ(verdict_of(*settings, "Settings.Port(1).On event")->verdict, MapVerdict::kSkipped);
    const VariableVerdict* trim = verdict_of(*settings, "Settings.Trim");
    ASSERT_NE(trim, nullptr);
    EXPECT_EQ(trim->values.front().value, "-1000");
    EXPECT_EQ(trim->values.front().written, "FC 18");
    EXPECT_EQ(trim->values.front().read_value, "-1000");
}

TEST_F(MemoryMapRun, LittleEndianIntsFailWithTheBytesReadBack) {
    simnode::FaultSet faults;
    faults.by_name.emplace("int-byte-order", simnode::FaultValue{1});
    const NodeReport r = run(faults);
    const MemoryMapSpace* settings = space_of(r, 253);
    ASSERT_NE(settings, nullptr);
    const VariableVerdict* trim = verdict_of(*settings, "Settings.Trim");
    ASSERT_NE(trim, nullptr);
    EXPECT_EQ(trim->verdict, MapVerdict::kFailed);
    EXPECT_FALSE(trim->reason.empty());
    bool swapped = false;
    for (const TestedValue& t : trim->values) swapped |= t.written == "FC 18" && t.read == "18 FC";
    EXPECT_TRUE(swapped);
    // A one-byte int cannot be stored in the wrong order; after Trim's original failed to read
    // back, nothing further was written.
    EXPECT_EQ(verdict_of(*settings, "Settings.Enabled")->verdict, MapVerdict::kVerified);
    EXPECT_EQ(verdict_of(*settings, "Settings.Label")->verdict, MapVerdict::kSkipped);
    EXPECT_NE(verdict_of(*settings, "Settings.Label")->reason.find("not reached"),
              std::string::npos);
}

}  // namespace
}  // namespace olcb::conform
