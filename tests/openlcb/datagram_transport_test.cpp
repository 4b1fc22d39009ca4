#include "openlcb/datagram_transport.hpp"

#include <gtest/gtest.h>

#include <numeric>

#include "base/error_codes.hpp"
#include "openlcb/gc_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using namespace test;
using Status = DatagramOutcome::Status;

std::vector<std::uint8_t> counting(std::size_t n) {
    std::vector<std::uint8_t> v(n);
    std::iota(v.begin(), v.end(), std::uint8_t{1});
    return v;
}

// ---------------- receiver ----------------

DatagramReceiver receiver(DatagramReceiverConfig config = {}) {
    DatagramReceiver r(config);
    r.set_alias(0x343);
    return r;
}

TEST(DatagramReceiver, OnlyFrameDeliveredAndAccepted) {
    auto r = receiver();
    r.on_frame(gc(":X1A34312CN20430000000040;"), t0);
    auto d = r.pop_datagram();
    ASSERT_TRUE(d);
    EXPECT_EQ(d->source_alias, 0x12C);
    EXPECT_EQ(d->dest_alias, 0x343);
    EXPECT_EQ(d->payload, (std::vector<std::uint8_t>{0x20, 0x43, 0, 0, 0, 0, 0x40}));
    EXPECT_FALSE(r.pop_datagram());
    EXPECT_TRUE(drain(r).empty()) << "the owner answers, not the receiver";
    EXPECT_EQ(r.buffers_in_use(), 1u);
    EXPECT_TRUE(r.accept(0x12C, datagram::ok_flags(true)));
    EXPECT_EQ(drain(r), (Strings{":X19A28343N012C80;"}));
    EXPECT_EQ(r.buffers_in_use(), 0u);
}

TEST(DatagramReceiver, OwnerRejectSendsCode) {
    auto r = receiver();
    r.on_frame(gc(":X1A34312CN99;"), t0);
    ASSERT_TRUE(r.pop_datagram());
    EXPECT_TRUE(r.reject(0x12C, base::to_u16(base::ErrorCode::kCommandUnknown)));
    EXPECT_EQ(drain(r), (Strings{":X19A48343N012C1042;"}));
    EXPECT_FALSE(r.reject(0x12C, base::to_u16(base::ErrorCode::kCommandUnknown)))
        << "nothing held any more";
}

TEST(DatagramReceiver, MultiFrameReassembled) {
    auto r = receiver();
    r.on_frame(gc(":X1B34312CN0102030405060708;"), t0);
    r.on_frame(gc(":X1C34312CN090A;"), t0);
    EXPECT_FALSE(r.pop_datagram());
    r.on_frame(gc(":X1D34312CN0B;"), t0);
    auto d = r.pop_datagram();
    ASSERT_TRUE(d);
    EXPECT_EQ(d->payload, counting(11));
    EXPECT_TRUE(drain(r).empty());
}

TEST(DatagramReceiver, FramesForOtherNodesIgnored) {
    auto r = receiver();
    r.on_frame(gc(":X1A34412CN01;"), t0);
    r.on_frame(gc(":X1C34412CN01;"), t0);
    r.on_frame(gc(":X19A2812CN034300;"), t0);
    EXPECT_FALSE(r.pop_datagram());
    EXPECT_TRUE(drain(r).empty());
    DatagramReceiver no_alias;
    no_alias.on_frame(gc(":X1A34312CN01;"), t0);
    EXPECT_FALSE(no_alias.pop_datagram());
}

