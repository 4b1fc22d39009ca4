// The serial link: a device that cannot be opened is an error naming it, never a link.
// (A pty-backed test of a working line needs tests/support/pty_relay.hpp, which needs libutil
// linked into conformance_tests: a tests/CMakeLists.txt change.)
#include <gtest/gtest.h>

#include <string>

#include "conformance/conform_test_util.hpp"
#include "conformance/link/link.hpp"

namespace olcb::conform {
namespace {

TEST(SerialLinkTest, AMissingDeviceIsAnErrorNamingIt) {
    std::string error;
    const std::string device = "/dev/olcb-no-such-serial-adapter";
    auto link = open_serial(device, SerialSettings{}, kTool, error);
    EXPECT_EQ(link, nullptr);
    EXPECT_NE(error.find(device), std::string::npos) << error;
}

TEST(SerialLinkTest, SomethingThatIsNoTerminalIsAnError) {
    std::string error;
    auto link = open_serial("/dev/null", SerialSettings{}, kTool, error);
    EXPECT_EQ(link, nullptr);
    EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace olcb::conform
