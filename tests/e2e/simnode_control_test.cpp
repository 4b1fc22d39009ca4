// simnode's live control as a tool developer uses it (docs/control.md): a hub client stays
// connected while faults change, memory is written behind the bus's back, nodes reboot, come and
// go; bad requests get errors; `simnode ctl` exits 0/1/2. Everything on 127.0.0.1, bounded.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "e2e/e2e_util.hpp"

namespace olcb::e2e {
namespace {

using Json = nlohmann::ordered_json;

constexpr NodeId kDefaultNode{0x05'01'01'01'22'00ull};
constexpr NodeId kAddedNode{0x05'01'01'01'22'10ull};
constexpr const char* kNode = "05.01.01.01.22.00";
constexpr const char* kInitComplete = ":X19100343N050101012200;";
constexpr std::size_t kMaxLine = std::size_t{64} * 1024;  // simnode's request line limit

// Reads what fd has (waiting up to timeout for the first byte) into text; false on EOF.
bool read_some(int fd, std::string& text, milliseconds timeout) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, static_cast<int>(timeout.count())) <= 0) return true;
    char chunk[4096];
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n <= 0) return false;
    text.append(chunk, static_cast<std::size_t>(n));
    return true;
}

// A raw GridConnect client of the hub: every line it received, and whether the hub dropped it.
class HubClient {
public:
    explicit HubClient(std::uint16_t port) : fd_(connect_to(port)) {}
    ~HubClient() {
        if (fd_ >= 0) ::close(fd_);
    }
    HubClient(const HubClient&) = delete;
    HubClient& operator=(const HubClient&) = delete;

    bool connected() const { return fd_ >= 0 && !closed_; }

    // The first line received since the last forget() that pred accepts, waiting up to timeout.
    std::optional<std::string> wait_line(const std::function<bool(const std::string&)>& pred,
                                         milliseconds timeout = milliseconds(5000)) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        for (;;) {
            std::size_t begin = 0;
            for (auto nl = text_.find('\n'); nl != std::string::npos;
                 nl = text_.find('\n', begin)) {
                std::string line = text_.substr(begin, nl - begin);
                begin = nl + 1;
                if (pred(line)) return line;
            }
            const auto left = std::chrono::duration_cast<milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0 || closed_) return std::nullopt;
            closed_ = !read_some(fd_, text_, std::min(left, milliseconds(50)));
        }
    }
    bool wait_exact(const std::string& frame, milliseconds timeout = milliseconds(5000)) {
        return wait_line([&](const std::string& l) { return l == frame; }, timeout).has_value();
    }
    // Drops what was received so far (reads what is waiting first).
    void forget() {
        while (!closed_) {
            const std::size_t before = text_.size();
            closed_ = !read_some(fd_, text_, milliseconds(0));
            if (text_.size() == before) break;
        }
        text_.clear();
    }
    void send(const std::string& frame) {
        const std::string line = frame + "\n";
        closed_ = closed_ || ::send(fd_, line.data(), line.size(), MSG_NOSIGNAL) !=
                                 static_cast<ssize_t>(line.size());
    }

private:
    int fd_;
    bool closed_ = false;
    std::string text_;
};

// One control connection: a request line out, a response line back.
class ControlLink {
public:
    explicit ControlLink(std::uint16_t port) : fd_(connect_to(port)) {}
    ~ControlLink() {
        if (fd_ >= 0) ::close(fd_);
    }
    ControlLink(const ControlLink&) = delete;
    ControlLink& operator=(const ControlLink&) = delete;

    bool connected() const { return fd_ >= 0; }

    std::optional<Json> ask_line(const std::string& text,
                                 milliseconds timeout = milliseconds(5000)) {
        const std::string line = text + "\n";
        for (std::size_t sent = 0; sent < line.size();) {
            const ssize_t n = ::send(fd_, line.data() + sent, line.size() - sent, MSG_NOSIGNAL);
            if (n <= 0) return std::nullopt;
            sent += static_cast<std::size_t>(n);
        }
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        while (input_.find('\n') == std::string::npos) {
            const auto left = std::chrono::duration_cast<milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0 || !read_some(fd_, input_, left)) return std::nullopt;
        }
        const auto nl = input_.find('\n');
        const std::string answer = input_.substr(0, nl);
        input_.erase(0, nl + 1);
        return Json::parse(answer);
    }
    std::optional<Json> ask(const Json& request) { return ask_line(request.dump()); }
    // True when simnode closed the connection within timeout.
    bool closed(milliseconds timeout) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        std::string ignored;
        while (std::chrono::steady_clock::now() < deadline) {
            if (!read_some(fd_, ignored, milliseconds(20))) return true;
        }
        return false;
    }

private:
    int fd_;
    std::string input_;
};

