// OpenLCB 16-bit error codes (MessageNetworkS table plus Memory Configuration's 0x1081..0x1083),
// carried by Optional Interaction Rejected, Terminate Due to Error, Datagram Rejected and the
// memory-config failure replies. The project's one definition of them.
#pragma once

#include <cstdint>
#include <string_view>

namespace olcb::base {

/// An error code as it travels: any 16-bit value may arrive, the names cover the standard's table.
enum class ErrorCode : std::uint16_t {
    kNone = 0x0000,                         ///< no information (allowed, not ideal)
    kPermanent = 0x1000,                    ///< permanent error, unspecified
    kSourceNotPermitted = 0x1020,           ///< source not permitted
    kNotFound = 0x1030,                     ///< not found
    kNotImplemented = 0x1040,               ///< not implemented
    kSubcommandUnknown = 0x1041,            ///< subcommand unknown
    kCommandUnknown = 0x1042,               ///< datagram type, stream type or command unknown
    kUnknownMtiOrTransport = 0x1043,        ///< unknown MTI, or datagram/stream not supported
    kInvalidArguments = 0x1080,             ///< invalid arguments (e.g. read count 0 or > 64)
    kSpaceUnknown = 0x1081,                 ///< memory config: address space unknown
    kOutOfBounds = 0x1082,                  ///< memory config: address out of bounds
    kReadOnly = 0x1083,                     ///< memory config: write to a read-only space
    kTemporary = 0x2000,                    ///< temporary error ("resend OK"), unspecified
    kTimeout = 0x2010,                      ///< timeout
    kTimeoutWaitingForEnd = 0x2011,         ///< timeout waiting for the end frame
    kBufferUnavailable = 0x2020,            ///< buffer unavailable / destination busy
    kOutOfOrder = 0x2040,                   ///< out of order
    kMiddleOrLastWithoutFirst = 0x2041,     ///< middle or last frame without a first
    kFirstBeforePreviousFinished = 0x2042,  ///< first frame before the previous one finished
    kTransferError = 0x2080,                ///< transfer error (ill-formed, checksum)
    kAccept = 0x8000,                       ///< the accept type flag; never in a reject
};

/// Mask of the type flags (bits 15-12; at most one is set: 0x1000, 0x2000 or 0x8000).
inline constexpr std::uint16_t kErrorTypeMask = 0xF000;

/// The raw 16-bit value of a code.
constexpr std::uint16_t to_u16(ErrorCode code) {
    return static_cast<std::uint16_t>(code);
}

/// True when the type bits say permanent (exactly 0x1000): the sender must not resend.
constexpr bool is_permanent(std::uint16_t code) {
    return (code & kErrorTypeMask) == to_u16(ErrorCode::kPermanent);
}
/// True when the type bits say permanent.
constexpr bool is_permanent(ErrorCode code) {
    return is_permanent(to_u16(code));
}

/// True when the type bits say temporary (exactly 0x2000): resending later may succeed.
constexpr bool is_temporary(std::uint16_t code) {
    return (code & kErrorTypeMask) == to_u16(ErrorCode::kTemporary);
}
/// True when the type bits say temporary.
constexpr bool is_temporary(ErrorCode code) {
    return is_temporary(to_u16(code));
}

/// Short English name of a code of the table ("address out of bounds"); "" for any other value.
constexpr std::string_view error_name(ErrorCode code) {
    switch (code) {
        case ErrorCode::kNone:
            return "no information";
        case ErrorCode::kPermanent:
            return "permanent error";
        case ErrorCode::kSourceNotPermitted:
            return "source not permitted";
        case ErrorCode::kNotFound:
            return "not found";
        case ErrorCode::kNotImplemented:
            return "not implemented";
        case ErrorCode::kSubcommandUnknown:
            return "subcommand unknown";
        case ErrorCode::kCommandUnknown:
            return "command or type unknown";
        case ErrorCode::kUnknownMtiOrTransport:
            return "unknown MTI or transport not supported";
        case ErrorCode::kInvalidArguments:
            return "invalid arguments";
        case ErrorCode::kSpaceUnknown:
            return "address space unknown";
        case ErrorCode::kOutOfBounds:
            return "address out of bounds";
        case ErrorCode::kReadOnly:
            return "write to read-only space";
        case ErrorCode::kTemporary:
            return "temporary error";
        case ErrorCode::kTimeout:
            return "timeout";
        case ErrorCode::kTimeoutWaitingForEnd:
            return "timeout waiting for end frame";
        case ErrorCode::kBufferUnavailable:
            return "buffer unavailable";
        case ErrorCode::kOutOfOrder:
            return "out of order";
        case ErrorCode::kMiddleOrLastWithoutFirst:
            return "middle or last frame without first";
        case ErrorCode::kFirstBeforePreviousFinished:
            return "first frame before previous finished";
        case ErrorCode::kTransferError:
            return "transfer error";
        case ErrorCode::kAccept:
            return "accept";
    }
    return "";
}

/// The name of a code of the table, else of its type ("temporary error"), else "unknown error".
constexpr std::string_view describe_error(std::uint16_t code) {
    if (const std::string_view name = error_name(ErrorCode{code}); !name.empty()) return name;
    if (is_permanent(code)) return "permanent error";
    if (is_temporary(code)) return "temporary error";
    return "unknown error";
}

}  // namespace olcb::base
