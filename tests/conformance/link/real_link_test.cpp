// The real-time link's tap: every frame in or out is seen by the observer before it goes on.
#include "conformance/link/real_link.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "openlcb/transport.hpp"

namespace olcb::conform {
namespace {

// A transport that keeps what is sent and delivers what the test gives it.
struct RecordingTransport final : Transport {
    void send(const CanFrame& frame) override { sent.push_back(frame); }
    void set_handler(FrameHandler h) override { handler = std::move(h); }
    std::vector<CanFrame> sent;
    FrameHandler handler;
};

CanFrame frame(std::uint32_t id) {
    CanFrame f;
    f.id = id;
    return f;
}

TEST(TapTransportTest, ObservesBothDirectionsThenForwards) {
    RecordingTransport inner;
    TapTransport tap(inner);
    std::vector<std::uint32_t> observed;
    std::vector<std::uint32_t> received;
    tap.set_observer([&](const CanFrame& f, TimePoint) { observed.push_back(f.id); });
    tap.set_handler([&](const CanFrame& f) {
        // The observer saw it first.
        EXPECT_FALSE(observed.empty());
        EXPECT_EQ(observed.back(), f.id);
        received.push_back(f.id);
    });
    tap.send(frame(0x19490123));
    ASSERT_EQ(inner.sent.size(), 1u);
    EXPECT_EQ(inner.sent[0].id, 0x19490123u);
    ASSERT_TRUE(inner.handler);
    inner.handler(frame(0x19170456));
    EXPECT_EQ(observed, (std::vector<std::uint32_t>{0x19490123, 0x19170456}));
    EXPECT_EQ(received, std::vector<std::uint32_t>{0x19170456});
}

}  // namespace
}  // namespace olcb::conform