#ifdef SIMNODE_PATH
// simnode with its hub and its control on free loopback ports, stopping itself after a minute.
class SimnodeControl : public ::testing::Test {
protected:
    void SetUp() override {
        child_ =
            Child::spawn(SIMNODE_PATH, {"--scenario", source_path("scenarios/default.ini").string(),
                                        "--listen", "127.0.0.1:0", "--control", "127.0.0.1:0",
                                        "--image-dir", images_.str(), "--run-for", "60"});
        ASSERT_TRUE(child_);
        const auto hub = child_->wait_listening();
        ASSERT_TRUE(hub) << child_->output();
        hub_port_ = *hub;
        const auto line = child_->wait_line("simnode: control on 127.0.0.1:");
        ASSERT_TRUE(line) << child_->output();
        control_port_ = static_cast<std::uint16_t>(std::stoi(line->substr(line->rfind(':') + 1)));
        ASSERT_TRUE(child_->wait_line("simnode: 1 node(s) initialized")) << child_->output();
        hub_client_ = std::make_unique<HubClient>(hub_port_);
        control_ = std::make_unique<ControlLink>(control_port_);
        ASSERT_TRUE(hub_client_->connected() && control_->connected());
    }

    void TearDown() override {
        if (!hub_client_) return;
        // The hub client was never dropped: it is still read, and still answered.
        hub_client_->forget();
        hub_client_->send(":X19490AAAN;");  // Verify Node ID Global from alias 0xAAA
        EXPECT_TRUE(hub_client_->wait_exact(":X19170343N050101012200;"))
            << "the hub client is no longer answered";
        EXPECT_TRUE(hub_client_->connected());
        EXPECT_EQ(child_->output().find("hub: dropped"), std::string::npos) << child_->output();
    }

    Json ok(const Json& request) {
        const auto r = control_->ask(request);
        EXPECT_TRUE(r) << "no answer to " << request.dump();
        if (!r) return Json();
        EXPECT_EQ((*r)["ok"], true) << request.dump() << " -> " << r->dump();
        return *r;
    }
    std::string refused(const Json& request) {
        const auto r = control_->ask(request);
        EXPECT_TRUE(r) << "no answer to " << request.dump();
        if (!r) return {};
        EXPECT_EQ((*r)["ok"], false) << request.dump() << " -> " << r->dump();
        return r->value("error", std::string());
    }

    TempDir images_{"simnode-control"};
    std::unique_ptr<Child> child_;
    std::uint16_t hub_port_ = 0;
    std::uint16_t control_port_ = 0;
    std::unique_ptr<HubClient> hub_client_;
    std::unique_ptr<ControlLink> control_;
};

TEST_F(SimnodeControl, ListsTheNodes) {
    const Json r = ok(Json{{"cmd", "list"}});
    ASSERT_EQ(r["nodes"].size(), 1u) << r.dump();
    const Json& node = r["nodes"][0];
    EXPECT_EQ(node["node_id"], kNode);
    EXPECT_EQ(node["alias"], "0x343");
    EXPECT_EQ(node["initialized"], true);
    EXPECT_EQ(node["faults"], Json::array());
    EXPECT_EQ(node["cdi"], source_path("scenarios/default.xml").lexically_normal().string());
    EXPECT_EQ(node["images"], (images_.path() / kNode).string());
}

TEST_F(SimnodeControl, AFaultChangesTheAnswersWhileTheClientStaysConnected) {
    ToolNode tool(hub_port_);
    ASSERT_TRUE(tool.wait_ready());
    const auto node = tool.find(kDefaultNode);
    ASSERT_TRUE(node);
    // A write to the CDI space: a good node refuses it as read-only (0x1083).
    const std::vector<std::uint8_t> write_cdi{0x20, 0x03, 0, 0, 0, 0, 0x41};
    auto ex = tool.datagram(*node, write_cdi);
    ASSERT_TRUE(ex.outcome);
    EXPECT_EQ(ex.outcome->error_code, 0x1083);

    hub_client_->forget();
    const Json set =
        ok(Json{{"cmd", "set-faults"}, {"node", kNode}, {"faults", "readonly-0x1041"}});
    EXPECT_EQ(set["faults"], Json({"readonly-0x1041"}));
    EXPECT_EQ(set["restarted"], true);
    EXPECT_TRUE(hub_client_->wait_exact(kInitComplete)) << "the rebuilt node logs in again";
    ASSERT_TRUE(tool.find(kDefaultNode));
    ex = tool.datagram(*node, write_cdi);
    ASSERT_TRUE(ex.outcome);
    EXPECT_EQ(ex.outcome->error_code, 0x1041) << "the fault answers";

    hub_client_->forget();
    ok(Json{{"cmd", "clear-faults"}, {"node", kNode}});
    EXPECT_TRUE(hub_client_->wait_exact(kInitComplete));
    ASSERT_TRUE(tool.find(kDefaultNode));
    ex = tool.datagram(*node, write_cdi);
    ASSERT_TRUE(ex.outcome);
    EXPECT_EQ(ex.outcome->error_code, 0x1083) << "cleared: the good answer again";
    EXPECT_EQ(tool.client().stats().disconnects, 0u);
}

