// One NodeStack against a raw GridConnect port on a SimNetwork: start-up, built-ins, datagram
// entry, alias defence and loss, restart, queues.
#include "openlcb/node_stack.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <vector>

#include "base/error_codes.hpp"
#include "openlcb/datagram_defs.hpp"
#include "openlcb/node_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;

const Strings kStartup = {
    ":X17050343N;",
    ":X16101343N;",
    ":X15012343N;",
    ":X14200343N;",
    ":X10700343N;",
    ":X10701343N050101012200;",
    ":X19100343N050101012200;",
};

class NodeStackTest : public test::StackFixture {
protected:
    using StackFixture::StackFixture;
};

TEST_F(NodeStackTest, StartupGivesTheWorkedExampleFramesWithRidAfter200ms) {
    int initialized_calls = 0;
    stack_.set_initialized_handler([&] {
        ++initialized_calls;
        EXPECT_TRUE(stack_.initialized());
    });
    const TimePoint t0 = net_.now();
    stack_.start(t0);
    net_.run_for(199ms);
    EXPECT_EQ(take(), (Strings{kStartup.begin(), kStartup.begin() + 4}));
    EXPECT_FALSE(stack_.initialized());
    EXPECT_EQ(stack_.alias(), 0x343);
    net_.run_for(1ms);
    EXPECT_EQ(take(), (Strings{kStartup.begin() + 4, kStartup.end()}));
    EXPECT_TRUE(stack_.initialized());
    EXPECT_EQ(initialized_calls, 1);
    EXPECT_EQ(net_.log_text(), kStartup);
    ASSERT_EQ(net_.log().size(), 7u);
    EXPECT_EQ(net_.log()[3].at, t0);
    EXPECT_EQ(net_.log()[4].at, t0 + 200ms);
    EXPECT_EQ(stack_.initializations(), 1u);
    net_.run_for(10s);
    EXPECT_TRUE(take().empty()) << "no unsolicited traffic after start-up";
    EXPECT_FALSE(stack_.next_deadline().has_value());
}

TEST_F(NodeStackTest, MessagesSentBeforeInitializationFollowInitializationComplete) {
    Message early;
    early.mti = Mti::kConsumerIdentifiedUnknown;
    early.payload = {0x05, 0x01, 0x01, 0x01, 0x22, 0x00, 0x00, 0x01};
    EXPECT_EQ(stack_.send_message(early), SendStatus::kQueued);
    stack_.set_initialized_handler([&] {
        Message m;
        m.mti = Mti::kProducerIdentifiedUnknown;
        m.payload = {0x05, 0x01, 0x01, 0x01, 0x22, 0x00, 0x00, 0x02};
        EXPECT_EQ(stack_.send_message(m), SendStatus::kSent);
    });
    stack_.start(net_.now());
    net_.run_for(300ms);
    Strings expected = kStartup;
    expected.push_back(":X194C7343N0501010122000001;");
    expected.push_back(":X19547343N0501010122000002;");
    EXPECT_EQ(take(), expected);
}

TEST_F(NodeStackTest, SimpleProtocolNodeUsesSimpleInitAndVerifiedMtis) {
    auto config = test::stack_config();
    config.protocols.set(Protocol::kSimpleProtocol);
    LoneStack simple(config);
    simple.start();
    ASSERT_EQ(simple.seen.size(), 7u);
    EXPECT_EQ(simple.seen.back(), ":X19101343N050101012200;");
    simple.inject(":X1949012CN;");
    EXPECT_EQ(simple.seen.back(), ":X19171343N050101012200;");
}

