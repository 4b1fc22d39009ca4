// A node's run (NodeRun, through run_node) in-process on the simulated clock: every check of the
// registry on the project's two scenarios has no false failure; against the simnode faults that
// model what real nodes do to a careless tool (real-world.md §1, §5) the node is never killed or
// reset by the run, a node that dies or restarts is reported as such, and its memory always ends
// byte-identical; a node that never comes back leaves a backup that restores it later.
#include "conformance/run/node_run.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "conformance/checks/protocol_checks.hpp"
#include "conformance/conform_test_util.hpp"
#include "conformance/run/runner.hpp"
#include "conformance/sim_bench.hpp"
#include "openlcb/sim_network.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::conform {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Memory = std::map<std::uint8_t, std::vector<std::uint8_t>>;

class SafetyTest : public ::testing::Test {
protected:
    void TearDown() override {
        std::error_code ignored;  // a backup path that cannot exist (/dev/null/...) included
        fs::remove(backup_, ignored);
    }

    void start(const std::string& faults, const std::string& cdi_file = "default.xml") {
        simnode::NodeConfig config;
        config.node_id = kDut;
        const fs::path dir = fs::path(OLCB_SOURCE_DIR) / "scenarios";
        config.cdi =
            read_text(fs::exists(dir / cdi_file) ? dir / cdi_file : dir / "faults" / cdi_file);
        config.user_name = "simnode safety";
        std::string error;
        auto parsed = simnode::parse_faults({faults}, error);
        ASSERT_TRUE(parsed) << error;
        config.faults = *parsed;
        dut_ = simnode::SimNode::create(config, error);
        ASSERT_TRUE(dut_) << error;
        net_.set_logging(false);
        net_.add_stack(dut_->stack());
        dut_->stack().start(net_.now());
        link_ = make_sim_link(net_, kTool);
        session_ = std::make_unique<Session>(*link_);
        ASSERT_TRUE(session_->start());
        node_ = session_->find_node(kDut);
        ASSERT_TRUE(node_);
        backup_ = fs::temp_directory_path() / ("safety_test_" + std::to_string(::getpid()));
        before_ = memory();
    }

    Memory memory() const {
        Memory m;
        for (std::uint8_t sp : dut_->memory().served_spaces()) {
            if (sp != 0xFF && sp != 0xFC) m[sp] = dut_->memory().read(sp, 0, 1u << 16);
        }
        return m;
    }

    NodeReport run(RunOptions options = {}) {
        options.backup_path = backup_.string();
        options.node_wait = std::chrono::seconds(5);
        ProtocolChecks checks = [options](Session& s, const NodeInfo& n, CheckContext& ctx) {
            ProtocolOptions po;
            po.selection = options.selection;
            po.read_only = options.read_only;
            return run_protocol_checks(s, n, po, ctx);
        };
        return run_node(*session_, *node_, options, checks, progress_);
    }

    static const CheckResult* find(const NodeReport& r, const std::string& id) {
        for (const auto& c : r.checks) {
            if (c.id == id) return &c;
        }
        return nullptr;
    }
    static std::string failures(const NodeReport& r) {
        std::string out;
        for (const auto& c : r.checks) {
            if (c.status == Status::kFail) out += "\n  " + c.id + ": " + c.message;
        }
        return out;
    }

    SimNetwork net_;
    std::unique_ptr<simnode::SimNode> dut_;
    std::unique_ptr<Link> link_;
    std::unique_ptr<Session> session_;
    std::optional<NodeInfo> node_;
    std::ostringstream progress_;
    fs::path backup_;
    Memory before_;
};

TEST_F(SafetyTest, OpenMrnLikeNodeWithRebootIsNeitherKilledNorReset) {
    start("abort-on-value,factory-reset-on-version-change", "openmrn-like.xml");
    RunOptions o;
    o.reboot = true;
    const NodeReport r = run(o);
    EXPECT_EQ(dut_->counters().aborts, 0u);
    EXPECT_EQ(dut_->counters().factory_resets, 0u);
    EXPECT_EQ(dut_->counters().reboots, 1u);
    EXPECT_EQ(find(r, "encoding.persist-after-reboot")->status, Status::kPass)
        << find(r, "encoding.persist-after-reboot")->message;
    const CheckResult* prot = find(r, "encoding.protected");
    ASSERT_NE(prot, nullptr);
    EXPECT_NE(prot->message.find("Internal data"), std::string::npos) << prot->message;
    EXPECT_EQ(find(r, "node.rebooted"), nullptr);
    EXPECT_EQ(memory(), before_);
    EXPECT_FALSE(r.incomplete);
}

