#include "memory/acdi.hpp"

#include <algorithm>
#include <string_view>

namespace olcb::memory {
namespace {

// The last byte of every slot stays 0 so the string is always NUL-terminated.
void put_slot(std::span<std::uint8_t> block, std::size_t offset, std::size_t size,
              std::string_view text) {
    const std::string_view clamped = clamp_utf8(text, size - 1);
    std::copy(clamped.begin(), clamped.end(), block.begin() + static_cast<std::ptrdiff_t>(offset));
}

// A slot without NUL is cut to size - 1 like an encoder would, so decode and SNIP agree.
std::string get_slot(std::span<const std::uint8_t> block, std::size_t offset, std::size_t size) {
    if (offset >= block.size()) return {};
    const std::size_t available = std::min(size, block.size() - offset);
    const std::string_view raw(reinterpret_cast<const char*>(block.data() + offset), available);
    return std::string(clamp_utf8(raw, size - 1));
}

std::uint8_t get_version(std::span<const std::uint8_t> block, std::size_t offset) {
    return offset < block.size() ? block[offset] : 0;
}

}  // namespace

std::array<std::uint8_t, acdi::kManufacturerBlockSize> encode_acdi_manufacturer(
    const AcdiManufacturer& data) {
    std::array<std::uint8_t, acdi::kManufacturerBlockSize> block{};
    block[acdi::kManufacturerVersionOffset] = data.version;
    put_slot(block, acdi::kManufacturerOffset, acdi::kManufacturerSize, data.manufacturer);
    put_slot(block, acdi::kModelOffset, acdi::kModelSize, data.model);
    put_slot(block, acdi::kHardwareVersionOffset, acdi::kHardwareVersionSize,
             data.hardware_version);
    put_slot(block, acdi::kSoftwareVersionOffset, acdi::kSoftwareVersionSize,
             data.software_version);
    return block;
}

std::array<std::uint8_t, acdi::kUserBlockSize> encode_acdi_user(const AcdiUser& data) {
    std::array<std::uint8_t, acdi::kUserBlockSize> block{};
    block[acdi::kUserVersionOffset] = data.version;
    put_slot(block, acdi::kUserNameOffset, acdi::kUserNameSize, data.name);
    put_slot(block, acdi::kUserDescriptionOffset, acdi::kUserDescriptionSize, data.description);
    return block;
}

AcdiManufacturer decode_acdi_manufacturer(std::span<const std::uint8_t> block) {
    AcdiManufacturer data;
    data.version = get_version(block, acdi::kManufacturerVersionOffset);
    data.manufacturer = get_slot(block, acdi::kManufacturerOffset, acdi::kManufacturerSize);
    data.model = get_slot(block, acdi::kModelOffset, acdi::kModelSize);
    data.hardware_version =
        get_slot(block, acdi::kHardwareVersionOffset, acdi::kHardwareVersionSize);
    data.software_version =
        get_slot(block, acdi::kSoftwareVersionOffset, acdi::kSoftwareVersionSize);
    return data;
}

AcdiUser decode_acdi_user(std::span<const std::uint8_t> block) {
    AcdiUser data;
    data.version = get_version(block, acdi::kUserVersionOffset);
    data.name = get_slot(block, acdi::kUserNameOffset, acdi::kUserNameSize);
    data.description = get_slot(block, acdi::kUserDescriptionOffset, acdi::kUserDescriptionSize);
    return data;
}

Snip snip_from_acdi(const AcdiManufacturer& manufacturer, const AcdiUser& user) {
    // Clamping to the slot sizes makes the SNIP strings exactly what a reader of the spaces sees,
    // even when the structs hold longer strings than the slots can.
    const auto slot = [](const std::string& text, std::size_t size) {
        return std::string(clamp_utf8(text, size - 1));
    };
    Snip snip;
    snip.manufacturer = slot(manufacturer.manufacturer, acdi::kManufacturerSize);
    snip.model = slot(manufacturer.model, acdi::kModelSize);
    snip.hardware_version = slot(manufacturer.hardware_version, acdi::kHardwareVersionSize);
    snip.software_version = slot(manufacturer.software_version, acdi::kSoftwareVersionSize);
    snip.user_name = slot(user.name, acdi::kUserNameSize);
    snip.user_description = slot(user.description, acdi::kUserDescriptionSize);
    return snip;
}

Snip snip_from_acdi(std::span<const std::uint8_t> manufacturer_block,
                    std::span<const std::uint8_t> user_block) {
    return snip_from_acdi(decode_acdi_manufacturer(manufacturer_block),
                          decode_acdi_user(user_block));
}

}  // namespace olcb::memory