TEST_F(NodeStackTest, VerifyNodeIdGlobalAndAddressed) {
    boot();
    inject(":X1949012CN;");
    EXPECT_EQ(take(), (Strings{":X19170343N050101012200;"}));
    inject(":X1949012CN050101012200;");
    EXPECT_EQ(take(), (Strings{":X19170343N050101012200;"}));
    inject(":X1949012CN050101012201;");
    EXPECT_TRUE(take().empty()) << "another node's ID: stay silent";
    inject(":X1949012CN0501;");
    EXPECT_TRUE(take().empty()) << "malformed ID: not ours";
    inject(":X1948812CN0343;");
    EXPECT_EQ(take(), (Strings{":X19170343N050101012200;"}));
    inject(":X1948812CN0343050101012201;");
    EXPECT_EQ(take(), (Strings{":X19170343N050101012200;"})) << "addressed: always answered";
    inject(":X1948812CN0344;");
    EXPECT_TRUE(take().empty()) << "addressed to someone else";
}

TEST_F(NodeStackTest, ProtocolSupportReplyOfTheWorkedExample) {
    boot();
    inject(":X1982812CN0343;");
    EXPECT_EQ(take(), (Strings{":X19668343N012C545800000000;"}));
    stack_.set_protocols(ProtocolSet{Protocol::kDatagram});
    inject(":X1982812CN0343;");
    EXPECT_EQ(take(), (Strings{":X19668343N012C400000000000;"}));
}

TEST_F(NodeStackTest, UnknownAddressedMtiGetsOirUnknownGlobalIsIgnored) {
    boot();
    inject(":X194F912CN0343;");
    EXPECT_EQ(take(), (Strings{":X19068343N012C104304F9;"}));
    inject(":X19DE812CN0343;");  // SNIP request with nobody handling it
    EXPECT_EQ(take(), (Strings{":X19068343N012C10430DE8;"}));
    inject(":X19970123N;");  // Identify Events global
    inject(":X195B4123N0102030405060708;");
    inject(":X19FF0123N01;");  // unknown global MTI
    EXPECT_TRUE(take().empty());
}

TEST_F(NodeStackTest, NoOirForRejectionsAndReplies) {
    boot();
    for (const char* text :
         {":X19068123N0343104304F9;", ":X190A8123N03431000;", ":X19668123N0343540000000000;",
          ":X19A28123N034300;", ":X19A48123N03431000;", ":X19A08123N03430441;", ":X19868123N0343;",
          ":X191E9123N034301;"}) {
        inject(text);
        EXPECT_TRUE(take().empty()) << text;
    }
    EXPECT_TRUE(NodeStack::never_rejected(to_u16(Mti::kTerminateDueToError)));
    EXPECT_FALSE(NodeStack::never_rejected(to_u16(Mti::kSnipRequest)));
}

TEST_F(NodeStackTest, OwnerSeesMessagesAndDecidesAboutOir) {
    std::vector<Message> seen;
    bool handle = true;
    stack_.set_message_handler([&](const Message& m) {
        seen.push_back(m);
        return handle;
    });
    boot();
    inject(":X1917012CN02010D000001;");  // teaches the cache 12C = runner
    inject(":X19DE812CN0343;");
    EXPECT_TRUE(take().empty()) << "the owner answered it";
    ASSERT_EQ(seen.size(), 2u);
    EXPECT_EQ(seen[0].mti, Mti::kVerifiedNodeId);
    EXPECT_FALSE(seen[0].destination.has_value());
    EXPECT_EQ(seen[1].mti, Mti::kSnipRequest);
    EXPECT_EQ(seen[1].source, (NodeHandle{kRunnerId, 0x12C}));
    ASSERT_TRUE(seen[1].destination.has_value());
    EXPECT_EQ(*seen[1].destination, (NodeHandle{kNodeId, 0x343}));
    EXPECT_TRUE(seen[1].payload.empty());
    handle = false;
    inject(":X19DE812CN0343;");
    EXPECT_EQ(take(), (Strings{":X19068343N012C10430DE8;"}));
    // Built-ins answer before the owner and are not passed on.
    seen.clear();
    inject(":X1948812CN0343;");
    EXPECT_EQ(take().size(), 1u);
    EXPECT_TRUE(seen.empty());
}

