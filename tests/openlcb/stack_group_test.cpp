// Many stacks behind one interface (openlcb/stack_group.cpp) on a simulated clock: the frames on
// the wire are those of every stack given every frame, at a cost linear in the stacks.
#include "openlcb/stack_group.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "openlcb/can_defs.hpp"
#include "openlcb/node_test_util.hpp"

namespace olcb {
namespace {

using namespace test;
using namespace std::chrono_literals;

constexpr NodeId kOutsider{0x02'01'0D'00'00'99ull};
constexpr std::uint16_t kOutsideAlias = 0x0AB;
constexpr NodeId kFirst{0x05'01'01'01'30'00ull};
const TimePoint kLimit = t0 + 10s;

// Flips the same bits in two of a node ID's 12-bit groups: the XOR of the groups, its first
// alias, stays the same.
constexpr std::uint64_t kSameFirstAlias = 0x0000'0010'0100ull;

// The stacks of a test, each answering Verify Node ID and taking no other global message: node
// IDs from kFirst on; with contend, every second one has the first alias of the one before.
std::vector<std::unique_ptr<NodeStack>> make_stacks(std::size_t n, bool contend = false) {
    std::vector<std::unique_ptr<NodeStack>> out;
    for (std::uint64_t k = 0; k < n; ++k) {
        const std::uint64_t id =
            contend ? (kFirst.value() + k / 2) ^ (k % 2 * kSameFirstAlias) : kFirst.value() + k;
        NodeStackConfig c = stack_config(NodeId(id));
        c.builtins.duplicate_id_pcer = true;
        out.push_back(std::make_unique<NodeStack>(c));
        out.back()->set_global_messages(std::vector<Mti>{});
    }
    return out;
}

bool all_initialized(const std::vector<std::unique_ptr<NodeStack>>& stacks) {
    return std::all_of(stacks.begin(), stacks.end(),
                       [](const auto& s) { return s->initialized(); });
}

// What StackDriver did before StackGroup: every frame to every stack, every stack asked for its
// deadline; the frames it sends, in order, are what the group must send.
class EveryStack {
public:
    explicit EveryStack(const std::vector<std::unique_ptr<NodeStack>>& stacks) {
        dirty_flags_.resize(stacks.size());
        for (std::size_t i = 0; i < stacks.size(); ++i) {
            stacks_.push_back(stacks[i].get());
            stacks[i]->set_output_handler([this, i] {
                if (dirty_flags_[i]) return;
                dirty_flags_[i] = true;
                dirty_.push_back(i);
            });
        }
    }
    void start_all(TimePoint now) {
        for (NodeStack* s : stacks_) s->start(now);
    }
    void deliver(const CanFrame& f, TimePoint now, std::size_t sender = SIZE_MAX) {
        for (std::size_t j = 0; j < stacks_.size(); ++j) {
            if (j != sender) stacks_[j]->on_frame(f, now);
        }
    }
    void flush(TimePoint now, Strings& wire) {
        for (std::size_t d = 0; d < dirty_.size(); ++d) {
            dirty_flags_[dirty_[d]] = false;
            std::vector<CanFrame> out;
            stacks_[dirty_[d]]->drain(out);
            for (const CanFrame& f : out) {
                wire.push_back(gridconnect::format(f));
                deliver(f, now, dirty_[d]);
            }
        }
        dirty_.clear();
    }
    std::optional<TimePoint> next_deadline() const {
        std::optional<TimePoint> best;
        for (const NodeStack* s : stacks_) {
            if (auto d = s->next_deadline(); d && (!best || *d < *best)) best = d;
        }
        return best;
    }
    void poll(TimePoint now) {
        for (NodeStack* s : stacks_) {
            if (auto d = s->next_deadline(); d && *d <= now) s->poll(now);
        }
    }
    bool has_output() const { return !dirty_.empty(); }

private:
    std::vector<NodeStack*> stacks_;
    std::vector<bool> dirty_flags_;
    std::vector<std::size_t> dirty_;
};

// Flushes and polls from deadline to deadline until nothing is due before kLimit; returns the
// time reached. Works on StackGroup and EveryStack alike.
template <class Group>
TimePoint settle(Group& g, TimePoint now, Strings& wire) {
    for (;;) {
        while (g.has_output()) {
            if constexpr (std::is_same_v<Group, StackGroup>) {
                g.flush(now, [&](const CanFrame& f) { wire.push_back(gridconnect::format(f)); });
            } else {
                g.flush(now, wire);
            }
        }
        const auto next = g.next_deadline();
        if (!next || *next > kLimit) return now;
        now = std::max(now, *next);
        g.poll(now);
    }
}

// Where two frame logs part, with the frames around it ("" when they are the same).
std::string difference(const Strings& got, const Strings& expected) {
    const auto [a, b] = std::mismatch(got.begin(), got.end(), expected.begin(), expected.end());
    if (a == got.end() && b == expected.end()) return "";
    const auto at = static_cast<std::size_t>(a - got.begin());
    std::string out = "frame " + std::to_string(at) + ":";
    for (std::size_t i = at >= 3 ? at - 3 : 0; i < at + 4; ++i) {
        out += "\n  " + (i < got.size() ? got[i] : std::string("-")) + "  " +
               (i < expected.size() ? expected[i] : std::string("-"));
    }
    return out;
}

// The same stacks twice, once in a StackGroup sharing one cache, once given every frame.
struct Twins {
    explicit Twins(std::size_t n) : grouped(make_stacks(n, true)), reference(make_stacks(n, true)) {
        for (auto& s : grouped) group.attach(*s);
    }
    void start() {
        group.start_all(t0);
        every.start_all(t0);
        now = settle(group, t0, wire);
        settle(every, t0, reference_wire);
    }
    // A frame from outside to both, then everything it leads to.
    void inject(const CanFrame& f) {
        now += 1s;
        group.deliver(f, now);
        every.deliver(f, now);
        now = settle(group, now, wire);
        settle(every, now, reference_wire);
    }

    std::vector<std::unique_ptr<NodeStack>> grouped, reference;
    StackGroup group{StackGroupOptions{.share_alias_cache = true}};
    EveryStack every{reference};
    TimePoint now = t0;
    Strings wire, reference_wire;
};

TEST(StackGroup, ALoginSendsWhatEveryStackGivenEveryFrameSends) {
    Twins twins(300);
    twins.start();
    ASSERT_TRUE(all_initialized(twins.grouped));
    ASSERT_TRUE(all_initialized(twins.reference));
    const bool conflicts = std::any_of(twins.grouped.begin(), twins.grouped.end(),
                                       [](auto& s) { return s->alias_allocator().attempts() > 1; });
    EXPECT_TRUE(conflicts) << "half of the nodes start on an alias another one wants";
    EXPECT_EQ(difference(twins.wire, twins.reference_wire), "");
}

TEST(StackGroup, ConflictsWithOutsideNodesAreHandledAsByEveryStack) {
    Twins twins(40);
    twins.start();
    const std::uint16_t a5 = twins.grouped[5]->alias();
    const std::uint16_t a7 = twins.grouped[7]->alias();
    const std::size_t before = twins.wire.size();
    twins.inject(can::make_cid(7, kOutsider, a5));  // answered with RID
    EXPECT_EQ(twins.wire.back(), gridconnect::format(can::make_rid(a5)));
    // Another node uses an alias in use: AMR, then a new reservation.
    twins.inject(can::make_node_id_frame(
        can::message_header(to_u16(Mti::kVerifiedNodeId) & 0xFFF, a7), kOutsider));
    EXPECT_NE(twins.grouped[7]->alias(), a7);
    EXPECT_TRUE(twins.grouped[7]->initialized());
    // Another node with a stack's node ID: the duplicate-node-ID PCER.
    twins.inject(can::make_amd(kOutsideAlias, twins.grouped[3]->node_id()));
    twins.inject(can::make_frame(
        can::message_header(to_u16(Mti::kVerifyNodeIdGlobal) & 0xFFF, kOutsideAlias)));
    twins.inject(can::make_ame(kOutsideAlias));
    EXPECT_GT(twins.wire.size(), before + 80u) << "two frames per node at least";
    EXPECT_EQ(difference(twins.wire, twins.reference_wire), "");
}

// Deliveries of one login per stack, for n stacks contending in pairs for their first aliases.
double deliveries_per_stack(std::size_t n) {
    auto stacks = make_stacks(n, true);
    StackGroup group(StackGroupOptions{.share_alias_cache = true});
    for (auto& s : stacks) group.attach(*s);
    group.start_all(t0);
    Strings wire;
    settle(group, t0, wire);
    EXPECT_TRUE(all_initialized(stacks));
    EXPECT_EQ(group.stats().frames_out, wire.size());
    return static_cast<double>(group.stats().deliveries) / static_cast<double>(n);
}

// Given every frame, 400 stacks would take 400 x 399 x 7 on_frame() calls for their logins.
TEST(StackGroup, ALoginCostsDeliveriesLinearInTheStacks) {
    const double small = deliveries_per_stack(100);
    const double large = deliveries_per_stack(400);
    EXPECT_LT(large, 2.0) << "only alias contention reaches another stack";
    EXPECT_LT(large, 2 * small + 1.0);
}

TEST(StackGroup, TimersAnOwnerSetsOutsideAnyCallAreKept) {
    auto stacks = make_stacks(3);
    StackGroup group;
    int notices = 0;
    group.set_notice([&] { ++notices; });
    for (auto& s : stacks) group.attach(*s);
    EXPECT_FALSE(group.next_deadline());
    bool ran = false;
    stacks[1]->schedule(t0 + 5s, [&](TimePoint) { ran = true; });
    EXPECT_EQ(notices, 1);
    EXPECT_EQ(group.next_deadline(), t0 + 5s);
    group.start_all(t0);
    EXPECT_EQ(group.next_deadline(), t0 + 200ms) << "the reservation waits";
    Strings wire;
    settle(group, t0, wire);
    EXPECT_TRUE(ran);
    EXPECT_EQ(group.stats().polls, 4u) << "three reservations, one timer";
    EXPECT_FALSE(group.next_deadline());
}

TEST(StackGroup, ADetachedStackIsGivenNothing) {
    auto stacks = make_stacks(3);
    StackGroup group(StackGroupOptions{.share_alias_cache = true});
    for (auto& s : stacks) group.attach(*s);
    group.start_all(t0);
    Strings wire;
    settle(group, t0, wire);
    group.detach(*stacks[1]);
    EXPECT_EQ(group.size(), 2u);
    const std::uint64_t before = group.stats().deliveries;
    group.deliver(can::make_frame(
                      can::message_header(to_u16(Mti::kVerifyNodeIdGlobal) & 0xFFF, kOutsideAlias)),
                  t0 + 1s);
    EXPECT_EQ(group.stats().deliveries, before + 2);
    EXPECT_FALSE(stacks[1]->has_output());
    EXPECT_EQ(stacks[1]->alias_cache().size(), 0u) << "a cache of its own again";
    EXPECT_NE(group.shared_alias_cache(), nullptr);
}

}  // namespace
}  // namespace olcb
