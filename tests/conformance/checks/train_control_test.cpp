// The train, search and FDI checks against simulated train nodes in-process: a train node
// passes them all, each train fault is caught by its check, the checks that change a train's
// state wait for --node, and on a node without Traction Control (the default scenario's I/O node)
// they SKIP saying which protocol its PIP lacks (CheckSpec::needs).
#include <gtest/gtest.h>

#include "conformance/sim_bench.hpp"
#include "simnode/train_node.hpp"

namespace olcb::conform {
namespace {

using testing::expect_status;

constexpr NodeId kTrain{0x05'01'01'01'22'60ull};
constexpr NodeId kStation{0x05'01'01'01'22'80ull};

simnode::NodeConfig train_config(const std::vector<std::string>& faults = {}) {
    simnode::NodeConfig c;
    c.node_id = kTrain;
    c.cdi = read_text(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios/train.xml");
    c.user_name = "Big Boy 1";
    simnode::TrainConfig t;
    t.identity.address = 1732;
    t.identity.long_address = true;
    t.heartbeat = 1;
    t.fdi = read_text(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios/fdi/train.xml");
    c.train = t;
    std::string error;
    auto parsed = simnode::parse_faults(faults, error);
    EXPECT_TRUE(parsed) << error;
    if (parsed) c.faults = *parsed;
    return c;
}

ProtocolOptions train_options(bool named = true) {
    ProtocolOptions o;
    o.named = named;
    o.selection.only = {"train.*", "search.*", "fdi.*"};
    o.selection.thorough = true;
    o.train_address = 1732;
    return o;
}

std::vector<CheckResult> run_train(const simnode::NodeConfig& config, const ProtocolOptions& o,
                                   testing::SimBench** bench_out = nullptr) {
    std::string error;
    static std::unique_ptr<testing::SimBench> bench;
    bench = testing::SimBench::serve(config, error);
    EXPECT_TRUE(bench) << error;
    if (!bench) return {};
    if (bench_out) *bench_out = bench.get();
    auto node = bench->start();
    if (!node) return {};
    CheckContext ctx;
    return run_protocol_checks(*bench->session, *node, o, ctx);
}

TEST(TrainChecksGating, OnTheDefaultNodeTheySkipNamingTheProtocolItsPipLacks) {
    testing::SimBench b;
    CheckContext ctx;
    auto node = b.start();
    ASSERT_TRUE(node);
    const auto results = run_protocol_checks(*b.session, *node, train_options(), ctx);
    const CheckResult& t = expect_status(results, "train.is-train-event", Status::kSkip);
    EXPECT_EQ(t.message, "not run: the node's PIP does not claim Traction Control");
    const CheckResult& f = expect_status(results, "fdi.space", Status::kSkip);
    EXPECT_EQ(f.message, "not run: the node's PIP does not claim Function Description Information");
    expect_status(results, "search.name-match", Status::kSkip);
}

TEST(TrainChecks, ATrainNodePassesThemAll) {
    testing::SimBench* b = nullptr;
    const auto results = run_train(train_config(), train_options(), &b);
    for (const char* id : {"train.is-train-event",
                           "train.memory-spaces",
                           "train.controller",
                           "train.reserve",
                           "train.speed",
                           "train.function",
                           "train.function-space",
                           "train.estop",
                           "train.global-estop",
                           "train.global-eoff",
                           "train.listener",
                           "train.listener-forward",
                           "train.heartbeat",
                           "fdi.space",
                           "fdi.read",
                           "fdi.no-bom",
                           "fdi.utf8",
                           "fdi.xml-declaration",
                           "fdi.well-formed",
                           "fdi.valid",
                           "fdi.schema-location",
                           "fdi.functions",
                           "fdi.read-only",
                           "search.name-match",
                           "search.address-match",
                           "search.no-match-silent",
                           "search.reserved-ignored"})
        expect_status(results, id, Status::kPass);
    // Allocation needs a command station.
    expect_status(results, "search.allocate", Status::kSkip);
    // Left stopped, released, without listeners.
    ASSERT_TRUE(b && b->dut->train());
    EXPECT_TRUE(b->dut->train()->set_speed().is_zero());
    EXPECT_TRUE(b->dut->train()->controller().is_zero());
    EXPECT_TRUE(b->dut->train()->listeners().empty());
}

TEST(TrainChecks, WithoutNodeTheStateChangingChecksSkip) {
    const auto results = run_train(train_config(), train_options(false));
    for (const char* id : {"train.speed", "train.function", "train.estop", "train.listener",
                           "train.heartbeat", "train.reserve"}) {
        const CheckResult& c = expect_status(results, id, Status::kSkip);
        EXPECT_EQ(c.message, "changes the train's state: runs only on a node named with --node")
            << id;
    }
    expect_status(results, "train.is-train-event", Status::kPass);
    expect_status(results, "train.controller", Status::kPass);
    expect_status(results, "fdi.functions", Status::kPass);
}

TEST(FdiChecks, AnFdiItsSchemaRefusesFailsFdiValidAndItsFunctionsAreStillAsked) {
    simnode::NodeConfig c = train_config();
    // The second function's <number> is no number: the schema refuses it.
    c.train->fdi =
        "<?xml version=\"1.0\"?>\n<fdi xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
        "xsi:noNamespaceSchemaLocation=\"https://openlcb.org/schema/fdi/1/1/fdi.xsd\">\n"
        "<segment><function kind=\"binary\"><name>Light</name><number>0</number></function>\n"
        "<function kind=\"binary\"><name>Bad</name><number>two</number></function>\n"
        "</segment></fdi>\n";
    const auto results = run_train(c, train_options());
    expect_status(results, "fdi.well-formed", Status::kPass);
    const CheckResult& v = expect_status(results, "fdi.valid", Status::kFail);
    EXPECT_NE(v.message.find("FDI"), std::string::npos) << v.message;
    // The model keeps the function it could read, and the train answers for it.
    expect_status(results, "fdi.functions", Status::kPass);
}

TEST(FdiChecks, OnANamedTrainTheFirstFunctionIsSetReadBackAndRestored) {
    // The only function is analog 0..31: set to 31, read back, set back to 0.
    simnode::NodeConfig c = train_config();
    c.train->fdi =
        "<?xml version=\"1.0\"?>\n<fdi xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
        "xsi:noNamespaceSchemaLocation=\"https://openlcb.org/schema/fdi/1/1/fdi.xsd\">\n"
        "<segment><function kind=\"analog\"><name>Volume</name><number>8</number>"
        "<min>0</min><max>31</max></function>\n</segment></fdi>\n";
    testing::SimBench* b = nullptr;
    const auto results = run_train(c, train_options(), &b);
    expect_status(results, "fdi.valid", Status::kPass);
    const CheckResult& f = expect_status(results, "fdi.functions", Status::kPass);
    EXPECT_NE(f.message.find("does not name is answered"), std::string::npos) << f.message;
    ASSERT_TRUE(b && b->dut->train());
    EXPECT_EQ(b->dut->train()->function(8), 0u);
    EXPECT_TRUE(b->dut->train()->controller().is_zero());
}

TEST(FdiChecks, WithoutNodeNoFunctionIsSet) {
    const auto results = run_train(train_config(), train_options(false));
    const CheckResult& f = expect_status(results, "fdi.functions", Status::kPass);
    EXPECT_NE(f.message.find("Set Function not tried"), std::string::npos) << f.message;
}

struct FaultCase {
    const char* fault;
    const char* check;
    Status status;
};

class TrainFault : public ::testing::TestWithParam<FaultCase> {};

TEST_P(TrainFault, IsCaughtByItsCheck) {
    const FaultCase f = GetParam();
    const auto results = run_train(train_config({f.fault}), train_options());
    expect_status(results, f.check, f.status);
}

INSTANTIATE_TEST_SUITE_P(
    Faults, TrainFault,
    ::testing::Values(FaultCase{"speed-byte-order", "train.speed", Status::kFail},
                      FaultCase{"listener-not-forwarded", "train.listener-forward", Status::kFail},
                      FaultCase{"heartbeat-ignored", "train.heartbeat", Status::kFail},
                      FaultCase{"no-fdi-space", "train.memory-spaces", Status::kPass},
                      FaultCase{"no-fdi-space", "fdi.space", Status::kFail},
                      FaultCase{"reserve-exclusive", "train.reserve", Status::kPass}),
    [](const auto& info) {
        std::string name = std::string(info.param.fault) + "_" + info.param.check;
        for (char& c : name)
            if (c == '-' || c == '.') c = '_';
        return name;
    });

TEST(TrainSearchChecks, ACommandStationCreatesTrainsForThem) {
    simnode::NodeConfig station = train_config();
    station.node_id = kStation;
    station.command_station = station.train;
    station.train.reset();
    std::string error;
    auto bench = testing::SimBench::serve(station, error);
    ASSERT_TRUE(bench) << error;
    std::vector<std::unique_ptr<simnode::SimNode>> created;
    bench->dut->set_train_factory([&](const simnode::NodeConfig& c) {
        std::string why;
        auto n = simnode::SimNode::create(c, why);
        if (!n) return false;
        bench->net.add_stack(n->stack());
        n->stack().start(bench->net.now());
        created.push_back(std::move(n));
        return true;
    });
    auto node = bench->start();
    ASSERT_TRUE(node);
    ProtocolOptions o = train_options();
    o.command_station = true;
    CheckContext ctx;
    const auto results = run_protocol_checks(*bench->session, *node, o, ctx);
    for (const char* id :
         {"search.allocate", "search.allocate-partial", "search.allocate-reserved"})
        expect_status(results, id, Status::kPass);
    // The station claims no Traction Control: the train checks are not its.
    expect_status(results, "train.speed", Status::kSkip);
    EXPECT_EQ(created.size(), 2u);  // one each for search.allocate and -partial
}

}  // namespace
}  // namespace olcb::conform