TEST_F(NodeStackTest, MultiFrameAddressedMessageIsReassembled) {
    std::vector<Message> seen;
    stack_.set_message_handler([&](const Message& m) {
        seen.push_back(m);
        return true;
    });
    boot();
    inject(":X19A0812CN1343044143;");
    inject(":X19A0812CN33434D452053;");
    EXPECT_TRUE(seen.empty());
    inject(":X19A0812CN234300;");
    ASSERT_EQ(seen.size(), 1u);
    EXPECT_EQ(seen[0].mti, Mti::kSnipReply);
    EXPECT_EQ(seen[0].payload, (std::vector<std::uint8_t>{0x04, 'A', 'C', 'M', 'E', ' ', 'S', 0}));
}

TEST_F(NodeStackTest, EventReportWithPayloadIsReassembled) {
    std::vector<Message> seen;
    stack_.set_message_handler([&](const Message& m) {
        seen.push_back(m);
        return true;
    });
    boot();
    inject(":X19F16123N0102030405060708;");
    inject(":X19F15123N1112131415161718;");
    EXPECT_TRUE(seen.empty());
    inject(":X19F14123N2122;");
    ASSERT_EQ(seen.size(), 1u);
    EXPECT_EQ(seen[0].mti, Mti::kEventReportWithPayload);
    EXPECT_EQ(seen[0].payload.size(), 18u);
    EXPECT_EQ(seen[0].payload.back(), 0x22);
    EXPECT_FALSE(seen[0].destination.has_value());
    EXPECT_TRUE(take().empty());
}

// A handler that takes a few global messages: the stack drops the others before decoding them,
// Verify Node ID Global still gets the built-in answer.
TEST_F(NodeStackTest, TheHandlerIsGivenOnlyTheGlobalMessagesItTakes) {
    std::vector<Mti> seen;
    stack_.set_message_handler([&](const Message& m) {
        seen.push_back(m.mti);
        return true;
    });
    stack_.set_global_messages(
        std::vector<Mti>{Mti::kIdentifyProducer, Mti::kEventReportWithPayload});
    EXPECT_TRUE(stack_.takes_global(0x914));
    EXPECT_FALSE(stack_.takes_global(0x547));
    boot();
    inject(":X19547123N0102030405060708;");  // Producer Identified
    inject(":X19914123N0102030405060708;");  // Identify Producer
    inject(":X19F16123N0102030405060708;");
    inject(":X19F14123N2122;");
    inject(":X19490123N;");
    EXPECT_EQ(seen, (std::vector<Mti>{Mti::kIdentifyProducer, Mti::kEventReportWithPayload}));
    EXPECT_EQ(take(), (Strings{":X19170343N050101012200;"}));
    stack_.set_global_messages(std::nullopt);
    inject(":X19547123N0102030405060708;");
    EXPECT_EQ(seen.back(), Mti::kProducerIdentifiedUnknown);
}

// The stacks of one interface share a cache their driver keeps: a restart leaves it alone.
TEST_F(NodeStackTest, ASharedAliasCacheOutlivesARestart) {
    auto shared = std::make_shared<AliasCache>();
    shared->add(0x12C, kRunnerId);
    stack_.share_alias_cache(shared);
    boot();
    EXPECT_EQ(&stack_.alias_cache(), shared.get());
    stack_.restart(net_.now());
    net_.run_for(300ms);
    EXPECT_EQ(&stack_.alias_cache(), shared.get());
    Message verify;
    verify.mti = Mti::kVerifyNodeIdAddressed;
    verify.destination = NodeHandle{kRunnerId, 0};  // resolved through the shared cache
    EXPECT_EQ(stack_.send_message(verify), SendStatus::kSent);
    stack_.share_alias_cache(nullptr);
    EXPECT_EQ(stack_.send_message(verify), SendStatus::kUnknownDestination);
}

