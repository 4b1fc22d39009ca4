// Train Control wire constants (TrainControlS §4, §7): the instruction and sub-command bytes of
// the Traction Control Command and Reply messages, their flag bits, the well-known event IDs and
// the protocol's memory spaces. The payload codecs are in train_control.hpp.
#pragma once

#include <cstdint>

#include "base/node_id.hpp"

namespace olcb::train {

/// Byte 0 of a command: bit 7 is the P bit (1 when a Train Node forwards the command to a
/// Listener, §4.3), bits 0-6 the instruction.
inline constexpr std::uint8_t kForwardedBit = 0x80;
inline constexpr std::uint8_t kInstructionMask = 0x7F;

/// Instructions (byte 0, bits 0-6) of commands; a reply carries the same value in byte 0.
enum class Instruction : std::uint8_t {
    kSetSpeed = 0x00,
    kSetFunction = 0x01,
    kEmergencyStop = 0x02,
    kQuerySpeeds = 0x10,
    kQueryFunction = 0x11,
    kController = 0x20,
    kListener = 0x30,
    kManagement = 0x40,
};

/// Byte 1 of Controller Configuration commands and replies.
enum class ControllerOp : std::uint8_t {
    kAssign = 0x01,
    kRelease = 0x02,
    kQuery = 0x03,
    kChangingNotify = 0x04,
};

/// Byte 1 of Listener Configuration commands and replies.
enum class ListenerOp : std::uint8_t {
    kAttach = 0x01,
    kDetach = 0x02,
    kQuery = 0x03,
};

/// Byte 1 of Train Control Management commands (Reserve, Release, No-op) and replies (Reserve
/// Reply, and the Heartbeat Request a train sends to its controller, which shares No-op's value).
enum class ManagementOp : std::uint8_t {
    kReserve = 0x01,
    kRelease = 0x02,
    kNoop = 0x03,
    kHeartbeatRequest = 0x03,
};

/// Listener flags (Attach Node byte 2, Query Nodes Reply byte 4). 0x01 is reserved.
namespace listener_flags {
inline constexpr std::uint8_t kReserved = 0x01;
inline constexpr std::uint8_t kReverse = 0x02;  ///< the forwarded speed's direction is flipped
inline constexpr std::uint8_t kLinkF0 = 0x04;   ///< Set Function of F0 is forwarded
inline constexpr std::uint8_t kLinkFn = 0x08;   ///< Set Function of any other number is forwarded
inline constexpr std::uint8_t kHide = 0x80;     ///< user interfaces do not show the listener
}  // namespace listener_flags

/// Query Speeds Reply status byte: bit 0 set iff in the Emergency Stop state (§4.4; TN §2.4.4).
inline constexpr std::uint8_t kStatusEmergencyStop = 0x01;

/// Assign Controller Reply result: 0 accepts; otherwise fail-code bits.
namespace assign_result {
inline constexpr std::uint8_t kOk = 0x00;
inline constexpr std::uint8_t kControllerRefused = 0x01;  ///< the assigned controller refused
inline constexpr std::uint8_t kTrainRefused = 0x02;       ///< the train refused
}  // namespace assign_result

/// The Query Controller Reply's flags byte: every bit is reserved in the adopted standard (0x01
/// was "alias follows" in the earlier working note, which OpenMRN still sends).
inline constexpr std::uint8_t kControllerFlagsReserved = 0xFF;

/// Error codes Train Control names (§4.2).
namespace error {
inline constexpr std::uint16_t kNotController = 0x1021;  ///< source not permitted: not a controller
inline constexpr std::uint16_t kNotFound = 0x1030;       ///< e.g. detaching a node not attached
inline constexpr std::uint16_t kAlreadyExists = 0x1032;  ///< e.g. attaching the train to itself
}  // namespace error

/// Well-known event IDs (§4.1).
inline constexpr EventId kIsTrain{0x0101'0000'0000'0303ull};
inline constexpr EventId kEmergencyStopAll{0x0100'0000'0000'FFFDull};
inline constexpr EventId kClearEmergencyStopAll{0x0100'0000'0000'FFFCull};
inline constexpr EventId kEmergencyOffAll{0x0100'0000'0000'FFFFull};
inline constexpr EventId kClearEmergencyOffAll{0x0100'0000'0000'FFFEull};

/// Memory spaces (§7): function values, one byte each, and the FDI (read-only XML).
inline constexpr std::uint8_t kFunctionSpace = 0xF9;
inline constexpr std::uint8_t kFdiSpace = 0xFA;
/// The highest address of F0-F68 in the function space (§7.1).
inline constexpr std::uint32_t kLastBasicFunction = 0x44;

/// Float16 NaN: what a node sends for a speed it cannot provide (§4.4).
inline constexpr std::uint16_t kSpeedUnknown = 0xFFFF;

}  // namespace olcb::train
