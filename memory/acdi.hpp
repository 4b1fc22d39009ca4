// ACDI memory spaces 252 (manufacturer, read-only) and 251 (user, read/write): fixed NUL-padded
// slots that carry the same strings as SNIP.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "memory/memory_config_defs.hpp"
#include "memory/snip.hpp"

namespace olcb::memory {

/// Layout of the ACDI spaces (byte offsets and slot sizes, NUL included). A slot holds the SNIP
/// string of the same name, so its size and the version bytes are SNIP's (memory/snip.hpp); the
/// slots follow each other after the version byte.
namespace acdi {
inline constexpr Space kManufacturerSpace = Space::kAcdiManufacturer;
inline constexpr std::size_t kManufacturerVersionOffset = 0;
inline constexpr std::size_t kManufacturerOffset = 1;
inline constexpr std::size_t kManufacturerSize = kSnipManufacturerMax;
inline constexpr std::size_t kModelOffset = kManufacturerOffset + kManufacturerSize;
inline constexpr std::size_t kModelSize = kSnipModelMax;
inline constexpr std::size_t kHardwareVersionOffset = kModelOffset + kModelSize;
inline constexpr std::size_t kHardwareVersionSize = kSnipHardwareVersionMax;
inline constexpr std::size_t kSoftwareVersionOffset = kHardwareVersionOffset + kHardwareVersionSize;
inline constexpr std::size_t kSoftwareVersionSize = kSnipSoftwareVersionMax;
inline constexpr std::size_t kManufacturerBlockSize = kSoftwareVersionOffset + kSoftwareVersionSize;
/// Default of <acdi fixed=...>.
inline constexpr std::uint8_t kManufacturerVersion = kSnipManufacturerVersion;

inline constexpr Space kUserSpace = Space::kAcdiUser;
inline constexpr std::size_t kUserVersionOffset = 0;
inline constexpr std::size_t kUserNameOffset = 1;
inline constexpr std::size_t kUserNameSize = kSnipUserNameMax;
inline constexpr std::size_t kUserDescriptionOffset = kUserNameOffset + kUserNameSize;
inline constexpr std::size_t kUserDescriptionSize = kSnipUserDescriptionMax;
inline constexpr std::size_t kUserBlockSize = kUserDescriptionOffset + kUserDescriptionSize;
/// Default of <acdi var=...>.
inline constexpr std::uint8_t kUserVersion = kSnipUserVersion;
}  // namespace acdi

/// Content of space 252.
struct AcdiManufacturer {
    std::uint8_t version = acdi::kManufacturerVersion;
    std::string manufacturer;
    std::string model;
    std::string hardware_version;
    std::string software_version;
    friend bool operator==(const AcdiManufacturer&, const AcdiManufacturer&) = default;
};

/// Content of space 251.
struct AcdiUser {
    std::uint8_t version = acdi::kUserVersion;
    std::string name;
    std::string description;
    friend bool operator==(const AcdiUser&, const AcdiUser&) = default;
};

/// The 125-byte image of space 252; strings clamped to slot size - 1, rest zero.
std::array<std::uint8_t, acdi::kManufacturerBlockSize> encode_acdi_manufacturer(
    const AcdiManufacturer& data);

/// The 128-byte image of space 251; strings clamped to slot size - 1, rest zero.
std::array<std::uint8_t, acdi::kUserBlockSize> encode_acdi_user(const AcdiUser& data);

/// Reads space 252 from an image (short images: missing fields are empty / version 0).
AcdiManufacturer decode_acdi_manufacturer(std::span<const std::uint8_t> block);

/// Reads space 251 from an image (short images: missing fields are empty / version 0).
AcdiUser decode_acdi_user(std::span<const std::uint8_t> block);

/// SNIP content equal to what the ACDI spaces hold, so SNIP and ACDI always agree.
Snip snip_from_acdi(const AcdiManufacturer& manufacturer, const AcdiUser& user);

/// SNIP content built straight from the space 252 and 251 images.
Snip snip_from_acdi(std::span<const std::uint8_t> manufacturer_block,
                    std::span<const std::uint8_t> user_block);

}  // namespace olcb::memory
