#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "memory/memory_space.hpp"
#include "support/temp_files.hpp"

namespace olcb::memory {
namespace {

std::vector<std::uint8_t> bytes_of(std::string_view text) {
    return {text.begin(), text.end()};
}

TEST(ConstantSpace, ReadsAndRefusesWrites) {
    ConstantSpace space(bytes_of("abcdef"), "fixed");
    EXPECT_EQ(space.size(), 6u);
    EXPECT_TRUE(space.read_only());
    EXPECT_EQ(space.lowest_address(), 0u);
    EXPECT_EQ(space.description(), "fixed");
    std::array<std::uint8_t, 4> out{};
    EXPECT_EQ(space.read(1, out), 4u);
    EXPECT_EQ(out, (std::array<std::uint8_t, 4>{'b', 'c', 'd', 'e'}));
    EXPECT_EQ(space.read(4, out), 2u);  // cut at the end
    EXPECT_EQ(out[0], 'e');
    EXPECT_EQ(out[1], 'f');
    EXPECT_EQ(space.read(6, out), 0u);
    EXPECT_EQ(space.read(std::numeric_limits<std::uint32_t>::max(), out), 0u);
    EXPECT_EQ(space.write(0, bytes_of("X")), WriteStatus::kReadOnly);
    EXPECT_EQ(space.bytes()[0], 'a');
}

TEST(ConstantSpace, CdiEndsWithExactlyOneNul) {
    const ConstantSpace plain = ConstantSpace::from_cdi("<cdi/>");
    EXPECT_EQ(plain.size(), 7u);
    EXPECT_EQ(plain.bytes().back(), 0);
    using namespace std::string_view_literals;
    const ConstantSpace nul_ended = ConstantSpace::from_cdi("<cdi/>\0"sv);
    EXPECT_EQ(nul_ended.size(), 7u);
    const ConstantSpace embedded = ConstantSpace::from_cdi("<a/>\0junk"sv);
    EXPECT_EQ(embedded.size(), 5u);
    EXPECT_EQ(ConstantSpace::from_cdi("").size(), 1u);
}

TEST(RamSpace, WritesAllOrNothing) {
    RamSpace space(std::vector<std::uint8_t>(8, 0));
    EXPECT_FALSE(space.read_only());
    EXPECT_EQ(space.write(6, bytes_of("AB")), WriteStatus::kOk);
    EXPECT_EQ(space.bytes()[6], 'A');
    EXPECT_EQ(space.bytes()[7], 'B');
    EXPECT_EQ(space.write(7, bytes_of("CD")), WriteStatus::kOutOfBounds);
    EXPECT_EQ(space.bytes()[7], 'B');
    EXPECT_EQ(space.write(9, bytes_of("C")), WriteStatus::kOutOfBounds);
    EXPECT_EQ(space.write(std::numeric_limits<std::uint32_t>::max(), bytes_of("C")),
              WriteStatus::kOutOfBounds);
    EXPECT_EQ(space.write(8, {}), WriteStatus::kOk);  // empty write at the end is harmless
    std::array<std::uint8_t, 8> out{};
    EXPECT_EQ(space.read(0, out), 8u);
    EXPECT_EQ(out[6], 'A');
}

TEST(Fits, HandlesOverflow) {
    EXPECT_TRUE(fits(8, 0, 8));
    EXPECT_TRUE(fits(8, 8, 0));
    EXPECT_FALSE(fits(8, 8, 1));
    EXPECT_FALSE(fits(8, 0, 9));
    EXPECT_FALSE(fits(8, 0xFFFFFFFF, 2));
    EXPECT_TRUE(fits(0x100000000ULL, 0xFFFFFFFF, 1));
}

TEST(ReadClamped, CopiesWhatLiesInsideTheBytes) {
    const std::vector<std::uint8_t> bytes = bytes_of("0123");
    std::array<std::uint8_t, 3> out{'-', '-', '-'};
    EXPECT_EQ(read_clamped(bytes, 0, out), 3u);
    EXPECT_EQ(out, (std::array<std::uint8_t, 3>{'0', '1', '2'}));
    out.fill('-');
    EXPECT_EQ(read_clamped(bytes, 2, out), 2u);
    EXPECT_EQ(out, (std::array<std::uint8_t, 3>{'2', '3', '-'}));  // the rest untouched
    EXPECT_EQ(read_clamped(bytes, 4, out), 0u);
    EXPECT_EQ(read_clamped(bytes, std::numeric_limits<std::uint32_t>::max(), out), 0u);
    EXPECT_EQ(read_clamped(bytes, 1, std::span<std::uint8_t>()), 0u);
    EXPECT_EQ(read_clamped({}, 0, out), 0u);
}

TEST(WriteStatus, Names) {
    EXPECT_EQ(to_string(WriteStatus::kOk), "ok");
    EXPECT_EQ(to_string(WriteStatus::kReadOnly), "read-only");
    EXPECT_EQ(to_string(WriteStatus::kOutOfBounds), "out of bounds");
    EXPECT_EQ(to_string(WriteStatus::kIoError), "I/O error");
}

TEST(ForwardingSpace, ForwardsUnlessOverridden) {
    RamSpace inner(std::vector<std::uint8_t>(4, 0), "inner");
    struct ClaimsReadOnly : ForwardingSpace {
        using ForwardingSpace::ForwardingSpace;
        bool read_only() const override { return true; }
    } wrapper(inner);
    EXPECT_TRUE(wrapper.read_only());
    EXPECT_EQ(wrapper.size(), 4u);
    EXPECT_EQ(wrapper.description(), "inner");
    // Only what was overridden changes: the write still reaches the inner space.
    EXPECT_EQ(wrapper.write(0, bytes_of("Z")), WriteStatus::kOk);
    std::array<std::uint8_t, 1> out{};
    EXPECT_EQ(wrapper.read(0, out), 1u);
    EXPECT_EQ(out[0], 'Z');
}

class ImageSpaceTest : public ::testing::Test {
protected:
    std::unique_ptr<ImageFile> open_image() {
        ImageOpenResult result =
            ImageFile::open(dir_.path() / "fd.img", 64, [](auto image) { image[0] = 0x42; });
        EXPECT_TRUE(result.ok()) << result.error;
        return std::move(result.image);
    }

    test_support::TempDir dir_{"olcb_space"};
};

TEST_F(ImageSpaceTest, WritesPersistAcrossReopen) {
    {
        ImageSpace space(open_image(), "config");
        EXPECT_EQ(space.size(), 64u);
        EXPECT_FALSE(space.read_only());
        EXPECT_EQ(space.description(), "config");
        std::array<std::uint8_t, 2> out{};
        EXPECT_EQ(space.read(0, out), 2u);
        EXPECT_EQ(out[0], 0x42);
        EXPECT_EQ(space.write(62, bytes_of("xy")), WriteStatus::kOk);
        EXPECT_EQ(space.write(63, bytes_of("xy")), WriteStatus::kOutOfBounds);
    }
    ImageSpace again(open_image());
    std::array<std::uint8_t, 4> out{};
    EXPECT_EQ(again.read(60, out), 4u);
    EXPECT_EQ(out[2], 'x');
    EXPECT_EQ(out[3], 'y');
    EXPECT_EQ(again.image().bytes()[0], 0x42);
}

}  // namespace
}  // namespace olcb::memory
