#include "base/host_port.hpp"

#include <gtest/gtest.h>

#include <string>

namespace olcb::base {
namespace {

HostPort parsed(std::string_view text, PortZero zero = PortZero::kAllowed) {
    std::string error;
    const auto hp = parse_host_port(text, error, zero);
    EXPECT_TRUE(hp.has_value()) << text << ": " << error;
    return hp.value_or(HostPort{"?", 1});
}

std::string error_of(std::string_view text, PortZero zero = PortZero::kAllowed) {
    std::string error;
    EXPECT_FALSE(parse_host_port(text, error, zero).has_value()) << text;
    return error;
}

TEST(HostPort, ParsesHostAndPort) {
    EXPECT_EQ(parsed("127.0.0.1:12021"), (HostPort{"127.0.0.1", 12021}));
    EXPECT_EQ(parsed("0.0.0.0:65535"), (HostPort{"0.0.0.0", 65535}));
    EXPECT_EQ(parsed("localhost:1"), (HostPort{"localhost", 1}));
    EXPECT_EQ(parsed("[::1]:12022"), (HostPort{"::1", 12022}));
    EXPECT_EQ(parsed("[fe80::1%eth0]:5"), (HostPort{"fe80::1%eth0", 5}));
}

TEST(HostPort, AMissingPortIs12021AndABarePortIsLocal) {
    EXPECT_EQ(parsed("192.168.1.10"), (HostPort{"192.168.1.10", kDefaultPort}));
    EXPECT_EQ(parsed("hub.local"), (HostPort{"hub.local", 12021}));
    EXPECT_EQ(parsed("[::1]"), (HostPort{"::1", 12021}));
    EXPECT_EQ(parsed("12022"), (HostPort{"127.0.0.1", 12022}));
    EXPECT_EQ(parsed("0"), (HostPort{"127.0.0.1", 0}));
}

TEST(HostPort, PortZeroOnlyWhereTheCallerListens) {
    EXPECT_EQ(parsed("127.0.0.1:0"), (HostPort{"127.0.0.1", 0}));
    EXPECT_EQ(parsed("127.0.0.1:1", PortZero::kRefused), (HostPort{"127.0.0.1", 1}));
    const std::string e = error_of("127.0.0.1:0", PortZero::kRefused);
    EXPECT_EQ(e,
              "'127.0.0.1:0' is not HOST:PORT: port 0 only asks for a free port when "
              "listening; give 1..65535");
    EXPECT_NE(error_of("0", PortZero::kRefused).find("port 0"), std::string::npos);
}

TEST(HostPort, RefusesWhatIsNotHostPortSayingWhy) {
    EXPECT_EQ(error_of("h:65536"),
              "'h:65536' is not HOST:PORT: the port must be a number 0..65535");
    EXPECT_NE(error_of("h:").find("the port must be a number"), std::string::npos);
    EXPECT_NE(error_of("h:+1").find("the port must be a number"), std::string::npos);
    EXPECT_NE(error_of("h:12x").find("the port must be a number"), std::string::npos);
    EXPECT_NE(error_of("h:99999999999999999999").find("the port must be a number"),
              std::string::npos);
    EXPECT_NE(error_of("99999").find("the port must be a number"), std::string::npos);
    EXPECT_NE(error_of(":12021").find("the host is empty"), std::string::npos);
    EXPECT_NE(error_of("").find("the host is empty"), std::string::npos);
    EXPECT_NE(error_of("[]:1").find("the host is empty"), std::string::npos);
    EXPECT_NE(error_of("::1").find("in brackets"), std::string::npos);
    EXPECT_NE(error_of("::1:12021").find("in brackets"), std::string::npos);
    EXPECT_NE(error_of("[::1").find("no ']'"), std::string::npos);
    EXPECT_NE(error_of("[::1]12021").find("':PORT' must follow"), std::string::npos);
}

TEST(HostPort, ToStringRoundTrips) {
    for (const HostPort& hp :
         {HostPort{"127.0.0.1", 12021}, HostPort{"::1", 0}, HostPort{"hub.local", 65535}}) {
        EXPECT_EQ(parsed(hp.to_string()), hp) << hp.to_string();
    }
    EXPECT_EQ((HostPort{"::1", 12021}).to_string(), "[::1]:12021");
    EXPECT_EQ((HostPort{"10.0.0.2", 1}).to_string(), "10.0.0.2:1");
    EXPECT_EQ(HostPort{}.to_string(), "127.0.0.1:12021");
}

}  // namespace
}  // namespace olcb::base