TEST(DatagramReceiver, MiddleWithoutFirstRejected2041) {
    auto r = receiver();
    r.on_frame(gc(":X1C34312CN0102030405060708;"), t0);
    EXPECT_EQ(drain(r), (Strings{":X19A48343N012C2041;"}));
    // The rest of that datagram is skipped without further rejects.
    r.on_frame(gc(":X1C34312CN0102030405060708;"), t0);
    r.on_frame(gc(":X1D34312CN01;"), t0);
    EXPECT_TRUE(drain(r).empty());
    EXPECT_FALSE(r.pop_datagram());
    EXPECT_TRUE(base::is_temporary(0x2041));
    EXPECT_EQ(0x2041 & 0xFFF0, base::to_u16(base::ErrorCode::kOutOfOrder));
    // And the next datagram from that source works.
    r.on_frame(gc(":X1A34312CN01;"), t0);
    EXPECT_TRUE(r.pop_datagram());
}

TEST(DatagramReceiver, LastWithoutFirstRejected2041) {
    auto r = receiver();
    r.on_frame(gc(":X1D34312CN01;"), t0);
    EXPECT_EQ(drain(r), (Strings{":X19A48343N012C2041;"}));
    EXPECT_EQ(r.rejections(), 1u);
    EXPECT_EQ(r.buffers_in_use(), 0u);
}

TEST(DatagramReceiver, FirstWhileInProgressRejected2042) {
    auto r = receiver();
    r.on_frame(gc(":X1B34312CN0102030405060708;"), t0);
    r.on_frame(gc(":X1B34312CN1112131415161718;"), t0);
    EXPECT_EQ(drain(r), (Strings{":X19A48343N012C2042;"}));
    r.on_frame(gc(":X1D34312CN19;"), t0);
    EXPECT_TRUE(drain(r).empty()) << "one reject per broken datagram";
    EXPECT_FALSE(r.pop_datagram());
    EXPECT_EQ(r.buffers_in_use(), 0u);
}

TEST(DatagramReceiver, OtherSourcesInterleave) {
    auto r = receiver();
    r.on_frame(gc(":X1B34312CN0102030405060708;"), t0);
    r.on_frame(gc(":X1B343555N1112131415161718;"), t0);
    r.on_frame(gc(":X1D343555N19;"), t0);
    r.on_frame(gc(":X1D34312CN09;"), t0);
    EXPECT_TRUE(drain(r).empty());
    auto a = r.pop_datagram();
    auto b = r.pop_datagram();
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->source_alias, 0x555);
    EXPECT_EQ(b->source_alias, 0x12C);
    EXPECT_EQ(b->payload, counting(9));
}

TEST(DatagramReceiver, MoreThan72BytesRejectedPermanently) {
    auto r = receiver();
    r.on_frame(gc(":X1B34312CN0102030405060708;"), t0);
    for (int i = 0; i < 8; ++i) r.on_frame(gc(":X1C34312CN0102030405060708;"), t0);
    EXPECT_TRUE(drain(r).empty()) << "72 bytes are still fine";
    r.on_frame(gc(":X1C34312CN01;"), t0);
    EXPECT_EQ(drain(r), (Strings{":X19A48343N012C1000;"}));
    r.on_frame(gc(":X1C34312CN0102030405060708;"), t0);
    r.on_frame(gc(":X1D34312CN01;"), t0);
    EXPECT_TRUE(drain(r).empty());
    EXPECT_FALSE(r.pop_datagram());
    EXPECT_EQ(r.buffers_in_use(), 0u);
}

TEST(DatagramReceiver, Exactly72BytesOnLastFrameAccepted) {
    auto r = receiver();
    r.on_frame(gc(":X1B34312CN0102030405060708;"), t0);
    for (int i = 0; i < 7; ++i) r.on_frame(gc(":X1C34312CN0102030405060708;"), t0);
    r.on_frame(gc(":X1D34312CN0102030405060708;"), t0);
    auto d = r.pop_datagram();
    ASSERT_TRUE(d);
    EXPECT_EQ(d->payload.size(), 72u);
}

