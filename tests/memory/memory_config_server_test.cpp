#include "memory/memory_config_server.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "memory/acdi.hpp"
#include "memory/memory_test_util.hpp"

namespace olcb::memory {
namespace {

using test::hex;

constexpr std::uint64_t kNodeId = 0x050101011234;
constexpr std::string_view kCdi = "<cdi/>";  // space 0xFF: 6 bytes + NUL = highest address 6

class ServerTest : public ::testing::Test {
protected:
    ServerTest()
        : cdi_(ConstantSpace::from_cdi(kCdi)),
          config_space_(std::vector<std::uint8_t>(256, 0)),
          acdi_fixed_(std::vector<std::uint8_t>(acdi::kManufacturerBlockSize, 0x11)),
          acdi_user_(std::vector<std::uint8_t>(acdi::kUserBlockSize, 0)),
          server_(make_config()) {
        server_.add_space(Space::kCdi, cdi_);
        server_.add_space(Space::kConfig, config_space_);
        server_.add_space(Space::kAcdiManufacturer, acdi_fixed_);
        server_.add_space(Space::kAcdiUser, acdi_user_);
    }

    static MemoryConfigServer::Config make_config() {
        MemoryConfigServer::Config config;
        config.node_id = kNodeId;
        return config;
    }

    Decision handle(std::string_view payload) { return server_.handle(Source{}, hex(payload)); }

    // Expects Datagram OK with Reply Pending and the given reply bytes.
    void expect_reply(std::string_view request, std::string_view reply) {
        SCOPED_TRACE(std::string(request));
        const Decision d = handle(request);
        EXPECT_TRUE(d.accepted);
        EXPECT_TRUE(d.reply_pending);
        EXPECT_EQ(d.reply_bytes(), hex(reply));
    }

    // Expects Datagram Rejected with code and nothing else.
    void expect_reject(std::string_view request, ErrorCode code) {
        SCOPED_TRACE(std::string(request));
        const Decision d = handle(request);
        EXPECT_FALSE(d.accepted);
        EXPECT_EQ(d.reject_error, code);
        EXPECT_FALSE(d.reply);
        EXPECT_EQ(d.effects, SideEffects{});
    }

