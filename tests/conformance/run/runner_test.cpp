// run_node end to end on a simulated network: the CDI is read once per run (the encoding checks
// reuse the protocol checks' layout), and a link that goes down mid-run stops the writes, turns
// the encoding results into "not judged", then restores when the link returns or keeps the
// backup and names the restore command when it does not.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "conformance/checks/protocol_checks.hpp"
#include "conformance/conform_test_util.hpp"
#include "conformance/link/link.hpp"
#include "conformance/link/session.hpp"
#include "conformance/run/runner.hpp"
#include "openlcb/sim_network.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::conform {
namespace {

namespace fs = std::filesystem;

// A memory-config datagram frame (single or first) whose command byte matches `mask`/`value`.
bool is_memory_command(const CanFrame& f, std::uint8_t mask, std::uint8_t value) {
    const std::uint32_t type = (f.id >> 24) & 0x1F;
    return (type == 0x1A || type == 0x1B) && f.len >= 2 && f.data[0] == 0x20 &&
           (f.data[1] & mask) == value;
}

// Forwards to a simulated link, but "loses" the transport at the first write command it sees
// (the adapter unplugged mid-run); with comes_back it returns at the next wait.
class FlakyLink final : public Link {
public:
    FlakyLink(std::unique_ptr<Link> inner, bool comes_back)
        : inner_(std::move(inner)), comes_back_(comes_back) {
        inner_->set_frame_observer([this](const CanFrame& f, TimePoint t) { observe(f, t); });
    }
    NodeStack& stack() override { return inner_->stack(); }
    TimePoint now() override { return inner_->now(); }
    bool run_until(const std::function<bool()>& pred, Duration max) override {
        if (!up_ && comes_back_) up_ = true;
        return inner_->run_until(pred, max);
    }
    void send_frame(const CanFrame& frame) override { inner_->send_frame(frame); }
    void set_frame_observer(FrameObserver observer) override { observer_ = std::move(observer); }
    bool up() override { return up_; }
    std::uint64_t losses() override { return losses_; }
    std::string loss_reason() override { return losses_ ? "serial /dev/ttyTEST: lost" : ""; }

    bool armed = false;  ///< lose the link at the next write command
    int cdi_reads_at_zero = 0;

private:
    void observe(const CanFrame& f, TimePoint t) {
        // 0x43: read from space 0xFF; bytes 2..5 the address, byte 6 the count. A download
        // reads 64 bytes at a time (the protocol checks' 8-byte probes are not downloads).
        if (is_memory_command(f, 0xFF, 0x43) && f.len >= 7 && f.data[2] == 0 && f.data[3] == 0 &&
            f.data[4] == 0 && f.data[5] == 0 && f.data[6] == 64) {
            ++cdi_reads_at_zero;
        }
        if (armed && is_memory_command(f, 0xFC, 0x00)) {
            armed = false;
            up_ = false;
            ++losses_;
        }
        if (observer_) observer_(f, t);
    }

    std::unique_ptr<Link> inner_;
    bool comes_back_;
    bool up_ = true;
    std::uint64_t losses_ = 0;
    FrameObserver observer_;
};

class RunnerTest : public ::testing::Test {
protected:
    void SetUp() override {
        simnode::NodeConfig config;
        config.node_id = kDut;
        config.cdi = read_text(fs::path(OLCB_SOURCE_DIR) / "scenarios" / "default.xml");
        std::string error;
        dut_ = simnode::SimNode::create(config, error);
        ASSERT_TRUE(dut_) << error;
        net_.set_logging(false);
        net_.add_stack(dut_->stack());
        dut_->stack().start(net_.now());
        backup_ = fs::temp_directory_path() / ("runner_test_" + std::to_string(::getpid()));
        fs::remove(backup_);
    }
    void TearDown() override { fs::remove(backup_); }