TEST(DatagramReceiver, BufferUnavailableRejected2020) {
    auto r = receiver({.max_buffers = 1});
    r.on_frame(gc(":X1A34312CN01;"), t0);  // delivered, not yet answered: holds the buffer
    ASSERT_TRUE(r.pop_datagram());
    r.on_frame(gc(":X1A343555N02;"), t0);
    EXPECT_EQ(drain(r), (Strings{":X19A48343N05552020;"}));
    r.on_frame(gc(":X1B343555N0102030405060708;"), t0);
    r.on_frame(gc(":X1C343555N0102030405060708;"), t0);
    r.on_frame(gc(":X1D343555N01;"), t0);
    EXPECT_EQ(drain(r), (Strings{":X19A48343N05552020;"})) << "one reject for the whole datagram";
    r.accept(0x12C);
    drain(r);
    r.on_frame(gc(":X1A343555N02;"), t0);
    EXPECT_TRUE(r.pop_datagram()) << "the retry succeeds once the buffer is free";
}

TEST(DatagramReceiver, SameSourceBeforeAnswerIsBusy) {
    auto r = receiver();
    r.on_frame(gc(":X1A34312CN01;"), t0);
    r.on_frame(gc(":X1A34312CN02;"), t0);
    EXPECT_EQ(drain(r), (Strings{":X19A48343N012C2020;"}));
    auto d = r.pop_datagram();
    ASSERT_TRUE(d);
    EXPECT_EQ(d->payload, (std::vector<std::uint8_t>{1}));
}

TEST(DatagramReceiver, ReleaseFreesTheBufferWithoutAnswer) {
    auto r = receiver({.max_buffers = 1});
    r.on_frame(gc(":X1A34312CN01;"), t0);
    ASSERT_TRUE(r.pop_datagram());
    EXPECT_TRUE(r.release(0x12C));
    EXPECT_TRUE(drain(r).empty()) << "released, not answered";
    EXPECT_EQ(r.buffers_in_use(), 0u);
    EXPECT_FALSE(r.release(0x12C)) << "nothing held any more";
    r.on_frame(gc(":X1A34312CN02;"), t0);
    EXPECT_TRUE(r.pop_datagram()) << "the one buffer is free for the next datagram";
    EXPECT_TRUE(drain(r).empty());
}

TEST(DatagramReceiver, StalePartialAbandoned) {
    auto r = receiver({.reassembly_timeout = 3s});
    r.on_frame(gc(":X1B34312CN0102030405060708;"), t0);
    EXPECT_EQ(r.next_deadline(), t0 + 3s);
    r.poll(t0 + 3s);
    EXPECT_EQ(r.buffers_in_use(), 0u);
    EXPECT_EQ(r.timeouts(), 1u);
    EXPECT_TRUE(drain(r).empty());
    EXPECT_FALSE(r.next_deadline());
}

TEST(DatagramReceiver, AliasChangeForgetsState) {
    auto r = receiver();
    r.on_frame(gc(":X1B34312CN0102030405060708;"), t0);
    r.set_alias(0xBD9);
    EXPECT_EQ(r.buffers_in_use(), 0u);
    r.on_frame(gc(":X1DBD912CN01;"), t0);
    EXPECT_EQ(drain(r), (Strings{":X19A48BD9N012C2041;"}));
}

// ---------------- sender ----------------

DatagramSender sender(DatagramSenderConfig config = {}) {
    DatagramSender s(config);
    s.set_alias(0x12C);
    return s;
}

// A sender whose one datagram (payload {1}) to 0x343 went out and waits for the answer.
DatagramSender waiting_sender() {
    auto s = sender();
    s.send(0x343, std::vector<std::uint8_t>{1}, t0);
    drain(s);
    return s;
}

// The outcome the sender reports next: a rejection with error_code.
void expect_rejected(DatagramSender& s, std::uint16_t error_code) {
    auto out = s.pop_outcome();
    ASSERT_TRUE(out);
    EXPECT_EQ(out->status, Status::kRejected);
    EXPECT_EQ(out->error_code, error_code);
}

