// Wire constants of the Memory Configuration Protocol (datagram content type 0x20): command and
// reply bytes, address spaces, option bits, error codes and sizes, with small pure helpers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "base/error_codes.hpp"

namespace olcb::memory {

/// Datagram content type (byte 0) of every Memory Configuration payload.
inline constexpr std::uint8_t kDatagramType = 0x20;
/// Largest datagram payload in bytes (type byte included).
inline constexpr std::size_t kMaxDatagram = 72;
/// Most data bytes one read or write datagram may carry (7 + 64 = 71 <= 72).
inline constexpr std::size_t kMaxReadWrite = 64;
/// Most bytes of the optional text after an error code, NUL included (7 + 2 + 63 = 72).
inline constexpr std::size_t kMaxErrorText = 63;
/// Most event IDs one Get Unique ID request may ask for (3-bit field).
inline constexpr std::size_t kMaxUniqueIds = 7;
/// Size of a node ID inside a payload.
inline constexpr std::size_t kNodeIdSize = 6;

/// Command byte (payload byte 1). Read/write family values are the byte-6 form (low bits 00);
/// OR in short_form_bits() for spaces 0xFD..0xFF.
enum class Command : std::uint8_t {
    kWrite = 0x00,
    kWriteUnderMask = 0x08,
    kWriteReply = 0x10,
    kWriteReplyFail = 0x18,
    kWriteStream = 0x20,
    kWriteStreamReply = 0x30,
    kWriteStreamReplyFail = 0x38,
    kRead = 0x40,
    kReadReply = 0x50,
    kReadReplyFail = 0x58,
    kReadStream = 0x60,
    kReadStreamReply = 0x70,
    kReadStreamReplyFail = 0x78,
    kGetConfigOptions = 0x80,
    kGetConfigOptionsReply = 0x82,
    kGetSpaceInfo = 0x84,
    kSpaceInfoNotPresent = 0x86,
    kSpaceInfoPresent = 0x87,
    kLock = 0x88,
    kLockReply = 0x8A,
    kGetUniqueId = 0x8C,
    kGetUniqueIdReply = 0x8D,
    kUnfreeze = 0xA0,
    kFreeze = 0xA1,
    kUpdateComplete = 0xA8,
    kResetReboot = 0xA9,
    kFactoryReset = 0xAA,
    kEnterBootloader = 0xAB,  ///< OpenMRN extension
};

/// Bits of a read/write-family command byte (values < 0x80).
namespace command_bits {
inline constexpr std::uint8_t kSpaceMask = 0x03;   ///< 00 = space in byte 6, else FD/FE/FF
inline constexpr std::uint8_t kReserved = 0x04;    ///< must be 0
inline constexpr std::uint8_t kFail = 0x08;        ///< reply: failed; command: write under mask
inline constexpr std::uint8_t kReply = 0x10;       ///< 1 = reply
inline constexpr std::uint8_t kStream = 0x20;      ///< 1 = stream variant
inline constexpr std::uint8_t kRead = 0x40;        ///< 1 = read, 0 = write
inline constexpr std::uint8_t kOther = 0x80;       ///< set = not a read/write-family command
inline constexpr std::uint8_t kFamilyMask = 0xFC;  ///< command without the space bits
}  // namespace command_bits

/// Address space number. Any byte value is a valid space; these are the well-known ones.
enum class Space : std::uint8_t {
    kCdi = 0xFF,               ///< CDI XML, read-only, NUL-terminated
    kAll = 0xFE,               ///< all memory, designer-defined
    kConfig = 0xFD,            ///< basic configuration memory laid out by the CDI segments
    kAcdiManufacturer = 0xFC,  ///< ACDI manufacturer data, read-only, 125 bytes
    kAcdiUser = 0xFB,          ///< ACDI user data, read/write, 128 bytes
    kFdi = 0xFA,               ///< train Function Description Information, read-only
    kTrainFunctions = 0xF9,    ///< train function data
    kDccCv = 0xF8,             ///< DCC CV proxy (OpenMRN)
    kFirmware = 0xEF,          ///< firmware upgrade
};

/// Which encoding of the space a read/write-family message uses (or should use).
enum class SpaceForm : std::uint8_t {
    kAuto,   ///< encoder: short form for 0xFD..0xFF, byte-6 form otherwise
    kShort,  ///< space in the command's low two bits (0xFD..0xFF only)
    kByte6,  ///< space number in payload byte 6
};

/// Available-commands bits of the Get Configuration Options reply (2 bytes).
namespace available_commands {
inline constexpr std::uint16_t kWriteUnderMask = 0x8000;
inline constexpr std::uint16_t kUnalignedReads = 0x4000;
inline constexpr std::uint16_t kUnalignedWrites = 0x2000;
inline constexpr std::uint16_t kStreamReads = 0x1000;  ///< proposed, OpenMRN only
inline constexpr std::uint16_t kAcdiManufacturerRead = 0x0800;
inline constexpr std::uint16_t kAcdiUserRead = 0x0400;
inline constexpr std::uint16_t kAcdiUserWrite = 0x0200;
}  // namespace available_commands

/// Write-lengths byte of the Get Configuration Options reply.
namespace write_lengths {
inline constexpr std::uint8_t kReservedSendOne = 0xE2;  ///< 0x80|0x40|0x20|0x02: send as 1
inline constexpr std::uint8_t kStreams = 0x01;          ///< stream writes supported
inline constexpr std::uint8_t kRecommended = 0xE2;      ///< what a datagram-only node sends
}  // namespace write_lengths

/// Flags byte of the Get Address Space Information reply.
namespace space_flags {
inline constexpr std::uint8_t kReadOnly = 0x01;
inline constexpr std::uint8_t kLowAddressPresent = 0x02;  ///< a 4-byte lowest address follows
}  // namespace space_flags

/// Error codes memory configuration uses: the project's one table (base/error_codes.hpp).
using base::error_name;
using base::ErrorCode;
using base::is_permanent;
using base::is_temporary;
using base::to_u16;

/// The raw byte of a space.
constexpr std::uint8_t to_u8(Space space) {
    return static_cast<std::uint8_t>(space);
}

/// The raw byte of a command.
constexpr std::uint8_t to_u8(Command command) {
    return static_cast<std::uint8_t>(command);
}

/// True when the space can be written in the command byte (0xFD, 0xFE, 0xFF).
constexpr bool has_short_form(Space space) {
    return to_u8(space) >= 0xFD;
}

/// Low two command bits for a short-form space (1/2/3), 0 for all other spaces.
constexpr std::uint8_t short_form_bits(Space space) {
    return has_short_form(space) ? static_cast<std::uint8_t>(to_u8(space) - 0xFC) : 0;
}

/// True when the command byte belongs to the read/write family (bit 7 clear).
constexpr bool is_read_write_family(std::uint8_t command) {
    return (command & command_bits::kOther) == 0;
}

/// The space a read/write-family command names in its low bits; nullopt when byte 6 holds it.
constexpr std::optional<Space> short_form_space(std::uint8_t command) {
    const std::uint8_t bits = command & command_bits::kSpaceMask;
    if (!is_read_write_family(command) || bits == 0) return std::nullopt;
    return static_cast<Space>(0xFC + bits);
}

/// The read/write-family command without its space bits (e.g. 0x43 -> 0x40).
constexpr std::uint8_t family_of(std::uint8_t command) {
    return is_read_write_family(command) ? command & command_bits::kFamilyMask : command;
}

/// True when the command byte is a reply (read/write-family reply bit, or 0x82/0x86/0x87/...).
constexpr bool is_reply(std::uint8_t command) {
    if (is_read_write_family(command)) return (command & command_bits::kReply) != 0;
    switch (static_cast<Command>(command)) {
        case Command::kGetConfigOptionsReply:
        case Command::kSpaceInfoNotPresent:
        case Command::kSpaceInfoPresent:
        case Command::kLockReply:
        case Command::kGetUniqueIdReply:
            return true;
        default:
            return false;
    }
}

/// True when the command byte is a read/write-family failure reply (0x18, 0x58, 0x38, 0x78...).
constexpr bool is_fail(std::uint8_t command) {
    return is_read_write_family(command) && (command & command_bits::kReply) != 0 &&
           (command & command_bits::kFail) != 0;
}

/// True when the command byte is a read/write-family stream variant.
constexpr bool is_stream(std::uint8_t command) {
    return is_read_write_family(command) && (command & command_bits::kStream) != 0;
}

/// True when a read count is acceptable (1..64); anything else is rejected with 0x1080.
constexpr bool is_valid_read_count(std::uint8_t count) {
    return count >= 1 && count <= kMaxReadWrite;
}

}  // namespace olcb::memory