TEST_F(SimnodeControl, DirectMemoryAndTheBusSeeEachOthersWrites) {
    ToolNode tool(hub_port_);
    ASSERT_TRUE(tool.wait_ready());
    const auto node = tool.find(kDefaultNode);
    ASSERT_TRUE(node);
    ok(Json{
        {"cmd", "write"}, {"node", kNode}, {"space", 253}, {"address", 100}, {"data", "c0ffee42"}});
    const auto over_bus = tool.read(*node, memory::Space::kConfig, 100, 4);
    ASSERT_TRUE(over_bus);
    EXPECT_EQ(*over_bus, (std::vector<std::uint8_t>{0xC0, 0xFF, 0xEE, 0x42}));

    ASSERT_TRUE(tool.write(*node, memory::Space::kConfig, 120, {0x12, 0x34, 0x56}));
    const Json r = ok(
        Json{{"cmd", "read"}, {"node", kNode}, {"space", "0xFD"}, {"address", 120}, {"count", 3}});
    EXPECT_EQ(r["data"], "123456");
    EXPECT_EQ(
        refused(
            Json{{"cmd", "read"}, {"node", kNode}, {"space", 253}, {"address", 178}, {"count", 2}}),
        "space 253 (0xFD) holds addresses 0..178; 2 byte(s) at 178 do not fit");
    // Stored like a Memory Config write, not in RAM only: a reboot keeps it.
    hub_client_->forget();
    ok(Json{{"cmd", "reboot"}, {"node", kNode}});
    ASSERT_TRUE(hub_client_->wait_exact(kInitComplete));
    ASSERT_TRUE(tool.find(kDefaultNode));
    const auto after_reboot = tool.read(*node, memory::Space::kConfig, 100, 4);
    ASSERT_TRUE(after_reboot);
    EXPECT_EQ(*after_reboot, (std::vector<std::uint8_t>{0xC0, 0xFF, 0xEE, 0x42}));
}

TEST_F(SimnodeControl, RebootSendsInitializationCompleteAgain) {
    hub_client_->forget();
    const Json r = ok(Json{{"cmd", "reboot"}, {"node", kNode}});
    EXPECT_EQ(r["node"], kNode);
    EXPECT_TRUE(hub_client_->wait_exact(":X17050343N;")) << "a fresh alias reservation";
    EXPECT_TRUE(hub_client_->wait_exact(":X10701343N050101012200;")) << "AMD";
    EXPECT_TRUE(hub_client_->wait_exact(kInitComplete));
}

TEST_F(SimnodeControl, AddedNodesAnswerAndRemovedOnesReleaseTheirAlias) {
    ToolNode tool(hub_port_);
    ASSERT_TRUE(tool.wait_ready());
    hub_client_->forget();
    const Json added = ok(Json{{"cmd", "add"},
                               {"node-id", "05.01.01.01.22.10"},
                               {"cdi", source_path("scenarios/default.xml").string()}});
    ASSERT_EQ(added["added"].size(), 1u) << added.dump();
    EXPECT_EQ(added["added"][0]["images"], (images_.path() / "05.01.01.01.22.10").string());
    const auto init = hub_client_->wait_line([](const std::string& l) {
        return l.starts_with(":X19100") && l.ends_with("N050101012210;");
    });
    ASSERT_TRUE(init) << "the added node's Initialization Complete";
    const std::string alias = init->substr(7, 3);
    const auto found = tool.find(kAddedNode);
    ASSERT_TRUE(found) << "the added node answers Verify Node ID";
    EXPECT_EQ(*found, std::stoi(alias, nullptr, 16));
    EXPECT_EQ(ok(Json{{"cmd", "list"}})["nodes"].size(), 2u);

    hub_client_->forget();
    const Json removed = ok(Json{{"cmd", "remove"}, {"node", "05.01.01.01.22.10"}});
    EXPECT_EQ(removed["alias"], "0x" + alias);
    EXPECT_TRUE(hub_client_->wait_exact(":X10703" + alias + "N050101012210;")) << "AMR";
    EXPECT_FALSE(tool.find(kAddedNode, milliseconds(1200))) << "a removed node answers nothing";
    EXPECT_TRUE(tool.find(kDefaultNode)) << "the other node is untouched";
    EXPECT_EQ(ok(Json{{"cmd", "list"}})["nodes"].size(), 1u);
    EXPECT_EQ(tool.client().stats().disconnects, 0u);
}

