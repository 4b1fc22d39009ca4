// Memory Configuration Protocol messages as values, and their datagram-payload codec.
//
// decode() is total: any byte string gives either a message or a DecodeError, never UB.
// encode() writes fields as given (so a tester can build e.g. a read of count 0 on purpose) but
// never produces more than kMaxDatagram bytes: data, ID lists and texts are clamped to fit.
// Tolerances on decode (documented choices):
//  * a failure reply without (part of) its error code reads the missing bits as 0
//    ("missing bits = 0", as for OIR/TDE/Datagram Rejected);
//  * the reserved bit 7 of a read count is ignored before checking 1..64;
//  * Get Configuration Options reply without the lowest-space byte reads it as 0;
//  * space-info reply (0x87) without the flags byte reads flags as 0;
//  * bytes after a fixed-size message are ignored;
//  * texts end at the first NUL or at the payload end, and are clamped (UTF-8-safe) to the
//    length an encoder may send, so decode(encode(decode(x))) == decode(x).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "memory/memory_config_defs.hpp"

namespace olcb::memory {

/// Read request: count (1..64) bytes of space from address.
struct Read {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    std::uint8_t count = 0;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const Read&, const Read&) = default;
};

/// Successful read reply carrying 1..64 data bytes.
struct ReadReply {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    std::vector<std::uint8_t> data;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const ReadReply&, const ReadReply&) = default;
};

/// Failed read reply: error code and optional text.
struct ReadReplyFail {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    ErrorCode error = ErrorCode::kNone;
    std::string text;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const ReadReplyFail&, const ReadReplyFail&) = default;
};

/// Write request carrying 1..64 data bytes.
struct Write {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    std::vector<std::uint8_t> data;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const Write&, const Write&) = default;
};

/// One byte of a write under mask: only bits set in mask take the value's bits.
struct MaskedByte {
    std::uint8_t mask = 0;
    std::uint8_t value = 0;
    friend bool operator==(const MaskedByte&, const MaskedByte&) = default;
};

/// Write-under-mask request: 1..32 (mask, value) pairs, sent as mask byte then data byte.
struct WriteUnderMask {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    std::vector<MaskedByte> bytes;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const WriteUnderMask&, const WriteUnderMask&) = default;
};

/// Successful write reply.
struct WriteReply {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const WriteReply&, const WriteReply&) = default;
};

/// Failed write reply: error code and optional text.
struct WriteReplyFail {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    ErrorCode error = ErrorCode::kNone;
    std::string text;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const WriteReplyFail&, const WriteReplyFail&) = default;
};

/// Read-stream request: count bytes (0 = to the end) into the requester's stream.
struct ReadStream {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    std::uint8_t source_stream_id = 0xFF;  ///< sent as 0xFF (not yet assigned)
    std::uint8_t destination_stream_id = 0;
    std::uint32_t count = 0;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const ReadStream&, const ReadStream&) = default;
};

/// Successful read-stream reply.
struct ReadStreamReply {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    std::uint8_t source_stream_id = 0;
    std::uint8_t destination_stream_id = 0;
    std::uint32_t count = 0;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const ReadStreamReply&, const ReadStreamReply&) = default;
};

/// Failed read-stream reply.
struct ReadStreamReplyFail {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    ErrorCode error = ErrorCode::kNone;
    std::string text;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const ReadStreamReplyFail&, const ReadStreamReplyFail&) = default;
};

/// Write-stream request naming the requester's source stream.
struct WriteStream {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    std::uint8_t source_stream_id = 0;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const WriteStream&, const WriteStream&) = default;
};

/// Successful write-stream reply.
struct WriteStreamReply {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    std::uint8_t source_stream_id = 0;
    std::uint8_t destination_stream_id = 0;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const WriteStreamReply&, const WriteStreamReply&) = default;
};

/// Failed write-stream reply.
struct WriteStreamReplyFail {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    ErrorCode error = ErrorCode::kNone;
    std::string text;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const WriteStreamReplyFail&, const WriteStreamReplyFail&) = default;
};

/// Get Configuration Options request (20 80).
struct GetConfigOptions {
    friend bool operator==(const GetConfigOptions&, const GetConfigOptions&) = default;
};

/// Get Configuration Options reply (20 82): see available_commands / write_lengths.
struct ConfigOptionsReply {
    std::uint16_t available_commands = 0;
    std::uint8_t write_lengths = write_lengths::kRecommended;
    Space highest_space = Space::kCdi;
    Space lowest_space = Space::kCdi;
    std::string name;  ///< optional; empty = not sent
    friend bool operator==(const ConfigOptionsReply&, const ConfigOptionsReply&) = default;
};

/// Get Address Space Information request (20 84 SP).
struct GetSpaceInfo {
    Space space = Space::kConfig;
    friend bool operator==(const GetSpaceInfo&, const GetSpaceInfo&) = default;
};

/// Address space information, space present (20 87).
struct SpaceInfoReply {
    Space space = Space::kConfig;
    std::uint32_t highest_address = 0;  ///< inclusive (size - 1)
    bool read_only = false;
    std::optional<std::uint32_t> lowest_address;  ///< sent only when set (flag bit 1)
    std::string description;                      ///< optional; empty = not sent
    friend bool operator==(const SpaceInfoReply&, const SpaceInfoReply&) = default;
};