TEST(DatagramSender, SendsAndReportsAcceptance) {
    auto s = sender();
    const std::uint8_t read[] = {0x20, 0x43, 0, 0, 0, 0, 0x40};
    auto id = s.send(0x343, read, t0);
    ASSERT_TRUE(id);
    EXPECT_EQ(drain(s), (Strings{":X1A34312CN20430000000040;"}));
    EXPECT_EQ(s.next_deadline(), t0 + 3s);
    EXPECT_TRUE(s.on_frame(gc(":X19A28343N012C80;"), t0 + 5ms));
    auto out = s.pop_outcome();
    ASSERT_TRUE(out);
    EXPECT_EQ(out->id, *id);
    EXPECT_EQ(out->status, Status::kAccepted);
    EXPECT_EQ(out->flags, 0x80);
    EXPECT_EQ(out->attempts, 1u);
    EXPECT_EQ(s.queued(), 0u);
    EXPECT_FALSE(s.next_deadline());
}

TEST(DatagramSender, OkWithoutFlagsByteMeansZeroFlags) {
    auto s = sender();
    s.send(0x343, std::vector<std::uint8_t>{1}, t0);
    EXPECT_TRUE(s.on_frame(gc(":X19A28343N012C;"), t0));
    EXPECT_EQ(s.pop_outcome()->flags, 0);
}

TEST(DatagramSender, AnswersForOthersIgnored) {
    auto s = waiting_sender();
    EXPECT_FALSE(s.on_frame(gc(":X19A28343N012D;"), t0));  // to another node
    EXPECT_FALSE(s.on_frame(gc(":X19A28344N012C;"), t0));  // from a node we did not send to
    EXPECT_FALSE(s.on_frame(gc(":X19A28343R012C;"), t0));  // remote frame
    EXPECT_FALSE(s.pop_outcome());
}

TEST(DatagramSender, TemporaryRejectResentThenGivesUpAfterBound) {
    auto s = sender({.max_resends = 2, .resend_delay = 100ms});
    const std::uint8_t data[] = {0x20, 0x43, 0, 0, 0, 0, 0x40};
    s.send(0x343, data, t0);
    EXPECT_EQ(drain(s).size(), 1u);
    for (int resend = 1; resend <= 2; ++resend) {
        const TimePoint now = t0 + resend * 1s;
        EXPECT_TRUE(s.on_frame(gc(":X19A48343N012C2020;"), now));
        EXPECT_TRUE(drain(s).empty()) << "waits resend_delay first";
        EXPECT_EQ(s.next_deadline(), now + 100ms);
        s.poll(now + 100ms);
        EXPECT_EQ(drain(s), (Strings{":X1A34312CN20430000000040;"}));
        EXPECT_FALSE(s.pop_outcome());
    }
    EXPECT_TRUE(s.on_frame(gc(":X19A48343N012C2020;"), t0 + 5s));
    auto out = s.pop_outcome();
    ASSERT_TRUE(out);
    EXPECT_EQ(out->status, Status::kRejected);
    EXPECT_EQ(out->error_code, 0x2020);
    EXPECT_EQ(out->attempts, 3u);
    EXPECT_TRUE(drain(s).empty());
}

TEST(DatagramSender, ImmediateResendWhenNoDelay) {
    auto s = sender({.resend_delay = Duration::zero()});
    s.send(0x343, std::vector<std::uint8_t>{7}, t0);
    drain(s);
    s.on_frame(gc(":X19A48343N012C2041;"), t0);
    EXPECT_EQ(drain(s), (Strings{":X1A34312CN07;"}));
    s.on_frame(gc(":X19A28343N012C00;"), t0);
    EXPECT_EQ(s.pop_outcome()->attempts, 2u);
}

