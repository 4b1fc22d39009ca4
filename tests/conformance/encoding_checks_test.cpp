#include "conformance/encoding_checks.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "cdi/parser.hpp"
#include "cdi/value_codec.hpp"
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
        auto parsed = cdi::parse(kCdi);
        ASSERT_TRUE(parsed.document);
        doc = std::move(*parsed.document);
        auto lr = cdi::build_layout(doc);
        ASSERT_TRUE(lr.layout);
        layout.emplace(std::move(*lr.layout));
        mem.spaces[253] = std::vector<std::uint8_t>(200, 0);
        mem.spaces[251] = std::vector<std::uint8_t>(128, 0);
    }
    std::vector<CheckResult> run(const EncodingOptions& o, EncodingHooks hooks = {}) {
        probes = plan_encoding(*layout, o);
        return run_encoding_checks(probes, mem, o, hooks);
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
};

TEST(BoundaryValues, IntCoversMinMaxZeroAndSignednessEdgeOnlyWhenValid) {
    cdi::Element e;
    e.kind = cdi::ElementKind::kInt;
    e.size = 1;
    auto v = boundary_values(e, false);
    std::vector<cdi::WideInt> ints;
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
    EXPECT_EQ(
        std::count_if(probes.begin(), probes.end(),
                      [](const Probe& p) { return p.path.find("Line") != std::string::npos; }),
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
        return true;
    };
    auto r = run(o, h);
    EXPECT_EQ(find(r, "encoding.persist-after-reboot").status, Status::kFail);
    EncodingHooks keep;
    keep.reboot = [] { return true; };
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
    probes = plan_encoding(*layout, o);
    SafetyBackup b("unused", "n");
    for (const auto& rr : ranges_to_backup(probes, o)) {
        auto got = mem.read(rr.space, rr.address, rr.length);
        ASSERT_TRUE(got.ok);
        b.add({rr.space, rr.address, got.data});
    }
    EncodingHooks h;
    h.snip_user_name = []() -> std::optional<std::string> { return "x"; };
    run_encoding_checks(probes, mem, o, h);
    EXPECT_NE(mem.spaces[253], before253);
    EXPECT_TRUE(restore(b, mem).identical);
    EXPECT_EQ(mem.spaces[253], before253);
    EXPECT_EQ(mem.spaces[251], before251);
}

TEST_F(Fixture, StopHookInterruptsBeforeTheNextWrite) {
    std::size_t allowed = 3;
    EncodingHooks h;
    h.stop = [&] { return mem.writes >= allowed; };
    auto r = run({}, h);
    EXPECT_EQ(mem.writes, allowed);
    EXPECT_EQ(find(r, "encoding.float").status, Status::kSkip);
}

TEST(SkippedEncodingChecks, AllSkip) {
    for (const auto& c : skipped_encoding_checks("--read-only")) {
        EXPECT_EQ(c.status, Status::kSkip);
        EXPECT_EQ(c.message, "--read-only");
    }
}

}  // namespace
}  // namespace olcb::conform
