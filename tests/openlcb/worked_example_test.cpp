// Cross-cutting, named after no unit: the fact sheet's worked examples (section 10).
// Byte for byte: the pieces of the core reproduce every frame listed.
#include <gtest/gtest.h>

#include <string>

#include "openlcb/addressed_framing.hpp"
#include "openlcb/alias_allocator.hpp"
#include "openlcb/alias_generator.hpp"
#include "openlcb/datagram_transport.hpp"
#include "openlcb/gc_test_util.hpp"
#include "openlcb/pip.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;

Strings encode(Mti mti, std::uint16_t src, std::optional<std::uint16_t> dst,
               std::vector<std::uint8_t> payload) {
    const Message m = test::make_message(mti, src, dst, std::move(payload));
    std::vector<CanFrame> frames;
    EXPECT_EQ(encode_message(m, frames), FramingError::kNone);
    return texts(frames);
}

std::vector<std::uint8_t> bytes_of(std::string_view s) {
    return {s.begin(), s.end()};
}

TEST(WorkedExample, AliasArithmetic) {
    AliasGenerator gen(kNodeId);
    EXPECT_EQ(gen.next(), 0x343);
    EXPECT_EQ(gen.next(), 0xBD9);
    EXPECT_EQ(gen.next(), 0x60D);
    EXPECT_EQ(gen.next(), 0xC82);
    EXPECT_EQ(AliasGenerator(kRunnerId).next(), 0x12C);
}

TEST(WorkedExample, StartupFrames) {
    AliasAllocator alloc(kNodeId);
    alloc.start(t0);
    EXPECT_EQ(drain(alloc),
              (Strings{":X17050343N;", ":X16101343N;", ":X15012343N;", ":X14200343N;"}));
    alloc.poll(t0 + 199ms);
    EXPECT_TRUE(drain(alloc).empty());
    alloc.poll(t0 + 200ms);
    EXPECT_EQ(drain(alloc), (Strings{":X10700343N;", ":X10701343N050101012200;"}));
    ASSERT_EQ(alloc.pop_event()->kind, AliasEvent::Kind::kPermitted);
    // The caller now sends Initialization Complete, then its events.
    const auto id = kNodeId.to_bytes();
    EXPECT_EQ(
        encode(Mti::kInitializationComplete, alloc.alias(), std::nullopt, {id.begin(), id.end()}),
        (Strings{":X19100343N050101012200;"}));
    const auto ev = EventId(kNodeId, 1).to_bytes();
    EXPECT_EQ(encode(Mti::kConsumerIdentifiedUnknown, alloc.alias(), std::nullopt,
                     {ev.begin(), ev.end()}),
              (Strings{":X194C7343N0501010122000001;"}));
}

TEST(WorkedExample, DiscoveryAndPip) {
    MessageAssembler as;
    auto verify = as.on_frame(gc(":X1949012CN;"), t0);
    ASSERT_TRUE(verify);
    EXPECT_EQ(verify->mti, Mti::kVerifyNodeIdGlobal);
    const auto id = kNodeId.to_bytes();
    EXPECT_EQ(encode(Mti::kVerifiedNodeId, 0x343, std::nullopt, {id.begin(), id.end()}),
              (Strings{":X19170343N050101012200;"}));

    auto psi = as.on_frame(gc(":X1982812CN0343;"), t0);
    ASSERT_TRUE(psi);
    EXPECT_EQ(psi->mti, Mti::kProtocolSupportInquiry);
    EXPECT_EQ(psi->destination->alias, 0x343);
    const auto flags = ProtocolSet{Protocol::kDatagram,      Protocol::kMemoryConfiguration,
                                   Protocol::kEventExchange, Protocol::kAcdi,
                                   Protocol::kSnip,          Protocol::kCdi}
                           .encode();
    EXPECT_EQ(
        encode(Mti::kProtocolSupportReply, 0x343, psi->source.alias, {flags.begin(), flags.end()}),
        (Strings{":X19668343N012C545800000000;"}));
}

