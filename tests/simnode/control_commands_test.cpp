// ControlCommands without sockets: requests on a NodeRegistry whose nodes run on an in-process
// bus through a StackDriver (real time, bounded loops), with a bus port recording every frame.
#include "simnode/control_commands.hpp"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <fstream>
#include <functional>
#include <future>

#include "openlcb/gridconnect.hpp"
#include "openlcb/in_process_bus.hpp"
#include "openlcb/stack_driver.hpp"
#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode {
namespace {

using test::kNodeId;
using Json = ControlJson;
using namespace std::chrono_literals;

constexpr const char* kNode = "05.01.01.01.22.00";
constexpr const char* kInitComplete = ":X19100343N050101012200;";

class ControlCommandsTest : public ::testing::Test {
protected:
    ControlCommandsTest()
        : bus_(io_),
          outside_(bus_.add_endpoint(
              [this](const CanFrame& f) { frames_.push_back(gridconnect::format(f)); })),
          driver_(io_, bus_.add_endpoint()),
          registry_(nodes_, driver_),
          commands_(registry_, scenario_) {
        scenario_.image_root = images_.path();
        commands_.set_log_handler([this](const std::string& line) { log_.push_back(line); });
    }

    // The default node with its images in the temp directory, started and initialized.
    void start_default() {
        NodeConfig c;
        c.node_id = kNodeId;
        c.cdi = test::default_cdi();
        c.cdi_file = "default.xml";
        c.image_dir = images_.path() / kNode;
        std::string error;
        ASSERT_TRUE(registry_.add(c, error)) << error;
        registry_.start_all();
        // The bus delivers after the stack sent: wait for the frame, not only the state.
        ASSERT_TRUE(run_until([this] { return initialized(kNodeId) && seen(kInitComplete); }));
    }

    bool run_until(const std::function<bool()>& done, std::chrono::milliseconds limit = 3s) {
        const auto end = std::chrono::steady_clock::now() + limit;
        while (!done() && std::chrono::steady_clock::now() < end) {
            io_.run_one_for(5ms);
            if (io_.stopped()) io_.restart();
        }
        return done();
    }

    bool initialized(NodeId id) const {
        const SimNode* node = registry_.find(id);
        return node != nullptr && node->stack().initialized();
    }

    bool seen(const std::string& frame) const {
        return std::find(frames_.begin(), frames_.end(), frame) != frames_.end();
    }

    Json ask(const Json& request) { return commands_.handle(request); }
    Json ask_line(std::string_view line) { return commands_.handle_line(line); }

    static std::string error_of(const Json& response) {
        EXPECT_EQ(response["ok"], false) << response.dump();
        return response.value("error", std::string());
    }