    ConstantSpace cdi_;
    RamSpace config_space_;
    ConstantSpace acdi_fixed_;
    RamSpace acdi_user_;
    MemoryConfigServer server_;
};

// ---- Get Configuration Options ---------------------------------------------------------------

TEST_F(ServerTest, ConfigOptionsWithAcdi) {
    // 0x8000|0x4000|0x2000 + 0x0800 (252) + 0x0400|0x0200 (251 writable); FF..FB served.
    expect_reply("20 80", "20 82 EE00 E2 FF FB");
}

TEST_F(ServerTest, ConfigOptionsWithoutAcdi) {
    server_.remove_space(Space::kAcdiManufacturer);
    server_.remove_space(Space::kAcdiUser);
    expect_reply("20 80", "20 82 E000 E2 FF FD");
}

TEST_F(ServerTest, ConfigOptionsReadOnlyUserSpaceAndLowSpace) {
    ConstantSpace user(std::vector<std::uint8_t>(128, 0));
    RamSpace low(std::vector<std::uint8_t>(4, 0));
    server_.add_space(Space::kAcdiUser, user);
    server_.add_space(static_cast<Space>(0x10), low);
    expect_reply("20 80", "20 82 EC00 E2 FF 10");
}

TEST_F(ServerTest, ConfigOptionsName) {
    MemoryConfigServer::Config config = make_config();
    config.name = "sim";
    MemoryConfigServer server(config);
    server.add_space(Space::kCdi, cdi_);
    EXPECT_EQ(server.handle({}, hex("20 80")).reply_bytes(), hex("20 82 E000 E2 FF FF 73696D 00"));
}

// ---- Get Address Space Information -----------------------------------------------------------

TEST_F(ServerTest, SpaceInfoPresent) {
    expect_reply("20 84 FF", "20 87 FF 00000006 01");
    expect_reply("20 84 FD", "20 87 FD 000000FF 00");
    expect_reply("20 84 FC", "20 87 FC 0000007C 01");
    expect_reply("20 84 FB", "20 87 FB 0000007F 00");
}

TEST_F(ServerTest, SpaceInfoNotPresent) {
    expect_reply("20 84 10", "20 86 10");
    expect_reply("20 84 FE", "20 86 FE");
}

TEST_F(ServerTest, SpaceInfoLowestAddressAndDescription) {
    struct Shifted : ForwardingSpace {
        using ForwardingSpace::ForwardingSpace;
        std::uint32_t lowest_address() const override { return 0x10; }
        std::string_view description() const override { return "cfg"; }
    } shifted(config_space_);
    server_.add_space(Space::kConfig, shifted);
    expect_reply("20 84 FD", "20 87 FD 000000FF 02 00000010 636667 00");
    // Below the lowest address nothing is readable.
    expect_reply("20 41 0000000F 01", "20 59 0000000F 1082");
}

TEST_F(ServerTest, SpaceInfoMissingSpaceByteIsRejected) {
    expect_reject("20 84", ErrorCode::kInvalidArguments);
}

// ---- Read ------------------------------------------------------------------------------------

TEST_F(ServerTest, ReadShortForm) {
    expect_reply("20 43 00000000 04", "20 53 00000000 3C636469");
}

TEST_F(ServerTest, ReadByte6FormOfShortSpaceAnswersInByte6Form) {
    expect_reply("20 40 00000000 FF 04", "20 50 00000000 FF 3C636469");
}

TEST_F(ServerTest, ReadAcdiSpaces) {
    expect_reply("20 40 0000007C FC 40", "20 50 0000007C FC 11");
    expect_reply("20 40 00000000 FB 02", "20 50 00000000 FB 0000");
}

TEST_F(ServerTest, ReadPartlyPastEndIsShort) {
    // "/>" and the NUL: 3 of the 64 asked for.
    expect_reply("20 43 00000004 40", "20 53 00000004 2F3E00");
    expect_reply("20 40 00000078 FB 40", "20 50 00000078 FB 0000000000000000");
}

TEST_F(ServerTest, ReadAtOrPastEndFails1082InSameForm) {
    expect_reply("20 43 00000007 40", "20 5B 00000007 1082");
    expect_reply("20 40 00000007 FF 40", "20 58 00000007 FF 1082");
    expect_reply("20 41 FFFFFFFF 01", "20 59 FFFFFFFF 1082");
    expect_reply("20 40 00000080 FB 01", "20 58 00000080 FB 1082");
}

TEST_F(ServerTest, ReadBadCountRejected1080) {
    expect_reject("20 43 00000000 00", ErrorCode::kInvalidArguments);
    expect_reject("20 43 00000000 41", ErrorCode::kInvalidArguments);
    expect_reject("20 43 00000000 80", ErrorCode::kInvalidArguments);  // bit 7 ignored -> 0
}

TEST_F(ServerTest, ReadCountReservedBitIgnored) {
    expect_reply("20 43 00000000 81", "20 53 00000000 3C");
}

TEST_F(ServerTest, ReadTruncatedRejected1080) {
    expect_reject("20 43 0000", ErrorCode::kInvalidArguments);
    expect_reject("20 40 00000000", ErrorCode::kInvalidArguments);  // no space byte
    expect_reject("20 43 00000000", ErrorCode::kInvalidArguments);  // no count
}

TEST_F(ServerTest, ReadUnknownSpaceRejected1081) {
    expect_reject("20 42 00000000 01", ErrorCode::kSpaceUnknown);
    expect_reject("20 40 00000000 10 01", ErrorCode::kSpaceUnknown);
}

TEST_F(ServerTest, ReadReplyUsesConfiguredTimeoutExponent) {
    MemoryConfigServer::Config config = make_config();
    config.reply_timeout_exponent = 3;
    MemoryConfigServer server(config);
    server.add_space(Space::kCdi, cdi_);
    const Decision d = server.handle({}, hex("20 43 00000000 01"));
    EXPECT_TRUE(d.reply_pending);
    EXPECT_EQ(d.reply_timeout_exponent, 3);
}

TEST_F(ServerTest, ReadWhereSpaceDeliversNothingFails1082) {
    struct Empty : ForwardingSpace {
        using ForwardingSpace::ForwardingSpace;
        std::size_t read(std::uint32_t, std::span<std::uint8_t>) override { return 0; }
    } empty(config_space_);
    server_.add_space(Space::kConfig, empty);
    expect_reply("20 41 00000000 04", "20 59 00000000 1082");
}

// ---- Write -----------------------------------------------------------------------------------

TEST_F(ServerTest, WriteShortFormStoresAndRepliesOk) {
    const Decision d = handle("20 01 00000010 AABB");
    EXPECT_TRUE(d.accepted);
    EXPECT_TRUE(d.reply_pending);
    EXPECT_EQ(d.reply_bytes(), hex("20 11 00000010"));
    EXPECT_EQ(config_space_.bytes()[0x10], 0xAA);
    EXPECT_EQ(config_space_.bytes()[0x11], 0xBB);
    ASSERT_TRUE(d.effects.written.has_value());
    EXPECT_EQ(*d.effects.written, (WrittenRange{Space::kConfig, 0x10, 2, true}));
    EXPECT_FALSE(d.effects.identification_changed);
    // Read back through the server.
    expect_reply("20 41 00000010 02", "20 51 00000010 AABB");
}

TEST_F(ServerTest, WriteByte6FormRepliesInByte6Form) {
    expect_reply("20 00 00000010 FD AA", "20 10 00000010 FD");
    EXPECT_EQ(config_space_.bytes()[0x10], 0xAA);
}

TEST_F(ServerTest, WriteSixtyFourBytes) {
    std::string request = "20 01 000000C0";
    for (int i = 0; i < 64; ++i) request += " 5A";
    expect_reply(request, "20 11 000000C0");
    EXPECT_EQ(config_space_.bytes()[0xFF], 0x5A);
}

TEST_F(ServerTest, WriteSameBytesReportsUnchanged) {
    const Decision d = handle("20 01 00000000 0000");
    ASSERT_TRUE(d.effects.written.has_value());
    EXPECT_FALSE(d.effects.written->changed);
}

TEST_F(ServerTest, WritePlainOkWhenConfigured) {
    MemoryConfigServer::Config config = make_config();
    config.write_reply_pending = false;
    MemoryConfigServer server(config);
    server.add_space(Space::kConfig, config_space_);
    Decision d = server.handle({}, hex("20 01 00000000 07"));
    EXPECT_TRUE(d.accepted);
    EXPECT_FALSE(d.reply_pending);
    EXPECT_FALSE(d.reply);
    EXPECT_EQ(config_space_.bytes()[0], 0x07);
    // A failure still needs a reply, so it is announced.
    d = server.handle({}, hex("20 01 00000100 07"));
    EXPECT_TRUE(d.reply_pending);
    EXPECT_EQ(d.reply_bytes(), hex("20 19 00000100 1082"));
}

TEST_F(ServerTest, WriteReadOnlyRejected1083) {
    expect_reject("20 03 00000000 41", ErrorCode::kReadOnly);
    expect_reject("20 00 00000000 FC 41", ErrorCode::kReadOnly);
    expect_reject("20 0B 00000000 FF 41", ErrorCode::kReadOnly);
    EXPECT_EQ(cdi_.bytes()[0], '<');
}

// A space writable but for some bytes (251's version byte) refuses those writes like a
// read-only space: Datagram Rejected 0x1083, no reply datagram, nothing stored.
TEST_F(ServerTest, WriteRefusedByTheSpaceAsReadOnlyRejected1083) {
    class FirstByteReadOnly : public ForwardingSpace {
    public:
        using ForwardingSpace::ForwardingSpace;
        WriteStatus write(std::uint32_t address, std::span<const std::uint8_t> in) override {
            if (address == 0 && !in.empty()) return WriteStatus::kReadOnly;
            return ForwardingSpace::write(address, in);
        }
    };
    FirstByteReadOnly guarded(acdi_user_);
    server_.add_space(Space::kAcdiUser, guarded);
    expect_reject("20 00 00000000 FB 0341", ErrorCode::kReadOnly);
    expect_reject("20 08 00000000 FB FF03", ErrorCode::kReadOnly);
    EXPECT_EQ(acdi_user_.bytes()[0], 0x00);
    EXPECT_EQ(acdi_user_.bytes()[1], 0x00);
    expect_reply("20 00 00000001 FB 41", "20 10 00000001 FB");
    EXPECT_EQ(acdi_user_.bytes()[1], 0x41);
    server_.add_space(Space::kAcdiUser, acdi_user_);
}

TEST_F(ServerTest, WriteUnknownSpaceRejected1081) {
    expect_reject("20 02 00000000 41", ErrorCode::kSpaceUnknown);
    expect_reject("20 00 00000000 20 41", ErrorCode::kSpaceUnknown);
}

TEST_F(ServerTest, WritePastEndFailsAndWritesNothing) {
    expect_reply("20 01 000000FF 0102", "20 19 000000FF 1082");
    EXPECT_EQ(config_space_.bytes()[0xFF], 0x00);
    expect_reply("20 01 00000100 01", "20 19 00000100 1082");
    expect_reply("20 01 FFFFFFFF 01", "20 19 FFFFFFFF 1082");
    expect_reply("20 00 0000007F FB 0102", "20 18 0000007F FB 1082");
    EXPECT_EQ(acdi_user_.bytes()[0x7F], 0x00);
}

TEST_F(ServerTest, WriteMalformedRejected1080) {
    expect_reject("20 01 00000000", ErrorCode::kInvalidArguments);  // no data
    std::string request = "20 01 00000000";
    for (int i = 0; i < 65; ++i) request += " 00";
    expect_reject(request, ErrorCode::kInvalidArguments);  // 65 bytes
}

TEST_F(ServerTest, WriteUnderMaskChangesOnlyMaskedBits) {
    ASSERT_EQ(config_space_.write(0x10, hex("F0 FF")), WriteStatus::kOk);
    // byte 0x10: mask 0F value 05 -> F5; byte 0x11: mask 80 value 00 -> 7F.
    const Decision d = handle("20 09 00000010 0F05 8000");
    EXPECT_EQ(d.reply_bytes(), hex("20 11 00000010"));
    EXPECT_EQ(config_space_.bytes()[0x10], 0xF5);
    EXPECT_EQ(config_space_.bytes()[0x11], 0x7F);
    ASSERT_TRUE(d.effects.written.has_value());
    EXPECT_EQ(*d.effects.written, (WrittenRange{Space::kConfig, 0x10, 2, true}));
}

TEST_F(ServerTest, WriteUnderMaskByte6FormAndErrors) {
    expect_reply("20 08 00000000 FB FF02", "20 10 00000000 FB");
    EXPECT_EQ(acdi_user_.bytes()[0], 0x02);
    expect_reject("20 09 00000000 0F", ErrorCode::kInvalidArguments);  // odd length
    expect_reply("20 09 000000FF 0F01 0F01", "20 19 000000FF 1082");
    expect_reject("20 08 00000000 FC FF01", ErrorCode::kReadOnly);
}

TEST_F(ServerTest, WriteToAcdiUserSpaceFlagsIdentificationChange) {
    const Decision d = handle("20 00 00000001 FB 4142");
    EXPECT_EQ(d.reply_bytes(), hex("20 10 00000001 FB"));
    EXPECT_TRUE(d.effects.identification_changed);
    EXPECT_EQ(decode_acdi_user(acdi_user_.bytes()).name, "AB");
    // Same bytes again: nothing changed, nothing to announce.
    EXPECT_FALSE(handle("20 00 00000001 FB 4142").effects.identification_changed);
}

TEST_F(ServerTest, WriteStorageFailureRepliesFail1000) {
    struct Broken : ForwardingSpace {
        using ForwardingSpace::ForwardingSpace;
        WriteStatus write(std::uint32_t, std::span<const std::uint8_t>) override {
            return WriteStatus::kIoError;
        }
    } broken(config_space_);
    server_.add_space(Space::kConfig, broken);
    const Decision d = handle("20 01 00000000 01");
    EXPECT_TRUE(d.accepted);
    EXPECT_EQ(d.reply_bytes(), hex("20 19 00000000 1000"));
    EXPECT_FALSE(d.effects.written.has_value());
    ASSERT_TRUE(d.effects.not_stored.has_value());
    EXPECT_EQ(d.effects.not_stored->address, 0u);
    EXPECT_EQ(d.effects.not_stored->length, 1u);
}

// ---- Lock, unique IDs, reset family ----------------------------------------------------------

TEST_F(ServerTest, LockIsTestAndSet) {
    expect_reply("20 88 010203040506", "20 8A 010203040506");
    EXPECT_EQ(server_.lock_holder(), 0x010203040506u);
    expect_reply("20 88 0A0B0C0D0E0F", "20 8A 010203040506");  // someone else: still held
    expect_reply("20 88 000000000000", "20 8A 000000000000");  // release
    expect_reply("20 88 0A0B0C0D0E0F", "20 8A 0A0B0C0D0E0F");
    server_.reset();
    EXPECT_EQ(server_.lock_holder(), 0u);
}

TEST_F(ServerTest, LockTruncatedRejected) {
    expect_reject("20 88 0102", ErrorCode::kInvalidArguments);
}

TEST_F(ServerTest, LockClearedByReboot) {
    handle("20 88 010203040506");
    handle("20 A9");
    EXPECT_EQ(server_.lock_holder(), 0u);
}

TEST_F(ServerTest, GetUniqueIdsFromNodeIdAndCounter) {
    MemoryConfigServer::Config config = make_config();
    config.unique_id_counter = 5;
    MemoryConfigServer server(config);
    Decision d = server.handle({}, hex("20 8C 02"));
    EXPECT_TRUE(d.reply_pending);
    EXPECT_EQ(d.reply_bytes(), hex("20 8D 0501010112340005 0501010112340006"));
    EXPECT_EQ(d.effects.unique_id_counter, 7u);
    d = server.handle({}, hex("20 8C 01"));
    EXPECT_EQ(d.reply_bytes(), hex("20 8D 0501010112340007"));
    d = server.handle({}, hex("20 8C 00"));
    EXPECT_EQ(d.reply_bytes(), hex("20 8D"));
    // Only the low three bits count: 0xF9 asks for 1.
    d = server.handle({}, hex("20 8C F9"));
    EXPECT_EQ(d.reply_bytes(), hex("20 8D 0501010112340008"));
    EXPECT_EQ(server.unique_id_counter(), 9u);
}

TEST_F(ServerTest, GetUniqueIdNeverWrapsAround) {
    MemoryConfigServer::Config config = make_config();
    config.unique_id_counter = 0xFFFF;
    MemoryConfigServer server(config);
    const Decision refused = server.handle({}, hex("20 8C 02"));
    EXPECT_FALSE(refused.accepted);
    EXPECT_EQ(refused.reject_error, ErrorCode::kPermanent);
    EXPECT_EQ(server.handle({}, hex("20 8C 01")).reply_bytes(), hex("20 8D 050101011234FFFF"));
    EXPECT_FALSE(server.handle({}, hex("20 8C 01")).accepted);
}

TEST_F(ServerTest, UpdateCompletePlainOk) {
    const Decision d = handle("20 A8");
    EXPECT_EQ(d, Decision::ok());
}

TEST_F(ServerTest, ResetRebootRequestsReboot) {
    const Decision d = handle("20 A9");
    EXPECT_TRUE(d.accepted);
    EXPECT_FALSE(d.reply_pending);
    EXPECT_FALSE(d.reply);
    EXPECT_TRUE(d.effects.reboot);
    EXPECT_FALSE(d.effects.factory_reset);
}

TEST_F(ServerTest, FactoryResetOnlyForOurNodeId) {
    const Decision d = handle("20 AA 050101011234");
    EXPECT_TRUE(d.accepted);
    EXPECT_FALSE(d.reply_pending);
    EXPECT_TRUE(d.effects.factory_reset);
    expect_reject("20 AA 050101011235", ErrorCode::kInvalidArguments);
    expect_reject("20 AA 0501", ErrorCode::kInvalidArguments);
}

TEST_F(ServerTest, FreezeUnfreezeBootloaderUnsupportedByDefault) {
    expect_reject("20 A1 EF", ErrorCode::kSubcommandUnknown);
    expect_reject("20 A0 EF", ErrorCode::kSubcommandUnknown);
    expect_reject("20 AB", ErrorCode::kSubcommandUnknown);
}

TEST_F(ServerTest, FreezeUnfreezeBootloaderWhenConfigured) {
    MemoryConfigServer::Config config = make_config();
    config.accept_freeze = true;
    config.accept_enter_bootloader = true;
    MemoryConfigServer server(config);
    Decision d = server.handle({}, hex("20 A1 EF"));
    EXPECT_TRUE(d.accepted);
    EXPECT_EQ(d.effects.freeze, Space::kFirmware);
    d = server.handle({}, hex("20 A0 EF"));
    EXPECT_EQ(d.effects.unfreeze, Space::kFirmware);
    d = server.handle({}, hex("20 AB"));
    EXPECT_TRUE(d.effects.enter_bootloader);
}

// ---- Unsupported and unknown -----------------------------------------------------------------

TEST_F(ServerTest, StreamsRejected1041) {
    expect_reject("20 61 00000000 FF 01 00000040", ErrorCode::kSubcommandUnknown);
    expect_reject("20 60 00000000 FD FF 01 00000000", ErrorCode::kSubcommandUnknown);
    expect_reject("20 21 00000000 05", ErrorCode::kSubcommandUnknown);
}

TEST_F(ServerTest, StreamReadsWhenEnabled) {
    server_.set_streams(true);
    // Options: "stream reads" 0x1000 as OpenMRN sends it; no 0x01 (stream writes) in lengths.
    expect_reply("20 80", "20 82 FE00 E2 FF FB");
    // The whole CDI (count 0 = to the end): OK with Reply Pending, no reply yet, a StreamRead.
    Decision d = handle("20 63 00000000 FF 05 00000000");
    EXPECT_TRUE(d.accepted);
    EXPECT_TRUE(d.reply_pending);
    EXPECT_FALSE(d.reply);
    ASSERT_TRUE(d.effects.stream_read);
    const StreamRead read = *d.effects.stream_read;
    EXPECT_EQ(read, (StreamRead{Space::kCdi, 0, 7, 0, 0x05, SpaceForm::kShort}));
    EXPECT_EQ(server_.stream_data(read), hex("3C6364692F3E00"));  // "<cdi/>" NUL
    EXPECT_EQ(MemoryConfigServer::stream_reply(read, 0x01, 0x05),
              hex("20 73 00000000 01 05 00000000"));
    EXPECT_EQ(MemoryConfigServer::stream_fail(read, ErrorCode::kBufferUnavailable),
              hex("20 7B 00000000 2020"));
    // A count past the end is cut there; byte-6 form of 253 is answered in that form.
    d = handle("20 60 000000F0 FD FF 06 00000100");
    ASSERT_TRUE(d.effects.stream_read);
    EXPECT_EQ(d.effects.stream_read->length, 16u);
    EXPECT_EQ(d.effects.stream_read->count, 0x100u);
    EXPECT_EQ(MemoryConfigServer::stream_reply(*d.effects.stream_read, 2, 6),
              hex("20 70 000000F0 FD 02 06 00000100"));
    // At/after the end fails 0x1082 like a datagram read; unknown space is rejected 0x1081.
    expect_reply("20 63 00000007 FF 05 00000000", "20 7B 00000007 1082");
    expect_reject("20 60 00000000 10 FF 05 00000000", ErrorCode::kSpaceUnknown);
    // Write streams stay unsupported.
    expect_reject("20 21 00000000 05", ErrorCode::kSubcommandUnknown);
}

TEST_F(ServerTest, UnknownCommandRejected1041) {
    expect_reject("20 C0", ErrorCode::kSubcommandUnknown);
    expect_reject("20 44 00000000 FD 01", ErrorCode::kSubcommandUnknown);  // reserved bit
    expect_reject("20 81", ErrorCode::kSubcommandUnknown);
}

TEST_F(ServerTest, RepliesSentToServerRejected1041) {
    expect_reject("20 53 00000000 3C", ErrorCode::kSubcommandUnknown);
    expect_reject("20 11 00000000", ErrorCode::kSubcommandUnknown);
    expect_reject("20 82 EE00 E2 FF FB", ErrorCode::kSubcommandUnknown);
}

TEST_F(ServerTest, NotMemoryConfigRejected1042) {
    expect_reject("21 00", ErrorCode::kCommandUnknown);
}

TEST_F(ServerTest, MissingCommandByteRejected1080) {
    expect_reject("20", ErrorCode::kInvalidArguments);
}

// ---- Persistence through the server -----------------------------------------------------------

TEST(ServerWithImage, AcknowledgedWriteIsInTheImageFile) {
    std::string pattern = ::testing::TempDir() + "olcb_server_XXXXXX";
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    const std::filesystem::path dir = pattern;
    const std::filesystem::path path = dir / "fd.img";
    {
        ImageOpenResult opened = ImageFile::open(path, 128);
        ASSERT_TRUE(opened.ok()) << opened.error;
        ImageSpace space(std::move(opened.image));
        MemoryConfigServer server(MemoryConfigServer::Config{});
        server.add_space(Space::kConfig, space);
        const Decision d = server.handle({}, hex("20 01 00000020 C0FFEE"));
        EXPECT_EQ(d.reply_bytes(), hex("20 11 00000020"));
        // Before the owner even sends the acknowledgement, the bytes are in the file.
        std::ifstream in(path, std::ios::binary);
        in.seekg(0x20);
        char buffer[3] = {};
        in.read(buffer, 3);
        EXPECT_EQ(static_cast<std::uint8_t>(buffer[0]), 0xC0);
        EXPECT_EQ(static_cast<std::uint8_t>(buffer[2]), 0xEE);
    }
    ImageOpenResult reopened = ImageFile::open(path, 128);
    ASSERT_TRUE(reopened.ok()) << reopened.error;
    EXPECT_EQ(reopened.image->bytes()[0x21], 0xFF);
    reopened.image.reset();
    std::filesystem::remove_all(dir);
}

// ---- Fault layering without copying the server -----------------------------------------------

TEST_F(ServerTest, FaultDropWritesByWrappingTheSpace) {
    struct DropWrites : ForwardingSpace {
        using ForwardingSpace::ForwardingSpace;
        WriteStatus write(std::uint32_t, std::span<const std::uint8_t>) override {
            return WriteStatus::kOk;
        }
    } dropping(config_space_);
    server_.add_space(Space::kConfig, dropping);
    expect_reply("20 01 00000000 42", "20 11 00000000");
    expect_reply("20 41 00000000 01", "20 51 00000000 00");
}

TEST_F(ServerTest, FaultGarbagePastEndByWrappingTheSpace) {
    struct Garbage : ForwardingSpace {
        using ForwardingSpace::ForwardingSpace;
        std::uint32_t size() const override { return inner().size() + 64; }
        std::size_t read(std::uint32_t address, std::span<std::uint8_t> out) override {
            std::fill(out.begin(), out.end(), 0xEE);
            const std::size_t real = inner().read(address, out);
            return std::max(real, out.size());
        }
    } garbage(cdi_);
    server_.add_space(Space::kCdi, garbage);
    expect_reply("20 43 00000007 02", "20 53 00000007 EEEE");
}

// An owner changes the typed reply, and the bytes follow when it is encoded once.
TEST_F(ServerTest, AnOwnerRewritesTheTypedReply) {
    Decision d = handle("20 43 00000000 01");
    ASSERT_TRUE(d.reply);
    std::get<ReadReply>(*d.reply).form = SpaceForm::kByte6;
    EXPECT_EQ(d.reply_bytes(), hex("20 50 00000000 FF 3C"));
}

// The owner that decoded a datagram hands the server its decoding: nothing is decoded again.
TEST_F(ServerTest, ADecodedRequestIsNotDecodedAgain) {
    const DecodeResult request = decode(hex("20 43 00000000 01"));
    const CodecCounts before = codec_counts();
    const Decision d = server_.handle(Source{}, request);
    EXPECT_EQ(codec_counts().decoded, before.decoded);
    EXPECT_EQ(codec_counts().encoded, before.encoded) << "the reply stays typed";
    EXPECT_EQ(d.reply_bytes(), hex("20 53 00000000 3C"));
}

}  // namespace
}  // namespace olcb::memory