TEST(WorkedExample, SnipReplyFrames) {
    MessageAssembler as;
    auto req = as.on_frame(gc(":X19DE812CN0343;"), t0);
    ASSERT_TRUE(req);
    EXPECT_EQ(req->mti, Mti::kSnipRequest);

    using namespace std::string_literals;
    const auto payload = bytes_of("\x04"s + "ACME Sim\0CDI Node\0"s + "1.0\0"s + "0.3.1\0"s +
                                  "\x02"s + "Test node\0"s + "Bench\0"s);
    ASSERT_EQ(payload.size(), 46u);
    const Strings expected = {
        ":X19A08343N112C0441434D4520;", ":X19A08343N312C53696D004344;",
        ":X19A08343N312C49204E6F6465;", ":X19A08343N312C00312E300030;",
        ":X19A08343N312C2E332E310002;", ":X19A08343N312C54657374206E;",
        ":X19A08343N312C6F6465004265;", ":X19A08343N212C6E636800;",
    };
    EXPECT_EQ(encode(Mti::kSnipReply, 0x343, req->source.alias, payload), expected);

    // And the runner's side reassembles exactly that payload.
    std::optional<Message> reply;
    for (const auto& f : expected) reply = as.on_frame(gc(f), t0);
    ASSERT_TRUE(reply);
    EXPECT_EQ(reply->mti, Mti::kSnipReply);
    EXPECT_EQ(reply->source.alias, 0x343);
    EXPECT_EQ(reply->destination->alias, 0x12C);
    EXPECT_EQ(reply->payload, payload);
}

TEST(WorkedExample, MemoryConfigReadDatagrams) {
    DatagramReceiver node_rx;
    node_rx.set_alias(0x343);
    DatagramSender node_tx;
    node_tx.set_alias(0x343);
    DatagramSender runner_tx;
    runner_tx.set_alias(0x12C);
    DatagramReceiver runner_rx;
    runner_rx.set_alias(0x12C);

    // Runner -> node: read 64 bytes of space 0xFF at 0.
    const std::uint8_t read[] = {0x20, 0x43, 0, 0, 0, 0, 0x40};
    runner_tx.send(0x343, read, t0);
    EXPECT_EQ(drain(runner_tx), (Strings{":X1A34312CN20430000000040;"}));
    node_rx.on_frame(gc(":X1A34312CN20430000000040;"), t0);
    auto request = node_rx.pop_datagram();
    ASSERT_TRUE(request);
    EXPECT_EQ(request->payload, std::vector<std::uint8_t>(std::begin(read), std::end(read)));
    node_rx.accept(request->source_alias, datagram::ok_flags(true));
    EXPECT_EQ(drain(node_rx), (Strings{":X19A28343N012C80;"}));
    EXPECT_TRUE(runner_tx.on_frame(gc(":X19A28343N012C80;"), t0));
    auto acked = runner_tx.pop_outcome();
    ASSERT_TRUE(acked);
    EXPECT_TRUE(datagram::is_reply_pending(acked->flags));

    // Node -> runner: the 70-byte reply.
    auto reply = std::vector<std::uint8_t>{0x20, 0x53, 0, 0, 0, 0};
    const auto text =
        bytes_of("<?xml version=\"1.0\"?>\n<cdi xmlns:xsi=\"http://www.w3.org/2001/XML");
    reply.insert(reply.end(), text.begin(), text.end());
    ASSERT_EQ(reply.size(), 70u);
    node_tx.send(0x12C, reply, t0);
    const Strings expected = {
        ":X1B12C343N2053000000003C3F;", ":X1C12C343N786D6C2076657273;",
        ":X1C12C343N696F6E3D22312E30;", ":X1C12C343N223F3E0A3C636469;",
        ":X1C12C343N20786D6C6E733A78;", ":X1C12C343N73693D2268747470;",
        ":X1C12C343N3A2F2F7777772E77;", ":X1C12C343N332E6F72672F3230;",
        ":X1D12C343N30312F584D4C;",
    };
    EXPECT_EQ(drain(node_tx), expected);
    for (const auto& f : expected) runner_rx.on_frame(gc(f), t0);
    auto got = runner_rx.pop_datagram();
    ASSERT_TRUE(got);
    EXPECT_EQ(got->payload, reply);
    runner_rx.accept(got->source_alias, 0);
    EXPECT_EQ(drain(runner_rx), (Strings{":X19A2812CN034300;"}));
    EXPECT_TRUE(node_tx.on_frame(gc(":X19A2812CN034300;"), t0));
    EXPECT_EQ(node_tx.pop_outcome()->status, DatagramOutcome::Status::kAccepted);
}

TEST(WorkedExample, AcdiReadRequestDecodes) {
    DatagramReceiver rx;
    rx.set_alias(0x343);
    rx.on_frame(gc(":X1A34312CN204000000000FC40;"), t0);
    auto d = rx.pop_datagram();
    ASSERT_TRUE(d);
    EXPECT_EQ(d->payload, (std::vector<std::uint8_t>{0x20, 0x40, 0, 0, 0, 0, 0xFC, 0x40}));
}

}  // namespace
}  // namespace olcb
