// The faults around restarts (docs/faults.md): abort-on-value, reset-rejected, lock-rejected,
// factory-reset-on-version-change and new-alias-on-reboot misbehave as documented, and a good
// node does not; and the shipped fault scenarios that combine them.
#include <gtest/gtest.h>

#include "memory/snip.hpp"
#include "simnode/faults/fault_test_util.hpp"
#include "simnode/scenario.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(RestartFaultTest, GoodNodeAnswersSnipWhateverTheValue) {
    start(default_config());
    write_ok(0xFD, kVersion, {0x80});
    EXPECT_FALSE(request_snip().empty());
    EXPECT_EQ(node_->watched_address(), std::nullopt);
}

TEST_F(RestartFaultTest, AbortOnValueGoesSilentThenRestarts) {
    start_with({"abort-on-value=2000"});
    EXPECT_EQ(node_->watched_address(), kVersion);
    EXPECT_FALSE(request_snip().empty()) << "value as at creation: SNIP is answered";
    write_ok(0xFD, kVersion, {0x80});
    take();
    send_text(":X19DE812CN0343;");  // SNIP request
    net_.run_for(10ms);
    EXPECT_TRUE(take().empty()) << "no SNIP reply, nothing at all";
    EXPECT_TRUE(node_->stack().silent());
    EXPECT_EQ(node_->counters().aborts, 1u);
    for (const char* frame : {":X1949012CN;",                     // Verify Node ID Global
                              ":X1948812CN0343;",                 // Verify Node ID addressed
                              ":X17050343N;",                     // CID for its alias
                              ":X19170343N020000000001;",         // another node uses its alias
                              ":X1A34312CN204000000000FD01;"}) {  // a read
        send_text(frame);
        net_.run_for(100ms);
    }
    net_.run_for(1480ms);  // 1990 ms after the SNIP request
    EXPECT_TRUE(take().empty()) << "silent for the whole period";
    net_.run_for(20ms);
    EXPECT_FALSE(node_->stack().silent());
    wait_restarted(1s);
    expect_startup(take(), 0x343);
    EXPECT_EQ(read(0xFD, kVersion, 1), (std::vector<std::uint8_t>{0x80})) << "memory persists";

    send_text(":X19DE812CN0343;");
    net_.run_for(10ms);
    EXPECT_TRUE(node_->stack().silent()) << "aborts again while the value differs";
    EXPECT_EQ(node_->counters().aborts, 2u);
    wait_restarted(3s);
    write_ok(0xFD, kVersion, {1});
    EXPECT_FALSE(request_snip().empty()) << "the byte put back: SNIP works again";
    EXPECT_EQ(node_->counters().aborts, 2u);
}

TEST_F(RestartFaultTest, AbortOnValueKeepsTheImageOnDisk) {
    TempDir dir;
    NodeConfig c = default_config();
    c.image_dir = dir.path();
    c.faults = faults_of({"abort-on-value=100"});
    start(c);
    write_ok(0xFD, kVersion, {0x80});
    send_text(":X19DE812CN0343;");
    net_.run_for(10ms);
    ASSERT_TRUE(node_->stack().silent());
    wait_restarted(1s);
    std::ifstream in(dir.path() / image_file_name(0xFD), std::ios::binary);
    EXPECT_EQ(in.get(), 0x80);
}

TEST_F(RestartFaultTest, GoodNodeObeysReset) {
    start(default_config());
    reboot();
    EXPECT_EQ(node_->counters().reboots, 1u);
    EXPECT_EQ(node_->stack().initializations(), 2u);
}

TEST_F(RestartFaultTest, DeafAfterInitIgnoresRequestsRightAfterEachStartUp) {
    start_with({"deaf-after-init=300"});  // start() returns 10 ms after Initialization Complete
    take();
    send_addressed(to_u16(Mti::kVerifyNodeIdAddressed));
    net_.run_for(50ms);
    EXPECT_EQ(count_prefix(take(), ":X19170"), 0u) << "an addressed Verify is not answered yet";
    send_global(to_u16(Mti::kVerifyNodeIdGlobal));
    net_.run_for(50ms);
    EXPECT_EQ(count_prefix(take(), ":X19170"), 1u) << "a global one is";
    const Answer lost = exchange(read_cmd(0xFD, 0, 1), 100ms);
    EXPECT_FALSE(lost.ok || lost.rejected || lost.reply) << "a datagram is dropped unanswered";
    net_.run_for(300ms);
    const Answer later = exchange(read_cmd(0xFD, 0, 1));
    EXPECT_TRUE(later.ok && later.reply) << "the node listens once the time is over";
    reboot();  // the Reset's own OK comes before the restart
    take();
    send_addressed(to_u16(Mti::kVerifyNodeIdAddressed));
    net_.run_for(50ms);
    EXPECT_EQ(count_prefix(take(), ":X19170"), 0u) << "deaf again after the restart";
    net_.run_for(300ms);
    send_addressed(to_u16(Mti::kVerifyNodeIdAddressed));
    net_.run_for(50ms);
    EXPECT_EQ(count_prefix(take(), ":X19170"), 1u);
}

