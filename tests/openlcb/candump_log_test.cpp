#include "openlcb/candump_log.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace olcb::candump {
namespace {

using std::chrono::microseconds;

CanFrame frame_of(std::uint32_t id, std::initializer_list<std::uint8_t> bytes) {
    CanFrame f;
    f.id = id;
    for (auto b : bytes) f.data[f.len++] = b;
    return f;
}

TEST(CandumpLog, FormatsTheCandumpLFormat) {
    const CanFrame f = frame_of(0x19490343, {0x05, 0x01, 0x01, 0x01, 0x22});
    EXPECT_EQ(format(f, microseconds(1700000000123456), "vcan0"),
              "(1700000000.123456) vcan0 19490343#0501010122");
    EXPECT_EQ(format(frame_of(0x10700343, {}), microseconds(5), "can0"),
              "(0000000000.000005) can0 10700343#");
    CanFrame standard = frame_of(0x123, {0xAB});
    standard.extended = false;
    EXPECT_EQ(format(standard, microseconds(1000000), "vcan0"), "(0000000001.000000) vcan0 123#AB");
    CanFrame remote = frame_of(0x19490343, {});
    remote.remote = true;
    remote.len = 3;
    EXPECT_EQ(format(remote, microseconds(0), "vcan0"), "(0000000000.000000) vcan0 19490343#R3");
}

TEST(CandumpLog, ParsesWhatItFormatsBack) {
    const CanFrame frames[] = {
        frame_of(0x19490343, {}),
        frame_of(0x19170343, {0x05, 0x01, 0x01, 0x01, 0x22, 0x00}),
        frame_of(0x1B12C343, {0x20, 0x53, 0, 0, 0, 0, 0x3C, 0x3F}),
    };
    std::int64_t t = 1700000000000000;
    for (const CanFrame& f : frames) {
        const std::string line = format(f, microseconds(t), "vcan0");
        const auto entry = parse(line + "\n");
        ASSERT_TRUE(entry) << line;
        EXPECT_EQ(entry->frame, f);
        EXPECT_EQ(entry->timestamp, microseconds(t));
        EXPECT_EQ(entry->interface, "vcan0");
        t += 1234567;
    }
}

TEST(CandumpLog, ParsesLowercaseDotSeparatedAndRemoteLines) {
    auto e = parse("(1700000000.000001) can0 1a34312c#20.43.00");
    ASSERT_TRUE(e);
    EXPECT_EQ(e->frame, frame_of(0x1A34312C, {0x20, 0x43, 0x00}));
    e = parse("(1.000000) vcan0 7FF#R");
    ASSERT_TRUE(e);
    EXPECT_FALSE(e->frame.extended);
    EXPECT_TRUE(e->frame.remote);
    EXPECT_EQ(e->frame.id, 0x7FFu);
}

TEST(CandumpLog, RejectsMalformedLines) {
    const char* bad[] = {
        "",
        "vcan0 19490343#",
        "(1700000000.123) vcan0 19490343#",  // micros must have 6 digits
        "(1700000000.123456)vcan0 19490343#",
        "(1700000000.123456) vcan0 1949034#",       // 7 ID digits
        "(1700000000.123456) vcan0 20000004#0000",  // error frame flag in the ID
        "(1700000000.123456) vcan0 800#",           // standard ID above 0x7FF
        "(1700000000.123456) vcan0 19490343#0102030405060708090A",
        "(1700000000.123456) vcan0 19490343#012",  // odd digit count
        "(1700000000.123456) vcan0 19490343#G0",
        "(1700000000.123456) vcan0 19490343##0102",  // CAN FD
        "(1700000000.123456) vcan0 19490343#R9",
        "(1700000000.123456) averyveryverylongname 19490343#",
    };
    for (const char* line : bad) EXPECT_FALSE(parse(line)) << line;
}

}  // namespace
}  // namespace olcb::candump