TEST_F(SimnodeControl, BadRequestsGetErrorsAndSimnodeGoesOn) {
    auto r = control_->ask_line("{\"cmd\": \"list\"");
    ASSERT_TRUE(r);
    EXPECT_EQ((*r)["ok"], false);
    EXPECT_TRUE((*r)["error"].get<std::string>().starts_with("not JSON: ")) << r->dump();
    EXPECT_TRUE(refused(Json{{"cmd", "explode"}}).starts_with("unknown command 'explode'"));
    EXPECT_EQ(refused(Json{
                  {"cmd", "read"}, {"node", kNode}, {"space", "x"}, {"address", 0}, {"count", 1}}),
              "\"space\" 'x' must be a whole number 0..255 (or a \"0x\" hex string)");
    EXPECT_TRUE(refused(Json{{"cmd", "set-faults"}, {"node", kNode}, {"faults", "no-such-fault"}})
                    .starts_with("unknown fault 'no-such-fault'"));
    EXPECT_EQ(
        refused(Json{
            {"cmd", "write"}, {"node", kNode}, {"space", 255}, {"address", 0}, {"data", "00"}}),
        "space 255 (0xFF) is read-only");
    EXPECT_EQ(refused(Json{{"cmd", "remove"}, {"node", "05.01.01.01.22.99"}}),
              "no node 05.01.01.01.22.99 (list shows the nodes)");
    EXPECT_EQ(ok(Json{{"cmd", "list"}, {"id", 7}})["id"], 7) << "the same connection goes on";

    // A line beyond the limit is refused and its connection closed; others are untouched.
    ControlLink flooder(control_port_);
    r = flooder.ask_line(std::string(kMaxLine + 10, ' ') + "x");
    ASSERT_TRUE(r);
    EXPECT_EQ((*r)["error"], "request line longer than 65536 bytes; closing");
    EXPECT_TRUE(flooder.closed(milliseconds(2000)));
    EXPECT_EQ(ok(Json{{"cmd", "list"}})["nodes"].size(), 1u);
    ControlLink fresh(control_port_);
    const auto again = fresh.ask(Json{{"cmd", "list"}});
    ASSERT_TRUE(again);
    EXPECT_EQ((*again)["ok"], true);
}

TEST_F(SimnodeControl, CtlPrintsReadablyAndExitsZeroOneTwo) {
    const std::string where = "127.0.0.1:" + std::to_string(control_port_);
    auto [code, out] = run_program(SIMNODE_PATH, {"ctl", where, "list"});
    EXPECT_EQ(code, 0) << out;
    EXPECT_NE(out.find("node 05.01.01.01.22.00 alias 0x343 cdi "), std::string::npos) << out;
    std::tie(code, out) =
        run_program(SIMNODE_PATH, {"ctl", "--json", where, "read", kNode, "253", "0", "2"});
    EXPECT_EQ(code, 0) << out;
    const Json r = Json::parse(out);
    EXPECT_EQ(r["ok"], true);
    EXPECT_EQ(r["data"].get<std::string>().size(), 4u);
    std::tie(code, out) =
        run_program(SIMNODE_PATH, {"ctl", where, "write", kNode, "253", "0x10", "ab"});
    EXPECT_EQ(code, 0);
    EXPECT_EQ(out, "node 05.01.01.01.22.00: wrote 1 byte(s) to space 253 at 16\n");
    std::tie(code, out) = run_program(SIMNODE_PATH, {"ctl", where, "reboot", "05.01.01.01.22.99"});
    EXPECT_EQ(code, 1) << "refused";
    std::tie(code, out) = run_program(SIMNODE_PATH, {"ctl", where});
    EXPECT_EQ(code, 2) << "usage";
    std::tie(code, out) = run_program(SIMNODE_PATH, {"ctl", where, "read", kNode, "253", "x", "1"});
    EXPECT_EQ(code, 2) << "usage";
    // Port 1 on loopback: nothing listens there.
    std::tie(code, out) = run_program(SIMNODE_PATH, {"ctl", "127.0.0.1:1", "list"});
    EXPECT_EQ(code, 2) << "connection error";
}
#endif

#ifdef SIMNODE_PATH
TEST(SimnodeControlAddress, ANonLoopbackAddressNeedsControlRemote) {
    TempDir images("simnode-control-remote");
    const auto [code, out] =
        run_program(SIMNODE_PATH, {"--scenario", source_path("scenarios/default.ini").string(),
                                   "--listen", "127.0.0.1:0", "--control", "0.0.0.0:0",
                                   "--image-dir", images.str(), "--run-for", "5"});
    EXPECT_EQ(code, 2) << out;
}
#endif

}  // namespace
}  // namespace olcb::e2e
