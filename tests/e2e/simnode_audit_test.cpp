// simnode --audit and --audit-junit as a tool developer uses them: scripted bad clients over
// TCP (raw GridConnect hub clients) break one rule each and the audit names it for exactly
// that client; the JUnit file has one testcase per rule; a killed simnode leaves a valid file;
// and lcc-conform's own traffic leaves only what docs/audit.md says it does.
#include <gtest/gtest.h>
#include <poll.h>

#include <chrono>
#include <deque>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <set>
#include <sstream>
#include <thread>

#include "e2e/conform_util.hpp"
#include "e2e/e2e_util.hpp"
#include "openlcb/addressed_framing.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/gridconnect.hpp"
#include "support/memory_commands.hpp"

namespace olcb::e2e {
namespace {

using nlohmann::json;
using std::chrono::steady_clock;
namespace fs = std::filesystem;

// The audit's rules (docs/audit.md) a scripted client breaks.
constexpr int kRuleCount = 26;

std::string file_text(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

json read_json(const fs::path& p) {
    return json::parse(file_text(p), nullptr, false);
}

// A raw GridConnect client of the hub, driven synchronously: it sends exactly the frames a
// script says, and waits for the node's answers where the script needs them.
class GcClient {
public:
    GcClient(std::uint16_t port, std::uint16_t alias, NodeId id)
        : fd_(connect_to(port)), alias_(alias), id_(id) {}
    ~GcClient() { close(); }
    GcClient(const GcClient&) = delete;
    GcClient& operator=(const GcClient&) = delete;

    bool connected() const { return fd_ >= 0; }
    std::uint16_t alias() const { return alias_; }
    void close() {
        if (fd_ >= 0) ::close(fd_);
        fd_ = -1;
    }

    void send(const CanFrame& f) {
        const std::string line = gridconnect::format(f) + "\n";
        if (fd_ >= 0) (void)!::write(fd_, line.data(), line.size());
    }
    // CID7..CID4, 200 ms, RID, AMD (CanFrameTransferS §6.2): Permitted, not yet Initialized.
    // The audit times frames as the hub reads them: on a loaded machine it may read the CID
    // frames late, so the wait has a margin (alias.rid-too-early is an error).
    void reserve() {
        for (int n = 7; n >= 4; --n) send(can::make_cid(n, id_, alias_));
        std::this_thread::sleep_for(milliseconds(300));
        send(can::make_rid(alias_));
        send(can::make_amd(alias_, id_));
    }
    // reserve(), then Initialization Complete (MessageNetworkS §3.4.1).
    void login() {
        reserve();
        send(message(Mti::kInitializationComplete, id_bytes(id_)));
    }
    CanFrame message(Mti mti, const std::vector<std::uint8_t>& data = {}) const {
        return can::make_frame(can::message_header(to_u16(mti) & 0xFFF, alias_), data);
    }
    CanFrame addressed(std::uint16_t can_mti, std::uint16_t dest,
                       const std::vector<std::uint8_t>& data = {}) const {
        std::vector<std::uint8_t> bytes{static_cast<std::uint8_t>(dest >> 8),
                                        static_cast<std::uint8_t>(dest & 0xFF)};
        bytes.insert(bytes.end(), data.begin(), data.end());
        return can::make_frame(can::message_header(can_mti, alias_), bytes);
    }
    void datagram(std::uint16_t dest, const std::vector<std::uint8_t>& payload) {
        Message m;
        m.mti = Mti::kDatagram;
        m.source.alias = alias_;
        m.destination = NodeHandle{NodeId(), dest};
        m.payload = payload;
        std::vector<CanFrame> frames;
        encode_message(m, frames);
        for (const CanFrame& f : frames) send(f);
    }
    void ack(std::uint16_t dest) {
        send(addressed(to_u16(Mti::kDatagramReceivedOk) & 0xFFF, dest));
    }

    // The next frame matching pred within timeout; the others stay for later questions.
    std::optional<CanFrame> next(const std::function<bool(const CanFrame&)>& pred,
                                 milliseconds timeout = milliseconds(3000)) {
        const auto deadline = steady_clock::now() + timeout;
        std::size_t looked = 0;  // frames already known not to match
        for (;;) {
            for (; looked < inbox_.size(); ++looked) {
                if (!pred(inbox_[looked])) continue;
                const CanFrame f = inbox_[looked];
                inbox_.erase(inbox_.begin() + static_cast<std::ptrdiff_t>(looked));
                return f;
            }
            const auto left =
                std::chrono::duration_cast<milliseconds>(deadline - steady_clock::now());
            if (left.count() <= 0 || fd_ < 0) return std::nullopt;
            pollfd p{fd_, POLLIN, 0};
            if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
            char buf[4096];
            const ssize_t n = ::read(fd_, buf, sizeof buf);
            if (n <= 0) return std::nullopt;
            parser_.feed(std::string_view(buf, static_cast<std::size_t>(n)),
                         [this](const CanFrame& f) { inbox_.push_back(f); });
        }
    }
    // The alias of node id (Verify Node ID global with its ID).
    std::optional<std::uint16_t> alias_of(NodeId id) {
        send(message(Mti::kVerifyNodeIdGlobal, id_bytes(id)));
        const auto f = next([&](const CanFrame& f) {
            return can::is_message(f.id) && can::can_mti(f.id) == 0x170 && f.len == 6 &&
                   NodeId::from_bytes({f.data.data(), 6}) == id;
        });
        if (!f) return std::nullopt;
        return can::source_alias(f->id);
    }
    // The node's Datagram Received OK (true, flags) or Rejected (false, code) to us.
    std::optional<std::pair<bool, std::uint16_t>> answer(std::uint16_t node) {
        const auto f = next([&](const CanFrame& f) {
            const auto mti = can::can_mti(f.id);
            return from_to_us(f, node) && (mti == 0xA28 || mti == 0xA48);
        });
        if (!f) return std::nullopt;
        if (can::can_mti(f->id) == 0xA28) return std::pair{true, f->len > 2 ? f->data[2] : 0};
        return std::pair{false, static_cast<std::uint16_t>(f->data[2] << 8 | f->data[3])};
    }
    // The node's next datagram to us, whole (its frames are not acknowledged here).
    std::optional<std::vector<std::uint8_t>> reply(std::uint16_t node,
                                                   milliseconds timeout = milliseconds(3000)) {
        std::vector<std::uint8_t> bytes;
        for (;;) {
            const auto f = next(
                [&](const CanFrame& f) {
                    return can::is_message(f.id) &&
                           can::is_datagram_format(can::frame_format(f.id)) &&
                           can::dest_alias(f.id) == alias_ && can::source_alias(f.id) == node;
                },
                timeout);
            if (!f) return std::nullopt;
            bytes.insert(bytes.end(), f->data.begin(), f->data.begin() + f->len);
            const auto format = can::frame_format(f->id);
            if (format == can::FrameFormat::kDatagramOnly ||
                format == can::FrameFormat::kDatagramLast)
                return bytes;
        }
    }
    // A whole exchange done right: the datagram, its answer, the reply acknowledged.
    bool exchange(std::uint16_t node, const std::vector<std::uint8_t>& payload) {
        datagram(node, payload);
        return finish_exchange(node);
    }
    // The answer to a datagram sent, and its reply acknowledged; false when none came.
    bool finish_exchange(std::uint16_t node) {
        const auto a = answer(node);
        if (!a || !a->first) return a.has_value();
        if ((a->second & datagram::kReplyPending) == 0) return true;
        const auto r = reply(node);
        if (r) ack(node);
        return r.has_value();
    }

private:
    static std::vector<std::uint8_t> id_bytes(NodeId id) {
        const auto b = id.to_bytes();
        return {b.begin(), b.end()};
    }
    bool from_to_us(const CanFrame& f, std::uint16_t node) const {
        return can::is_message(f.id) &&
               can::frame_format(f.id) == can::FrameFormat::kGlobalAddressed &&
               can::source_alias(f.id) == node && f.len >= 2 &&
               can::addressed_dest(f.data[0], f.data[1]) == alias_;
    }

    int fd_ = -1;
    std::uint16_t alias_;
    NodeId id_;
    gridconnect::Parser parser_;
    std::deque<CanFrame> inbox_;
};

using test_support::read_cmd;
using test_support::update_complete_cmd;
using test_support::write_cmd;

#if defined(SIMNODE_PATH)

// The nodes of the scripted run: one plain default node, and a few with a fault that lets a
// script's misbehaviour be seen at all on a loopback (answers that do not come at once).
constexpr NodeId kPlain{0x05'01'01'01'22'00ull};
constexpr NodeId kLate{0x05'01'01'01'22'01ull};   // latency=400: OK and reply 400 ms late
constexpr NodeId kBusy{0x05'01'01'01'22'02ull};   // reject-temporary=40
constexpr NodeId kSlow1{0x05'01'01'01'22'03ull};  // slow-reply: OK at once, reply 1.5 s late
constexpr NodeId kSlow2{0x05'01'01'01'22'04ull};  // the same, for a second script
// reply-pending=1: OK with flags 0x81 (the reply within 2 s), the reply 1 s later.
constexpr NodeId kPromise{0x05'01'01'01'22'05ull};

// One simnode with --audit and --audit-junit, on a free port, with its images in a temp dir.
struct AuditedSimnode {
    TempDir dir{"simnode-audit-e2e"};
    std::unique_ptr<Child> child;
    std::uint16_t port = 0;
    fs::path json_path = dir.path() / "audit.json";
    fs::path junit_path = dir.path() / "audit.xml";

    std::uint16_t control_port = 0;  // with_control: live control (`simnode ctl`)

    explicit AuditedSimnode(std::vector<std::string> nodes, bool with_control = false) {
        std::vector<std::string> args{
            "--listen",         "127.0.0.1:0",   "--image-dir",       dir.str() + "/img", "--audit",
            json_path.string(), "--audit-junit", junit_path.string(), "--run-for",        "120"};
        if (with_control) args.insert(args.end(), {"--control", "127.0.0.1:0"});
        args.insert(args.end(), nodes.begin(), nodes.end());
        child = Child::spawn(SIMNODE_PATH, args);
        if (!child) return;
        if (const auto p = child->wait_listening()) port = *p;
        if (with_control) {
            const auto line = child->wait_line("simnode: control on 127.0.0.1:");
            if (line)
                control_port =
                    static_cast<std::uint16_t>(std::stoi(line->substr(line->rfind(':') + 1)));
        }
        child->wait_line("simnode: ", milliseconds(5000));  // "N node(s) initialized"
    }
    static AuditedSimnode default_scenario() {
        return AuditedSimnode({"--scenario", source_path("scenarios/default.ini").string()});
    }
    // SIGTERM and the exit status.
    int stop() {
        child->signal(SIGTERM);
        if (!child->wait_for(milliseconds(10000))) return -1;
        return child->wait();
    }
};

// The rules each scripted client's findings name, by client alias.
using FoundByClient = std::map<std::uint16_t, std::set<std::string>>;

FoundByClient rules_by_client(const json& audit) {
    FoundByClient out;
    for (const json& f : audit["findings"]) {
        const auto alias = static_cast<std::uint16_t>(
            std::stoul(f["client"]["alias"].get<std::string>(), nullptr, 16));
        out[alias].insert(f["rule"].get<std::string>());
    }
    return out;
}

// What the scripted run left, shared by the tests that judge it.
struct ScriptRun {
    std::unique_ptr<AuditedSimnode> sim;
    std::string audit_text;  // the JSON file once simnode stopped
    std::string junit;
    json audit() const { return json::parse(audit_text, nullptr, false); }
    int exit_code = 0;
    bool ran = false;
};
// Allocated once and never freed: its destructor would stop a simnode while the program exits.
ScriptRun& script_run() {
    static ScriptRun* const run = new ScriptRun;
    return *run;
}

// Every scripted bad client against one simnode: each breaks one rule, on its own alias.
class SimnodeAuditScripts : public ::testing::Test {
protected:
    static void SetUpTestSuite();
    static void TearDownTestSuite() { script_run().sim.reset(); }
    // The rules found for the script on alias.
    static std::set<std::string> found(std::uint16_t alias) {
        const auto by = rules_by_client(script_run().audit());
        const auto it = by.find(alias);
        return it == by.end() ? std::set<std::string>{} : it->second;
    }
    static std::set<std::string> only(const char* rule) { return {rule}; }
};

// Script aliases: 0x6nn, node IDs 02.01.0D.00.06.nn.
GcClient client(std::uint16_t port, std::uint16_t n) {
    return GcClient(port, static_cast<std::uint16_t>(0x600 + n),
                    NodeId(0x02'01'0D'00'06'00ull + n));
}

// The segment the scripts run on: the hub's port and the alias of each node.
struct Segment {
    std::uint16_t port = 0;
    std::map<NodeId, std::uint16_t> at;
    std::uint16_t plain() const { return at.at(kPlain); }
};

void alias_scripts(const Segment& seg) {
    {  // alias.unreserved: traffic from an alias it never reserved
        GcClient c = client(seg.port, 1);
        c.send(c.message(Mti::kVerifyNodeIdGlobal));
        c.send(c.addressed(0x828, seg.plain()));
    }
    {  // alias.rid-too-early: RID right after the CID frames
        GcClient c = client(seg.port, 2);
        const NodeId id(0x02'01'0D'00'06'02ull);
        for (int n = 7; n >= 4; --n) c.send(can::make_cid(n, id, c.alias()));
        c.send(can::make_rid(c.alias()));
        c.send(can::make_amd(c.alias(), id));
    }
    {  // message.unknown-mti
        GcClient c = client(seg.port, 3);
        c.login();
        c.send(c.addressed(0x4F9, seg.plain()));
        ASSERT_TRUE(c.next([](const CanFrame& f) { return can::can_mti(f.id) == 0x068; }));
    }
    {  // datagram.frame-sequence: a lone last frame
        GcClient c = client(seg.port, 4);
        c.login();
        c.send(can::make_frame(
            can::addressed_header(can::FrameFormat::kDatagramLast, seg.plain(), c.alias()),
            std::vector<std::uint8_t>{1, 2}));
        ASSERT_TRUE(c.answer(seg.plain()));
    }
}

// Two datagrams to node, the second sent before the first was answered (or, with
// wait_for_ok, right after its Datagram Received OK); both exchanges then finished.
void two_datagrams(const Segment& seg, std::uint16_t n, NodeId node, std::uint32_t second,
                   bool wait_for_ok) {
    GcClient c = client(seg.port, n);
    c.login();
    const std::uint16_t to = seg.at.at(node);
    c.datagram(to, read_cmd(0xFD, 0, 8));
    if (wait_for_ok) {
        ASSERT_TRUE(c.answer(to));
    }
    c.datagram(to, read_cmd(0xFD, second, 8));
    if (wait_for_ok) {
        ASSERT_TRUE(c.answer(to));
        for (int i = 0; i < 2; ++i) {
            if (c.reply(to)) c.ack(to);
        }
        return;
    }
    ASSERT_TRUE(c.finish_exchange(to));
    ASSERT_TRUE(c.finish_exchange(to));
}

void datagram_scripts(const Segment& seg) {
    two_datagrams(seg, 5, kLate, 8, false);   // datagram.overlap
    two_datagrams(seg, 6, kLate, 0, false);   // datagram.resend-without-reject
    two_datagrams(seg, 7, kSlow1, 0, true);   // datagram.resend-after-ok
    two_datagrams(seg, 12, kSlow2, 8, true);  // memory.request-before-reply
    {  // datagram.resend-before-timeout: OpenLCB_Java's ~270 ms wait for a reply promised in 2 s
        GcClient c = client(seg.port, 26);
        c.login();
        const std::uint16_t to = seg.at.at(kPromise);
        c.datagram(to, read_cmd(0xFF, 0, 64));
        const auto a = c.answer(to);
        ASSERT_TRUE(a && a->first);
        ASSERT_EQ(a->second, 0x81);
        std::this_thread::sleep_for(milliseconds(270));
        c.datagram(to, read_cmd(0xFF, 0, 64));
        ASSERT_TRUE(c.answer(to));
        for (int i = 0; i < 2; ++i) {  // both reads are answered: acknowledge both replies
            ASSERT_TRUE(c.reply(to));
            c.ack(to);
        }
    }
    {  // message.before-init-complete: python-openlcb's examples never send it
        GcClient c = client(seg.port, 27);
        c.reserve();
        c.send(c.message(Mti::kVerifyNodeIdGlobal));
        ASSERT_TRUE(c.exchange(seg.plain(), read_cmd(0xFD, 0, 8)));
    }
    {  // datagram.resend-after-permanent: an unknown space, rejected 0x1081, asked again
        GcClient c = client(seg.port, 8);
        c.login();
        c.datagram(seg.plain(), read_cmd(0x50, 0, 8));
        const auto a = c.answer(seg.plain());
        ASSERT_TRUE(a && !a->first);
        c.datagram(seg.plain(), read_cmd(0x50, 0, 8));
        ASSERT_TRUE(c.answer(seg.plain()));
    }
    {  // datagram.retry-storm: resent at once after each temporary reject
        GcClient c = client(seg.port, 9);
        c.login();
        for (int i = 0; i < 8; ++i) {
            c.datagram(seg.at.at(kBusy), read_cmd(0xFD, 0, 8));
            const auto a = c.answer(seg.at.at(kBusy));
            ASSERT_TRUE(a && !a->first);
        }
    }
    {  // datagram.reply-ack-late
        GcClient c = client(seg.port, 11);
        c.login();
        c.datagram(seg.plain(), read_cmd(0xFD, 0, 8));
        ASSERT_TRUE(c.answer(seg.plain()));
        ASSERT_TRUE(c.reply(seg.plain()));
        std::this_thread::sleep_for(milliseconds(900));
        c.ack(seg.plain());
    }
    {  // snip.request-before-reply: twice to the late node
        GcClient c = client(seg.port, 13);
        c.login();
        c.send(c.addressed(0xDE8, seg.at.at(kLate)));
        c.send(c.addressed(0xDE8, seg.at.at(kLate)));
        std::this_thread::sleep_for(milliseconds(1000));  // both replies, unread
    }
}

// One write (and Update Complete after it, unless told not to) by script n, done right.
void write_script(const Segment& seg, std::uint16_t n, std::uint8_t space, std::uint32_t address,
                  const std::vector<std::uint8_t>& data, bool update_complete = true) {
    GcClient c = client(seg.port, n);
    c.login();
    EXPECT_TRUE(c.exchange(seg.plain(), write_cmd(space, address, data))) << n;
    if (update_complete) {
        EXPECT_TRUE(c.exchange(seg.plain(), update_complete_cmd())) << n;
    }
}

void memory_scripts(const Segment& seg) {
    {  // memory.read-past-end
        GcClient c = client(seg.port, 14);
        c.login();
        ASSERT_TRUE(c.exchange(seg.plain(), read_cmd(0xFD, 179, 8)));
    }
    write_script(seg, 15, 0xFF, 0, {'<'});                                // memory.write-read-only
    write_script(seg, 16, 0xFD, 178, {1, 1});                             // memory.write-past-end
    write_script(seg, 17, 0xFD, 1, {0});                                  // memory.write-straddles
    write_script(seg, 18, 0xFB, 0, {2});                                  // memory.write-uncovered
    write_script(seg, 19, 0xFD, 1, {0x07, 0xD0});                         // cdi.int-out-of-range
    write_script(seg, 20, 0xFD, 16, {0x45, 0x00});                        // cdi.float-out-of-range
    write_script(seg, 21, 0xFD, 30, std::vector<std::uint8_t>(16, 'A'));  // cdi.string-invalid
    write_script(seg, 22, 0xFD, 15, {7});                                 // cdi.not-in-map
    write_script(seg, 23, 0xFD, 178, {2});                                // cdi.action-value
    write_script(seg, 24, 0xFD, 0, {1}, false);  // memory.no-update-complete
    write_script(seg, 25, 0xFD, 0, {1});         // a good write: nothing
}

void run_scripts(std::uint16_t port) {
    Segment seg{port, {}};
    GcClient probe(port, 0x5FF, NodeId(0x02'01'0D'00'05'FFull));
    probe.login();
    for (const NodeId id : {kPlain, kLate, kBusy, kSlow1, kSlow2, kPromise}) {
        const auto a = probe.alias_of(id);
        ASSERT_TRUE(a) << id.to_string();
        seg.at[id] = *a;
    }
    // datagram.reply-unacknowledged: the reply is never acknowledged; the client stays on
    // while the other scripts run.
    GcClient unacked = client(port, 10);
    unacked.login();
    unacked.datagram(seg.plain(), read_cmd(0xFF, 0, 64));
    ASSERT_TRUE(unacked.answer(seg.plain()));
    ASSERT_TRUE(unacked.reply(seg.plain()));
    const auto unacked_since = steady_clock::now();
    alias_scripts(seg);
    datagram_scripts(seg);
    memory_scripts(seg);
    // The unacknowledged reply is due 3 s after it came.
    std::this_thread::sleep_until(unacked_since + milliseconds(3500));
}

void SimnodeAuditScripts::SetUpTestSuite() {
    const std::string cdi = source_path("scenarios/default.xml").string();
    ScriptRun& run = script_run();
    run.sim = std::make_unique<AuditedSimnode>(std::vector<std::string>{
        "--cdi", cdi, "--node.plain.node-id=05.01.01.01.22.00",
        "--node.late.node-id=05.01.01.01.22.01", "--node.late.fault=latency=400",
        "--node.busy.node-id=05.01.01.01.22.02", "--node.busy.fault=reject-temporary=40",
        "--node.slow1.node-id=05.01.01.01.22.03", "--node.slow1.fault=slow-reply=1500",
        "--node.slow2.node-id=05.01.01.01.22.04", "--node.slow2.fault=slow-reply=1500",
        "--node.promise.node-id=05.01.01.01.22.05", "--node.promise.fault=reply-pending=1"});
    if (!run.sim->child || run.sim->port == 0) return;
    run_scripts(run.sim->port);
    run.exit_code = run.sim->stop();
    run.audit_text = file_text(run.sim->json_path);
    run.junit = file_text(run.sim->junit_path);
    run.ran = true;
}

#define REQUIRE_RUN()                                                                           \
    do {                                                                                        \
        ASSERT_TRUE(script_run().ran)                                                           \
            << (script_run().sim && script_run().sim->child ? script_run().sim->child->output() \
                                                            : std::string("no simnode"));       \
    } while (0)

TEST_F(SimnodeAuditScripts, SimnodeStopsCleanlyWithACompleteAudit) {
    REQUIRE_RUN();
    EXPECT_EQ(script_run().exit_code, 0);
    const json audit = script_run().audit();
    ASSERT_FALSE(audit.is_discarded());
    EXPECT_EQ(audit["complete"], true);
    EXPECT_EQ(audit["rules"].size(), static_cast<std::size_t>(kRuleCount));
}

TEST_F(SimnodeAuditScripts, EachScriptedClientIsFoundBreakingItsRuleAndNothingElse) {
    REQUIRE_RUN();
    const std::map<std::uint16_t, const char*> expected = {
        {0x601, "alias.unreserved"},
        {0x602, "alias.rid-too-early"},
        {0x603, "message.unknown-mti"},
        {0x604, "datagram.frame-sequence"},
        {0x605, "datagram.overlap"},
        {0x606, "datagram.resend-without-reject"},
        {0x607, "datagram.resend-after-ok"},
        {0x608, "datagram.resend-after-permanent"},
        {0x609, "datagram.retry-storm"},
        {0x60A, "datagram.reply-unacknowledged"},
        {0x60B, "datagram.reply-ack-late"},
        {0x60C, "memory.request-before-reply"},
        {0x60D, "snip.request-before-reply"},
        {0x60E, "memory.read-past-end"},
        {0x60F, "memory.write-read-only"},
        {0x610, "memory.write-past-end"},
        {0x611, "memory.write-straddles"},
        {0x612, "memory.write-uncovered"},
        {0x613, "cdi.int-out-of-range"},
        {0x614, "cdi.float-out-of-range"},
        {0x615, "cdi.string-invalid"},
        {0x616, "cdi.not-in-map"},
        {0x617, "cdi.action-value"},
        {0x618, "memory.no-update-complete"},
        {0x61A, "datagram.resend-before-timeout"},
        {0x61B, "message.before-init-complete"},
    };
    ASSERT_EQ(expected.size(), static_cast<std::size_t>(kRuleCount));
    std::set<std::string> covered;
    for (const auto& [alias, rule] : expected) {
        EXPECT_EQ(found(alias), only(rule)) << "client 0x" << std::hex << alias;
        covered.insert(rule);
    }
    EXPECT_EQ(covered.size(), static_cast<std::size_t>(kRuleCount));  // every rule once
    EXPECT_EQ(found(0x619), std::set<std::string>{});                 // the good writer
    EXPECT_EQ(found(0x5FF), std::set<std::string>{});  // the probe that found the nodes
}

TEST_F(SimnodeAuditScripts, AFindingNamesClientNodeFramesStandardAndTime) {
    REQUIRE_RUN();
    const json* f = nullptr;
    const json audit = script_run().audit();
    for (const json& x : audit["findings"]) {
        if (x["rule"] == "cdi.int-out-of-range") f = &x;
    }
    ASSERT_NE(f, nullptr);
    EXPECT_EQ((*f)["level"], "error");
    EXPECT_EQ((*f)["standard"], "CDI §5.1.4.2");
    EXPECT_EQ((*f)["client"]["alias"], "0x613");
    EXPECT_EQ((*f)["client"]["node_id"], "02.01.0D.00.06.13");
    EXPECT_TRUE((*f)["client"]["remote"].get<std::string>().starts_with("127.0.0.1:"));
    EXPECT_EQ((*f)["node"]["node_id"], "05.01.01.01.22.00");
    EXPECT_EQ((*f)["frames"].size(), 1u);
    EXPECT_TRUE((*f)["frames"][0].get<std::string>().starts_with(":X1A"));  // a one-frame write
    EXPECT_GT((*f)["time"].get<double>(), 0.0);
}

TEST_F(SimnodeAuditScripts, TheJunitFileHasOneTestcasePerRuleAndAFailurePerErrorRule) {
    REQUIRE_RUN();
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_string(script_run().junit.c_str())) << script_run().junit;
    const auto suite = doc.child("testsuites").child("testsuite");
    std::set<std::string> names;
    int failures = 0;
    for (auto tc : suite.children("testcase")) {
        names.insert(tc.attribute("name").value());
        if (tc.child("failure")) ++failures;
    }
    EXPECT_EQ(names.size(), static_cast<std::size_t>(kRuleCount));
    std::set<std::string> error_rules;
    const json audit = script_run().audit();
    for (const json& f : audit["findings"]) {
        if (f["level"] == "error") error_rules.insert(f["rule"].get<std::string>());
    }
    EXPECT_EQ(failures, static_cast<int>(error_rules.size()));
    EXPECT_EQ(suite.attribute("failures").as_int(), failures);
    const auto warning =
        suite.find_child_by_attribute("testcase", "name", "memory.no-update-complete");
    EXPECT_FALSE(warning.child("failure"));
    EXPECT_TRUE(warning.child("system-out"));
    const auto note =
        suite.find_child_by_attribute("testcase", "name", "memory.request-before-reply");
    EXPECT_FALSE(note.child("failure"));
    EXPECT_TRUE(note.child("system-out"));
}

TEST(SimnodeAudit, TheFileIsValidFromTheStartAndAfterSimnodeIsKilled) {
    AuditedSimnode sim = AuditedSimnode::default_scenario();
    ASSERT_NE(sim.port, 0) << (sim.child ? sim.child->output() : "");
    const json at_start = read_json(sim.json_path);
    ASSERT_FALSE(at_start.is_discarded());
    EXPECT_EQ(at_start["complete"], false);
    EXPECT_TRUE(at_start["findings"].empty());
    {
        GcClient c(sim.port, 0x701, NodeId(0x02'01'0D'00'07'01ull));
        c.send(c.message(Mti::kVerifyNodeIdGlobal));  // never reserved
    }
    const auto deadline = steady_clock::now() + milliseconds(3000);
    json seen;
    while (steady_clock::now() < deadline) {
        seen = read_json(sim.json_path);
        if (!seen.is_discarded() && !seen["findings"].empty()) break;
        std::this_thread::sleep_for(milliseconds(50));
    }
    sim.child->signal(SIGKILL);
    sim.child->wait();
    const json after = read_json(sim.json_path);
    ASSERT_FALSE(after.is_discarded());
    EXPECT_EQ(after["complete"], false);
    ASSERT_EQ(after["findings"].size(), 1u);
    EXPECT_EQ(after["findings"][0]["rule"], "alias.unreserved");
    pugi::xml_document doc;
    EXPECT_TRUE(doc.load_file(sim.junit_path.c_str()));
}

// simnode joined to another hub (--connect, an in-process segment bridged to it): the tools
// on that hub are audited through the nodes' own port, their aliases taken as reserved.
TEST(SimnodeAudit, ToolsOnABridgedHubAreAuditedToo) {
    TempDir dir("simnode-audit-bridge");
    auto hub = Child::spawn(
        SIMNODE_PATH, {"--scenario", source_path("scenarios/default.ini").string(), "--listen",
                       "127.0.0.1:0", "--image-dir", dir.str() + "/hub", "--run-for", "60"});
    ASSERT_TRUE(hub);
    const auto port = hub->wait_listening();
    ASSERT_TRUE(port) << hub->output();
    const fs::path audit = dir.path() / "audit.json";
    auto bridged = Child::spawn(
        SIMNODE_PATH,
        {"--node-id", "05.01.01.01.22.10", "--cdi", source_path("scenarios/default.xml").string(),
         "--connect", "127.0.0.1:" + std::to_string(*port), "--image-dir", dir.str() + "/bridged",
         "--audit", audit.string(), "--run-for", "60"});
    ASSERT_TRUE(bridged);
    ASSERT_TRUE(bridged->wait_line("simnode: 1 node(s) initialized")) << bridged->output();
    {
        GcClient c(*port, 0x620, NodeId(0x02'01'0D'00'06'20ull));
        c.login();
        const auto node = c.alias_of(NodeId(0x05'01'01'01'22'10ull));
        ASSERT_TRUE(node);
        EXPECT_TRUE(c.exchange(*node, write_cmd(0xFD, 1, {0x07, 0xD0})));  // Trim 2000
        EXPECT_TRUE(c.exchange(*node, update_complete_cmd()));
    }
    bridged->signal(SIGTERM);
    ASSERT_TRUE(bridged->wait_for(milliseconds(10000)));
    EXPECT_EQ(bridged->wait(), 0);
    hub->signal(SIGTERM);
    const json j = read_json(audit);
    ASSERT_FALSE(j.is_discarded());
    ASSERT_EQ(j["findings"].size(), 1u) << j.dump(2);
    const json& f = j["findings"][0];
    EXPECT_EQ(f["rule"], "cdi.int-out-of-range");
    EXPECT_EQ(f["client"]["alias"], "0x620");
    EXPECT_TRUE(f["client"]["remote"].is_null());  // a bridge has no client address
    EXPECT_EQ(f["node"]["node_id"], "05.01.01.01.22.10");
}

TEST(SimnodeAudit, AnAuditFileThatCannotBeWrittenStopsSimnodeAtStart) {
    TempDir dir("simnode-audit-bad");
    const auto [code, out] = run_program(
        SIMNODE_PATH, {"--scenario", source_path("scenarios/default.ini").string(), "--listen",
                       "127.0.0.1:0", "--image-dir", dir.str(), "--audit",
                       (dir.path() / "no-such-dir" / "a.json").string(), "--run-for", "5"});
    EXPECT_EQ(code, 1) << out;
}

#if defined(LCC_CONFORM_PATH)

// lcc-conform against an audited simnode: the rules its run leaves in the audit.
std::set<std::string> conform_rules(const std::vector<std::string>& args) {
    AuditedSimnode sim = AuditedSimnode::default_scenario();
    EXPECT_NE(sim.port, 0);
    std::vector<std::string> all{"--connect", "127.0.0.1:" + std::to_string(sim.port)};
    all.insert(all.end(), args.begin(), args.end());
    const auto [code, out] = conform(all);
    EXPECT_EQ(code, 0) << out;
    EXPECT_EQ(sim.stop(), 0);
    const json audit = read_json(sim.json_path);
    EXPECT_FALSE(audit.is_discarded());
    std::set<std::string> rules;
    for (const json& f : audit["findings"]) {
        rules.insert(f["rule"].get<std::string>());
        // Normal configuration traffic never breaks an error rule (docs/audit.md).
        if (f["level"] == "error") ADD_FAILURE() << f.dump();
    }
    return rules;
}

TEST(SimnodeAuditLccConform, ABackupLeavesAnEmptyAudit) {
    TempDir dir("simnode-audit-backup");
    const std::string file = (dir.path() / "backup.txt").string();
    EXPECT_EQ(conform_rules({"backup", "--node", "05.01.01.01.22.00", file}),
              std::set<std::string>{});
}

TEST(SimnodeAuditLccConform, ARestoreLeavesOnlyTheNoteOfAMissingUpdateComplete) {
    TempDir dir("simnode-audit-restore");
    const fs::path file = dir.path() / "backup.txt";
    {
        AuditedSimnode sim = AuditedSimnode::default_scenario();
        ASSERT_NE(sim.port, 0);
        const auto [code, out] = conform({"--connect", "127.0.0.1:" + std::to_string(sim.port),
                                          "backup", "--node", "05.01.01.01.22.00", file.string()});
        ASSERT_EQ(code, 0) << out;
        EXPECT_EQ(sim.stop(), 0);
    }
    // Change the user name, so the restore has something to write.
    std::string text = read_text(file);
    const auto at = text.find("simnode default");
    ASSERT_NE(at, std::string::npos) << text;
    text.replace(at, 15, "audited node");
    std::ofstream(file) << text;
    // lcc-conform sends no Update Complete after restoring (reported, docs/audit.md).
    EXPECT_EQ(conform_rules({"restore", file.string()}),
              std::set<std::string>{"memory.no-update-complete"});
}

TEST(SimnodeAuditLccConform, TheEncodingChecksLeaveOnlyTheNoteOfAMissingUpdateComplete) {
    TempDir dir("simnode-audit-encoding");
    EXPECT_EQ(conform_rules({"--only", "encoding.*", "--backup", (dir.path() / "b.txt").string()}),
              std::set<std::string>{"memory.no-update-complete"});
}

// `simnode ctl add` (issue 33): the added node's replies were held unacknowledged against the
// client and its writes went unjudged, because the audit never learned the node.
TEST(SimnodeAuditLccConform, ANodeAddedWhileRunningIsAuditedAsTheScenariosNode) {
    AuditedSimnode sim({"--scenario", source_path("scenarios/default.ini").string()}, true);
    ASSERT_NE(sim.port, 0);
    ASSERT_NE(sim.control_port, 0) << sim.child->output();
    const std::string scenario_node = "05.01.01.01.22.00";
    const std::string added_node = "05.01.01.01.22.20";
    const auto [added, said] =
        run_program(SIMNODE_PATH, {"ctl", "127.0.0.1:" + std::to_string(sim.control_port), "add",
                                   "node-id=" + added_node,
                                   "cdi=" + source_path("scenarios/default.xml").string()});
    ASSERT_EQ(added, 0) << said;
    // The same work on each: reads and writes (the encoding checks, their safety backup first).
    for (const std::string& node : {scenario_node, added_node}) {
        TempDir backup("simnode-audit-added");
        const auto [code, out] =
            conform({"--connect", "127.0.0.1:" + std::to_string(sim.port), "--node", node, "--only",
                     "encoding.*", "--backup", (backup.path() / "b.txt").string()});
        EXPECT_EQ(code, 0) << node << "\n" << out;
    }
    {  // and a write the CDI forbids, to the added node: judged
        GcClient c(sim.port, 0x630, NodeId(0x02'01'0D'00'06'30ull));
        c.login();
        const auto alias = c.alias_of(NodeId(0x05'01'01'01'22'20ull));
        ASSERT_TRUE(alias);
        EXPECT_TRUE(c.exchange(*alias, write_cmd(0xFD, 1, {0x07, 0xD0})));  // Trim 2000
        EXPECT_TRUE(c.exchange(*alias, update_complete_cmd()));
    }
    EXPECT_EQ(sim.stop(), 0);
    const json audit = read_json(sim.json_path);
    ASSERT_FALSE(audit.is_discarded());
    const auto node_of = [](const json& f) {
        return f["node"].is_null() ? std::string() : f["node"]["node_id"].get<std::string>();
    };
    std::map<std::string, std::set<std::string>> by_node;  // rules found, by node
    for (const json& f : audit["findings"]) {
        if (f["client"]["alias"] != "0x630")
            by_node[node_of(f)].insert(f["rule"].get<std::string>());
    }
    EXPECT_EQ(by_node[added_node], by_node[scenario_node]) << audit.dump(2);
    EXPECT_EQ(by_node[scenario_node], std::set<std::string>{"memory.no-update-complete"})
        << audit.dump(2);
    std::set<std::string> forbidden_write;
    for (const json& f : audit["findings"]) {
        if (f["client"]["alias"] == "0x630") {
            forbidden_write.insert(f["rule"].get<std::string>() + " " + node_of(f));
        }
    }
    EXPECT_EQ(forbidden_write, std::set<std::string>{"cdi.int-out-of-range " + added_node})
        << audit.dump(2);
}

TEST(SimnodeAuditLccConform, AFullRunFindsOnlyWhatItsDeliberateProbesBreak) {
    TempDir dir("simnode-audit-full");
    AuditedSimnode sim = AuditedSimnode::default_scenario();
    ASSERT_NE(sim.port, 0);
    const auto [code, out] = conform({"--connect", "127.0.0.1:" + std::to_string(sim.port),
                                      "--backup", (dir.path() / "b.txt").string()});
    EXPECT_EQ(code, 0) << out;
    EXPECT_EQ(sim.stop(), 0);
    const json audit = read_json(sim.json_path);
    ASSERT_FALSE(audit.is_discarded());
    std::set<std::string> rules;
    for (const json& f : audit["findings"]) rules.insert(f["rule"].get<std::string>());
    // docs/audit.md names the lcc-conform check behind each.
    const std::set<std::string> expected = {
        "alias.unreserved",     // frame.collision, frame.capacity
        "message.unknown-mti",  // message.oir-unknown-mti, -other-silent, unknown-global-ignored
        "datagram.frame-sequence",  // datagram.out-of-order
        "memory.read-past-end",     // memory.read-past-end.<sp>
        "memory.write-read-only",   // memory.readonly-refused.<sp>
        "memory.write-straddles",   // memory.write-under-mask
        // No memory.no-update-complete: the run's last write is events.follow-write's, which
        // sends Update Complete, and the restore writes only what differs (here nothing).
    };
    EXPECT_EQ(rules, expected) << audit.dump(2);
}

#endif  // LCC_CONFORM_PATH
#endif  // SIMNODE_PATH

}  // namespace
}  // namespace olcb::e2e
