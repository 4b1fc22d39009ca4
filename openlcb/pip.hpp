// Protocol Support Reply flags (fact sheet 3.1): which protocols a node implements.
#pragma once

#include <array>
#include <cstdint>
#include <initializer_list>
#include <span>
#include <string_view>

namespace olcb {

/// One protocol bit; the value is its bit in a 48-bit word whose top byte is wire byte 0.
enum class Protocol : std::uint64_t {
    kSimpleProtocol = 1ull << 47,
    kDatagram = 1ull << 46,
    kStream = 1ull << 45,
    kMemoryConfiguration = 1ull << 44,
    kReservation = 1ull << 43,
    kEventExchange = 1ull << 42,
    kIdentification = 1ull << 41,
    kTeachingLearning = 1ull << 40,
    kRemoteButton = 1ull << 39,
    kAcdi = 1ull << 38,
    kDisplay = 1ull << 37,
    kSnip = 1ull << 36,
    kCdi = 1ull << 35,
    kTractionControl = 1ull << 34,
    kFdi = 1ull << 33,
    kFunctionConfiguration = 1ull << 30,
    kFirmwareUpgrade = 1ull << 29,
    kFirmwareUpgradeActive = 1ull << 28,
};

/// The protocol's name as the standard gives it ("Traction Control").
constexpr std::string_view protocol_name(Protocol p) {
    switch (p) {
        case Protocol::kSimpleProtocol:
            return "Simple Protocol";
        case Protocol::kDatagram:
            return "Datagram";
        case Protocol::kStream:
            return "Stream";
        case Protocol::kMemoryConfiguration:
            return "Memory Configuration";
        case Protocol::kReservation:
            return "Reservation";
        case Protocol::kEventExchange:
            return "Event Exchange";
        case Protocol::kIdentification:
            return "Identification";
        case Protocol::kTeachingLearning:
            return "Teaching/Learning Configuration";
        case Protocol::kRemoteButton:
            return "Remote Button";
        case Protocol::kAcdi:
            return "Abbreviated Default CDI";
        case Protocol::kDisplay:
            return "Display";
        case Protocol::kSnip:
            return "Simple Node Information";
        case Protocol::kCdi:
            return "Configuration Description Information";
        case Protocol::kTractionControl:
            return "Traction Control";
        case Protocol::kFdi:
            return "Function Description Information";
        case Protocol::kFunctionConfiguration:
            return "Function Configuration";
        case Protocol::kFirmwareUpgrade:
            return "Firmware Upgrade";
        case Protocol::kFirmwareUpgradeActive:
            return "Firmware Upgrade Active";
    }
    return "unknown protocol";
}

/// A set of Protocol flags with the 6-byte wire codec.
class ProtocolSet {
public:
    /// Number of flag bytes a full reply carries.
    static constexpr std::size_t kWireSize = 6;

    /// The empty set.
    constexpr ProtocolSet() = default;
    /// The set of the listed protocols.
    constexpr ProtocolSet(std::initializer_list<Protocol> protocols) {
        for (Protocol p : protocols) set(p);
    }
    /// Set from a raw 48-bit word (byte 0 most significant); bits above 47 are dropped.
    static constexpr ProtocolSet from_bits(std::uint64_t bits) {
        ProtocolSet s;
        s.bits_ = bits & 0xFFFF'FFFF'FFFFull;
        return s;
    }
    /// Raw 48-bit word, reserved bits included as received.
    constexpr std::uint64_t bits() const { return bits_; }
    /// True when p is in the set.
    constexpr bool has(Protocol p) const { return (bits_ & static_cast<std::uint64_t>(p)) != 0; }
    /// Adds or removes p.
    constexpr ProtocolSet& set(Protocol p, bool on = true) {
        if (on) {
            bits_ |= static_cast<std::uint64_t>(p);
        } else {
            bits_ &= ~static_cast<std::uint64_t>(p);
        }
        return *this;
    }
    /// The 6 flag bytes, byte 0 first.
    constexpr std::array<std::uint8_t, kWireSize> encode() const {
        std::array<std::uint8_t, kWireSize> out{};
        for (std::size_t i = 0; i < kWireSize; ++i) {
            out[i] = static_cast<std::uint8_t>(bits_ >> (8 * (kWireSize - 1 - i)));
        }
        return out;
    }
    /// Set from received flag bytes: missing trailing bytes read as 0, extra bytes are ignored.
    static constexpr ProtocolSet decode(std::span<const std::uint8_t> bytes) {
        std::uint64_t bits = 0;
        for (std::size_t i = 0; i < kWireSize; ++i) {
            bits = bits << 8 | (i < bytes.size() ? bytes[i] : 0);
        }
        return from_bits(bits);
    }

    /// Union of two sets.
    friend constexpr ProtocolSet operator|(ProtocolSet a, ProtocolSet b) {
        return from_bits(a.bits_ | b.bits_);
    }
    /// Same bits.
    friend constexpr bool operator==(ProtocolSet, ProtocolSet) = default;

private:
    std::uint64_t bits_ = 0;
};

}  // namespace olcb
