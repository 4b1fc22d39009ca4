// The encoding faults: integers, strings, event IDs and floats stored in a wrong form.
#include <gtest/gtest.h>

#include <cstring>

#include "simnode/faults/fault_test_util.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(FaultTest, IntByteOrder) {
    start_with({"int-byte-order"});
    EXPECT_EQ(read(0xFD, kTrim, 2), (std::vector<std::uint8_t>{0xFB, 0xFF}));  // -5 little-endian
    write_ok(0xFD, kDelay, {0, 0, 1, 2});
    EXPECT_EQ(read(0xFD, kDelay, 4), (std::vector<std::uint8_t>{2, 1, 0, 0}));
}

TEST_F(FaultTest, StringUnterminated) {
    start_with({"string-unterminated"});
    EXPECT_EQ(read(0xFD, kLabel, 16), bytes_of("                "));
    write_ok(0xFD, kLabel, {'a', 'b', 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    EXPECT_EQ(read(0xFD, kLabel, 16), bytes_of("ab              "));
    EXPECT_EQ(node_->snip().user_name, "Test node") << "ACDI strings keep their NUL";
}

TEST_F(FaultTest, EventIdByteOrder) {
    start_with({"eventid-byte-order"});
    const auto frames = take();
    EXPECT_EQ(read(0xFD, kPort0On, 8), (std::vector<std::uint8_t>{0, 0, 0, 0x22, 1, 1, 1, 5}));
    EXPECT_EQ(count_prefix(frames, ":X194C7343N0000002201010105"), 1u);
    write_ok(0xFD, kPort0On, {1, 2, 3, 4, 5, 6, 7, 8});
    EXPECT_EQ(read(0xFD, kPort0On, 8), (std::vector<std::uint8_t>{8, 7, 6, 5, 4, 3, 2, 1}));
}

TEST_F(FaultTest, FloatWidth) {
    start_with({"float-width"});
    double tenth = 0.1;
    std::uint64_t bits = 0;
    std::memcpy(&bits, &tenth, 8);
    std::vector<std::uint8_t> be(8);
    for (int i = 0; i < 8; ++i) be[i] = static_cast<std::uint8_t>(bits >> (56 - 8 * i));
    write_ok(0xFD, kScale, be);
    const auto back = read(0xFD, kScale, 8);
    EXPECT_NE(back, be);
    const double as_float = static_cast<float>(0.1);
    std::memcpy(&bits, &as_float, 8);
    for (int i = 0; i < 8; ++i) be[i] = static_cast<std::uint8_t>(bits >> (56 - 8 * i));
    EXPECT_EQ(back, be) << "stored with single precision";
}

}  // namespace
}  // namespace olcb::simnode::test
