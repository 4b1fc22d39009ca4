#include "conformance/run/encoding_checks.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "cdi/parser.hpp"
#include "cdi/value_codec.hpp"
#include "conformance/conform_test_util.hpp"
#include "conformance/fake_memory.hpp"

namespace olcb::conform {
namespace {

constexpr const char* kCdi = R"(<?xml version="1.0"?>
<cdi xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance"
     xsi:noNamespaceSchemaLocation="http://openlcb.org/schema/cdi/1/4/cdi.xsd">
<acdi/>
<segment space="253">
  <int size="2"><name>Delay</name><min>0</min><max>1000</max></int>
  <int size="1"><name>Trim</name><min>-5</min><max>5</max></int>
  <int size="1"><name>Mode</name><map><relation><property>3</property><value>x</value></relation></map></int>
  <string size="8"><name>Label</name></string>
  <eventid><name>Ev</name></eventid>
  <float size="4"><name>Gain</name><min>-2</min><max>2</max></float>
  <action size="1"><name>Go</name><value>1</value></action>
  <group replication="10"><name>Line</name><int size="4"><name>N</name></int></group>
</segment>
</cdi>)";

struct Fixture : ::testing::Test {
    void SetUp() override {
        load_cdi(kCdi, doc, layout);
        mem.spaces[253] = std::vector<std::uint8_t>(200, 0);
        mem.spaces[251] = std::vector<std::uint8_t>(128, 0);
    }
    std::vector<CheckResult> run(const EncodingOptions& o, const EncodingHooks& hooks = {}) {
        probes = plan_encoding(*layout, o).probes;
        outcome = run_encoding_checks(probes, mem, o, hooks);
        return outcome.results;
    }
    const CheckResult& find(const std::vector<CheckResult>& r, const std::string& id) {
        auto it =
            std::find_if(r.begin(), r.end(), [&](const CheckResult& c) { return c.id == id; });
        EXPECT_NE(it, r.end()) << id;
        return *it;
    }
    cdi::Document doc;
    std::optional<cdi::Layout> layout;
    testing::FakeMemory mem;
    std::vector<Probe> probes;
    EncodingOutcome outcome;
};

TEST(BoundaryValues, IntCoversMinMaxZeroAndSignednessEdgeOnlyWhenValid) {
    cdi::Element e;
    e.kind = cdi::ElementKind::kInt;
    e.size = 1;
    auto v = boundary_values(e, false);
    std::vector<cdi::WideInt> ints;
    ints.reserve(v.size());
    for (auto& x : v) ints.push_back(*x.as_int());
    EXPECT_EQ(ints, (std::vector<cdi::WideInt>{0, 255, 128}));
    e.int_min = -5;
    e.int_max = 5;
    ints.clear();
    for (auto& x : boundary_values(e, false)) ints.push_back(*x.as_int());
    EXPECT_EQ(ints, (std::vector<cdi::WideInt>{-5, 5, 0, -1}));
}

TEST(BoundaryValues, StringHasEmptyFullAndMultibyteAtTheBoundary) {
    cdi::Element e;
    e.kind = cdi::ElementKind::kString;
    e.size = 6;
    auto v = boundary_values(e, false);
    ASSERT_EQ(v.size(), 4u);
    EXPECT_EQ(*v[0].as_string(), "");
    EXPECT_EQ(*v[1].as_string(), "ABCDE");
    EXPECT_EQ(*v[2].as_string(), "xxx\xC3\xA9");
    EXPECT_EQ(*v[3].as_string(), "yy\xE2\x82\xAC");
}

TEST(BoundaryValues, ActionAndBlobAreNeverWritten) {
    cdi::Element e;
    e.kind = cdi::ElementKind::kAction;
    e.size = 1;
    e.action_value = 1;
    EXPECT_TRUE(boundary_values(e, true).empty());
}

TEST(ReplicaSampled, FirstLastAndSpread) {
    std::vector<std::uint64_t> picked;
    for (std::uint64_t i = 0; i < 10; ++i) {
        if (replica_sampled(i, 10, 3)) picked.push_back(i);
    }
    EXPECT_EQ(picked, (std::vector<std::uint64_t>{0, 5, 9}));
    EXPECT_TRUE(replica_sampled(7, 10, 0));
    EXPECT_TRUE(replica_sampled(1, 2, 3));
}

TEST_F(Fixture, GoodNodePassesEveryCheckAndNeverWritesTheAction) {
    EncodingOptions o;
    auto r = run(o);
    for (const auto& c : r) {
        if (c.id == "encoding.persist-after-reboot" || c.id == "snip.follows-acdi-user-write") {
            EXPECT_EQ(c.status, Status::kSkip) << c.id;
        } else {
            EXPECT_EQ(c.status, Status::kPass) << c.id << ": " << c.message;
        }
    }
    // Line(1..10)/N sampled to 3 replicas; the action (address 25) untouched.
    EXPECT_EQ(std::count_if(probes.begin(), probes.end(),
                            [](const Probe& p) { return p.key.find("Line") != std::string::npos; }),
              3);
    for (const auto& p : probes) EXPECT_NE(p.element->kind, cdi::ElementKind::kAction);
}

TEST_F(Fixture, ByteOrderFaultFailsIntEventIdAndFloat) {
    mem.reverse_writes = true;
    auto r = run({});
    EXPECT_EQ(find(r, "encoding.int").status, Status::kFail);
    EXPECT_EQ(find(r, "encoding.int").category, Category::kEncoding);
    EXPECT_FALSE(find(r, "encoding.int").expected.empty());
    EXPECT_EQ(find(r, "encoding.eventid").status, Status::kFail);
    EXPECT_EQ(find(r, "encoding.float").status, Status::kFail);
}

TEST_F(Fixture, DroppedWritesFail) {
    mem.drop_writes = true;
    auto r = run({});
    EXPECT_EQ(find(r, "encoding.int").status, Status::kFail);
    EXPECT_EQ(find(r, "encoding.string").status, Status::kFail);
}

TEST_F(Fixture, UnterminatedStoredStringFails) {
    std::fill(mem.spaces[253].begin() + 4, mem.spaces[253].begin() + 12, 'Z');
    auto r = run({});
    EXPECT_EQ(find(r, "encoding.stored-strings").status, Status::kFail);
}

TEST_F(Fixture, LostOnRebootFailsPersistence) {
    EncodingOptions o;
    o.reboot = true;
    auto snapshot = mem.spaces[253];
    EncodingHooks h;
    h.reboot = [&] {
        mem.spaces[253] = snapshot;
        return RebootOutcome{true, 0, false};
    };
    auto r = run(o, h);
    EXPECT_EQ(find(r, "encoding.persist-after-reboot").status, Status::kFail);
    EncodingHooks keep;
    keep.reboot = [] { return RebootOutcome{true, 0, false}; };
    r = run(o, keep);
    EXPECT_EQ(find(r, "encoding.persist-after-reboot").status, Status::kPass);
}

TEST_F(Fixture, SnipFollowsUserNameWrite) {
    EncodingOptions o;
    o.acdi_user = true;
    EncodingHooks h;
    h.snip_user_name = [&]() -> std::optional<std::string> {
        const auto& s = mem.spaces[251];
        return std::string(reinterpret_cast<const char*>(s.data() + 1));
    };
    EXPECT_EQ(find(run(o, h), "snip.follows-acdi-user-write").status, Status::kPass);
    h.snip_user_name = []() -> std::optional<std::string> { return "old"; };
    auto r = run(o, h);
    EXPECT_EQ(find(r, "snip.follows-acdi-user-write").status, Status::kFail);
    EXPECT_EQ(find(r, "snip.follows-acdi-user-write").category, Category::kSnip);
}

TEST_F(Fixture, BackupCoversEveryWrittenByteAndRestoreUndoesTheRun) {
    EncodingOptions o;
    o.acdi_user = true;
    for (std::size_t i = 0; i < mem.spaces[253].size(); ++i) {
        mem.spaces[253][i] = static_cast<std::uint8_t>(i % 7 == 0 ? 0 : 'a' + i % 7);
    }
    auto before253 = mem.spaces[253];
    auto before251 = mem.spaces[251];
    probes = plan_encoding(*layout, o).probes;
    SafetyBackup b("unused", "n");
    for (const auto& rr : ranges_to_backup(probes, o)) {
        auto got = mem.read(rr.space, rr.address, rr.length);
        ASSERT_TRUE(got.ok);
        b.add({rr.space, rr.address, got.data});
    }
    EncodingHooks h;
    h.snip_user_name = []() -> std::optional<std::string> { return "x"; };
    mem.writes = 0;
    run_encoding_checks(probes, mem, o, h);
    EXPECT_GT(mem.writes, 40u);
    // Every variable got its original back before the next one was touched.
    EXPECT_EQ(mem.spaces[253], before253);
    EXPECT_EQ(mem.spaces[251], before251);
    EXPECT_TRUE(restore(b, mem).identical);
    EXPECT_EQ(mem.spaces[253], before253);
    EXPECT_EQ(mem.spaces[251], before251);
}

TEST_F(Fixture, StopHookInterruptsBeforeTheNextWrite) {
    std::size_t allowed = 3;
    EncodingHooks h;
    h.stop = [&] { return mem.writes >= allowed; };
    const auto before = mem.spaces[253];
    auto r = run({}, h);
    // The interrupted variable still gets its original back (at most one write more).
    EXPECT_GE(mem.writes, allowed);
    EXPECT_LE(mem.writes, allowed + 1);
    EXPECT_EQ(mem.spaces[253], before);
    EXPECT_EQ(find(r, "encoding.float").status, Status::kSkip);
}

TEST(SkippedEncodingChecks, AllSkip) {
    for (const auto& c : skipped_encoding_checks("--read-only")) {
        EXPECT_EQ(c.status, Status::kSkip);
        EXPECT_EQ(c.message, "--read-only");
    }
}

// Counts, after every write, the variables whose bytes differ from the original image.
struct WatchedMemory : MemoryAccess {
    testing::FakeMemory& inner;
    std::map<std::uint8_t, std::vector<std::uint8_t>> original;
    std::vector<Probe> variables;
    std::size_t most_differing = 0;
    std::size_t accesses = 0;
    explicit WatchedMemory(testing::FakeMemory& m) : inner(m), original(m.spaces) {}
    std::size_t differing() const {
        std::size_t n = 0;
        for (const Probe& v : variables) {
            const auto& now = inner.spaces.at(v.space);
            const auto& was = original.at(v.space);
            if (!std::equal(now.begin() + v.address, now.begin() + v.address + v.size,
                            was.begin() + v.address))
                ++n;
        }
        return n;
    }
    AccessResult read(std::uint8_t sp, std::uint32_t a, std::size_t n) override {
        ++accesses;
        return inner.read(sp, a, n);
    }
    AccessResult write(std::uint8_t sp, std::uint32_t a, std::span<const std::uint8_t> d) override {
        ++accesses;
        auto r = inner.write(sp, a, d);
        most_differing = std::max(most_differing, differing());
        return r;
    }
};

TEST_F(Fixture, AtMostOneVariableDiffersFromItsOriginalAtAnyTime) {
    EncodingOptions o;
    o.sample = 0;
    WatchedMemory watched(mem);
    watched.variables = plan_encoding(*layout, o).probes;
    ASSERT_GT(watched.variables.size(), 10u);
    probes = watched.variables;
    run_encoding_checks(probes, watched, o, {});
    EXPECT_EQ(watched.most_differing, 1u);
    EXPECT_EQ(watched.differing(), 0u);
}

TEST_F(Fixture, NodeDeathStopsAtOnceAndHandsTheVariableInFlightBack) {
    EncodingOptions o;
    EncodingHooks h;
    std::size_t writes_seen = 0, writes_at_death = 0;
    std::string died_at;
    h.after_access = [&](const AccessStep& step) {
        if (step.what != "writing") return true;
        if (++writes_seen < 5) return true;
        died_at = step.key;
        writes_at_death = mem.writes;
        return false;
    };
    const auto before = mem.spaces[253];
    auto r = run(o, h);
    EXPECT_TRUE(outcome.node_died);
    EXPECT_EQ(mem.writes, writes_at_death);  // not one write more after the death
    ASSERT_EQ(outcome.in_flight.size(), 1u);
    EXPECT_EQ(outcome.in_flight[0].key, died_at);
    const InFlight& f = outcome.in_flight[0];
    EXPECT_TRUE(std::equal(f.original.begin(), f.original.end(), before.begin() + f.address));
    EXPECT_EQ(find(r, "encoding.float").status, Status::kSkip);
    EXPECT_NE(find(r, "encoding.float").message.find("stopped answering"), std::string::npos);
}

TEST_F(Fixture, AnOriginalThatDoesNotReadBackStopsEveryFurtherWrite) {
    struct Stubborn : MemoryAccess {
        testing::FakeMemory& m;
        std::size_t writes = 0;
        explicit Stubborn(testing::FakeMemory& f) : m(f) {}
        AccessResult read(std::uint8_t s, std::uint32_t a, std::size_t n) override {
            return m.read(s, a, n);
        }
        AccessResult write(std::uint8_t s, std::uint32_t a,
                           std::span<const std::uint8_t> d) override {
            // Acknowledges, but drops, the original of the first variable (its 3rd write).
            if (++writes == 3) return {true, 0, {}};
            return m.write(s, a, d);
        }
    } stubborn(mem);
    EncodingOptions o;
    probes = plan_encoding(*layout, o).probes;
    outcome = run_encoding_checks(probes, stubborn, o, {});
    EXPECT_TRUE(outcome.restore_failed);
    EXPECT_EQ(stubborn.writes, 3u);  // 2 test values of the first int, then its original
    EXPECT_EQ(find(outcome.results, "encoding.original-restored").status, Status::kFail);
}

TEST_F(Fixture, RejectedResetSkipsPersistenceQuotingTheCodeAndPutsValuesBack) {
    EncodingOptions o;
    o.reboot = true;
    const auto before = mem.spaces[253];
    EncodingHooks h;
    bool values_in_place = false;
    h.reboot = [&] {
        values_in_place = mem.spaces[253] != before;
        return RebootOutcome{false, 0x1041, false};
    };
    auto r = run(o, h);
    EXPECT_TRUE(values_in_place);
    const CheckResult& p = find(r, "encoding.persist-after-reboot");
    EXPECT_EQ(p.status, Status::kSkip);
    EXPECT_EQ(p.message, "Reset/Reboot rejected with 0x1041; persistence not tested");
    EXPECT_EQ(mem.spaces[253], before);
}

constexpr const char* kProtectedCdi = R"(<?xml version="1.0"?>
<cdi><segment space="253">
  <group><name>Internal data</name><description>Do not change these settings.</description>
    <int size="2"><name>Version</name></int>
    <int size="2"><name>Next event ID</name></int>
  </group>
  <group><name>Locked</name><hints><readOnly/></hints><int size="1"><name>Serial</name></int></group>
  <int size="1"><name>Speed</name><description>Don't change unless told to.</description></int>
  <int size="1"><name>Trim</name></int>
  <group replication="2"><name>Port</name><int size="1"><name>Mode</name></int></group>
  <action size="1"><name>Reset</name><value>1</value></action>
</segment></cdi>)";