    test::TempDir images_;
    boost::asio::io_context io_;
    InProcessBus bus_;
    Transport& outside_;
    std::vector<std::string> frames_;
    StackDriver driver_;
    std::vector<std::unique_ptr<SimNode>> nodes_;
    NodeRegistry registry_;
    Scenario scenario_;
    ControlCommands commands_;
    std::vector<std::string> log_;
};

TEST_F(ControlCommandsTest, ListDescribesEveryNode) {
    start_default();
    const Json r = ask(Json{{"cmd", "list"}});
    ASSERT_EQ(r["ok"], true) << r.dump();
    ASSERT_EQ(r["nodes"].size(), 1u);
    const Json& n = r["nodes"][0];
    EXPECT_EQ(n["node_id"], kNode);
    EXPECT_EQ(n["alias"], "0x343");
    EXPECT_EQ(n["initialized"], true);
    EXPECT_EQ(n["cdi"], "default.xml");
    EXPECT_EQ(n["faults"], Json::array());
    EXPECT_EQ(n["images"], (images_.path() / kNode).string());
    const Json fd = Json{{"space", 253}, {"size", 179}, {"writable", true}};
    EXPECT_NE(std::find(n["spaces"].begin(), n["spaces"].end(), fd), n["spaces"].end())
        << n["spaces"].dump();
}

TEST_F(ControlCommandsTest, MalformedRequestsGetClearErrors) {
    start_default();
    EXPECT_TRUE(error_of(ask_line("{\"cmd\":")).starts_with("not JSON: "))
        << ask_line("{\"cmd\":").dump();
    EXPECT_TRUE(error_of(ask_line("\xff\xfe")).starts_with("not JSON: "));
    const std::string junk(10000, 'x');
    EXPECT_LT(error_of(ask_line(junk)).size(), 300u) << "the parser's quote of the line is cut";
    EXPECT_EQ(error_of(ask_line("[1,2]")), "a request is a JSON object, e.g. {\"cmd\":\"list\"}");
    EXPECT_TRUE(error_of(ask_line("{}")).starts_with("the request needs \"cmd\""));
    EXPECT_TRUE(error_of(ask_line("{\"cmd\":5}")).starts_with("the request needs \"cmd\""));
    EXPECT_TRUE(error_of(ask_line("{\"cmd\":\"frobnicate\"}"))
                    .starts_with("unknown command 'frobnicate' (commands: list, "));
    EXPECT_EQ(error_of(ask_line("{\"cmd\":\"list\",\"verbose\":true}")),
              "unknown field 'verbose' of list (fields: none)");
    EXPECT_EQ(error_of(ask(Json{{"cmd", "reboot"}})), "the request needs \"node\"");
    EXPECT_EQ(error_of(ask(Json{{"cmd", "reboot"}, {"node", 5}})),
              "\"node\" '5' is not a node ID such as 05.01.01.01.22.00");
    EXPECT_EQ(error_of(ask(Json{{"cmd", "reboot"}, {"node", "05.01.01.01.22.99"}})),
              "no node 05.01.01.01.22.99 (list shows the nodes)");
    const Json bad_address{
        {"cmd", "read"}, {"node", kNode}, {"space", 253}, {"address", -1}, {"count", 4}};
    EXPECT_EQ(error_of(ask(bad_address)),
              "\"address\" '-1' must be a whole number 0..4294967295 (or a \"0x\" hex string)");
    const Json bad_count{
        {"cmd", "read"}, {"node", kNode}, {"space", "0xFD"}, {"address", "0x10"}, {"count", 4097}};
    EXPECT_TRUE(
        error_of(ask(bad_count)).starts_with("\"count\" '4097' must be a whole number 1.."));
    const Json odd_hex{
        {"cmd", "write"}, {"node", kNode}, {"space", 253}, {"address", 0}, {"data", "123"}};
    EXPECT_TRUE(error_of(ask(odd_hex)).starts_with("\"data\" must be 1..4096 bytes as hex"));
    EXPECT_EQ(error_of(ask(Json{{"cmd", "set-faults"}, {"node", kNode}, {"faults", {1, 2}}})),
              "\"faults\" must be a string or a list of strings");
}

TEST_F(ControlCommandsTest, DeeplyNestedRequestsAreRefusedUnparsed) {
    start_default();
    // 32,739 levels filled a 64 KiB line: quoting the value printed it recursively, which
    // overflowed the stack under ASan.
    const std::size_t deep = 32'739;
    const std::string line =
        "{\"cmd\":\"read\",\"node\":" + std::string(deep, '[') + std::string(deep, ']') + "}";
    EXPECT_EQ(error_of(ask_line(line)),
              "request nested deeper than 32 levels of arrays and objects");
    EXPECT_EQ(error_of(ask_line(std::string(65'536, '{'))),
              "request nested deeper than 32 levels of arrays and objects");
    // 32 levels pass; brackets in strings are text.
    const auto nested_id = [](std::size_t levels) {
        return "{\"cmd\":\"list\",\"id\":" + std::string(levels - 1, '[') +
               std::string(levels - 1, ']') + "}";
    };
    EXPECT_EQ(ask_line(nested_id(32))["ok"], true);
    EXPECT_EQ(error_of(ask_line(nested_id(33))),
              "request nested deeper than 32 levels of arrays and objects");
    const std::string in_string = "{\"cmd\":\"list\",\"id\":\"" + std::string(100, '[') + "\\\"" +
                                  std::string(100, '{') + "\"}";
    const Json r = ask_line(in_string);
    EXPECT_EQ(r["ok"], true) << r.dump().substr(0, 200);
}

TEST_F(ControlCommandsTest, TheRequestIdIsEchoedWhenItIsAScalar) {
    start_default();
    EXPECT_EQ(ask(Json{{"cmd", "list"}, {"id", 42}})["id"], 42);
    EXPECT_EQ(ask(Json{{"cmd", "nope"}, {"id", "a"}})["id"], "a");
    EXPECT_FALSE(ask(Json{{"cmd", "list"}, {"id", Json::array({1})}}).contains("id"));
}

TEST_F(ControlCommandsTest, ReadAndWriteHonourTheSpaceBounds) {
    start_default();
    const Json write{
        {"cmd", "write"}, {"node", kNode}, {"space", 253}, {"address", 175}, {"data", "0a0b 0c0d"}};
    const Json w = ask(write);
    ASSERT_EQ(w["ok"], true) << w.dump();
    EXPECT_EQ(w["written"], 4);
    const Json r =
        ask(Json{{"cmd", "read"}, {"node", kNode}, {"space", 253}, {"address", 175}, {"count", 4}});
    ASSERT_EQ(r["ok"], true) << r.dump();
    EXPECT_EQ(r["data"], "0a0b0c0d");
    EXPECT_EQ(registry_.find(kNodeId)->memory().read(253, 175, 4),
              (std::vector<std::uint8_t>{10, 11, 12, 13}));
    EXPECT_EQ(
        error_of(ask(Json{
            {"cmd", "read"}, {"node", kNode}, {"space", 253}, {"address", 176}, {"count", 4}})),
        "space 253 (0xFD) holds addresses 0..178; 4 byte(s) at 176 do not fit");
    Json past = write;
    past["address"] = 179;
    EXPECT_EQ(error_of(ask(past)),
              "space 253 (0xFD) holds addresses 0..178; 4 byte(s) at 179 do not fit");
    Json cdi = write;
    cdi["space"] = 255;
    EXPECT_EQ(error_of(ask(cdi)), "space 255 (0xFF) is read-only");
    Json version = write;  // 251 is read and write, its version byte included (CDI §5.1.2)
    version["space"] = 251;
    version["address"] = 0;
    EXPECT_EQ(ask(version)["ok"], true);
    Json unknown = write;
    unknown["space"] = 7;
    EXPECT_EQ(error_of(ask(unknown)),
              "node 05.01.01.01.22.00 serves no space 7 (0x07) (it serves 251, 252, 253, 255)");
}

TEST_F(ControlCommandsTest, WritingTheUserNameAnnouncesTheNodeAgain) {
    start_default();
    frames_.clear();
    const Json r = ask(Json{{"cmd", "write"},
                            {"node", kNode},
                            {"space", 251},
                            {"address", 1},
                            {"data", "4e657700"}});  // "New"
    ASSERT_EQ(r["ok"], true) << r.dump();
    EXPECT_TRUE(run_until([this] { return seen(kInitComplete); })) << "SNIP changed";
    EXPECT_EQ(registry_.find(kNodeId)->snip().user_name, "New");
}

TEST_F(ControlCommandsTest, SetFaultsRebuildsTheNodeWithThemAndClearRemovesThem) {
    start_default();
    EXPECT_TRUE(error_of(ask(Json{{"cmd", "set-faults"}, {"node", kNode}, {"faults", "bogus"}}))
                    .starts_with("unknown fault 'bogus' (known: "));
    frames_.clear();
    Json r = ask(Json{{"cmd", "set-faults"},
                      {"node", kNode},
                      {"faults", {"reject-temporary=2", "int-byte-order"}}});
    ASSERT_EQ(r["ok"], true) << r.dump();
    EXPECT_EQ(r["restarted"], true);
    EXPECT_EQ(r["faults"], Json({"int-byte-order", "reject-temporary=2"}));
    EXPECT_TRUE(run_until([this] { return seen(kInitComplete) && initialized(kNodeId); }));
    EXPECT_EQ(registry_.find(kNodeId)->config().faults.value("reject-temporary"), FaultValue{2});
    // A parameter given again replaces the old one; the rest stays.
    r = ask(Json{{"cmd", "set-faults"}, {"node", kNode}, {"faults", "reject-temporary=5"}});
    EXPECT_EQ(r["faults"], Json({"int-byte-order", "reject-temporary=5"}));
    r = ask(Json{{"cmd", "set-faults"}, {"node", kNode}, {"faults", "int-byte-order"}});
    EXPECT_EQ(r["restarted"], false) << "nothing changed, nothing restarted";
    EXPECT_TRUE(error_of(ask(Json{{"cmd", "clear-faults"}, {"node", kNode}, {"faults", "nope"}}))
                    .starts_with("unknown fault 'nope'"));
    r = ask(Json{{"cmd", "clear-faults"}, {"node", kNode}, {"faults", "reject-temporary"}});
    EXPECT_EQ(r["faults"], Json({"int-byte-order"})) << r.dump();
    r = ask(Json{{"cmd", "clear-faults"}, {"node", kNode}});
    EXPECT_EQ(r["faults"], Json::array());
    EXPECT_TRUE(registry_.find(kNodeId)->config().faults.none());
    ASSERT_FALSE(log_.empty());
    EXPECT_EQ(log_.back(), "control: node 05.01.01.01.22.00 faults none (restarted)");
}

TEST_F(ControlCommandsTest, RebootSendsInitializationCompleteAgain) {
    NodeConfig c;
    c.node_id = kNodeId;
    c.cdi = test::default_cdi();
    std::string error;
    ASSERT_TRUE(registry_.add(c, error)) << error;
    EXPECT_EQ(error_of(ask(Json{{"cmd", "reboot"}, {"node", kNode}})),
              "the nodes have not started yet (simnode waits for its hub)");
    registry_.start_all();
    ASSERT_TRUE(run_until([this] { return seen(kInitComplete); }));
    frames_.clear();
    const Json r = ask(Json{{"cmd", "reboot"}, {"node", kNode}});
    ASSERT_EQ(r["ok"], true) << r.dump();
    EXPECT_TRUE(run_until([this] { return seen(kInitComplete); }));
    ASSERT_FALSE(frames_.empty());
    EXPECT_EQ(frames_.front(), ":X17050343N;") << "a fresh alias reservation (CID7)";
}

TEST_F(ControlCommandsTest, AddStartsANodeFromScenarioKeys) {
    start_default();
    const std::string cdi = std::string(OLCB_SOURCE_DIR) + "/scenarios/default.xml";
    EXPECT_EQ(error_of(ask(Json{{"cmd", "add"}, {"node-id", kNode}, {"cdi", cdi}})),
              "node 05.01.01.01.22.00 is already running");
    EXPECT_EQ(error_of(ask(Json{{"cmd", "add"}, {"node-id", "05.01.01.01.22.10"}})),
              "node: cdi is missing");
    EXPECT_EQ(error_of(ask(Json{{"cmd", "add"}, {"listen", "1"}})),
              "'listen' is not a node key (see docs/scenarios.md)");
    EXPECT_EQ(error_of(ask(Json{{"cmd", "add"}, {"node-id", true}})),
              "\"node-id\" must be a string, a number or a list of them");
    frames_.clear();
    const Json r = ask(Json{{"cmd", "add"},
                            {"node-id", "05.01.01.01.22.10"},
                            {"count", 2},
                            {"cdi", cdi},
                            {"fault", {"reject-temporary"}}});
    ASSERT_EQ(r["ok"], true) << r.dump();
    ASSERT_EQ(r["added"].size(), 2u);
    EXPECT_EQ(r["added"][1]["node_id"], "05.01.01.01.22.11");
    EXPECT_EQ(r["added"][0]["faults"], Json({"reject-temporary=3"}));
    EXPECT_EQ(r["added"][0]["images"], (images_.path() / "05.01.01.01.22.10").string())
        << "the scenario's image root";
    const NodeId added{0x05'01'01'01'22'11ull};
    ASSERT_TRUE(run_until([&] { return initialized(added); }));
    char init[40];
    std::snprintf(init, sizeof init, ":X19100%03XN050101012211;",
                  registry_.find(added)->stack().alias());
    EXPECT_TRUE(run_until([&] { return seen(init); })) << init;
    EXPECT_EQ(registry_.nodes().size(), 3u);
}

TEST_F(ControlCommandsTest, AddIsBoundedInNodesBeforeBuildingThem) {
    start_default();
    const std::string cdi = std::string(OLCB_SOURCE_DIR) + "/scenarios/default.xml";
    // Refused before 100,000 configs are built, each with its copy of the CDI text.
    EXPECT_EQ(
        error_of(ask(Json{
            {"cmd", "add"}, {"node-id", "05.01.01.01.30.00"}, {"count", 100000}, {"cdi", cdi}})),
        "one add makes at most 1000 nodes (count 100000)");
    EXPECT_EQ(error_of(ask(Json{{"cmd", "add"},
                                {"node-id", "05.01.01.01.30.00"},
                                {"count", "99999999999999999999999"},
                                {"cdi", cdi}})),
              "one add makes at most 1000 nodes (count 99999999999999999999999)");
    static_assert(kMaxControlNodes == 4095, "one node per alias of the segment");
    commands_.set_max_nodes(3);
    EXPECT_EQ(error_of(ask(Json{
                  {"cmd", "add"}, {"node-id", "05.01.01.01.30.00"}, {"count", 3}, {"cdi", cdi}})),
              "simnode runs at most 3 nodes; 1 run now, so at most 2 more can be added");
    EXPECT_EQ(registry_.nodes().size(), 1u) << "nothing added";
    EXPECT_EQ(
        ask(Json{
            {"cmd", "add"}, {"node-id", "05.01.01.01.30.00"}, {"count", 2}, {"cdi", cdi}})["ok"],
        true);
    EXPECT_EQ(registry_.nodes().size(), 3u);
}

TEST_F(ControlCommandsTest, AddRefusesACdiThatIsNoRegularFileAtOnce) {
    start_default();
    const test::TempDir dir("simnode-control-fifo");
    const auto fifo = dir.path() / "cdi.xml";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    // Before, open() waited for a writer on the io thread: every node and the hub froze.
    auto added = std::async(std::launch::async, [&] {
        return ask(Json{{"cmd", "add"}, {"node-id", "05.01.01.01.30.00"}, {"cdi", fifo.string()}});
    });
    if (added.wait_for(1s) != std::future_status::ready) {
        std::ofstream(fifo) << "";  // a writer that comes and goes releases the blocked open
        FAIL() << "add blocked on a FIFO without a writer: " << added.get().dump();
    }
    EXPECT_EQ(error_of(added.get()),
              "node: CDI file: cannot read " + fifo.string() + ": not a regular file");
    const auto start = std::chrono::steady_clock::now();
    // Before, /dev/zero was read until memory ran out (bad_alloc at 518 MiB).
    EXPECT_EQ(
        error_of(ask(Json{{"cmd", "add"}, {"node-id", "05.01.01.01.30.00"}, {"cdi", "/dev/zero"}})),
        "node: CDI file: cannot read /dev/zero: not a regular file");
    EXPECT_LT(std::chrono::steady_clock::now() - start, 1s);
    EXPECT_EQ(registry_.nodes().size(), 1u);
}

TEST_F(ControlCommandsTest, RemoveReleasesTheAlias) {
    start_default();
    frames_.clear();
    const Json r = ask(Json{{"cmd", "remove"}, {"node", kNode}});
    ASSERT_EQ(r["ok"], true) << r.dump();
    EXPECT_EQ(r["alias"], "0x343");
    EXPECT_TRUE(run_until([this] { return seen(":X10703343N050101012200;"); })) << "AMR";
    EXPECT_EQ(registry_.find(kNodeId), nullptr);
    EXPECT_EQ(error_of(ask(Json{{"cmd", "remove"}, {"node", kNode}})),
              "no node 05.01.01.01.22.00 (list shows the nodes)");
    // The images were let go: the same node can come back at once.
    const std::string cdi = std::string(OLCB_SOURCE_DIR) + "/scenarios/default.xml";
    EXPECT_EQ(ask(Json{{"cmd", "add"}, {"node-id", kNode}, {"cdi", cdi}})["ok"], true);
}

}  // namespace
}  // namespace olcb::simnode
