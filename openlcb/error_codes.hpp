// OpenLCB 16-bit error codes (fact sheet 3.2), carried by OIR, TDE and Datagram Rejected.
#pragma once

#include <cstdint>
#include <string_view>

namespace olcb::error_code {

/// Type flag: the condition will not go away; the sender must not resend.
inline constexpr std::uint16_t kPermanent = 0x1000;
/// Type flag: resending later may succeed.
inline constexpr std::uint16_t kTemporary = 0x2000;
/// Type flag: acceptance; never appears in a reject.
inline constexpr std::uint16_t kAccept = 0x8000;
/// Mask of the type flags (bits 15-12).
inline constexpr std::uint16_t kTypeMask = 0xF000;

inline constexpr std::uint16_t kNoInformation = 0x0000;
inline constexpr std::uint16_t kPermanentError = 0x1000;
inline constexpr std::uint16_t kSourceNotPermitted = 0x1020;
inline constexpr std::uint16_t kNotFound = 0x1030;
inline constexpr std::uint16_t kNotImplemented = 0x1040;
inline constexpr std::uint16_t kSubcommandUnknown = 0x1041;
inline constexpr std::uint16_t kCommandUnknown = 0x1042;  ///< also datagram/stream type unknown
inline constexpr std::uint16_t kUnknownMtiOrTransport = 0x1043;
inline constexpr std::uint16_t kInvalidArguments = 0x1080;
inline constexpr std::uint16_t kAddressSpaceUnknown = 0x1081;
inline constexpr std::uint16_t kOutOfBounds = 0x1082;
inline constexpr std::uint16_t kWriteToReadOnly = 0x1083;
inline constexpr std::uint16_t kTemporaryError = 0x2000;
inline constexpr std::uint16_t kTimeout = 0x2010;
inline constexpr std::uint16_t kTimeoutWaitingForEnd = 0x2011;
inline constexpr std::uint16_t kBufferUnavailable = 0x2020;
inline constexpr std::uint16_t kOutOfOrder = 0x2040;
inline constexpr std::uint16_t kMiddleOrLastWithoutFirst = 0x2041;
inline constexpr std::uint16_t kFirstBeforePreviousFinished = 0x2042;
inline constexpr std::uint16_t kTransferError = 0x2080;

/// True when the temporary flag is set ("resend OK").
constexpr bool is_temporary(std::uint16_t code) {
    return (code & kTemporary) != 0;
}
/// True when the permanent flag is set (do not resend).
constexpr bool is_permanent(std::uint16_t code) {
    return (code & kPermanent) != 0;
}

/// Short description of a code of the table, else of its type class ("temporary error").
constexpr std::string_view describe(std::uint16_t code) {
    switch (code) {
        case kNoInformation:
            return "no information";
        case kPermanentError:
            return "permanent error";
        case kSourceNotPermitted:
            return "source not permitted";
        case kNotFound:
            return "not found";
        case kNotImplemented:
            return "not implemented";
        case kSubcommandUnknown:
            return "subcommand unknown";
        case kCommandUnknown:
            return "command or type unknown";
        case kUnknownMtiOrTransport:
            return "unknown MTI or transport not supported";
        case kInvalidArguments:
            return "invalid arguments";
        case kAddressSpaceUnknown:
            return "address space unknown";
        case kOutOfBounds:
            return "address out of bounds";
        case kWriteToReadOnly:
            return "write to read-only space";
        case kTemporaryError:
            return "temporary error";
        case kTimeout:
            return "timeout";
        case kTimeoutWaitingForEnd:
            return "timeout waiting for end frame";
        case kBufferUnavailable:
            return "buffer unavailable";
        case kOutOfOrder:
            return "out of order";
        case kMiddleOrLastWithoutFirst:
            return "middle or last frame without first";
        case kFirstBeforePreviousFinished:
            return "first frame before previous finished";
        case kTransferError:
            return "transfer error";
        case kAccept:
            return "accept";
        default:
            break;
    }
    if (is_permanent(code)) return "permanent error";
    if (is_temporary(code)) return "temporary error";
    return "unknown error";
}

}  // namespace olcb::error_code