struct ProtectedFixture : ::testing::Test {
    void SetUp() override {
        load_cdi(kProtectedCdi, doc, layout);
        mem.spaces[253] = std::vector<std::uint8_t>(16, 0);
        mem.spaces[253][0] = 2;  // Version
    }
    std::vector<std::string> keys(const EncodingPlan& p) const {
        std::vector<std::string> out;
        out.reserve(p.probes.size());
        for (const Probe& x : p.probes) out.push_back(x.key);
        return out;
    }
    cdi::Document doc;
    std::optional<cdi::Layout> layout;
    testing::FakeMemory mem;
};

TEST_F(ProtectedFixture, ProtectedSettingsAreLeftAloneWithTheirReason) {
    EncodingPlan plan = plan_encoding(*layout, {});
    EXPECT_EQ(keys(plan),
              (std::vector<std::string>{"seg0.Trim", "seg0.Port(0).Mode", "seg0.Port(1).Mode"}));
    std::map<std::string, std::string> reasons;
    for (const Unwritten& u : plan.unwritten) reasons[u.key] = u.reason;
    EXPECT_EQ(reasons["seg0.Internal data.Version"], "'do not change' in group 'Internal data'");
    EXPECT_EQ(reasons["seg0.Locked.Serial"], "read-only hint of group 'Locked'");
    EXPECT_EQ(reasons["seg0.Speed"], "'do not change' in variable 'Speed'");
    EXPECT_EQ(reasons["seg0.Reset"], "<action> triggers a command");
    const auto checks = unwritten_checks(plan.unwritten, false);
    ASSERT_EQ(checks.size(), 5u);
    for (const auto& c : checks) {
        EXPECT_EQ(c.id, "encoding.protected");
        EXPECT_EQ(c.status, Status::kSkip);
    }
}

