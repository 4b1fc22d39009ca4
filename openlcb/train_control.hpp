// Train Control payloads (TrainControlS §4.3, §4.4): a speed as the float16 the wire carries, and
// every command and reply decoded into a typed value and encoded back, byte for byte.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "base/node_id.hpp"
#include "openlcb/train_control_defs.hpp"

namespace olcb::train {

/// A speed and direction: IEEE float16 in scale metres per second, its sign the direction
/// (negative, -0 included, is reverse). Kept as the 16 bits themselves, so -0 and NaN survive.
class Speed {
public:
    constexpr Speed() = default;
    static constexpr Speed from_bits(std::uint16_t bits) { return Speed(bits); }
    /// value scale m/s forward (reverse = false) or reverse; the magnitude is rounded to float16.
    static Speed of(double value, bool reverse);
    static constexpr Speed unknown() { return Speed(kSpeedUnknown); }

    constexpr std::uint16_t bits() const { return bits_; }
    constexpr bool reverse() const { return (bits_ & 0x8000) != 0; }
    constexpr bool is_nan() const { return (bits_ & 0x7C00) == 0x7C00 && (bits_ & 0x03FF) != 0; }
    /// True for +0 and -0.
    constexpr bool is_zero() const { return (bits_ & 0x7FFF) == 0; }
    /// The magnitude in scale m/s.
    double magnitude() const;
    /// The same magnitude in the other direction.
    constexpr Speed flipped() const { return Speed(bits_ ^ 0x8000); }
    /// Zero in the same direction (what Emergency Stop and a heartbeat timeout leave).
    constexpr Speed stopped() const { return Speed(bits_ & 0x8000); }
    /// "0.75 reverse", "0 forward", "NaN (0xFFFF)": for reports.
    std::string to_string() const;

    friend constexpr bool operator==(Speed, Speed) = default;

private:
    constexpr explicit Speed(std::uint16_t bits) : bits_(bits) {}
    std::uint16_t bits_ = 0;
};

// ---- commands (Traction Control Command, MTI 0x05EB) ----

struct SetSpeed {
    Speed speed;
};
/// A function address is 24 bits on the wire (the function space's address with a zero top
/// byte).
struct SetFunction {
    std::uint32_t address = 0;
    std::uint16_t value = 0;
};
struct EmergencyStop {};
struct QuerySpeeds {};
struct QueryFunction {
    std::uint32_t address = 0;
};
struct AssignController {
    std::uint8_t flags = 0;
    NodeId controller;
};
struct ReleaseController {
    std::uint8_t flags = 0;
    NodeId controller;
};
struct QueryController {};
struct ControllerChangingNotify {
    std::uint8_t flags = 0;
    NodeId new_controller;
};
/// Attach Node, or update the flags of a node already attached.
struct AttachListener {
    std::uint8_t flags = 0;
    NodeId listener;
};
struct DetachListener {
    std::uint8_t flags = 0;
    NodeId listener;
};
/// Query Nodes; without an index the reply carries the count only.
struct QueryListeners {
    std::optional<std::uint8_t> index;
};
struct Reserve {};
struct Release {};
struct Noop {};

using CommandBody =
    std::variant<SetSpeed, SetFunction, EmergencyStop, QuerySpeeds, QueryFunction, AssignController,
                 ReleaseController, QueryController, ControllerChangingNotify, AttachListener,
                 DetachListener, QueryListeners, Reserve, Release, Noop>;

/// One command; forwarded is the P bit (meaningful for Set Speed, Set Function, E-Stop).
struct Command {
    CommandBody body;
    bool forwarded = false;
};

/// The payload of a command.
std::vector<std::uint8_t> encode(const Command& command);

// ---- replies (Traction Control Reply, MTI 0x01E9) ----

/// Query Speeds Reply: Set Speed, status (bit 0: Emergency Stop), Commanded and Actual Speed
/// (NaN when the node cannot tell).
struct SpeedsReply {
    Speed set;
    std::uint8_t status = 0;
    Speed commanded = Speed::unknown();
    Speed actual = Speed::unknown();
};
struct FunctionReply {
    std::uint32_t address = 0;
    std::uint16_t value = 0;
};
struct AssignReply {
    std::uint8_t result = assign_result::kOk;
};
/// Query Controller Reply: flags, then the active controller (zero: none).
struct ControllerReply {
    std::uint8_t flags = 0;
    NodeId controller;
};
struct ChangingNotifyReply {
    std::uint8_t result = 0;
};
/// Attach or Detach Node Reply: the node ID of the request and a 2-byte OpenLCB error code.
struct ListenerChangeReply {
    ListenerOp op = ListenerOp::kAttach;
    NodeId listener;
    std::uint16_t code = 0;
};
/// Query Nodes Reply: the count, and the entry when an index in range was asked.
struct ListenerEntry {
    std::uint8_t index = 0;
    std::uint8_t flags = 0;
    NodeId node;
};
struct ListenersReply {
    std::uint8_t count = 0;
    std::optional<ListenerEntry> entry;
};
struct ReserveReply {
    std::uint8_t result = 0;
};
/// Sent by a train to its controller: reply with any command within timeout seconds.
struct HeartbeatRequest {
    std::uint8_t timeout = 0;
};

using Reply =
    std::variant<SpeedsReply, FunctionReply, AssignReply, ControllerReply, ChangingNotifyReply,
                 ListenerChangeReply, ListenersReply, ReserveReply, HeartbeatRequest>;

/// The payload of a reply.
std::vector<std::uint8_t> encode(const Reply& reply);

/// A payload decoded, or why it could not be.
template <typename T>
struct Decoded {
    std::optional<T> value;
    std::string error;  ///< "" when value is set: "3 bytes, a Query Speeds Reply needs 8", ...
    bool ok() const { return value.has_value(); }
};

/// A command payload. Extra trailing bytes are accepted (optional fields of newer versions).
Decoded<Command> decode_command(std::span<const std::uint8_t> payload);
/// A reply payload, likewise.
Decoded<Reply> decode_reply(std::span<const std::uint8_t> payload);

/// "Set Speed 0.75 reverse", "Query Controller", ...: one line for traces and reports.
std::string describe(const Command& command);
std::string describe(const Reply& reply);

}  // namespace olcb::train