/// Address space information, space not present (20 86 SP); trailing bytes are ignored.
struct SpaceInfoNotPresent {
    Space space = Space::kConfig;
    friend bool operator==(const SpaceInfoNotPresent&, const SpaceInfoNotPresent&) = default;
};

/// Lock/Reserve request (20 88 + node ID; 0 releases).
struct Lock {
    std::uint64_t node_id = 0;  ///< 48 bits used
    friend bool operator==(const Lock&, const Lock&) = default;
};

/// Lock/Reserve reply: the node now holding the lock (20 8A + node ID).
struct LockReply {
    std::uint64_t node_id = 0;  ///< 48 bits used
    friend bool operator==(const LockReply&, const LockReply&) = default;
};

/// Get Unique ID request for count (0..7) event IDs (20 8C n).
struct GetUniqueId {
    std::uint8_t count = 1;
    friend bool operator==(const GetUniqueId&, const GetUniqueId&) = default;
};

/// Get Unique ID reply: up to 7 never-reused event IDs (20 8D ...).
struct UniqueIdReply {
    std::vector<std::uint64_t> event_ids;
    friend bool operator==(const UniqueIdReply&, const UniqueIdReply&) = default;
};

/// Freeze a space (20 A1 SP), e.g. 0xEF before a firmware upgrade.
struct Freeze {
    Space space = Space::kFirmware;
    friend bool operator==(const Freeze&, const Freeze&) = default;
};

/// Unfreeze a space (20 A0 SP).
struct Unfreeze {
    Space space = Space::kFirmware;
    friend bool operator==(const Unfreeze&, const Unfreeze&) = default;
};

/// Update Complete (20 A8).
struct UpdateComplete {
    friend bool operator==(const UpdateComplete&, const UpdateComplete&) = default;
};

/// Reset/Reboot (20 A9).
struct ResetReboot {
    friend bool operator==(const ResetReboot&, const ResetReboot&) = default;
};

/// Reinitialize/Factory Reset of the node whose ID is given (20 AA + node ID).
struct FactoryReset {
    std::uint64_t node_id = 0;  ///< the target node, as a safety check
    friend bool operator==(const FactoryReset&, const FactoryReset&) = default;
};

/// Enter bootloader (20 AB, OpenMRN extension).
struct EnterBootloader {
    friend bool operator==(const EnterBootloader&, const EnterBootloader&) = default;
};

/// Any Memory Configuration command or reply.
using Message =
    std::variant<Read, ReadReply, ReadReplyFail, Write, WriteUnderMask, WriteReply, WriteReplyFail,
                 ReadStream, ReadStreamReply, ReadStreamReplyFail, WriteStream, WriteStreamReply,
                 WriteStreamReplyFail, GetConfigOptions, ConfigOptionsReply, GetSpaceInfo,
                 SpaceInfoReply, SpaceInfoNotPresent, Lock, LockReply, GetUniqueId, UniqueIdReply,
                 Freeze, Unfreeze, UpdateComplete, ResetReboot, FactoryReset, EnterBootloader>;

/// Why a payload is not a valid Memory Configuration message.
enum class DecodeError : std::uint8_t {
    kNone,             ///< decoded fine
    kEmpty,            ///< no bytes at all
    kTooLong,          ///< more than 72 bytes
    kNotMemoryConfig,  ///< byte 0 is not 0x20
    kTruncated,        ///< ends inside a fixed-size field (command, address, ID, ...)
    kMissingSpace,     ///< byte-6 form without the space byte
    kUnknownCommand,   ///< command byte not defined by the protocol
    kBadCount,         ///< read count 0 or > 64, or Get Unique ID reply with > 7 IDs
    kNoData,           ///< write / read reply / write under mask without data
    kTooMuchData,      ///< more than 64 data bytes
    kOddMaskData,      ///< write under mask with an odd number of bytes
    kBadLength,        ///< Get Unique ID reply not 2 + 8n bytes
};

/// One-phrase description of a decode error.
std::string_view to_string(DecodeError error);

/// The error code a server rejects such a datagram with (0x1041 unknown command, else 0x1080).
ErrorCode reject_code(DecodeError error);

/// Outcome of decode(): the message when error == DecodeError::kNone.
struct DecodeResult {
    Message message;
    DecodeError error = DecodeError::kNone;
    /// True when a message was decoded.
    bool ok() const { return error == DecodeError::kNone; }
};

/// Decodes one datagram payload (starting with 0x20). Never fails other than by value.
DecodeResult decode(std::span<const std::uint8_t> payload);

/// Encodes a message into a datagram payload of at most 72 bytes.
std::vector<std::uint8_t> encode(const Message& message);

/// How many payloads decode() and encode() handled in this process: a test holds an owner (a
/// node with faults on) to decoding each datagram once and encoding each reply once.
struct CodecCounts {
    std::uint64_t decoded = 0;
    std::uint64_t encoded = 0;
};
/// The counts so far.
CodecCounts codec_counts();

/// The form encode() will use for a space: kShort only for 0xFD..0xFF unless kByte6 is asked.
SpaceForm resolve_form(Space space, SpaceForm requested);

/// One-line human description of any payload for traffic monitors, e.g.
/// "read FF @0x00000040 x64" or "read-reply-fail FC @0x0000007D 0x1082 address out of bounds".
std::string describe(std::span<const std::uint8_t> payload);

}  // namespace olcb::memory