TEST_F(RestartFaultTest, ResetRejected) {
    start_with({"reset-rejected"});
    EXPECT_TRUE(exchange({0x20, 0x88, 2, 1, 0x0D, 0, 0, 1}).reply);  // take the lock
    take();
    const Answer a = exchange({0x20, 0xA9});
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1041);
    EXPECT_FALSE(a.ok);
    net_.run_for(1s);
    const auto frames = take();
    EXPECT_EQ(count_prefix(frames, ":X17"), 0u) << "no CID: the node does not restart";
    EXPECT_EQ(count_prefix(frames, ":X19100"), 0u);
    EXPECT_EQ(node_->counters().reboots, 0u);
    EXPECT_EQ(node_->stack().initializations(), 1u);
    EXPECT_NE(node_->server().lock_holder(), 0u) << "nothing a reset clears was cleared";
}

TEST_F(FaultTest, GoodNodeLocksAndReportsStandardErrors) {
    start(default_config());
    Answer a = exchange({0x20, 0x88, 2, 1, 0x0D, 0, 0, 1});
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x8A, 2, 1, 0x0D, 0, 0, 1}));
    a = exchange(read_cmd(0x10, 0, 4));
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1081);
    a = exchange(write_cmd(0xFF, 0, {'x'}));
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1083);
    EXPECT_EQ(read(0xFC, 0, 64).size(), 64u) << "a good node fills the count asked";
}

TEST_F(FaultTest, LockRejected) {
    start_with({"lock-rejected"});
    const Answer a = exchange({0x20, 0x88, 2, 1, 0x0D, 0, 0, 1});
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1041);
    EXPECT_FALSE(a.reply);
    EXPECT_EQ(node_->server().lock_holder(), 0u);
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{2})) << "the rest still works";
}

TEST_F(RestartFaultTest, GoodNodeKeepsAChangedVersionOverReboot) {
    start(default_config());
    write_ok(0xFD, kVersion, {0});
    write_ok(0xFD, kDelay, {0, 0, 1, 2});
    reboot();
    EXPECT_EQ(read(0xFD, kVersion, 1), (std::vector<std::uint8_t>{0}));
    EXPECT_EQ(read(0xFD, kDelay, 4), (std::vector<std::uint8_t>{0, 0, 1, 2}));
    EXPECT_EQ(node_->counters().factory_resets, 0u);
}

TEST_F(RestartFaultTest, FactoryResetOnVersionChange) {
    start_with({"factory-reset-on-version-change"});
    write_ok(0xFD, kDelay, {0, 0, 1, 2});
    reboot();
    EXPECT_EQ(read(0xFD, kDelay, 4), (std::vector<std::uint8_t>{0, 0, 1, 2}))
        << "version unchanged: settings kept";
    EXPECT_EQ(node_->counters().factory_resets, 0u);

    write_ok(0xFD, kVersion, {0});
    write_ok(0xFB, 1, bytes_of(std::string("Changed") + '\0'));
    EXPECT_EQ(node_->snip().user_name, "Changed");
    reboot();
    EXPECT_EQ(node_->counters().factory_resets, 1u);
    EXPECT_EQ(read(0xFD, kVersion, 1), (std::vector<std::uint8_t>{1}));
    EXPECT_EQ(read(0xFD, kDelay, 4), kDefaultDelay) << "every setting wiped";
    EXPECT_EQ(node_->snip().user_name, "Test node") << "space 251 too";
}

TEST_F(RestartFaultTest, FactoryResetOnVersionChangeAtARebootOnWrite) {
    start_with({"reboot-on-write", "factory-reset-on-version-change"});
    const Answer a = exchange(write_cmd(0xFD, kVersion, {7}), 500ms);
    EXPECT_TRUE(a.ok);
    wait_restarted(1s);
    EXPECT_EQ(node_->counters().factory_resets, 1u);
    EXPECT_EQ(read(0xFD, kVersion, 1), (std::vector<std::uint8_t>{1}));
}

TEST_F(RestartFaultTest, OpenMrnLikeAbortThenFactoryReset) {
    start_with({"abort-on-value=500", "factory-reset-on-version-change"});
    write_ok(0xFD, kDelay, {0, 0, 1, 2});
    write_ok(0xFD, kVersion, {0x80});
    send_text(":X19DE812CN0343;");
    net_.run_for(10ms);
    ASSERT_TRUE(node_->stack().silent());
    wait_restarted(1s);
    EXPECT_EQ(node_->counters().aborts, 1u);
    EXPECT_EQ(node_->counters().factory_resets, 1u);
    EXPECT_EQ(read(0xFD, kDelay, 4), kDefaultDelay);
    EXPECT_FALSE(request_snip().empty()) << "version restored by the wipe: no more aborts";
}

