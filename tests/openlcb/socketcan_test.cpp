#include "openlcb/socketcan.hpp"

#include <gtest/gtest.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstring>
#include <string>
#include <vector>

#include "openlcb/tcp_test_util.hpp"

namespace olcb::socketcan {
namespace {

TEST(SocketCanConversion, SendSetsTheExtendedFlagMasksTheIdAndClampsTheLength) {
    CanFrame f;
    f.id = 0xFFFFFFFF;
    f.len = 12;
    f.data = {1, 2, 3, 4, 5, 6, 7, 8};
    const ::can_frame k = to_kernel(f);
    EXPECT_EQ(k.can_id, 0x1FFFFFFFu | CAN_EFF_FLAG);
    EXPECT_EQ(k.can_dlc, 8);
    EXPECT_EQ(k.data[7], 8);

    CanFrame g;
    g.id = 0x19490343;
    g.len = 2;
    g.data = {0xAB, 0xCD, 0xEE};
    const ::can_frame kg = to_kernel(g);
    EXPECT_EQ(kg.can_id, 0x19490343u | 0x80000000u);
    EXPECT_EQ(kg.can_dlc, 2);
    EXPECT_EQ(kg.data[0], 0xAB);
    EXPECT_EQ(kg.data[1], 0xCD);
    EXPECT_EQ(kg.data[2], 0);  // bytes past len are not copied
}

TEST(SocketCanConversion, ReceiveKeepsExtendedDataFrames) {
    ::can_frame k{};
    k.can_id = 0x19170343u | CAN_EFF_FLAG;
    k.can_dlc = 6;
    const std::uint8_t bytes[] = {5, 1, 1, 1, 0x22, 0};
    std::copy(std::begin(bytes), std::end(bytes), k.data);
    const auto f = from_kernel(k);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->id, 0x19170343u);
    EXPECT_EQ(f->len, 6);
    EXPECT_TRUE(f->extended);
    EXPECT_FALSE(f->remote);
    EXPECT_EQ(f->data[4], 0x22);
    EXPECT_EQ(to_kernel(*f).can_id, k.can_id);
}

TEST(SocketCanConversion, ReceiveDropsStandardRemoteAndErrorFrames) {
    ::can_frame k{};
    k.can_id = 0x123;  // standard frame
    EXPECT_FALSE(from_kernel(k));
    k.can_id = 0x19490343u | CAN_EFF_FLAG | CAN_RTR_FLAG;
    EXPECT_FALSE(from_kernel(k));
    k.can_id = 0x00000004u | CAN_EFF_FLAG | CAN_ERR_FLAG;
    EXPECT_FALSE(from_kernel(k));
    k.can_id = CAN_ERR_FLAG | 0x4;
    EXPECT_FALSE(from_kernel(k));
}

TEST(SocketCanConversion, ReceiveClampsAnOversizedLength) {
    ::can_frame k{};
    k.can_id = 0x19490343u | CAN_EFF_FLAG;
    k.can_dlc = 15;
    const auto f = from_kernel(k);
    ASSERT_TRUE(f);
    EXPECT_EQ(f->len, 8);
}

TEST(SocketCanPort, OpeningAnInvalidNameFailsClearly) {
    boost::asio::io_context io;
    SocketCanPort port(io);
    const auto error = port.open("");
    ASSERT_TRUE(error);
    EXPECT_NE(error->message.find("invalid interface name"), std::string::npos);
    EXPECT_FALSE(port.is_open());
    port.send(CanFrame{});
    EXPECT_EQ(port.stats().frames_dropped, 1u);
}

TEST(SocketCanPort, LiveVcan0FramesReachOtherSocketsNotTheSender) {
    boost::asio::io_context io;
    SocketCanPort a(io);
    SocketCanPort b(io);
    if (const auto error = a.open("vcan0")) {
        GTEST_SKIP() << error->message;
    }
    ASSERT_FALSE(b.open("vcan0"));
    std::vector<CanFrame> got_a, got_b;
    a.set_handler([&](const CanFrame& f) { got_a.push_back(f); });
    b.set_handler([&](const CanFrame& f) { got_b.push_back(f); });
    CanFrame f;
    f.id = 0x19490343;
    CanFrame standard;
    standard.id = 0x123;
    standard.extended = false;
    a.send(standard);  // never put on the bus
    a.send(f);
    ASSERT_TRUE(test::run_until(
        io, [&] { return !got_b.empty(); }, std::chrono::seconds(5)));
    test::run_until(
        io, [] { return false; }, std::chrono::milliseconds(50));
    EXPECT_EQ(got_b, std::vector<CanFrame>{f});
    EXPECT_TRUE(got_a.empty());
    EXPECT_EQ(a.stats().frames_ignored, 1u);
}

// Other equipment's standard, remote and error-less frames stay in the kernel: the port's queue
// holds OpenLCB's frames only (what keeps a stream whole while cangen floods the bus).
TEST(SocketCanPort, LiveVcan0ForeignFramesNeverReachThePort) {
    boost::asio::io_context io;
    SocketCanPort port(io);
    if (const auto error = port.open("vcan0")) {
        GTEST_SKIP() << error->message;
    }
    std::vector<CanFrame> got;
    port.set_handler([&](const CanFrame& f) { got.push_back(f); });
    const int raw = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    ASSERT_GE(raw, 0);
    sockaddr_can address{};
    address.can_family = AF_CAN;
    address.can_ifindex = static_cast<int>(::if_nametoindex("vcan0"));
    ASSERT_EQ(::bind(raw, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);
    const auto frame = [](canid_t id, std::uint8_t dlc) {
        ::can_frame f{};
        f.can_id = id;
        f.can_dlc = dlc;
        return f;
    };
    const ::can_frame standard = frame(0x123, 2);
    const ::can_frame remote = frame(0x19490343 | CAN_EFF_FLAG | CAN_RTR_FLAG, 0);
    const ::can_frame openlcb = frame(0x19490343 | CAN_EFF_FLAG, 0);
    for (const ::can_frame& f : {standard, remote, standard, openlcb}) {
        ASSERT_EQ(::write(raw, &f, sizeof f), static_cast<ssize_t>(sizeof f));
    }
    ::close(raw);
    ASSERT_TRUE(test::run_until(
        io, [&] { return !got.empty(); }, std::chrono::seconds(5)));
    test::run_until(
        io, [] { return false; }, std::chrono::milliseconds(50));
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got.front().id, 0x19490343u);
    EXPECT_EQ(port.stats().frames_ignored, 0u) << "filtered by the kernel, not by from_kernel()";
}

// Sets an interface up or down as `ip link set IF up|down` does; false without the right
// (CAP_NET_ADMIN: root in ci/vm) or the interface.
bool set_link(const char* interface, bool up) {
    const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW);
    if (fd < 0) return false;
    ::ifreq request{};
    std::strncpy(request.ifr_name, interface, IFNAMSIZ - 1);
    bool ok = ::ioctl(fd, SIOCGIFFLAGS, &request) == 0;
    if (ok) {
        request.ifr_flags =
            static_cast<short>(up ? (request.ifr_flags | IFF_UP) : (request.ifr_flags & ~IFF_UP));
        ok = ::ioctl(fd, SIOCSIFFLAGS, &request) == 0;
    }
    ::close(fd);
    return ok;
}