TEST_F(NodeStackTest, NothingIsDispatchedOrSentBeforeInitialization) {
    std::vector<Message> seen;
    stack_.set_message_handler([&](const Message& m) {
        seen.push_back(m);
        return true;
    });
    const std::vector<std::uint8_t> payload = {0x20, 0x80};
    EXPECT_FALSE(stack_.send_datagram(0x12C, payload, net_.now()).has_value());
    stack_.start(net_.now());
    net_.run_for(100ms);
    take();
    inject(":X1949012CN;");
    inject(":X1948812CN0343;");
    inject(":X19970123N;");
    EXPECT_TRUE(take().empty()) << "an Inhibited node answers nothing";
    EXPECT_TRUE(seen.empty());
    EXPECT_FALSE(stack_.send_datagram(0x12C, payload, net_.now()).has_value());
}

TEST_F(NodeStackTest, DisabledBuiltinsLeaveTheMessageToTheOwner) {
    std::vector<Mti> seen;
    stack_.set_message_handler([&](const Message& m) {
        seen.push_back(m.mti);
        return true;
    });
    stack_.builtins().verify_node_id = false;
    stack_.builtins().protocol_support = false;
    boot();
    inject(":X1949012CN;");
    inject(":X1948812CN0343;");
    inject(":X1982812CN0343;");
    EXPECT_TRUE(take().empty());
    EXPECT_EQ(seen, (std::vector<Mti>{Mti::kVerifyNodeIdGlobal, Mti::kVerifyNodeIdAddressed,
                                      Mti::kProtocolSupportInquiry}));
    stack_.builtins().reject_unknown_addressed = false;
    stack_.set_message_handler({});
    inject(":X194F912CN0343;");
    EXPECT_TRUE(take().empty()) << "OIR switched off";
}

TEST_F(NodeStackTest, DatagramWithoutHandlerGetsOirOncePerDatagram) {
    boot();
    inject(":X1A34312CN20430000000040;");
    EXPECT_EQ(take(), (Strings{":X19068343N012C10431C48;"}));
    inject(":X1B34312CN2043000000004041;");
    inject(":X1C34312CN0102030405060708;");
    EXPECT_TRUE(take().empty());
    inject(":X1D34312CN01;");
    EXPECT_EQ(take(), (Strings{":X19068343N012C10431C48;"}));
    inject(":X1A34412CN20430000000040;");
    EXPECT_TRUE(take().empty()) << "datagram for another node";
    stack_.builtins().reject_datagrams_without_handler = false;
    inject(":X1A34312CN20430000000040;");
    EXPECT_TRUE(take().empty());
}

TEST_F(NodeStackTest, DatagramHandlerAnswersNowOrLater) {
    std::vector<ReceivedDatagram> got;
    stack_.set_datagram_handler([&](const ReceivedDatagram& d) { got.push_back(d); });
    boot();
    inject(":X1A34312CN20430000000040;");
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].source_alias, 0x12C);
    EXPECT_EQ(got[0].payload, (std::vector<std::uint8_t>{0x20, 0x43, 0, 0, 0, 0, 0x40}));
    EXPECT_TRUE(take().empty()) << "the owner has not answered yet";
    EXPECT_TRUE(stack_.accept_datagram(0x12C, datagram::ok_flags(true)));
    net_.run_for(0ms);
    EXPECT_EQ(take(), (Strings{":X19A28343N012C80;"}));
    inject(":X1A34312CN2099;");
    ASSERT_EQ(got.size(), 2u);
    EXPECT_TRUE(stack_.reject_datagram(0x12C, base::to_u16(base::ErrorCode::kSubcommandUnknown)));
    net_.run_for(0ms);
    EXPECT_EQ(take(), (Strings{":X19A48343N012C1041;"}));
    EXPECT_FALSE(stack_.accept_datagram(0x12C)) << "nothing held";
}

TEST_F(NodeStackTest, AnswersAmeAndDefendsAliasAgainstCid) {
    boot();
    inject(":X10702123N;");
    EXPECT_EQ(take(), (Strings{":X10701343N050101012200;"}));
    inject(":X10702123N050101012200;");
    EXPECT_EQ(take(), (Strings{":X10701343N050101012200;"}));
    inject(":X10702123N050101012201;");
    EXPECT_TRUE(take().empty());
    inject(":X17020343N;");
    EXPECT_EQ(take(), (Strings{":X10700343N;"}));
    EXPECT_EQ(stack_.alias(), 0x343);
    EXPECT_TRUE(stack_.initialized());
}

