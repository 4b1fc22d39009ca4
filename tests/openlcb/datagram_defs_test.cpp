// Datagram constants (openlcb/datagram_defs.hpp): Datagram Received OK flags and content types.
#include "openlcb/datagram_defs.hpp"

#include <gtest/gtest.h>

#include <chrono>

namespace olcb {
namespace {

TEST(DatagramDefs, OkFlags) {
    EXPECT_EQ(datagram::ok_flags(true), 0x80);
    EXPECT_EQ(datagram::ok_flags(true, 3), 0x83);
    EXPECT_EQ(datagram::ok_flags(false, 99), 0x0F);
    EXPECT_TRUE(datagram::is_reply_pending(0x80));
    EXPECT_FALSE(datagram::reply_timeout(0x80));
    EXPECT_EQ(datagram::reply_timeout(0x83), std::chrono::seconds(8));
    EXPECT_TRUE(datagram::is_two_byte_type(0xE5));
    EXPECT_TRUE(datagram::is_six_byte_type(0xF0));
    EXPECT_FALSE(datagram::is_six_byte_type(0x20));
    EXPECT_EQ(datagram::kMaxSize, 72u);
}

}  // namespace
}  // namespace olcb
