#include "memory/memory_config_codec.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "memory/memory_test_util.hpp"

namespace olcb::memory {
namespace {

using test::hex;

template <typename M>
M decode_as(const std::vector<std::uint8_t>& payload) {
    const DecodeResult result = decode(payload);
    EXPECT_TRUE(result.ok()) << to_string(result.error);
    const M* message = std::get_if<M>(&result.message);
    EXPECT_NE(message, nullptr) << "decoded as alternative " << result.message.index();
    return message ? *message : M{};
}

DecodeError decode_error(std::string_view payload) {
    return decode(hex(payload)).error;
}

// ---- golden bytes of the fact sheet --------------------------------------------------------

TEST(MemoryConfigCodec, ReadCdiShortForm) {
    EXPECT_EQ(encode(Read{Space::kCdi, 0, 64}), hex("20 43 00000000 40"));
    const auto read = decode_as<Read>(hex("20 43 00000000 40"));
    EXPECT_EQ(read.space, Space::kCdi);
    EXPECT_EQ(read.address, 0u);
    EXPECT_EQ(read.count, 64);
    EXPECT_EQ(read.form, SpaceForm::kShort);
}

TEST(MemoryConfigCodec, ReadAcdiByte6Form) {
    EXPECT_EQ(encode(Read{Space::kAcdiManufacturer, 0, 64}), hex("20 40 00000000 FC 40"));
    // Even when asked for the short form, a space below 0xFD must use byte 6.
    EXPECT_EQ(encode(Read{Space::kAcdiManufacturer, 0, 64, SpaceForm::kShort}),
              hex("20 40 00000000 FC 40"));
    const auto read = decode_as<Read>(hex("20 40 00000000 FC 40"));
    EXPECT_EQ(read.space, Space::kAcdiManufacturer);
    EXPECT_EQ(read.count, 64);
    EXPECT_EQ(read.form, SpaceForm::kByte6);
}

TEST(MemoryConfigCodec, Byte6FormForAHighSpaceIsKeptSoTheServerCanEchoIt) {
    const auto read = decode_as<Read>(hex("20 40 00000040 FF 40"));
    EXPECT_EQ(read.space, Space::kCdi);
    EXPECT_EQ(read.address, 0x40u);
    EXPECT_EQ(read.form, SpaceForm::kByte6);
    const ReadReply reply{read.space, read.address, {1, 2}, read.form};
    EXPECT_EQ(encode(reply), hex("20 50 00000040 FF 0102"));
}

TEST(MemoryConfigCodec, ReadReplyOk) {
    const auto payload = hex("20 53 00000000 3C3F786D6C");
    const auto reply = decode_as<ReadReply>(payload);
    EXPECT_EQ(reply.space, Space::kCdi);
    EXPECT_EQ(reply.data, hex("3C3F786D6C"));
    EXPECT_EQ(encode(reply), payload);
}

TEST(MemoryConfigCodec, ReadReplyFailOutOfBounds) {
    const auto fail = decode_as<ReadReplyFail>(hex("20 5B 000003E8 10 82"));
    EXPECT_EQ(fail.space, Space::kCdi);
    EXPECT_EQ(fail.address, 1000u);
    EXPECT_EQ(fail.error, ErrorCode::kOutOfBounds);
    EXPECT_EQ(fail.text, "");
    EXPECT_EQ(encode(ReadReplyFail{Space::kCdi, 1000, ErrorCode::kOutOfBounds, ""}),
              hex("20 5B 000003E8 1082"));
}

TEST(MemoryConfigCodec, FailReplyTextIsNulTerminated) {
    const WriteReplyFail fail{Space::kAcdiUser, 3, ErrorCode::kReadOnly, "ro", SpaceForm::kByte6};
    EXPECT_EQ(encode(fail), hex("20 18 00000003 FB 1083 726F00"));
    EXPECT_EQ(decode_as<WriteReplyFail>(encode(fail)), fail);
}

TEST(MemoryConfigCodec, GetConfigOptionsAndReply) {
    EXPECT_EQ(encode(GetConfigOptions{}), hex("20 80"));
    decode_as<GetConfigOptions>(hex("20 80"));

    const ConfigOptionsReply reply{available_commands::kAcdiManufacturerRead |
                                       available_commands::kAcdiUserRead |
                                       available_commands::kAcdiUserWrite,
                                   write_lengths::kRecommended, Space::kCdi, Space::kAcdiUser, ""};
    EXPECT_EQ(encode(reply), hex("20 82 0E00 E2 FF FB"));
    const auto decoded = decode_as<ConfigOptionsReply>(hex("20 82 0E00 E2 FF FB"));
    EXPECT_EQ(decoded.available_commands, 0x0E00);
    EXPECT_EQ(decoded.write_lengths, 0xE2);
    EXPECT_EQ(decoded.highest_space, Space::kCdi);
    EXPECT_EQ(decoded.lowest_space, Space::kAcdiUser);

    const auto named = decode_as<ConfigOptionsReply>(hex("20 82 0E00 E2 FF FB 53696D00"));
    EXPECT_EQ(named.name, "Sim");
}

TEST(MemoryConfigCodec, ConfigOptionsReplyWithoutLowestSpaceReadsItAsZero) {
    const auto decoded = decode_as<ConfigOptionsReply>(hex("20 82 0E00 E2 FF"));
    EXPECT_EQ(decoded.lowest_space, Space{0});
    EXPECT_EQ(decode_error("20 82 0E00 E2"), DecodeError::kTruncated);
}

TEST(MemoryConfigCodec, SpaceInfoPresentReadOnly) {
    const SpaceInfoReply info{Space::kCdi, 999, true, std::nullopt, ""};
    EXPECT_EQ(encode(info), hex("20 87 FF 000003E7 01"));
    const auto decoded = decode_as<SpaceInfoReply>(hex("20 87 FF 000003E7 01"));
    EXPECT_EQ(decoded.space, Space::kCdi);
    EXPECT_EQ(decoded.highest_address, 999u);
    EXPECT_TRUE(decoded.read_only);
    EXPECT_FALSE(decoded.lowest_address.has_value());
}

TEST(MemoryConfigCodec, SpaceInfoWithLowAddressAndDescription) {
    const SpaceInfoReply info{Space::kConfig, 0x1FF, false, 0x100u, "config"};
    const auto payload = hex("20 87 FD 000001FF 02 00000100 636F6E66696700");
    EXPECT_EQ(encode(info), payload);
    EXPECT_EQ(decode_as<SpaceInfoReply>(payload), info);
    EXPECT_EQ(decode_error("20 87 FD 000001FF 02 0000"), DecodeError::kTruncated);
}

TEST(MemoryConfigCodec, SpaceInfoWithoutFlagsByteReadsFlagsAsZero) {
    const auto decoded = decode_as<SpaceInfoReply>(hex("20 87 FD 000001FF"));
    EXPECT_FALSE(decoded.read_only);
    EXPECT_FALSE(decoded.lowest_address.has_value());
}

TEST(MemoryConfigCodec, SpaceInfoNotPresent) {
    EXPECT_EQ(encode(SpaceInfoNotPresent{Space::kAcdiManufacturer}), hex("20 86 FC"));
    EXPECT_EQ(decode_as<SpaceInfoNotPresent>(hex("20 86 FC")).space, Space::kAcdiManufacturer);
    // The rest of a not-present reply is optional and ignored.
    EXPECT_EQ(decode_as<SpaceInfoNotPresent>(hex("20 86 FC 00000000 00")).space,
              Space::kAcdiManufacturer);
    EXPECT_EQ(encode(GetSpaceInfo{Space::kCdi}), hex("20 84 FF"));
}

TEST(MemoryConfigCodec, WriteAndWriteUnderMaskGolden) {
    EXPECT_EQ(encode(Write{Space::kConfig, 0x10, {0xAA, 0xBB}}), hex("20 01 00000010 AABB"));
    EXPECT_EQ(encode(Write{Space::kAcdiUser, 1, {0x41}}), hex("20 00 00000001 FB 41"));
    EXPECT_EQ(encode(WriteUnderMask{Space::kConfig, 4, {{0x0F, 0x05}, {0xF0, 0xA0}}}),
              hex("20 09 00000004 0F05 F0A0"));
    EXPECT_EQ(encode(WriteReply{Space::kConfig, 0x10}), hex("20 11 00000010"));
}

TEST(MemoryConfigCodec, OtherCommandsGolden) {
    EXPECT_EQ(encode(Lock{0x02010D000001}), hex("20 88 02010D000001"));
    EXPECT_EQ(encode(Lock{0}), hex("20 88 000000000000"));
    EXPECT_EQ(encode(LockReply{0x02010D000001}), hex("20 8A 02010D000001"));
    EXPECT_EQ(encode(GetUniqueId{2}), hex("20 8C 02"));
    EXPECT_EQ(encode(UniqueIdReply{{0x0501010122000001}}), hex("20 8D 0501010122000001"));
    EXPECT_EQ(encode(Unfreeze{Space::kFirmware}), hex("20 A0 EF"));
    EXPECT_EQ(encode(Freeze{Space::kFirmware}), hex("20 A1 EF"));
    EXPECT_EQ(encode(UpdateComplete{}), hex("20 A8"));
    EXPECT_EQ(encode(ResetReboot{}), hex("20 A9"));
    EXPECT_EQ(encode(FactoryReset{0x050101012200}), hex("20 AA 050101012200"));
    EXPECT_EQ(encode(EnterBootloader{}), hex("20 AB"));
    // Only 48 bits of a node ID exist on the wire.
    EXPECT_EQ(encode(Lock{0xFF'050101012200}), hex("20 88 050101012200"));
}

TEST(MemoryConfigCodec, StreamGolden) {
    EXPECT_EQ(encode(ReadStream{Space::kCdi, 0, 0xFF, 0x05, 0}),
              hex("20 63 00000000 FF 05 00000000"));
    EXPECT_EQ(encode(ReadStreamReply{Space::kCdi, 0, 0x07, 0x05, 1000}),
              hex("20 73 00000000 07 05 000003E8"));
    EXPECT_EQ(encode(WriteStream{Space::kConfig, 8, 0x03}), hex("20 21 00000008 03"));
    EXPECT_EQ(encode(WriteStreamReply{Space::kConfig, 8, 0x03, 0x09}), hex("20 31 00000008 0309"));
    EXPECT_EQ(encode(WriteStreamReplyFail{Space::kConfig, 8, ErrorCode::kSubcommandUnknown, ""}),
              hex("20 39 00000008 1041"));
    EXPECT_EQ(encode(ReadStreamReplyFail{Space::kAcdiUser, 8, ErrorCode::kSubcommandUnknown, ""}),
              hex("20 78 00000008 FB 1041"));
}

// ---- decode error paths --------------------------------------------------------------------

TEST(MemoryConfigCodecErrors, EnvelopeErrors) {
    EXPECT_EQ(decode({}).error, DecodeError::kEmpty);
    EXPECT_EQ(decode_error("21 43"), DecodeError::kNotMemoryConfig);
    EXPECT_EQ(decode_error("20"), DecodeError::kTruncated);
    std::vector<std::uint8_t> too_long(73, 0);
    too_long[0] = 0x20;
    too_long[1] = 0x01;
    EXPECT_EQ(decode(too_long).error, DecodeError::kTooLong);
}

TEST(MemoryConfigCodecErrors, TruncatedHeader) {
    EXPECT_EQ(decode_error("20 43"), DecodeError::kTruncated);
    EXPECT_EQ(decode_error("20 43 000000"), DecodeError::kTruncated);
    EXPECT_EQ(decode_error("20 53 00"), DecodeError::kTruncated);
    EXPECT_EQ(decode_error("20 43 00000000"), DecodeError::kTruncated);  // no count
}

TEST(MemoryConfigCodecErrors, MissingSpaceByte) {
    EXPECT_EQ(decode_error("20 40 00000000"), DecodeError::kMissingSpace);
    EXPECT_EQ(decode_error("20 00 00000000"), DecodeError::kMissingSpace);
    EXPECT_EQ(decode_error("20 58 00000000"), DecodeError::kMissingSpace);
    EXPECT_EQ(decode_error("20 84"), DecodeError::kMissingSpace);
    EXPECT_EQ(decode_error("20 86"), DecodeError::kMissingSpace);
    EXPECT_EQ(decode_error("20 87"), DecodeError::kMissingSpace);
    EXPECT_EQ(decode_error("20 A0"), DecodeError::kMissingSpace);
    EXPECT_EQ(decode_error("20 A1"), DecodeError::kMissingSpace);
}

TEST(MemoryConfigCodecErrors, ReadCountOutOfRangeIsRejectedWith1080) {
    EXPECT_EQ(decode_error("20 43 00000000 00"), DecodeError::kBadCount);
    EXPECT_EQ(decode_error("20 43 00000000 41"), DecodeError::kBadCount);  // 65
    EXPECT_EQ(decode_error("20 40 00000000 FC 7F"), DecodeError::kBadCount);
    EXPECT_EQ(reject_code(DecodeError::kBadCount), ErrorCode::kInvalidArguments);
    // Bit 7 is reserved and ignored: 0x80 is a count of 0, 0xC0 a count of 64.
    EXPECT_EQ(decode_error("20 43 00000000 80"), DecodeError::kBadCount);
    EXPECT_EQ(decode_as<Read>(hex("20 43 00000000 C0")).count, 64);
}

TEST(MemoryConfigCodecErrors, WriteWithoutDataOrWithTooMuch) {
    EXPECT_EQ(decode_error("20 01 00000000"), DecodeError::kNoData);
    EXPECT_EQ(decode_error("20 00 00000000 FB"), DecodeError::kNoData);
    EXPECT_EQ(decode_error("20 53 00000000"), DecodeError::kNoData);
    auto payload = hex("20 01 00000000");
    payload.resize(payload.size() + 65, 0x11);
    EXPECT_EQ(decode(payload).error, DecodeError::kTooMuchData);
    payload.pop_back();
    EXPECT_EQ(decode_as<Write>(payload).data.size(), 64u);
}

TEST(MemoryConfigCodecErrors, WriteUnderMaskNeedsWholePairs) {
    EXPECT_EQ(decode_error("20 09 00000000 0F"), DecodeError::kOddMaskData);
    EXPECT_EQ(decode_error("20 09 00000000 0F05 F0"), DecodeError::kOddMaskData);
    EXPECT_EQ(decode_error("20 09 00000000"), DecodeError::kNoData);
    EXPECT_EQ(reject_code(DecodeError::kOddMaskData), ErrorCode::kInvalidArguments);
}

TEST(MemoryConfigCodecErrors, FailReplyMissingErrorBitsReadAsZero) {
    // Decision: like OIR/TDE/Datagram Rejected, missing error bytes are 0 ("no information").
    EXPECT_EQ(decode_as<ReadReplyFail>(hex("20 5B 00000000")).error, ErrorCode::kNone);
    EXPECT_EQ(decode_as<ReadReplyFail>(hex("20 5B 00000000 10")).error, ErrorCode::kPermanent);
    EXPECT_EQ(decode_as<WriteReplyFail>(hex("20 18 00000000 FB")).error, ErrorCode::kNone);
}

TEST(MemoryConfigCodecErrors, UnknownCommands) {
    for (const char* payload :
         {"20 81", "20 83", "20 85", "20 89", "20 8B", "20 8E", "20 A2", "20 FF",
          "20 44 00000000 00", "20 48 00000000 FF 01", "20 68 00000000", "20 28 00000000"}) {
        EXPECT_EQ(decode_error(payload), DecodeError::kUnknownCommand) << payload;
    }
    EXPECT_EQ(reject_code(DecodeError::kUnknownCommand), ErrorCode::kSubcommandUnknown);
}

TEST(MemoryConfigCodecErrors, TruncatedFixedFields) {
    EXPECT_EQ(decode_error("20 88 0201"), DecodeError::kTruncated);
    EXPECT_EQ(decode_error("20 8A"), DecodeError::kTruncated);
    EXPECT_EQ(decode_error("20 AA 05010101"), DecodeError::kTruncated);
    EXPECT_EQ(decode_error("20 8C"), DecodeError::kTruncated);
    EXPECT_EQ(decode_error("20 87 FF 0000"), DecodeError::kTruncated);
    EXPECT_EQ(decode_error("20 63 00000000 FF 05 0000"), DecodeError::kTruncated);
    EXPECT_EQ(decode_error("20 73 00000000 07"), DecodeError::kTruncated);
    EXPECT_EQ(decode_error("20 21 00000000"), DecodeError::kTruncated);
    EXPECT_EQ(decode_error("20 31 00000000 03"), DecodeError::kTruncated);
}

TEST(MemoryConfigCodecErrors, UniqueIdReplyLength) {
    EXPECT_EQ(decode_error("20 8D 0102030405"), DecodeError::kBadLength);
    std::vector<std::uint8_t> eight = hex("20 8D");
    eight.resize(2 + 8 * 8, 0x01);
    EXPECT_EQ(decode(eight).error, DecodeError::kBadCount);
    EXPECT_TRUE(decode_as<UniqueIdReply>(hex("20 8D")).event_ids.empty());
    // Only 3 bits carry the requested count.
    EXPECT_EQ(decode_as<GetUniqueId>(hex("20 8C FA")).count, 2);
}

TEST(MemoryConfigCodecErrors, TrailingBytesAfterFixedMessagesAreIgnored) {
    EXPECT_EQ(decode_as<Read>(hex("20 43 00000000 40 99")).count, 64);
    decode_as<ResetReboot>(hex("20 A9 00"));
}

// ---- round trips ---------------------------------------------------------------------------

std::vector<Message> every_message(SpaceForm form, Space space) {
    const std::vector<std::uint8_t> data{0x01, 0x02, 0x03};
    return {
        Read{space, 0x12345678, 64, form},
        Read{space, 0, 1, form},
        ReadReply{space, 0x40, data, form},
        ReadReply{space, 0x40, std::vector<std::uint8_t>(64, 0xEE), form},
        ReadReplyFail{space, 0x7D, ErrorCode::kOutOfBounds, "", form},
        ReadReplyFail{space, 0x7D, ErrorCode::kOutOfBounds, "past the end", form},
        Write{space, 0xFFFFFFFF, data, form},
        WriteUnderMask{space, 2, {{0x01, 0x01}, {0xFF, 0x00}}, form},
        WriteReply{space, 9, form},
        WriteReplyFail{space, 9, ErrorCode::kReadOnly, "read-only", form},
        ReadStream{space, 4, 0xFF, 0x02, 0, form},
        ReadStreamReply{space, 4, 0x11, 0x02, 100, form},
        ReadStreamReplyFail{space, 4, ErrorCode::kSubcommandUnknown, "", form},
        WriteStream{space, 4, 0x11, form},
        WriteStreamReply{space, 4, 0x11, 0x22, form},
        WriteStreamReplyFail{space, 4, ErrorCode::kBufferUnavailable, "busy", form},
        GetConfigOptions{},
        ConfigOptionsReply{0xEE00, 0xE3, Space::kCdi, Space::kAcdiUser, "simnode"},
        ConfigOptionsReply{0x0000, 0xE2, Space::kCdi, Space::kConfig, ""},
        GetSpaceInfo{space},
        SpaceInfoReply{space, 0xFFFF, true, std::nullopt, ""},
        SpaceInfoReply{space, 0xFFFF, false, 0x10u, "described"},
        SpaceInfoNotPresent{space},
        Lock{0x02010D000001},
        LockReply{0},
        GetUniqueId{7},
        UniqueIdReply{{1, 0xFFFFFFFFFFFFFFFF, 0x0501010122000001}},
        Freeze{space},
        Unfreeze{space},
        UpdateComplete{},
        ResetReboot{},
        FactoryReset{0x050101012200},
        EnterBootloader{},
    };
}

TEST(MemoryConfigCodecRoundTrip, EveryMessageInBothForms) {
    for (const auto& [form, space] :
         {std::pair{SpaceForm::kShort, Space::kCdi}, std::pair{SpaceForm::kShort, Space::kConfig},
          std::pair{SpaceForm::kByte6, Space::kAll}, std::pair{SpaceForm::kByte6, Space::kCdi},
          std::pair{SpaceForm::kByte6, Space::kAcdiManufacturer},
          std::pair{SpaceForm::kByte6, Space{0x00}}}) {
        for (const Message& message : every_message(form, space)) {
            const auto payload = encode(message);
            SCOPED_TRACE(describe(payload));
            EXPECT_LE(payload.size(), kMaxDatagram);
            const DecodeResult result = decode(payload);
            ASSERT_TRUE(result.ok()) << to_string(result.error);
            EXPECT_EQ(result.message, message);
        }
    }
}

TEST(MemoryConfigCodecRoundTrip, AutoFormPicksShortOnlyForHighSpaces) {
    for (const Space space : {Space::kConfig, Space::kAll, Space::kCdi}) {
        const auto payload = encode(Read{space, 0, 8});
        EXPECT_EQ(payload.size(), 7u);
        EXPECT_EQ(decode_as<Read>(payload).form, SpaceForm::kShort);
    }
    const auto payload = encode(Read{Space::kAcdiUser, 0, 8});
    EXPECT_EQ(payload.size(), 8u);
    EXPECT_EQ(decode_as<Read>(payload).form, SpaceForm::kByte6);
    EXPECT_EQ(resolve_form(Space::kCdi, SpaceForm::kAuto), SpaceForm::kShort);
    EXPECT_EQ(resolve_form(Space::kCdi, SpaceForm::kByte6), SpaceForm::kByte6);
    EXPECT_EQ(resolve_form(Space::kAcdiUser, SpaceForm::kShort), SpaceForm::kByte6);
}

TEST(MemoryConfigCodecRoundTrip, EncoderClampsToOneDatagram) {
    const Write big{Space::kAcdiUser, 0, std::vector<std::uint8_t>(100, 7)};
    const auto payload = encode(big);
    EXPECT_EQ(payload.size(), 7u + kMaxReadWrite);
    EXPECT_EQ(decode_as<Write>(payload).data.size(), kMaxReadWrite);

    const ReadReplyFail long_text{Space::kAcdiUser, 0, ErrorCode::kPermanent,
                                  std::string(200, 'x')};
    const auto fail_payload = encode(long_text);
    EXPECT_EQ(fail_payload.size(), kMaxDatagram);
    EXPECT_EQ(decode_as<ReadReplyFail>(fail_payload).text.size(), kMaxErrorText - 1);

    const SpaceInfoReply long_desc{Space::kConfig, 1, false, 0u, std::string(100, 'd')};
    EXPECT_EQ(encode(long_desc).size(), kMaxDatagram);

    UniqueIdReply ids;
    ids.event_ids.assign(10, 0x42);
    EXPECT_EQ(decode_as<UniqueIdReply>(encode(ids)).event_ids.size(), kMaxUniqueIds);
}

TEST(MemoryConfigCodecRoundTrip, EncoderKeepsInvalidCountsForTesters) {
    // A conformance runner sends count 0 and 65 on purpose to see them rejected.
    EXPECT_EQ(encode(Read{Space::kCdi, 0, 0}), hex("20 43 00000000 00"));
    EXPECT_EQ(encode(Read{Space::kCdi, 0, 65}), hex("20 43 00000000 41"));
}

TEST(MemoryConfigCodecRoundTrip, UnterminatedTextDecodesToTheSameMessageAfterReencoding) {
    const auto payload = hex("20 5B 00000000 1082 414243");  // "ABC" without NUL
    const auto first = decode_as<ReadReplyFail>(payload);
    EXPECT_EQ(first.text, "ABC");
    EXPECT_EQ(decode_as<ReadReplyFail>(encode(first)), first);
}

// ---- describe ------------------------------------------------------------------------------

TEST(MemoryConfigDescribe, OneLineSummaries) {
    EXPECT_EQ(describe(hex("20 43 00000040 40")), "read FF @0x00000040 x64");
    EXPECT_EQ(describe(hex("20 58 0000007D FC 1082")),
              "read-reply-fail FC @0x0000007D 0x1082 address out of bounds");
    EXPECT_EQ(describe(hex("20 40 00000000 FF 40")), "read FF @0x00000000 x64 (byte-6 form)");
    EXPECT_EQ(describe(hex("20 53 00000000 3C3F")), "read-reply FF @0x00000000 x2");
    EXPECT_EQ(describe(hex("20 18 00000003 FB 1083 726F00")),
              "write-reply-fail FB @0x00000003 0x1083 write to read-only space \"ro\"");
    EXPECT_EQ(describe(hex("20 87 FF 000003E7 01")), "space-info FF present hi 0x000003E7 ro");
    EXPECT_EQ(describe(hex("20 86 FC")), "space-info FC not present");
    EXPECT_EQ(describe(hex("20 82 0E00 E2 FF FB")),
              "config-options cmds 0x0E00 lengths 0xE2 spaces FF..FB");
    EXPECT_EQ(describe(hex("20 88 02010D000001")), "lock 02.01.0D.00.00.01");
    EXPECT_EQ(describe(hex("20 88 000000000000")), "lock 00.00.00.00.00.00 (release)");
    EXPECT_EQ(describe(hex("20 AA 050101012200")), "factory-reset 05.01.01.01.22.00");
    EXPECT_EQ(describe(hex("20 A9")), "reset-reboot");
}

TEST(MemoryConfigDescribe, InvalidPayloadsSayWhy) {
    EXPECT_EQ(describe(hex("20 43 00000000 00")),
              "invalid memory-config payload: count out of range [20 43 00 00 00 00 00]");
    EXPECT_EQ(describe({}), "invalid memory-config payload: empty payload []");
    EXPECT_EQ(describe(hex("20 01 00000000 0102030405")), "write FD @0x00000000 x5");
    EXPECT_EQ(
        describe(hex("30 01 00000000 0102030405")),
        "invalid memory-config payload: not a memory-config payload [30 01 00 00 00 00 01 02 ...]");
}

TEST(MemoryConfigDescribe, ControlCharactersInTextStayOnOneLine) {
    const auto text = describe(hex("20 5B 00000000 1082 410A4200"));
    EXPECT_EQ(text.find('\n'), std::string::npos);
    EXPECT_NE(text.find("A\\x0AB"), std::string::npos) << text;
}

}  // namespace
}  // namespace olcb::memory
