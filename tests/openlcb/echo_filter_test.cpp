#include "openlcb/echo_filter.hpp"

#include <gtest/gtest.h>

#include "openlcb/tcp_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using test::numbered_frame;

const TimePoint kT0 = TimePoint{} + 1000s;

TEST(EchoFilter, EchoWithinTheWindowIsRecognisedOncePerSend) {
    EchoFilter filter(16, 2s);
    const auto f = numbered_frame(0x123, 1);
    filter.sent(f, kT0);
    EXPECT_TRUE(filter.is_echo(f, kT0 + 10ms));
    EXPECT_FALSE(filter.is_echo(f, kT0 + 20ms));  // a second copy is another node's
    EXPECT_EQ(filter.echoes(), 1u);
}

TEST(EchoFilter, FrameSentTwiceHasTwoEchoesAndTheThirdCopyIsDelivered) {
    EchoFilter filter(16, 2s);
    const auto f = numbered_frame(0x123, 1);
    filter.sent(f, kT0);
    filter.sent(f, kT0 + 1ms);
    EXPECT_TRUE(filter.is_echo(f, kT0 + 2ms));
    EXPECT_TRUE(filter.is_echo(f, kT0 + 3ms));
    EXPECT_FALSE(filter.is_echo(f, kT0 + 4ms));
    EXPECT_EQ(filter.echoes(), 2u);
}

TEST(EchoFilter, EchoesInterleavedWithOtherFramesAndOutOfOrder) {
    EchoFilter filter(16, 2s);
    filter.sent(numbered_frame(0x123, 1), kT0);
    filter.sent(numbered_frame(0x123, 2), kT0);
    filter.sent(numbered_frame(0x123, 3), kT0);
    EXPECT_FALSE(filter.is_echo(numbered_frame(0x456, 1), kT0 + 1ms));
    EXPECT_TRUE(filter.is_echo(numbered_frame(0x123, 2), kT0 + 1ms));
    EXPECT_TRUE(filter.is_echo(numbered_frame(0x123, 1), kT0 + 1ms));
    EXPECT_FALSE(filter.is_echo(numbered_frame(0x123, 2), kT0 + 1ms));
    EXPECT_TRUE(filter.is_echo(numbered_frame(0x123, 3), kT0 + 1ms));
    EXPECT_EQ(filter.echoes(), 3u);
}

TEST(EchoFilter, SentFrameExpiresAfterTheWindow) {
    EchoFilter filter(16, 2s);
    const auto f = numbered_frame(0x123, 1);
    filter.sent(f, kT0);
    filter.sent(numbered_frame(0x123, 2), kT0 + 1s);
    EXPECT_FALSE(filter.is_echo(f, kT0 + 2s + 1ms));
    EXPECT_TRUE(filter.is_echo(numbered_frame(0x123, 2), kT0 + 3s));  // exactly the window
    EXPECT_EQ(filter.echoes(), 1u);
}

TEST(EchoFilter, RemembersAtMostCapacityFrames) {
    EchoFilter filter(3, 2s);
    for (std::uint32_t i = 1; i <= 5; ++i) filter.sent(numbered_frame(0x123, i), kT0);
    EXPECT_FALSE(filter.is_echo(numbered_frame(0x123, 1), kT0));
    EXPECT_FALSE(filter.is_echo(numbered_frame(0x123, 2), kT0));
    for (std::uint32_t i = 3; i <= 5; ++i) {
        EXPECT_TRUE(filter.is_echo(numbered_frame(0x123, i), kT0)) << i;
    }
}

TEST(EchoFilter, ZeroCapacityRecognisesNothing) {
    EchoFilter filter(0, 2s);
    filter.sent(numbered_frame(0x123, 1), kT0);
    EXPECT_FALSE(filter.is_echo(numbered_frame(0x123, 1), kT0));
}

TEST(EchoFilter, DifferentIdDataLengthOrKindIsNoEcho) {
    EchoFilter filter(16, 2s);
    const auto f = numbered_frame(0x123, 1);
    filter.sent(f, kT0);
    auto other_id = f;
    other_id.id ^= 1;
    auto other_data = f;
    other_data.data[7] ^= 0x80;
    auto shorter = f;
    shorter.len = 7;
    auto standard = f;
    standard.extended = false;
    auto remote = f;
    remote.remote = true;
    for (const auto& g : {other_id, other_data, shorter, standard, remote}) {
        EXPECT_FALSE(filter.is_echo(g, kT0 + 1ms));
    }
    EXPECT_TRUE(filter.is_echo(f, kT0 + 1ms));
}

TEST(EchoFilter, BytesPastTheLengthDoNotMatter) {
    EchoFilter filter(16, 2s);
    CanFrame f;
    f.id = 0x19170123;
    f.len = 2;
    f.data = {1, 2, 3, 4, 5, 6, 7, 8};
    filter.sent(f, kT0);
    CanFrame g = f;
    g.data = {1, 2, 0, 0, 0, 0, 0, 0};
    EXPECT_TRUE(filter.is_echo(g, kT0));
}

TEST(EchoFilter, ClearForgetsEverything) {
    EchoFilter filter(16, 2s);
    filter.sent(numbered_frame(0x123, 1), kT0);
    filter.sent(numbered_frame(0x123, 2), kT0);
    filter.clear();
    EXPECT_FALSE(filter.is_echo(numbered_frame(0x123, 1), kT0));
    EXPECT_FALSE(filter.is_echo(numbered_frame(0x123, 2), kT0));
    filter.sent(numbered_frame(0x123, 1), kT0);
    EXPECT_TRUE(filter.is_echo(numbered_frame(0x123, 1), kT0));
}

TEST(EchoFilter, StaysBoundedUnderManySendsWithoutEchoes) {
    EchoFilter filter(8, 2s);
    for (std::uint32_t i = 0; i < 100000; ++i) {
        filter.sent(numbered_frame(0x123, i), kT0 + std::chrono::microseconds(i));
    }
    // Only the last eight are remembered.
    EXPECT_FALSE(filter.is_echo(numbered_frame(0x123, 99991), kT0 + 1s));
    EXPECT_TRUE(filter.is_echo(numbered_frame(0x123, 99992), kT0 + 1s));
    EXPECT_TRUE(filter.is_echo(numbered_frame(0x123, 99999), kT0 + 1s));
}

}  // namespace
}  // namespace olcb