TEST_F(SafetyTest, WriteProtectedProbesInternalDataOneAtATimeAndTheNodeSurvives) {
    start("abort-on-value,factory-reset-on-version-change", "openmrn-like.xml");
    RunOptions o;
    o.reboot = true;
    o.protection.write_protected = true;
    const NodeReport r = run(o);
    EXPECT_EQ(dut_->counters().aborts, 0u);
    EXPECT_EQ(dut_->counters().factory_resets, 0u);
    EXPECT_EQ(find(r, "encoding.protected"), nullptr);  // nothing left alone
    EXPECT_EQ(memory(), before_);
    EXPECT_EQ(find(r, "encoding.restore")->status, Status::kPass);
}

TEST_F(SafetyTest, RebootOnWriteIsReportedWithTheVariableAndNothingMoreIsWritten) {
    start("reboot-on-write=7");
    const NodeReport r = run();
    ASSERT_EQ(dut_->counters().write_reboots, 1u);
    const CheckResult* rebooted = find(r, "node.rebooted");
    ASSERT_NE(rebooted, nullptr) << failures(r);
    EXPECT_EQ(rebooted->category, Category::kNode);
    EXPECT_NE(rebooted->message.find("last test value written"), std::string::npos)
        << rebooted->message;
    // The 7th write (write-under-mask made 2) is the original going back into the first variable
    // after its 4 test values.
    EXPECT_NE(rebooted->message.find("restoring Node identity.User Name"), std::string::npos)
        << rebooted->message;
    // The writes after the reboot are the restore alone: no encoding check failed because of it.
    for (const char* id : {"encoding.int", "encoding.string", "encoding.eventid"}) {
        EXPECT_NE(find(r, id)->status, Status::kFail) << id << ": " << find(r, id)->message;
    }
    EXPECT_EQ(find(r, "encoding.restore")->status, Status::kPass);
    EXPECT_EQ(memory(), before_);
    // No clause forbids a restart (node.rebooted WARNs), but the checks after it never ran.
    EXPECT_EQ(rebooted->status, Status::kWarn);
    EXPECT_TRUE(r.incomplete);
    EXPECT_EQ(exit_code({r}), 2);
}

TEST_F(SafetyTest, AbortOnValueNeverFiresOnTheDefaultNode) {
    start("abort-on-value");
    RunOptions o;
    o.protection.write_protected = true;
    const NodeReport r = run(o);
    EXPECT_EQ(dut_->counters().aborts, 0u);
    EXPECT_EQ(r.count(Status::kFail), 0u) << failures(r);
    EXPECT_EQ(memory(), before_);
}

TEST_F(SafetyTest, RejectedResetAndLockQuoteTheCodeWithoutAFailure) {
    start("reset-rejected,lock-rejected");
    RunOptions o;
    o.reboot = true;
    const NodeReport r = run(o);
    EXPECT_EQ(r.count(Status::kFail), 0u) << failures(r);
    const CheckResult* persist = find(r, "encoding.persist-after-reboot");
    EXPECT_EQ(persist->status, Status::kSkip);
    EXPECT_EQ(persist->message, "Reset/Reboot rejected with 0x1041; persistence not tested");
    const CheckResult* lock = find(r, "memory.lock");
    EXPECT_EQ(lock->status, Status::kSkip);  // optional: "not implemented" is no finding
    EXPECT_NE(lock->message.find("0x1041"), std::string::npos) << lock->message;
    EXPECT_EQ(memory(), before_);
}