    // One run of every check with the link `comes_back` (or nullopt: a link that never fails).
    NodeReport run(std::optional<bool> comes_back, bool with_protocol_checks = true) {
        auto flaky =
            std::make_unique<FlakyLink>(make_sim_link(net_, kTool), comes_back.value_or(true));
        link_ = flaky.get();
        holder_ = std::move(flaky);
        session_ = std::make_unique<Session>(*holder_);
        EXPECT_TRUE(session_->start());
        auto node = session_->find_node(kDut);
        EXPECT_TRUE(node);
        if (!node) return {};
        link_->armed = comes_back.has_value();
        RunOptions options;
        options.sample = 1;
        options.backup_path = backup_.string();
        options.link_wait = std::chrono::seconds(5);
        options.restore_command = "lcc-conform --serial /dev/ttyTEST restore";
        ProtocolChecks checks;
        if (with_protocol_checks) {
            checks = [](Session& s, const NodeInfo& n, CheckContext& ctx) {
                return run_protocol_checks(s, n, ProtocolOptions{}, ctx);
            };
        }
        return run_node(*session_, *node, options, checks, progress_);
    }

    static const CheckResult* find(const NodeReport& r, const std::string& id) {
        for (const auto& c : r.checks) {
            if (c.id == id) return &c;
        }
        return nullptr;
    }

    SimNetwork net_;
    std::unique_ptr<simnode::SimNode> dut_;
    std::unique_ptr<Link> holder_;
    FlakyLink* link_ = nullptr;
    std::unique_ptr<Session> session_;
    std::ostringstream progress_;
    fs::path backup_;
};

TEST_F(RunnerTest, TheCdiIsReadOncePerRun) {
    const NodeReport r = run(std::nullopt);
    ASSERT_NE(find(r, "encoding.restore"), nullptr);
    EXPECT_EQ(find(r, "encoding.restore")->status, Status::kPass);
    EXPECT_EQ(find(r, "encoding.int")->status, Status::kPass);
    EXPECT_EQ(link_->cdi_reads_at_zero, 1);
    EXPECT_EQ(find(r, "link.lost"), nullptr);
}

TEST_F(RunnerTest, WithoutProtocolChecksTheRunnerReadsTheCdiItself) {
    const NodeReport r = run(std::nullopt, false);
    ASSERT_NE(find(r, "encoding.int"), nullptr);
    EXPECT_EQ(find(r, "encoding.int")->status, Status::kPass);
    EXPECT_EQ(find(r, "encoding.restore")->status, Status::kPass);
    EXPECT_EQ(link_->cdi_reads_at_zero, 1);
}

TEST_F(RunnerTest, LinkLostAndBackRestoresAndReportsTheLoss) {
    const NodeReport r = run(true);
    const CheckResult* lost = find(r, "link.lost");
    ASSERT_NE(lost, nullptr);
    EXPECT_EQ(lost->status, Status::kFail);
    EXPECT_EQ(lost->category, Category::kLink);
    EXPECT_NE(lost->message.find("/dev/ttyTEST"), std::string::npos) << lost->message;
    for (const char* id : {"encoding.int", "encoding.string", "encoding.eventid"}) {
        ASSERT_NE(find(r, id), nullptr) << id;
        EXPECT_EQ(find(r, id)->status, Status::kSkip) << id;
    }
    ASSERT_NE(find(r, "encoding.restore"), nullptr);
    EXPECT_EQ(find(r, "encoding.restore")->status, Status::kPass)
        << find(r, "encoding.restore")->message;
    EXPECT_FALSE(fs::exists(backup_));
    EXPECT_NE(progress_.str().find("waiting up to 5 s"), std::string::npos) << progress_.str();
}

TEST_F(RunnerTest, LinkThatStaysDownKeepsTheBackupAndNamesTheCommand) {
    const NodeReport r = run(false);
    ASSERT_NE(find(r, "link.lost"), nullptr);
    EXPECT_NE(find(r, "link.lost")->message.find("still down"), std::string::npos);
    const CheckResult* restored = find(r, "encoding.restore");
    ASSERT_NE(restored, nullptr);
    EXPECT_EQ(restored->status, Status::kFail);
    EXPECT_NE(
        restored->message.find("lcc-conform --serial /dev/ttyTEST restore " + backup_.string()),
        std::string::npos)
        << restored->message;
    EXPECT_TRUE(fs::exists(backup_));
}

}  // namespace
}  // namespace olcb::conform
