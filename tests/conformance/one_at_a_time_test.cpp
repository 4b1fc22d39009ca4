// The safety rule, proved on the wire: every frame lcc-conform sends during a full run against
// an in-process simnode is replayed onto a shadow of the node's memory. At no moment does more
// than one variable differ from its original, and while one does, lcc-conform sends nothing but
// that variable's own writes and reads, the datagram acks the protocol requires, Verify Node ID
// (the liveness question) and, for the ACDI user name, the SNIP request that reads it back.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <sstream>

#include "cdi/parser.hpp"
#include "conformance/checks/protocol_checks.hpp"
#include "conformance/conform_test_util.hpp"
#include "conformance/run/runner.hpp"
#include "conformance/sim_bench.hpp"
#include "openlcb/sim_network.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::conform {
namespace {

namespace fs = std::filesystem;

struct Variable {
    std::uint8_t space = 0;
    std::uint32_t address = 0, size = 0;
    std::string key;
    bool eventid = false;
};

// Replays the tool's frames onto a shadow memory and records every breach of the rule.
class Shadow {
public:
    Shadow(std::vector<Variable> vars, std::map<std::uint8_t, std::vector<std::uint8_t>> mem)
        : vars_(std::move(vars)), original_(mem), now_(std::move(mem)) {}

    void frame(const CanFrame& f, std::uint16_t tool) {
        if (!f.extended || (f.id & 0xFFF) != tool || (f.id & 0x08000000) == 0) return;
        const std::uint32_t type = (f.id >> 24) & 0x07;
        if (type >= 2 && type <= 5) return datagram_frame(type, f);
        if (type != 1) return;
        const auto mti = static_cast<std::uint16_t>((f.id >> 12) & 0xFFF);
        if (mti == 0xA28 || mti == 0xA48) return;  // acks of the node's replies
        // Verify Node ID: the liveness question asked after the node's Initialization Complete
        // (simnode re-announces itself after a write to 251); it reads no configuration.
        if (mti == 0x488 || mti == 0x490) return;
        const auto differing = differs();
        if (differing.empty()) return;
        if (mti == 0xDE8 && differing.size() == 1 && differing[0]->space == 251) return;
        // events.follow-write: Identify Producer/Consumer are that event variable's read-back.
        if ((mti == 0x914 || mti == 0x8F4) && differing.size() == 1 && differing[0]->eventid)
            return;
        breaches_.push_back("message MTI " + std::to_string(mti) + " while " + differing[0]->key +
                            " holds a test value");
    }
    std::size_t most_differing() const { return most_; }
    std::size_t writes() const { return writes_; }
    const std::vector<std::string>& breaches() const { return breaches_; }
    std::vector<const Variable*> differs() const {
        std::vector<const Variable*> out;
        for (const Variable& v : vars_) {
            const auto& a = now_.at(v.space);
            const auto& b = original_.at(v.space);
            if (!std::equal(a.begin() + v.address, a.begin() + v.address + v.size,
                            b.begin() + v.address))
                out.push_back(&v);
        }
        return out;
    }

private:
    void datagram_frame(std::uint32_t type, const CanFrame& f) {
        if (type == 2 || type == 3) buffer_.clear();
        buffer_.insert(buffer_.end(), f.data.begin(), f.data.begin() + f.len);
        if (type == 2 || type == 5) datagram(buffer_);
    }
    void datagram(const std::vector<std::uint8_t>& d) {
        if (d.size() < 7 || d[0] != 0x20) return other_request(d);
        const std::uint8_t cmd = d[1];
        const bool write = (cmd & 0xFC) == 0x00, read = (cmd & 0xFC) == 0x40;
        if (!write && !read) return other_request(d);
        const std::uint32_t address = std::uint32_t{d[2]} << 24 | d[3] << 16 | d[4] << 8 | d[5];
        const std::size_t data_at = (cmd & 0x03) == 0 ? 7 : 6;
        const std::uint8_t space =
            (cmd & 0x03) == 0 ? d[6] : static_cast<std::uint8_t>(0xFC + (cmd & 0x03));
        const auto before = differs();
        std::uint32_t length = read ? d[data_at] : static_cast<std::uint32_t>(d.size() - data_at);
        if (!before.empty() && !inside(*before[0], space, address, length)) {
            breaches_.push_back(std::string(read ? "read" : "write") + " of space " +
                                std::to_string(space) + " @" + std::to_string(address) + " while " +
                                before[0]->key + " holds a test value");
        }
        if (!write || !now_.count(space)) return;
        ++writes_;
        auto& bytes = now_[space];
        for (std::size_t i = data_at; i < d.size() && address + (i - data_at) < bytes.size(); ++i)
            bytes[address + (i - data_at)] = d[i];
        most_ = std::max(most_, differs().size());
    }
    void other_request(const std::vector<std::uint8_t>& d) {
        const auto differing = differs();
        // Update Complete after an event variable's write is part of events.follow-write.
        const bool update_complete = d.size() == 2 && d[0] == 0x20 && d[1] == 0xA8;
        if (update_complete && differing.size() == 1 && differing[0]->eventid) return;
        if (!differing.empty()) {
            breaches_.push_back("datagram " + std::to_string(d.empty() ? 0 : d[1]) + " while " +
                                differing[0]->key + " holds a test value");
        }
    }
    static bool inside(const Variable& v, std::uint8_t space, std::uint32_t at, std::uint32_t n) {
        return v.space == space && at >= v.address && at + n <= v.address + v.size;
    }