// vcan1 is the live tests' own interface for taking down: ci/vm brings it up for them.
TEST(SocketCanPort, LiveVcan1DownAtOpenIsOneClearError) {
    if (!set_link("vcan1", false)) GTEST_SKIP() << "vcan1 cannot be set down here";
    boost::asio::io_context io;
    SocketCanPort port(io);
    const auto error = port.open("vcan1");
    ASSERT_TRUE(set_link("vcan1", true));
    ASSERT_TRUE(error);
    EXPECT_EQ(error->errno_value, ENETDOWN);
    EXPECT_EQ(error->message, "SocketCAN vcan1: the interface is down (ip link set vcan1 up)");
    EXPECT_FALSE(port.is_open());
}

// Down mid-run: reported once with the reason, frames dropped meanwhile; up again: reported, and
// frames flow both ways on the same socket.
TEST(SocketCanPort, LiveVcan1DownAndUpIsReportedAndFramesFlowAgain) {
    boost::asio::io_context io;
    SocketCanPort a(io);
    SocketCanPort b(io);
    if (const auto error = a.open("vcan1")) GTEST_SKIP() << error->message;
    ASSERT_FALSE(b.open("vcan1"));
    std::vector<std::string> events;
    a.set_connection_handler([&](bool up, const std::string& reason) {
        events.push_back(up ? "up" : "down: " + reason);
    });
    std::vector<CanFrame> got;
    b.set_handler([&](const CanFrame& f) { got.push_back(f); });
    if (!set_link("vcan1", false)) GTEST_SKIP() << "vcan1 cannot be set down here";
    const bool down_seen = test::run_until(
        io, [&] { return !events.empty(); }, std::chrono::seconds(5));
    CanFrame f;
    f.id = 0x19490343;
    a.send(f);
    const auto dropped = a.stats().frames_dropped;
    const bool link_was_down = !a.link_up();
    ASSERT_TRUE(set_link("vcan1", true));
    ASSERT_TRUE(down_seen);
    EXPECT_TRUE(link_was_down);
    EXPECT_EQ(dropped, 1u);
    EXPECT_EQ(events.front(), "down: SocketCAN vcan1 went down (Network is down)");
    ASSERT_TRUE(test::run_until(
        io, [&] { return events.size() == 2; }, std::chrono::seconds(5)));
    EXPECT_EQ(events.back(), "up");
    EXPECT_TRUE(a.link_up());
    EXPECT_EQ(a.stats().link_losses, 1u);
    a.send(f);
    ASSERT_TRUE(test::run_until(
        io, [&] { return !got.empty(); }, std::chrono::seconds(5)));
    EXPECT_EQ(got, std::vector<CanFrame>{f});
}

}  // namespace
}  // namespace olcb::socketcan
