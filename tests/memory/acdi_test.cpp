#include "memory/acdi.hpp"

#include <gtest/gtest.h>

#include <string>

namespace olcb::memory {
namespace {

std::string slot(std::span<const std::uint8_t> block, std::size_t offset, std::size_t size) {
    const auto bytes = block.subspan(offset, size);
    return std::string(bytes.begin(), bytes.end());
}

AcdiManufacturer example_manufacturer() {
    return AcdiManufacturer{4, "ACME Sim", "CDI Node", "1.0", "0.3.1"};
}

AcdiUser example_user() {
    return AcdiUser{2, "Test node", "Bench"};
}

TEST(Acdi, LayoutConstantsTileTheSpaces) {
    EXPECT_EQ(acdi::kManufacturerSpace, Space{0xFC});
    EXPECT_EQ(acdi::kUserSpace, Space{0xFB});
    EXPECT_EQ(acdi::kManufacturerOffset, 1u);
    EXPECT_EQ(acdi::kModelOffset, acdi::kManufacturerOffset + acdi::kManufacturerSize);
    EXPECT_EQ(acdi::kHardwareVersionOffset, acdi::kModelOffset + acdi::kModelSize);
    EXPECT_EQ(acdi::kSoftwareVersionOffset,
              acdi::kHardwareVersionOffset + acdi::kHardwareVersionSize);
    EXPECT_EQ(acdi::kManufacturerBlockSize,
              acdi::kSoftwareVersionOffset + acdi::kSoftwareVersionSize);
    EXPECT_EQ(acdi::kManufacturerBlockSize, 125u);
    // The offsets the standard's table gives (the layout derives them from SNIP's sizes).
    EXPECT_EQ(acdi::kModelOffset, 42u);
    EXPECT_EQ(acdi::kHardwareVersionOffset, 83u);
    EXPECT_EQ(acdi::kSoftwareVersionOffset, 104u);
    EXPECT_EQ(acdi::kUserDescriptionOffset, 64u);
    EXPECT_EQ(acdi::kUserNameOffset, 1u);
    EXPECT_EQ(acdi::kUserDescriptionOffset, acdi::kUserNameOffset + acdi::kUserNameSize);
    EXPECT_EQ(acdi::kUserBlockSize, acdi::kUserDescriptionOffset + acdi::kUserDescriptionSize);
    EXPECT_EQ(acdi::kUserBlockSize, 128u);
}

TEST(Acdi, ManufacturerBlockIsNulPaddedAtFixedOffsets) {
    const auto block = encode_acdi_manufacturer(example_manufacturer());
    EXPECT_EQ(block.size(), 125u);
    EXPECT_EQ(block[0], 4);
    EXPECT_EQ(slot(block, 1, 41), std::string("ACME Sim") + std::string(33, '\0'));
    EXPECT_EQ(slot(block, 42, 41), std::string("CDI Node") + std::string(33, '\0'));
    EXPECT_EQ(slot(block, 83, 21), std::string("1.0") + std::string(18, '\0'));
    EXPECT_EQ(slot(block, 104, 21), std::string("0.3.1") + std::string(16, '\0'));
    EXPECT_EQ(decode_acdi_manufacturer(block), example_manufacturer());
}

TEST(Acdi, UserBlockIsNulPaddedAtFixedOffsets) {
    const auto block = encode_acdi_user(example_user());
    EXPECT_EQ(block.size(), 128u);
    EXPECT_EQ(block[0], 2);
    EXPECT_EQ(slot(block, 1, 63), std::string("Test node") + std::string(54, '\0'));
    EXPECT_EQ(slot(block, 64, 64), std::string("Bench") + std::string(59, '\0'));
    EXPECT_EQ(decode_acdi_user(block), example_user());
}

TEST(Acdi, LongStringsKeepTheirSlotTerminator) {
    AcdiUser user{2, std::string(80, 'n'), std::string(80, 'd')};
    const auto block = encode_acdi_user(user);
    EXPECT_EQ(block[acdi::kUserNameOffset + acdi::kUserNameSize - 1], 0);
    EXPECT_EQ(block[acdi::kUserDescriptionOffset + acdi::kUserDescriptionSize - 1], 0);
    const AcdiUser back = decode_acdi_user(block);
    EXPECT_EQ(back.name, std::string(62, 'n'));
    EXPECT_EQ(back.description, std::string(63, 'd'));
}

TEST(Acdi, SlotWithoutNulIsCutToSlotSizeMinusOne) {
    std::array<std::uint8_t, 125> block{};
    block.fill('x');
    const AcdiManufacturer data = decode_acdi_manufacturer(block);
    EXPECT_EQ(data.manufacturer, std::string(40, 'x'));
    EXPECT_EQ(data.hardware_version, std::string(20, 'x'));
}

TEST(Acdi, ShortImagesGiveEmptyFields) {
    const std::vector<std::uint8_t> partial{4, 'A', 'B'};
    const AcdiManufacturer data = decode_acdi_manufacturer(partial);
    EXPECT_EQ(data.version, 4);
    EXPECT_EQ(data.manufacturer, "AB");
    EXPECT_EQ(data.model, "");
    EXPECT_EQ(decode_acdi_user({}).version, 0);
}

TEST(Acdi, SnipFromAcdiEqualsTheWorkedExample) {
    const auto m = encode_acdi_manufacturer(example_manufacturer());
    const auto u = encode_acdi_user(example_user());
    const Snip snip = snip_from_acdi(m, u);
    EXPECT_EQ(snip.manufacturer, "ACME Sim");
    EXPECT_EQ(snip.user_description, "Bench");
    EXPECT_EQ(encode_snip(snip).size(), 46u);
    EXPECT_EQ(snip.manufacturer_version, 4);
    EXPECT_EQ(snip.user_version, 2);
}

TEST(Acdi, SnipAndAcdiAgreeEvenForOverlongOrUtf8Strings) {
    const AcdiManufacturer m{4, std::string(39, 'a') + "\xC3\xA9", std::string(60, 'b'), "hw",
                             std::string(30, 's')};
    const AcdiUser u{2, std::string(61, 'n') + "\xE2\x82\xAC", std::string(70, 'd')};
    const Snip from_structs = snip_from_acdi(m, u);
    const Snip from_blocks = snip_from_acdi(encode_acdi_manufacturer(m), encode_acdi_user(u));
    EXPECT_EQ(from_structs, from_blocks);
    // And what a SNIP requester decodes is exactly what a space reader sees.
    EXPECT_EQ(decode_snip(encode_snip(from_blocks)), from_blocks);
    EXPECT_EQ(from_blocks.manufacturer, std::string(39, 'a'));  // "é" does not fit in 40
    EXPECT_EQ(from_blocks.user_name, std::string(61, 'n'));     // "€" does not fit in 62
}

}  // namespace
}  // namespace olcb::memory