    std::vector<Variable> vars_;
    std::map<std::uint8_t, std::vector<std::uint8_t>> original_, now_;
    std::vector<std::uint8_t> buffer_;
    std::vector<std::string> breaches_;
    std::size_t most_ = 0, writes_ = 0;
};

TEST(OneVariableAtATime, ProvedOnEveryFrameOfAFullRun) {
    simnode::NodeConfig config;
    config.node_id = kDut;
    config.cdi = read_text(fs::path(OLCB_SOURCE_DIR) / "scenarios" / "default.xml");
    config.user_name = "simnode default";
    std::string error;
    auto bench = testing::SimBench::serve(config, error, true);
    ASSERT_TRUE(bench) << error;
    const simnode::SimNode& dut = *bench->dut;
    std::vector<Variable> vars;
    const auto& layout = *dut.memory().model().layout;
    for (cdi::Cursor c = layout.begin(); c.valid(); c.next()) {
        vars.push_back({static_cast<std::uint8_t>(c.space()),
                        static_cast<std::uint32_t>(c.address()),
                        static_cast<std::uint32_t>(c.size()), c.path(),
                        c.element().kind == cdi::ElementKind::kEventId});
    }
    std::map<std::uint8_t, std::vector<std::uint8_t>> mem;
    for (std::uint8_t sp : {251, 253}) mem[sp] = dut.memory().read(sp, 0, 1024);

    auto node = bench->start();
    ASSERT_TRUE(node);
    Session& session = *bench->session;
    const SimNetwork& net = bench->net;
    const std::size_t first = net.log().size();
    RunOptions options;
    options.sample = 0;
    options.backup_path =
        (fs::temp_directory_path() / ("one_at_a_time_" + std::to_string(::getpid()))).string();
    std::ostringstream progress;
    ProtocolChecks checks = [](Session& s, const NodeInfo& n, CheckContext& ctx) {
        return run_protocol_checks(s, n, ProtocolOptions{}, ctx);
    };
    const NodeReport report = run_node(session, *node, options, checks, progress);
    ASSERT_EQ(report.count(Status::kFail), 0u);

    Shadow shadow(vars, mem);
    const auto& log = net.log();
    for (std::size_t i = first; i < log.size(); ++i)
        shadow.frame(log[i].frame, session.tool_alias());
    EXPECT_GT(shadow.writes(), 100u);  // the replay saw the run's writes
    EXPECT_EQ(shadow.most_differing(), 1u);
    EXPECT_TRUE(shadow.differs().empty());
    for (const std::string& b : shadow.breaches()) ADD_FAILURE() << b;
}

}  // namespace
}  // namespace olcb::conform
