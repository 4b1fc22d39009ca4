// Many SimNodes behind one interface, as simnode runs them (a StackGroup sharing one alias
// cache), on a simulated clock: a node's start-up costs the same work however many nodes start
// with it, counted in frames and deliveries (issue 32: 3,000 nodes took a minute).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "openlcb/can_defs.hpp"
#include "openlcb/gridconnect.hpp"
#include "openlcb/stack_group.hpp"
#include "simnode/sim_node.hpp"
#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode {
namespace {

using namespace std::chrono_literals;
using test::kClientAlias;

constexpr NodeId kFirst{0x05'01'01'01'30'00ull};
const TimePoint kStart = TimePoint{} + 1h;

// n default-CDI nodes, RAM only, in one group; the frames leaving it are kept as text.
class Segment {
public:
    explicit Segment(std::size_t n, const std::vector<std::string>& faults = {}) {
        for (std::uint64_t k = 0; k < n; ++k) {
            NodeConfig c;
            c.node_id = NodeId(kFirst.value() + k);
            c.cdi = test::default_cdi();
            if (k == 0) c.faults = test::faults_of(faults);
            std::string error;
            nodes_.push_back(SimNode::create(c, error));
            EXPECT_TRUE(nodes_.back()) << error;
            group_.attach(nodes_.back()->stack());
        }
    }
    // Starts every node and runs until nothing is due for a second.
    void start() {
        group_.start_all(now_);
        settle();
    }
    // A frame from outside the group, then what it leads to.
    void inject(const CanFrame& f) {
        group_.deliver(f, now_);
        settle();
    }
    bool all_initialized() const {
        return std::all_of(nodes_.begin(), nodes_.end(),
                           [](const auto& n) { return n->stack().initialized(); });
    }
    std::size_t count(const std::string& prefix) const {
        return static_cast<std::size_t>(
            std::count_if(wire_.begin(), wire_.end(),
                          [&](const std::string& f) { return f.starts_with(prefix); }));
    }
    SimNode& node(std::size_t k) { return *nodes_[k]; }
    const StackGroup::Stats& stats() const { return group_.stats(); }
    std::size_t frames() const { return wire_.size(); }

private:
    void settle() {
        const TimePoint limit = now_ + 1s;
        for (;;) {
            while (group_.has_output()) {
                group_.flush(
                    now_, [this](const CanFrame& f) { wire_.push_back(gridconnect::format(f)); });
            }
            const auto next = group_.next_deadline();
            if (!next || *next > limit) return;
            now_ = std::max(now_, *next);
            group_.poll(now_);
        }
    }

    std::vector<std::unique_ptr<SimNode>> nodes_;
    StackGroup group_{StackGroupOptions{.share_alias_cache = true}};
    TimePoint now_ = kStart;
    std::vector<std::string> wire_;
};

struct Login {
    double frames = 0;      // frames sent per node
    double deliveries = 0;  // on_frame() calls per node
};

Login login(std::size_t n) {
    Segment segment(n);
    segment.start();
    EXPECT_TRUE(segment.all_initialized());
    const auto per_node = [n](std::uint64_t total) {
        return static_cast<double>(total) / static_cast<double>(n);
    };
    return {per_node(segment.stats().frames_out), per_node(segment.stats().deliveries)};
}

// Given every frame, each of 160 nodes would take some 160 x 20 on_frame() calls to start.
TEST(SimNodeScale, AStartUpCostsTheSameWorkPerNodeAtAnyCount) {
    const Login small = login(40);
    const Login large = login(160);
    // Every node: CID x4, RID, AMD, Initialization Complete, its events identified; contention
    // for an alias adds a few frames.
    EXPECT_GE(small.frames, 7.0);
    EXPECT_LT(large.frames, small.frames * 1.25);
    EXPECT_LT(large.deliveries, 2.0) << "only alias contention reaches another node";
    EXPECT_LT(large.deliveries, 2 * small.deliveries + 1.0);
}

TEST(SimNodeScale, QueriesReachEveryNodeAndRequestsOnlyTheirs) {
    Segment segment(50);
    segment.start();
    ASSERT_TRUE(segment.all_initialized());
    std::uint64_t before = segment.stats().deliveries;
    segment.inject(can::make_frame(
        can::message_header(to_u16(Mti::kVerifyNodeIdGlobal) & 0xFFF, kClientAlias)));
    EXPECT_EQ(segment.count(":X19170"), 50u);
    EXPECT_EQ(segment.stats().deliveries - before, 50u) << "Verified Node IDs reach nobody";

    // A SNIP request reaches its node alone.
    const std::uint16_t alias = segment.node(7).stack().alias();
    before = segment.stats().deliveries;
    segment.inject(
        can::make_frame(can::message_header(to_u16(Mti::kSnipRequest) & 0xFFF, kClientAlias),
                        std::vector<std::uint8_t>{static_cast<std::uint8_t>(alias >> 8),
                                                  static_cast<std::uint8_t>(alias & 0xFF)}));
    EXPECT_EQ(segment.stats().deliveries - before, 1u);
    EXPECT_GE(segment.count(":X19A08"), 1u);

    // Identify Producer or Consumer: every node looks, the one with the event answers.
    const auto events = segment.node(3).events();
    ASSERT_FALSE(events.empty());
    const auto [event, role] = events.front();
    const bool producer = produces(role);
    const std::string answer = producer ? ":X19547" : ":X194C7";
    const std::size_t identified = segment.count(answer);
    before = segment.stats().deliveries;
    segment.inject(can::make_frame(
        can::message_header(
            to_u16(producer ? Mti::kIdentifyProducer : Mti::kIdentifyConsumer) & 0xFFF,
            kClientAlias),
        event.to_bytes()));
    EXPECT_EQ(segment.stats().deliveries - before, 50u);
    EXPECT_EQ(segment.count(answer), identified + 1);
}

TEST(SimNodeScale, AFaultThatWatchesEveryFrameStillSeesThem) {
    Segment segment(20, {"answers-standard-frames"});
    segment.start();
    ASSERT_TRUE(segment.all_initialized());
    CanFrame standard;
    standard.extended = false;
    standard.id = 0x123;
    const std::uint64_t before = segment.stats().deliveries;
    segment.inject(standard);
    EXPECT_EQ(segment.stats().deliveries - before, 1u);
    const SimNode& faulty = segment.node(0);
    const std::string verified = gridconnect::format(can::make_node_id_frame(
        can::message_header(to_u16(Mti::kVerifiedNodeId) & 0xFFF, faulty.stack().alias()),
        faulty.node_id()));
    EXPECT_EQ(segment.count(verified), 1u) << "the faulty node answered the standard frame";
}

}  // namespace
}  // namespace olcb::simnode