TEST_F(RestartFaultTest, GoodNodeComesBackOnTheSameAlias) {
    start(default_config());
    reboot();
    EXPECT_EQ(alias(), 0x343);
}

TEST_F(RestartFaultTest, NewAliasOnReboot) {
    start_with({"new-alias-on-reboot"});
    EXPECT_EQ(alias(), 0x343) << "the first start-up is as usual";
    take();
    reboot();
    const std::uint16_t second = alias();
    EXPECT_NE(second, 0x343);
    expect_startup(take(), second, 1);  // after the Datagram OK
    const memory::Snip snip = memory::decode_snip(request_snip());
    EXPECT_EQ(snip.user_name, "Test node") << "reachable on the new alias";
    reboot();
    EXPECT_NE(alias(), second);
    EXPECT_NE(alias(), 0x343);
}

TEST_F(RestartFaultTest, NewAliasOnRebootAppliesToEveryRestart) {
    start_with({"new-alias-on-reboot", "reboot-on-write"});
    const Answer a = exchange(write_cmd(0xFD, kDelay, {0, 0, 0, 1}), 500ms);
    EXPECT_TRUE(a.ok);
    wait_restarted(1s);
    EXPECT_NE(alias(), 0x343);
}

class ShippedScenarioTest : public RestartFaultTest {
protected:
    /// The node of a shipped scenario (relative to scenarios/), RAM-only.
    static NodeConfig scenario_node(const std::string& relative) {
        const std::filesystem::path file =
            std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios" / relative;
        std::string error;
        const auto s = parse_scenario_text(read_source_file("scenarios/" + relative),
                                           file.parent_path(), {}, error);
        EXPECT_TRUE(s) << error;
        if (!s || s->nodes.size() != 1) return default_config();
        NodeConfig c = s->nodes.front();
        c.image_dir.clear();
        return c;
    }
};

TEST_F(ShippedScenarioTest, OpenMrnLikeCrashesOnAChangedVersionThenWipesItsSettings) {
    start(scenario_node("faults/openmrn-like.ini"));
    EXPECT_EQ(node_->cdi_problem(), "");
    EXPECT_EQ(node_->config().faults.value("factory-reset-on-version-change"), FaultValue{1});
    EXPECT_EQ(node_->config().faults.value("abort-on-value"), FaultValue{3000});
    const std::string head = "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
    EXPECT_EQ(read(0xFF, 0, static_cast<std::uint8_t>(head.size())), bytes_of(head));
    ASSERT_EQ(node_->watched_address(), 128u) << "the Internal data Version";
    EXPECT_EQ(read(0xFD, 128, 2), (std::vector<std::uint8_t>{0, 2}));
    const std::uint32_t port1_description = 132;
    write_ok(0xFD, port1_description, bytes_of(std::string("Yard lead") + '\0'));
    EXPECT_FALSE(request_snip().empty()) << "Version 2: SNIP is answered";
    write_ok(0xFD, 128, {0x80, 0x02});
    send_text(":X19DE812CN0343;");
    net_.run_for(10ms);
    ASSERT_TRUE(node_->stack().silent());
    net_.run_for(2900ms);
    EXPECT_TRUE(node_->stack().silent());
    wait_restarted(1s);
    EXPECT_EQ(node_->counters().factory_resets, 1u);
    EXPECT_EQ(read(0xFD, 128, 2), (std::vector<std::uint8_t>{0, 2}));
    EXPECT_EQ(read(0xFD, port1_description, 1), (std::vector<std::uint8_t>{0}));
    EXPECT_EQ(memory::decode_snip(request_snip()).user_name, "simnode OpenMRN-like");
}

TEST_F(ShippedScenarioTest, OneLineCdiIsServedAsWritten) {
    start(scenario_node("one-line.ini"));
    EXPECT_TRUE(node_->config().faults.none());
    EXPECT_EQ(node_->cdi_problem(), "");
    const auto cdi = served_cdi();
    ASSERT_FALSE(cdi.empty());
    EXPECT_EQ(cdi.back(), 0);
    const std::string text(cdi.begin(), cdi.end() - 1);
    EXPECT_EQ(text.rfind("<?xml version=\"1.0\"?><cdi ", 0), 0u);
    EXPECT_EQ(text.find('\n'), std::string::npos);
    EXPECT_EQ(text, read_source_file("scenarios/one-line.xml"));
    EXPECT_EQ(read(0xFB, 1, 16), bytes_of("simnode one-line"));
}

}  // namespace
}  // namespace olcb::simnode::test
