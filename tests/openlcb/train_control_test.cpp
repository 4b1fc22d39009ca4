// Train Control payloads on the wire: each command and reply as the GridConnect frames CAN
// carries, decoded back, and the float16 speed with its sign as the direction.
#include "openlcb/train_control.hpp"

#include <gtest/gtest.h>

#include "openlcb/addressed_framing.hpp"
#include "openlcb/gc_test_util.hpp"

namespace olcb::train {
namespace {

using namespace test;

constexpr NodeId kThrottle{0x02'01'0D'00'00'01ull};

Strings frames_of(Mti mti, std::uint16_t src, std::uint16_t dst, std::vector<std::uint8_t> p) {
    std::vector<CanFrame> frames;
    EXPECT_EQ(encode_message(make_message(mti, src, dst, std::move(p)), frames),
              FramingError::kNone);
    return texts(frames);
}

Strings command_frames(const Command& c) {
    return frames_of(Mti::kTractionControlCommand, 0x12C, 0x343, encode(c));
}

Strings reply_frames(const Reply& r) {
    return frames_of(Mti::kTractionControlReply, 0x343, 0x12C, encode(r));
}

Command round_trip(const Command& c) {
    const auto d = decode_command(encode(c));
    EXPECT_TRUE(d.ok()) << d.error;
    return d.value.value_or(Command{});
}

Reply round_trip(const Reply& r) {
    const auto d = decode_reply(encode(r));
    EXPECT_TRUE(d.ok()) << d.error;
    return d.value.value_or(Reply{});
}

TEST(TrainSpeed, SignIsTheDirectionAndZeroKeepsIt) {
    EXPECT_EQ(Speed::of(0.75, true).bits(), 0xBA00);
    EXPECT_EQ(Speed::of(0.75, false).bits(), 0x3A00);
    EXPECT_EQ(Speed::of(0, true).bits(), 0x8000);
    EXPECT_TRUE(Speed::of(0, true).reverse());
    EXPECT_TRUE(Speed::of(0, true).is_zero());
    // The technical note's example: 0x5640 is 100 scale m/s.
    EXPECT_EQ(Speed::of(100, false).bits(), 0x5640);
    EXPECT_EQ(Speed::from_bits(0x5640).magnitude(), 100.0);
    EXPECT_EQ(Speed::of(0.75, true).stopped().bits(), 0x8000);
    EXPECT_EQ(Speed::of(0.75, true).flipped(), Speed::of(0.75, false));
    EXPECT_EQ(Speed::of(0.75, true).to_string(), "0.75 reverse");
    EXPECT_EQ(Speed::of(0, false).to_string(), "0 forward");
    EXPECT_TRUE(Speed::unknown().is_nan());
    EXPECT_EQ(Speed::unknown().to_string(), "NaN (0xFFFF)");
    EXPECT_FALSE(Speed::from_bits(0x7C00).is_nan());  // infinity is a speed, if a silly one
}

TEST(TrainCommand, SetSpeedAndTheForwardedBit) {
    EXPECT_EQ(command_frames({SetSpeed{Speed::of(0.75, true)}}),
              (Strings{":X195EB12CN034300BA00;"}));
    EXPECT_EQ(command_frames({SetSpeed{Speed::of(0.75, true)}, true}),
              (Strings{":X195EB12CN034380BA00;"}));
    const Command c = round_trip({SetSpeed{Speed::of(0.5, false)}, true});
    EXPECT_TRUE(c.forwarded);
    EXPECT_EQ(std::get<SetSpeed>(c.body).speed.bits(), 0x3800);
}

TEST(TrainCommand, FunctionsTakeAThreeByteAddressAndTwoByteValue) {
    EXPECT_EQ(command_frames({SetFunction{0, 1}}), (Strings{":X195EB12CN0343010000000001;"}));
    EXPECT_EQ(command_frames({SetFunction{0x012345, 0xABCD}}),
              (Strings{":X195EB12CN034301012345ABCD;"}));
    EXPECT_EQ(command_frames({QueryFunction{28}}), (Strings{":X195EB12CN03431100001C;"}));
    const Command c = round_trip({SetFunction{0x012345, 0xABCD}});
    EXPECT_EQ(std::get<SetFunction>(c.body).address, 0x012345u);
    EXPECT_EQ(std::get<SetFunction>(c.body).value, 0xABCD);
}

TEST(TrainCommand, ControllerListenerAndManagement) {
    EXPECT_EQ(command_frames({AssignController{0, kThrottle}}),
              (Strings{":X195EB12CN134320010002010D;", ":X195EB12CN2343000001;"}));
    EXPECT_EQ(command_frames({QueryController{}}), (Strings{":X195EB12CN03432003;"}));
    EXPECT_EQ(command_frames({AttachListener{listener_flags::kReverse, kThrottle}}),
              (Strings{":X195EB12CN134330010202010D;", ":X195EB12CN2343000001;"}));
    EXPECT_EQ(command_frames({QueryListeners{}}), (Strings{":X195EB12CN03433003;"}));
    EXPECT_EQ(command_frames({QueryListeners{1}}), (Strings{":X195EB12CN0343300301;"}));
    EXPECT_EQ(command_frames({Reserve{}}), (Strings{":X195EB12CN03434001;"}));
    EXPECT_EQ(command_frames({Release{}}), (Strings{":X195EB12CN03434002;"}));
    EXPECT_EQ(command_frames({Noop{}}), (Strings{":X195EB12CN03434003;"}));
    EXPECT_EQ(command_frames({EmergencyStop{}}), (Strings{":X195EB12CN034302;"}));
    const Command a = round_trip({AttachListener{listener_flags::kLinkF0, kThrottle}});
    EXPECT_EQ(std::get<AttachListener>(a.body).listener, kThrottle);
    EXPECT_EQ(std::get<AttachListener>(a.body).flags, listener_flags::kLinkF0);
    EXPECT_FALSE(std::get<QueryListeners>(round_trip({QueryListeners{}}).body).index);
    EXPECT_EQ(std::get<QueryListeners>(round_trip({QueryListeners{3}}).body).index, 3);
}

TEST(TrainReply, QuerySpeedsReplyIsTheTechnicalNotesTwoFrames) {
    // TrainControlTN §2.4.4: all three speeds 0x4420, from alias 0x123 to alias 0x456.
    const SpeedsReply r{Speed::from_bits(0x4420), 0, Speed::from_bits(0x4420),
                        Speed::from_bits(0x4420)};
    EXPECT_EQ(frames_of(Mti::kTractionControlReply, 0x123, 0x456, encode(Reply{r})),
              (Strings{":X191E9123N1456104420004420;", ":X191E9123N24564420;"}));
    const auto back = std::get<SpeedsReply>(round_trip(Reply{r}));
    EXPECT_EQ(back.set.bits(), 0x4420);
    EXPECT_EQ(back.actual.bits(), 0x4420);
}

TEST(TrainReply, EveryReplyRoundTrips) {
    EXPECT_EQ(reply_frames(FunctionReply{0, 1}), (Strings{":X191E9343N012C110000000001;"}));
    EXPECT_EQ(reply_frames(AssignReply{0}), (Strings{":X191E9343N012C200100;"}));
    EXPECT_EQ(reply_frames(ControllerReply{0, kThrottle}),
              (Strings{":X191E9343N112C20030002010D;", ":X191E9343N212C000001;"}));
    EXPECT_EQ(reply_frames(ReserveReply{1}), (Strings{":X191E9343N012C400101;"}));
    EXPECT_EQ(reply_frames(HeartbeatRequest{3}), (Strings{":X191E9343N012C400303;"}));
    const auto change = std::get<ListenerChangeReply>(
        round_trip(Reply{ListenerChangeReply{ListenerOp::kDetach, kThrottle, error::kNotFound}}));
    EXPECT_EQ(change.op, ListenerOp::kDetach);
    EXPECT_EQ(change.code, 0x1030);
    const auto query = std::get<ListenersReply>(
        round_trip(Reply{ListenersReply{2, ListenerEntry{1, listener_flags::kLinkF0, kThrottle}}}));
    EXPECT_EQ(query.count, 2);
    ASSERT_TRUE(query.entry);
    EXPECT_EQ(query.entry->node, kThrottle);
    EXPECT_FALSE(std::get<ListenersReply>(round_trip(Reply{ListenersReply{0, {}}})).entry);
    EXPECT_EQ(std::get<ControllerReply>(round_trip(Reply{ControllerReply{1, kThrottle}})).flags, 1);
}

TEST(TrainDecode, ShortAndUnknownPayloadsSayWhy) {
    const std::vector<std::uint8_t> short_speed = {0x00, 0x3A};
    EXPECT_EQ(decode_command(short_speed).error, "2 bytes, Set Speed needs 3");
    const std::vector<std::uint8_t> unknown = {0x55};
    EXPECT_EQ(decode_command(unknown).error, "unknown instruction 0x55");
    const std::vector<std::uint8_t> short_reply = {0x10, 0x3A, 0x00, 0x00};
    EXPECT_EQ(decode_reply(short_reply).error, "4 bytes, a Query Speeds Reply needs 8");
    const std::vector<std::uint8_t> bad_sub = {0x20, 0x09};
    EXPECT_EQ(decode_command(bad_sub).error, "unknown Controller Configuration sub-command 0x09");
    EXPECT_FALSE(decode_reply({}).ok());
}

TEST(TrainDescribe, OneLinePerMessage) {
    EXPECT_EQ(describe(Command{SetSpeed{Speed::of(0.75, true)}, true}),
              "Set Speed 0.75 reverse (forwarded)");
    EXPECT_EQ(describe(Reply{ReserveReply{1}}), "Reserve Reply 0x01");
    EXPECT_EQ(describe(Reply{ControllerReply{0, kThrottle}}),
              "Query Controller Reply flags 0x00, controller 02.01.0D.00.00.01");
}

}  // namespace
}  // namespace olcb::train