// OpenLcbCLib ignores requests sent the moment it is back from a Reset (deaf-after-init): the
// Lock the run takes again after --reboot's reset waits until the node answers, instead of being
// lost and costing the acknowledgement and reply timeouts (6 s more than a listening node in
// simulated time; 2.5 s with the wait, the rest spent by the protocol checks' own Reset).
TEST_F(SafetyTest, TheLockAfterTheResetWaitsUntilTheNodeListens) {
    struct Baseline : SafetyTest {
        void TestBody() override {}
        using SafetyTest::net_;
        using SafetyTest::run;
        using SafetyTest::start;
        using SafetyTest::TearDown;
    };
    RunOptions o;
    o.reboot = true;
    Baseline quick;
    quick.start("write-past-end-spills");  // a fault no default run meets
    TimePoint t = quick.net_.now();
    EXPECT_EQ(quick.run(o).count(Status::kFail), 0u);
    const Duration base = quick.net_.now() - t;
    quick.TearDown();

    start("deaf-after-init=250");
    t = net_.now();
    const NodeReport r = run(o);
    const Duration deaf = net_.now() - t;
    EXPECT_EQ(r.count(Status::kFail), 0u) << failures(r);
    EXPECT_EQ(find(r, "encoding.persist-after-reboot")->status, Status::kPass);
    EXPECT_EQ(memory(), before_);
    EXPECT_LT(deaf - base, 4s)
        << std::chrono::duration_cast<std::chrono::milliseconds>(deaf - base).count() << " ms more";
}

TEST_F(SafetyTest, NewAliasOnRebootIsFollowed) {
    start("new-alias-on-reboot");
    RunOptions o;
    o.reboot = true;
    const std::uint16_t first = node_->alias;
    const NodeReport r = run(o);
    EXPECT_NE(session_->alias_of(*node_), first);
    EXPECT_EQ(r.count(Status::kFail), 0u) << failures(r);
    EXPECT_EQ(find(r, "encoding.persist-after-reboot")->status, Status::kPass);
    EXPECT_EQ(memory(), before_);
}

TEST_F(SafetyTest, FieldReadsOnlyIsFlaggedAndTheRunStillTestsAndRestores251) {
    start("field-reads-only");
    const NodeReport r = run();
    const CheckResult* fb = find(r, "memory.short-read.fb");
    ASSERT_NE(fb, nullptr);
    EXPECT_EQ(fb->status, Status::kWarn) << fb->message;
    EXPECT_EQ(find(r, "snip.matches-acdi")->status, Status::kPass)
        << find(r, "snip.matches-acdi")->message;
    EXPECT_EQ(find(r, "snip.follows-acdi-user-write")->status, Status::kPass);
    EXPECT_EQ(find(r, "encoding.string")->status, Status::kPass);
    EXPECT_EQ(find(r, "encoding.restore")->status, Status::kPass);
    EXPECT_EQ(memory(), before_);
}

TEST_F(SafetyTest, ANodeHoldingAnotherLockIsNotWritten) {
    start("");
    // Another tool holds the node's lock.
    const std::vector<std::uint8_t> lock = {0x20, 0x88, 0x02, 0x01, 0x12, 0xFE, 0x00, 0x09};
    dut_->server().handle({0x020112FE0009ull, 0x123}, lock);
    ASSERT_NE(dut_->server().lock_holder(), 0u);
    const NodeReport r = run();
    const CheckResult* i = find(r, "encoding.int");
    EXPECT_EQ(i->status, Status::kSkip);
    EXPECT_NE(i->message.find("locked by 02.01.12.FE.00.09"), std::string::npos) << i->message;
    EXPECT_FALSE(fs::exists(backup_));
    EXPECT_EQ(memory(), before_);
}

TEST_F(SafetyTest, ANodeThatNeverComesBackKeepsTheBackupAndItRestoresLater) {
    start("abort-on-value=60000,factory-reset-on-version-change", "openmrn-like.xml");
    // A node that already holds a changed Version dies at the next SNIP request: here the
    // protocol checks' own. Nothing is written; the run says why and exits 2.
    RunOptions o;
    o.protection.write_protected = true;
    dut_->memory().space(253)->write(128, std::vector<std::uint8_t>{0x00, 0x07});
    const NodeReport r = run(o);
    ASSERT_NE(find(r, "node.stopped-answering"), nullptr) << failures(r);
    EXPECT_TRUE(r.incomplete);
    EXPECT_EQ(exit_code({r}), 2);
}

// ---- the write ledger: every write a run sends is restored and counted ----