TEST_F(NodeStackTest, AliasConflictSendsAmrAndTakesNextAliasWithoutNewInitComplete) {
    std::vector<AliasEvent> events;
    int inits = 0;
    stack_.set_alias_event_handler([&](const AliasEvent& e) { events.push_back(e); });
    stack_.set_initialized_handler([&] { ++inits; });
    boot();
    inject(":X19170343N020304050607;");  // another node sends with our alias
    EXPECT_EQ(take(), (Strings{":X10703343N050101012200;", ":X17050BD9N;", ":X16101BD9N;",
                               ":X15012BD9N;", ":X14200BD9N;"}));
    EXPECT_FALSE(stack_.initialized());
    Message m;
    m.mti = Mti::kProducerIdentifiedUnknown;
    m.payload = {5, 1, 1, 1, 0x22, 0, 0, 9};
    EXPECT_EQ(stack_.send_message(m), SendStatus::kQueued) << "inhibited while re-reserving";
    net_.run_for(200ms);
    EXPECT_EQ(take(), (Strings{":X10700BD9N;", ":X10701BD9N050101012200;",
                               ":X19547BD9N0501010122000009;"}));
    EXPECT_TRUE(stack_.initialized());
    EXPECT_EQ(stack_.alias(), 0xBD9);
    EXPECT_EQ(inits, 1) << "no second Initialization Complete by default";
    EXPECT_EQ(stack_.initializations(), 1u);
    ASSERT_GE(events.size(), 3u);
    EXPECT_EQ(events[events.size() - 2], (AliasEvent{AliasEvent::Kind::kAliasLost, 0x343}));
    EXPECT_EQ(events.back(), (AliasEvent{AliasEvent::Kind::kPermitted, 0xBD9}));
    inject(":X1948812CN0BD9;");
    EXPECT_EQ(take(), (Strings{":X19170BD9N050101012200;"}));
    inject(":X1948812CN0343;");
    EXPECT_TRUE(take().empty()) << "the old alias is gone";
}

TEST(NodeStackConfigTest, AliasChangeCanReinitialize) {
    auto config = test::stack_config();
    config.reinitialize_after_alias_change = true;
    LoneStack lone(config);
    lone.start();
    lone.inject(":X19170343N020304050607;", 300ms);
    EXPECT_EQ(lone.seen.back(), ":X19100BD9N050101012200;");
    EXPECT_EQ(lone.stack.initializations(), 2u);
}

TEST_F(NodeStackTest, ConflictDuringReservationRestartsSilently) {
    stack_.start(net_.now());
    net_.run_for(100ms);
    take();
    inject(":X10700343N;");  // someone else reserves 343 meanwhile
    EXPECT_EQ(take(), (Strings{":X17050BD9N;", ":X16101BD9N;", ":X15012BD9N;", ":X14200BD9N;"}));
    net_.run_for(200ms);
    EXPECT_EQ(take(),
              (Strings{":X10700BD9N;", ":X10701BD9N050101012200;", ":X19100BD9N050101012200;"}));
}

TEST_F(NodeStackTest, ReinitializeSendsInitializationCompleteAgain) {
    int inits = 0;
    stack_.set_initialized_handler([&] { ++inits; });
    stack_.reinitialize(net_.now());
    EXPECT_EQ(inits, 0) << "not initialized yet: ignored";
    boot();
    stack_.reinitialize(net_.now());
    net_.run_for(0ms);
    EXPECT_EQ(take(), (Strings{":X19100343N050101012200;"}));
    EXPECT_EQ(inits, 2);
    EXPECT_EQ(stack_.alias(), 0x343);
}

TEST_F(NodeStackTest, RestartRunsStartupAgainWithoutAmr) {
    boot();
    stack_.restart(net_.now());
    EXPECT_FALSE(stack_.initialized());
    net_.run_for(300ms);
    EXPECT_EQ(take(), kStartup) << "a rebooted node starts over from its first alias, no AMR";
    EXPECT_EQ(stack_.initializations(), 2u);
}

