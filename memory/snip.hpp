// Simple Node Information Protocol payload: version bytes and the six identification strings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace olcb::memory {

/// Manufacturer-section version byte this codec sends (= number of strings in that section).
inline constexpr std::uint8_t kSnipManufacturerVersion = 4;
/// User-section version byte this codec sends.
inline constexpr std::uint8_t kSnipUserVersion = 2;
/// Version byte value old nodes send in either section, meaning 4 resp. 2.
inline constexpr std::uint8_t kSnipLegacyVersion = 1;
/// Maximum sizes of each string, NUL included.
inline constexpr std::size_t kSnipManufacturerMax = 41;
inline constexpr std::size_t kSnipModelMax = 41;
inline constexpr std::size_t kSnipHardwareVersionMax = 21;
inline constexpr std::size_t kSnipSoftwareVersionMax = 21;
inline constexpr std::size_t kSnipUserNameMax = 63;
inline constexpr std::size_t kSnipUserDescriptionMax = 64;
/// Largest payload this codec produces (2 version bytes + the six maxima).
inline constexpr std::size_t kSnipMaxPayload = 253;

/// The content of a SNIP reply.
struct Snip {
    std::uint8_t manufacturer_version = kSnipManufacturerVersion;  ///< as received
    std::string manufacturer;
    std::string model;
    std::string hardware_version;
    std::string software_version;
    std::uint8_t user_version = kSnipUserVersion;  ///< as received
    std::string user_name;
    std::string user_description;
    friend bool operator==(const Snip&, const Snip&) = default;
};

/// The longest prefix of text before its first NUL that fits max_bytes without splitting a
/// UTF-8 sequence (base::truncate_utf8 of the text before the NUL).
std::string_view clamp_utf8(std::string_view text, std::size_t max_bytes);

/// Encodes a SNIP payload: version bytes 4 and 2, each string clamped to its maximum (NUL
/// included) and sent with its real length + NUL.
std::vector<std::uint8_t> encode_snip(const Snip& snip);

/// Decodes tolerantly: legacy version 1 means 4/2, extra strings of higher versions are skipped,
/// missing trailing fields are empty, a string without NUL runs to the payload end.
Snip decode_snip(std::span<const std::uint8_t> payload);

/// Length of the complete SNIP payload at the start of bytes (version bytes and NULs counted as
/// their sections demand), nullopt while more bytes are needed.
std::optional<std::size_t> complete_snip_size(std::span<const std::uint8_t> bytes);

/// True when bytes already hold a whole SNIP payload (for legacy nodes sending f=0 frames).
bool is_complete_snip(std::span<const std::uint8_t> bytes);

}  // namespace olcb::memory