// A protocol probe's writes are the run's writes: restored from the backup and counted, never
// "nothing written" (it once printed that after three writes).
TEST_F(SafetyTest, AProtocolProbesWritesAreRestoredAndCounted) {
    start("");
    RunOptions o;
    o.selection.only = {"memory.write-under-mask"};
    const NodeReport r = run(o);
    EXPECT_EQ(r.restore.writes, 2u) << r.restore_summary;
    ASSERT_TRUE(r.restore.identical.has_value());
    EXPECT_TRUE(*r.restore.identical);
    EXPECT_TRUE(
        r.restore_summary.starts_with("node memory byte-identical to before (2 writes sent"))
        << r.restore_summary;
    EXPECT_EQ(find(r, "encoding.restore")->status, Status::kPass);
    EXPECT_FALSE(fs::exists(backup_)) << "deleted once verified";
    EXPECT_EQ(memory(), before_);
}

TEST_F(SafetyTest, NothingWrittenIsSaidOnlyWhenTheLedgerIsEmpty) {
    start("");
    RunOptions o;
    o.selection.only = {"memory.read-*"};
    const NodeReport r = run(o);
    EXPECT_EQ(r.restore.writes, 0u);
    EXPECT_TRUE(r.restore_summary.starts_with("nothing written")) << r.restore_summary;
    EXPECT_FALSE(r.restore.identical.has_value());
}

// A node that ignores Write Under Mask's mask and goes silent for 5 s: the byte it changed is
// put back once it answers again; the checks it missed make the run incomplete.
TEST_F(SafetyTest, AMaskIgnoringNodeThatGoesSilentIsRestoredWhenItAnswers) {
    start("mask-ignored=5000");
    const NodeReport r = run();
    EXPECT_EQ(find(r, "memory.write-under-mask")->status, Status::kFail);
    EXPECT_EQ(find(r, "encoding.restore")->status, Status::kPass) << r.restore_summary;
    EXPECT_TRUE(r.restore_summary.starts_with("node memory byte-identical")) << r.restore_summary;
    EXPECT_EQ(memory(), before_);
    EXPECT_TRUE(r.incomplete) << "checks were not run while it was silent";
    EXPECT_GE(exit_code({r}), 1);
}

// The same node silent for longer than --node-wait: no PASS over the changed byte; the backup is
// kept, the restore command named, and restoring it later puts the byte back.
TEST_F(SafetyTest, AMaskIgnoringNodeThatStaysSilentKeepsTheBackup) {
    start("mask-ignored=40000");
    const NodeReport r = run();  // --node-wait 5 s
    EXPECT_TRUE(r.incomplete);
    EXPECT_EQ(exit_code({r}), 2);
    const CheckResult* restore = find(r, "encoding.restore");
    ASSERT_NE(restore, nullptr);
    EXPECT_EQ(restore->status, Status::kFail);
    EXPECT_NE(r.restore_summary.find("lcc-conform restore " + fs::absolute(backup_).string()),
              std::string::npos)
        << r.restore_summary;
    EXPECT_EQ(r.restore.backup_kept, fs::absolute(backup_).string());
    ASSERT_TRUE(fs::exists(backup_));
    EXPECT_NE(memory(), before_) << "the node kept the byte it changed";
    net_.run_for(std::chrono::seconds(40));
    std::string error;
    const auto restored = restore_file(*session_, backup_.string(), error);
    ASSERT_TRUE(restored) << error;
    EXPECT_TRUE(restored->identical) << restored->summary();
    EXPECT_EQ(memory(), before_);
}

// --write-past-end on a node that keeps the byte: a WARN naming it and a restore line that says
// so, never "byte-identical"; without the option no write crosses an end.
TEST_F(SafetyTest, AByteStoredPastTheEndIsNamedAndNeverCalledIdentical) {
    start("write-past-end-grows", "io-board.xml");
    RunOptions o;
    o.selection.only = {"memory.write-past-end.fd"};
    o.selection.write_past_end = true;
    const NodeReport r = run(o);
    const CheckResult* fd = find(r, "memory.write-past-end.fd");
    ASSERT_NE(fd, nullptr);
    EXPECT_EQ(fd->status, Status::kWarn) << fd->message;
    EXPECT_NE(fd->message.find("may have stored 1 byte past the end of space 0xFD"),
              std::string::npos)
        << fd->message;
    EXPECT_EQ(find(r, "memory.write-past-end.fb"), nullptr) << "--only names one space";
    for (const LedgerEntry& e : session_->ledger().entries())
        EXPECT_NE(e.write.space, 0xFB) << "no probe of 0xFB was sent";
    EXPECT_EQ(r.restore_summary.find("byte-identical"), std::string::npos) << r.restore_summary;
    EXPECT_NE(r.restore_summary.find("identical to before except 1 unrestorable byte past the end"),
              std::string::npos)
        << r.restore_summary;
    ASSERT_EQ(r.restore.past_end.size(), 1u);
    EXPECT_EQ(r.restore.past_end[0].space, 0xFD);
    EXPECT_EQ(find(r, "encoding.restore")->status, Status::kWarn);
    EXPECT_EQ(dut_->memory().past_end(0xFD).size(), 1u);
    EXPECT_EQ(memory(), before_) << "every readable byte is as before";
}