TEST(DatagramSender, PermanentRejectNotResent) {
    auto s = sender();
    s.send(0x343, std::vector<std::uint8_t>{0x20, 0x43}, t0);
    drain(s);
    EXPECT_TRUE(s.on_frame(gc(":X19A48343N012C1042;"), t0 + 1ms));
    s.poll(t0 + 10s);
    EXPECT_TRUE(drain(s).empty());
    auto out = s.pop_outcome();
    ASSERT_TRUE(out);
    EXPECT_EQ(out->status, Status::kRejected);
    EXPECT_EQ(out->error_code, 0x1042);
    EXPECT_EQ(out->attempts, 1u);
}

TEST(DatagramSender, TruncatedRejectReadsAsZeroAndIsNotResent) {
    auto s = waiting_sender();
    EXPECT_TRUE(s.on_frame(gc(":X19A48343N012C;"), t0));
    expect_rejected(s, 0);
}

TEST(DatagramSender, OirForDatagramRejects) {
    auto s = waiting_sender();
    EXPECT_FALSE(s.on_frame(gc(":X19068343N012C10430DE8;"), t0)) << "OIR about another MTI";
    EXPECT_TRUE(s.on_frame(gc(":X19068343N012C10431C48;"), t0));
    expect_rejected(s, 0x1043);
}

TEST(DatagramSender, TimeoutAfterThreeSecondsReported) {
    auto s = waiting_sender();
    s.poll(t0 + 2999ms);
    EXPECT_FALSE(s.pop_outcome());
    s.poll(t0 + 3s);
    auto out = s.pop_outcome();
    ASSERT_TRUE(out);
    EXPECT_EQ(out->status, Status::kTimedOut);
    EXPECT_EQ(out->error_code, base::to_u16(base::ErrorCode::kTimeout));
    EXPECT_TRUE(drain(s).empty()) << "a timeout is not resent";
    EXPECT_FALSE(s.on_frame(gc(":X19A28343N012C;"), t0 + 4s)) << "late OK ignored";
}

TEST(DatagramSender, SecondDatagramToSameDestinationWaitsForFirstOk) {
    auto s = sender();
    auto first = s.send(0x343, std::vector<std::uint8_t>{1}, t0);
    auto second = s.send(0x343, std::vector<std::uint8_t>{2}, t0);
    auto other = s.send(0x555, std::vector<std::uint8_t>{3}, t0);
    ASSERT_TRUE(first && second && other);
    EXPECT_EQ(drain(s), (Strings{":X1A34312CN01;", ":X1A55512CN03;"}));
    s.poll(t0 + 1s);
    EXPECT_TRUE(drain(s).empty());
    s.on_frame(gc(":X19A28343N012C;"), t0 + 1s);
    EXPECT_EQ(drain(s), (Strings{":X1A34312CN02;"}));
    EXPECT_EQ(s.pop_outcome()->id, *first);
    EXPECT_EQ(s.next_deadline(), t0 + 3s) << "the 0x555 one is oldest";
    s.poll(t0 + 3s);
    auto out = s.pop_outcome();
    EXPECT_EQ(out->id, *other);
    EXPECT_EQ(out->status, Status::kTimedOut);
    s.on_frame(gc(":X19A28343N012C;"), t0 + 3s);
    EXPECT_EQ(s.pop_outcome()->id, *second);
}

TEST(DatagramSender, TimeoutStartsNextQueuedDatagram) {
    auto s = sender();
    s.send(0x343, std::vector<std::uint8_t>{1}, t0);
    s.send(0x343, std::vector<std::uint8_t>{2}, t0);
    drain(s);
    s.poll(t0 + 3s);
    EXPECT_EQ(drain(s), (Strings{":X1A34312CN02;"}));
    EXPECT_EQ(s.next_deadline(), t0 + 6s);
}