TEST_F(ProtectedFixture, WriteProtectedProbesThemButNeverAcrossAReset) {
    EncodingOptions o;
    o.reboot = true;
    o.protection.write_protected = true;
    EncodingPlan plan = plan_encoding(*layout, o);
    EXPECT_EQ(plan.probes.size(), 7u);  // every variable but the action
    ASSERT_EQ(plan.unwritten.size(), 1u);
    EXPECT_EQ(plan.unwritten[0].key, "seg0.Reset");
    const auto before = mem.spaces[253];
    bool protected_changed_at_reset = true, unprotected_changed_at_reset = false;
    EncodingHooks h;
    h.reboot = [&] {
        const auto& now = mem.spaces[253];
        protected_changed_at_reset = !std::equal(now.begin(), now.begin() + 6, before.begin());
        unprotected_changed_at_reset = !std::equal(now.begin() + 6, now.end(), before.begin() + 6);
        return RebootOutcome{true, 0, false};
    };
    auto out = run_encoding_checks(plan.probes, mem, o, h);
    EXPECT_FALSE(protected_changed_at_reset);
    EXPECT_TRUE(unprotected_changed_at_reset);
    EXPECT_EQ(mem.spaces[253], before);
}

TEST_F(ProtectedFixture, ExcludeAndOnlySelectByBackupKey) {
    EncodingOptions o;
    o.protection.exclude = {"*.Port(1).*"};
    EncodingPlan plan = plan_encoding(*layout, o);
    EXPECT_EQ(keys(plan), (std::vector<std::string>{"seg0.Trim", "seg0.Port(0).Mode"}));
    o.protection.exclude.clear();
    o.protection.only = {"seg0.Port*"};
    plan = plan_encoding(*layout, o);
    EXPECT_EQ(keys(plan), (std::vector<std::string>{"seg0.Port(0).Mode", "seg0.Port(1).Mode"}));
    const auto checks = unwritten_checks(plan.unwritten, false);
    ASSERT_FALSE(checks.empty());
    EXPECT_EQ(checks.back().id, "encoding.excluded");
    EXPECT_NE(checks.back().message.find("(not matched by --only)"), std::string::npos)
        << checks.back().message;
}

}  // namespace
}  // namespace olcb::conform