TEST_F(SafetyTest, WithoutWritePastEndNoWriteCrossesAnEnd) {
    start("write-past-end-grows", "io-board.xml");
    RunOptions o;
    o.selection.thorough = true;
    const NodeReport r = run(o);
    for (const LedgerEntry& e : session_->ledger().entries()) EXPECT_EQ(e.past_end, 0u) << e.origin;
    EXPECT_TRUE(dut_->memory().past_end(0xFD).empty());
    EXPECT_TRUE(dut_->memory().past_end(0xFB).empty());
    EXPECT_EQ(find(r, "memory.write-past-end.fd"), nullptr);
    EXPECT_EQ(memory(), before_);
}

// A backup file that cannot be written (a read-only directory, a full disk): nothing reaches the
// node, and the run is incomplete (exit 2) with one line on stderr, never a clean run of SKIPs
// with exit 0 as before.
TEST_F(SafetyTest, AnUnwritableBackupWritesNothingAndMakesTheRunIncomplete) {
    start("");
    backup_ = "/dev/null/safety.txt";  // no file can be made there, even by root
    const NodeReport r = run();
    EXPECT_TRUE(r.incomplete);
    EXPECT_EQ(exit_code({r}), 2);
    const std::string why =
        "the safety backup could not be written (cannot open /dev/null/safety.txt for writing: "
        "Not a directory), so nothing was written to the node";
    EXPECT_NE(std::find(r.incomplete_reasons.begin(), r.incomplete_reasons.end(), why),
              r.incomplete_reasons.end())
        << ::testing::PrintToString(r.incomplete_reasons);
    EXPECT_NE(progress_.str().find("lcc-conform: 05.01.01.01.22.00: " + why + "\n"),
              std::string::npos)
        << progress_.str();
    EXPECT_EQ(session_->ledger().sent(kDut), 0u);
    EXPECT_EQ(r.restore.writes, 0u);
    EXPECT_TRUE(r.restore_summary.starts_with("nothing written")) << r.restore_summary;
    EXPECT_EQ(find(r, "encoding.restore"), nullptr);
    EXPECT_EQ(memory(), before_);
}

// The whole run, every check of the registry (--thorough and --reboot too), in-process: no false
// failure on the project's two scenarios.
void expect_no_failure_in_process(const std::string& cdi_file) {
    const std::string cdi =
        read_text(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios" / cdi_file);
    testing::SimBench b({}, cdi);
    auto node = b.start();
    ASSERT_TRUE(node);
    RunOptions options;
    options.reboot = true;
    options.selection.thorough = true;
    options.backup_path = (std::filesystem::temp_directory_path() /
                           ("registry_full_" + cdi_file + std::to_string(::getpid())))
                              .string();
    ProtocolChecks checks = [&](Session& s, const NodeInfo& n, CheckContext& ctx) {
        ProtocolOptions o;
        o.reboot = true;
        o.selection = options.selection;
        return run_protocol_checks(s, n, o, ctx);
    };
    std::ostringstream progress;
    const NodeReport report = run_node(*b.session, *node, options, checks, progress);
    std::set<std::string> ids;
    for (const CheckResult& c : report.checks) {
        EXPECT_NE(c.status, Status::kFail) << cdi_file << ": " << c.id << " " << c.message;
        EXPECT_TRUE(ids.insert(c.id).second) << "duplicate " << c.id;
    }
    EXPECT_GT(report.checks.size(), 80u);
    EXPECT_NE(report.restore_summary.find("byte-identical"), std::string::npos)
        << report.restore_summary;
}

TEST(CheckRunTest, DefaultScenarioHasNoFailureInProcess) {
    expect_no_failure_in_process("default.xml");
}

TEST(CheckRunTest, IoBoardScenarioHasNoFailureInProcess) {
    expect_no_failure_in_process("io-board.xml");
}

}  // namespace
}  // namespace olcb::conform