TEST(DatagramSender, SettleEndsTheWaitAndStartsTheNextDatagram) {
    auto s = sender();
    auto first = s.send(0x343, std::vector<std::uint8_t>{1}, t0);
    auto second = s.send(0x343, std::vector<std::uint8_t>{2}, t0);
    ASSERT_TRUE(first && second);
    drain(s);
    EXPECT_FALSE(s.settle(*second, t0 + 10ms)) << "still queued: nothing to settle";
    EXPECT_TRUE(s.settle(*first, t0 + 10ms));
    EXPECT_EQ(drain(s), (Strings{":X1A34312CN02;"})) << "goes at once, not after 3 s";
    auto out = s.pop_outcome();
    ASSERT_TRUE(out);
    EXPECT_EQ(out->id, *first);
    EXPECT_EQ(out->status, Status::kUnacknowledged);
    EXPECT_EQ(out->error_code, 0);
    EXPECT_EQ(s.next_deadline(), t0 + 10ms + 3s) << "the second waits for its own OK";
    EXPECT_FALSE(s.settle(*first, t0 + 20ms)) << "already ended";
    s.on_frame(gc(":X19A28343N012C;"), t0 + 20ms);
    EXPECT_EQ(s.pop_outcome()->id, *second) << "an OK belongs to the datagram in flight";
}

TEST(DatagramSender, RefusesBadRequests) {
    auto s = sender({.max_queued = 2});
    EXPECT_FALSE(s.send(0x343, counting(73), t0));
    EXPECT_FALSE(s.send(0, counting(1), t0));
    EXPECT_TRUE(s.send(0x343, counting(72), t0));
    EXPECT_TRUE(s.send(0x343, counting(1), t0));
    EXPECT_FALSE(s.send(0x343, counting(1), t0)) << "queue full";
    DatagramSender no_alias;
    EXPECT_FALSE(no_alias.send(0x343, counting(1), t0));
}

TEST(DatagramSender, AbortAllReportsEachDatagram) {
    auto s = sender();
    s.send(0x343, counting(1), t0);
    s.send(0x343, counting(1), t0);
    s.abort_all();
    EXPECT_EQ(s.pop_outcome()->status, Status::kAborted);
    EXPECT_EQ(s.pop_outcome()->status, Status::kAborted);
    EXPECT_FALSE(s.pop_outcome());
    EXPECT_EQ(s.queued(), 0u);
}

TEST(DatagramSender, AbortToDropsOnlyThatDestinationAndFreesIt) {
    auto s = sender();
    const auto a = s.send(0x343, counting(1), t0);
    const auto b = s.send(0x343, counting(1), t0);  // queued behind a
    const auto other = s.send(0x555, counting(1), t0);
    drain(s);
    EXPECT_EQ(s.abort_to(0x343), 2u);
    const auto first = s.pop_outcome();
    const auto second = s.pop_outcome();
    ASSERT_TRUE(first && second);
    EXPECT_EQ(first->id, *a);
    EXPECT_EQ(second->id, *b);
    EXPECT_EQ(first->status, Status::kAborted);
    EXPECT_EQ(second->status, Status::kAborted);
    EXPECT_FALSE(s.pop_outcome());
    EXPECT_EQ(s.queued(), 1u) << "the datagram to 0x555 still waits";
    EXPECT_TRUE(drain(s).empty()) << "nothing queued to 0x343 was started";
    s.send(0x343, std::vector<std::uint8_t>{2}, t0);
    EXPECT_EQ(drain(s), (Strings{":X1A34312CN02;"})) << "the next one goes at once";
    EXPECT_EQ(s.abort_to(0x777), 0u);
    EXPECT_TRUE(other.has_value());
}

TEST(Datagram, SenderAndReceiverTalk) {
    auto s = sender();
    auto r = receiver();
    s.send(0x343, counting(40), t0);
    while (auto f = s.pop_frame()) r.on_frame(*f, t0);
    auto d = r.pop_datagram();
    ASSERT_TRUE(d);
    EXPECT_EQ(d->payload, counting(40));
    r.accept(d->source_alias);
    while (auto f = r.pop_frame()) s.on_frame(*f, t0);
    EXPECT_EQ(s.pop_outcome()->status, Status::kAccepted);
}

}  // namespace
}  // namespace olcb