TEST_F(NodeStackTest, SendMessageResolvesNodeIdsThroughTheCache) {
    boot();
    Message m;
    m.mti = Mti::kSnipRequest;
    m.destination = NodeHandle{kRunnerId, 0};
    EXPECT_EQ(stack_.send_message(m), SendStatus::kUnknownDestination);
    m.destination.reset();
    EXPECT_EQ(stack_.send_message(m), SendStatus::kUnknownDestination);
    inject(":X1917012CN02010D000001;");
    EXPECT_EQ(stack_.alias_cache().alias_of(kRunnerId), 0x12C);
    EXPECT_EQ(stack_.alias_cache().node_of(0x12C), kRunnerId);
    m.destination = NodeHandle{kRunnerId, 0};
    EXPECT_EQ(stack_.send_message(m), SendStatus::kSent);
    net_.run_for(0ms);
    EXPECT_EQ(take(), (Strings{":X19DE8343N012C;"}));
    Message bad;
    bad.mti = Mti::kVerifiedNodeId;
    bad.payload.assign(9, 0);
    EXPECT_EQ(stack_.send_message(bad), SendStatus::kFramingError);
}

TEST_F(NodeStackTest, QueuesAreBounded) {
    auto config = test::stack_config();
    config.max_pending_messages = 2;
    config.max_output_frames = 10;
    NodeStack small(config);
    Message m;
    m.mti = Mti::kIdentifyEventsGlobal;
    EXPECT_EQ(small.send_message(m), SendStatus::kQueued);
    EXPECT_EQ(small.send_message(m), SendStatus::kQueued);
    EXPECT_EQ(small.send_message(m), SendStatus::kQueueFull);
    small.start(net_.now());  // 4 CID frames, never drained
    const TimePoint t = net_.now() + 200ms;
    small.poll(t);  // RID, AMD, Init Complete, 2 queued messages = 9 frames
    EXPECT_EQ(small.dropped_frames(), 0u);
    for (int i = 0; i < 5; ++i) small.on_frame(gc(":X1949012CN;"), t);
    EXPECT_EQ(small.dropped_frames(), 4u);
    std::vector<CanFrame> out;
    EXPECT_EQ(small.drain(out), 10u);
    EXPECT_FALSE(small.has_output());
}

TEST_F(NodeStackTest, DuplicateNodeIdHaltsWhenConfigured) {
    auto config = test::stack_config();
    config.alias.halt_on_duplicate = true;
    LoneStack lone(config);
    lone.start();
    lone.seen.clear();
    lone.inject(":X10701456N050101012200;");
    EXPECT_EQ(lone.seen, (Strings{":X195B4343N0101000000000201;"}));
    EXPECT_TRUE(lone.stack.halted());
    EXPECT_FALSE(lone.stack.initialized());
    Message m;
    m.mti = Mti::kIdentifyEventsGlobal;
    EXPECT_EQ(lone.stack.send_message(m), SendStatus::kHalted);
    lone.seen.clear();
    lone.inject(":X1949012CN;", 1s);
    EXPECT_TRUE(lone.seen.empty()) << "silent until reset";
    lone.stack.restart(lone.net.now());
    lone.net.run_for(300ms);
    EXPECT_TRUE(lone.stack.initialized());
}

TEST_F(NodeStackTest, IgnoresNonOpenLcbFrames) {
    boot();
    CanFrame standard = gc(":S123N0102;");
    CanFrame remote = gc(":X19490123R;");
    CanFrame too_long = gc(":X1949012CN;");
    too_long.len = 9;
    for (const CanFrame& f : {standard, remote, too_long}) {
        port_.send(f);
        net_.run_for(0ms);
    }
    EXPECT_TRUE(take().empty());
    EXPECT_TRUE(stack_.initialized());
}

}  // namespace
}  // namespace olcb
