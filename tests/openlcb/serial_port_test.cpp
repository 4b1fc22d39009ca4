#include "openlcb/serial_port.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "openlcb/gridconnect.hpp"
#include "openlcb/tcp_test_util.hpp"
#include "support/pty_relay.hpp"
#include "support/temp_files.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using test::numbered_frame;
using test::PtyPair;
using test::PtyRelay;
using test::run_until;
namespace fs = std::filesystem;

constexpr auto kLimit = 5s;

std::string line(const CanFrame& f) {
    return gridconnect::format(f) + "\r\n";
}

// A private directory for device symlinks, removed afterwards.
using test_support::TempDir;

// Points `link` at `target` atomically.
void point(const fs::path& link, const fs::path& target) {
    auto temp = link;
    temp += ".tmp";
    std::error_code ignored;
    fs::remove(temp, ignored);
    fs::create_symlink(target, temp);
    fs::rename(temp, link);
}

// A pty behind the symlink <dir>/ttyUSB0, as udev names an adapter: unplug() takes both away
// (the path never points at a freed pts number), plug() brings a fresh pty under the same path.
struct UsbAdapter {
    UsbAdapter() { plug(); }
    void plug() {
        pty = std::make_unique<PtyPair>();
        point(link, pty->slave_path());
    }
    void unplug() {
        pty->close();
        fs::remove(link);
    }
    TempDir dir;
    fs::path link = dir.path() / "ttyUSB0";
    std::unique_ptr<PtyPair> pty;
};

struct Transition {
    bool up;
    std::string reason;
};

SerialOptions fast_reopen() {
    SerialOptions o;
    o.initial_backoff = 5ms;
    o.max_backoff = 40ms;
    return o;
}

TEST(SerialPort, SentFramesReachTheDeviceAsCrlfLines) {
    boost::asio::io_context io;
    PtyPair pty;
    SerialPort port(io, pty.slave_path());
    ASSERT_EQ(port.open(), std::nullopt);
    EXPECT_TRUE(port.connected());
    EXPECT_EQ(port.device(), pty.slave_path());

    CanFrame standard;
    standard.extended = false;
    standard.id = 0x123;
    standard.len = 1;
    standard.data[0] = 0xAB;
    port.send(numbered_frame(0x101, 1));
    port.send(standard);
    const std::string expected = line(numbered_frame(0x101, 1)) + ":S123NAB;\r\n";
    std::string got;
    EXPECT_TRUE(run_until(
        io,
        [&] {
            got += pty.read_master();
            return got.size() >= expected.size();
        },
        kLimit));
    EXPECT_EQ(got, expected);
    EXPECT_EQ(port.stats().frames_sent, 2u);
    EXPECT_EQ(port.stats().opens, 1u);
    EXPECT_TRUE(run_until(
        io, [&] { return port.queued_bytes() == 0; }, kLimit));
}

TEST(SerialPort, ParsesEveryLineEndingLowercaseAndGarbage) {
    boost::asio::io_context io;
    PtyPair pty;
    SerialPort port(io, pty.slave_path());
    std::vector<std::string> received;
    port.set_handler([&](const CanFrame& f) { received.push_back(gridconnect::format(f)); });
    ASSERT_EQ(port.open(), std::nullopt);

    // The tail of a line sent before we opened, then noise, then frames in every style.
    pty.write_master("4010203;\r\nnoise 12 ;\n");
    pty.write_master(":X195B4001N01;\r\n");     // CRLF
    pty.write_master(":X195B4002N02;\n");       // LF
    pty.write_master(":X195B4003N03;\r");       // CR
    pty.write_master(":X195B4004N04;:X195B4");  // no separator, and a frame split in two writes
    ASSERT_TRUE(run_until(
        io, [&] { return received.size() == 4; }, kLimit));
    pty.write_master("005N05;");
    pty.write_master(":x195b4006n0a0b;\r\n");        // lowercase
    pty.write_master(":X195B4007N0;\r\n");           // odd number of data digits: broken
    pty.write_master(":X195B40:X195B4008N08;\r\n");  // cut short by the next ':': broken
    ASSERT_TRUE(run_until(
        io, [&] { return received.size() == 7; }, kLimit));
    EXPECT_EQ(received, (std::vector<std::string>{
                            ":X195B4001N01;", ":X195B4002N02;", ":X195B4003N03;", ":X195B4004N04;",
                            ":X195B4005N05;", ":X195B4006N0A0B;", ":X195B4008N08;"}));
    EXPECT_EQ(port.stats().parse_errors, 2u);
    EXPECT_EQ(port.stats().frames_received, 7u);
}

TEST(SerialPort, OpeningAMissingDeviceNamesThePath) {
    boost::asio::io_context io;
    const std::string path = "/nonexistent-olcb-dir/ttyACM9";
    SerialPort port(io, path);
    const auto error = port.open();
    ASSERT_TRUE(error.has_value());
    EXPECT_NE(error->find("serial " + path + ": "), std::string::npos) << *error;
    EXPECT_NE(error->find("No such file"), std::string::npos) << *error;
    EXPECT_FALSE(port.connected());
    port.send(numbered_frame(0x101, 1));
    EXPECT_EQ(port.stats().frames_dropped, 1u);
    // Nothing is retried after a failed first open.
    run_until(
        io, [] { return false; }, 30ms);
    EXPECT_EQ(port.stats().opens, 0u);
}

TEST(SerialPort, OpeningSomethingThatIsNoTerminalFails) {
    boost::asio::io_context io;
    TempDir dir;
    const auto file = dir.path() / "plain-file";
    std::ofstream(file) << "x";
    SerialPort port(io, file.string());
    const auto error = port.open();
    ASSERT_TRUE(error.has_value());
    EXPECT_NE(error->find(file.string()), std::string::npos) << *error;
    EXPECT_FALSE(port.connected());
}

TEST(SerialPort, UnsupportedBaudRateIsRefused) {
    boost::asio::io_context io;
    PtyPair pty;
    SerialOptions options;
    options.baud = 12345;
    SerialPort port(io, pty.slave_path(), options);
    const auto error = port.open();
    ASSERT_TRUE(error.has_value());
    EXPECT_NE(error->find("12345"), std::string::npos) << *error;
    EXPECT_FALSE(port.connected());
}

TEST(SerialPort, HardwareFlowControlAndOtherBaudRatesOpenOnAPty) {
    boost::asio::io_context io;
    PtyPair pty;
    SerialOptions options;
    options.baud = 57600;
    options.rtscts = true;
    SerialPort port(io, pty.slave_path(), options);
    EXPECT_EQ(port.open(), std::nullopt);
    EXPECT_TRUE(port.connected());
}

TEST(SerialPort, ReopensTheSamePathAfterTheDeviceWentAway) {
    boost::asio::io_context io;
    UsbAdapter adapter;
    const fs::path& link = adapter.link;

    SerialPort port(io, link.string(), fast_reopen());
    std::vector<Transition> transitions;
    port.set_connection_handler([&](bool up, const std::string& reason) {
        transitions.push_back({up, reason});
    });
    std::vector<CanFrame> received;
    port.set_handler([&](const CanFrame& f) { received.push_back(f); });
    ASSERT_EQ(port.open(), std::nullopt);
    EXPECT_TRUE(transitions.empty());  // the first open is reported by open() itself

    adapter.unplug();
    ASSERT_TRUE(run_until(
        io, [&] { return !transitions.empty(); }, kLimit));
    EXPECT_FALSE(port.connected());
    EXPECT_FALSE(transitions[0].up);
    EXPECT_NE(transitions[0].reason.find("serial " + link.string() + ": lost ("), std::string::npos)
        << transitions[0].reason;
    EXPECT_EQ(port.stats().losses, 1u);
    port.send(numbered_frame(0x101, 1));
    EXPECT_EQ(port.stats().frames_dropped, 1u);
    EXPECT_EQ(port.queued_bytes(), 0u);

    // Several reopen attempts fail while the device is missing; none of them is reported.
    run_until(
        io, [] { return false; }, 60ms);
    EXPECT_EQ(transitions.size(), 1u);

    adapter.plug();
    ASSERT_TRUE(run_until(
        io, [&] { return port.connected(); }, kLimit));
    ASSERT_EQ(transitions.size(), 2u);
    EXPECT_TRUE(transitions[1].up);
    EXPECT_EQ(transitions[1].reason, "");
    EXPECT_EQ(port.stats().opens, 2u);

    port.send(numbered_frame(0x101, 2));
    std::string got;
    EXPECT_TRUE(run_until(
        io,
        [&] {
            got += adapter.pty->read_master();
            return got.size() >= line(numbered_frame(0x101, 2)).size();
        },
        kLimit));
    EXPECT_EQ(got, line(numbered_frame(0x101, 2)));
    adapter.pty->write_master(line(numbered_frame(0x202, 3)));
    ASSERT_TRUE(run_until(
        io, [&] { return !received.empty(); }, kLimit));
    EXPECT_EQ(received.front(), numbered_frame(0x202, 3));
}

TEST(SerialPort, CloseStopsReopening) {
    boost::asio::io_context io;
    UsbAdapter adapter;
    const fs::path& link = adapter.link;
    SerialPort port(io, link.string(), fast_reopen());
    int downs = 0;
    port.set_connection_handler([&](bool up, const std::string&) { downs += up ? 0 : 1; });
    ASSERT_EQ(port.open(), std::nullopt);
    adapter.unplug();
    ASSERT_TRUE(run_until(
        io, [&] { return downs == 1; }, kLimit));
    port.close();
    adapter.plug();
    run_until(
        io, [] { return false; }, 100ms);
    EXPECT_FALSE(port.connected());
    EXPECT_EQ(port.stats().opens, 1u);
}

TEST(SerialPort, QueueBeyondTheLimitDropsNewFrames) {
    boost::asio::io_context io;
    PtyPair pty;
    SerialOptions options;
    options.max_queue_bytes = 3 * line(numbered_frame(0x101, 1)).size();
    SerialPort port(io, pty.slave_path(), options);
    ASSERT_EQ(port.open(), std::nullopt);
    for (std::uint32_t i = 0; i < 5; ++i) port.send(numbered_frame(0x101, i));
    EXPECT_EQ(port.stats().frames_sent, 3u);
    EXPECT_EQ(port.stats().frames_dropped, 2u);
    EXPECT_LE(port.queued_bytes(), options.max_queue_bytes);
    std::string got;
    EXPECT_TRUE(run_until(
        io,
        [&] {
            got += pty.read_master();
            return got.size() >= options.max_queue_bytes;
        },
        kLimit));
    EXPECT_EQ(got, line(numbered_frame(0x101, 0)) + line(numbered_frame(0x101, 1)) +
                       line(numbered_frame(0x101, 2)));
}

// Sends frame and reads it off the master, so the adapter side can then answer it.
bool send_and_see_on_the_wire(boost::asio::io_context& io, SerialPort& port, PtyPair& pty,
                              const CanFrame& frame) {
    port.send(frame);
    std::string got;
    return run_until(
        io,
        [&] {
            got += pty.read_master();
            return got == line(frame);
        },
        kLimit);
}

TEST(SerialPort, EchoOfOurOwnFrameIsDroppedAndOtherNodesFramesDelivered) {
    boost::asio::io_context io;
    PtyPair pty;
    SerialPort port(io, pty.slave_path());
    std::vector<CanFrame> received;
    port.set_handler([&](const CanFrame& f) { received.push_back(f); });
    ASSERT_EQ(port.open(), std::nullopt);

    const auto ours = numbered_frame(0x101, 1);
    const auto theirs = numbered_frame(0x202, 1);
    ASSERT_TRUE(send_and_see_on_the_wire(io, port, pty, ours));
    // The adapter echoes our frame; another node sends one; a second copy of ours would be a
    // node using our alias, which must stay visible.
    pty.write_master(line(ours) + line(theirs) + line(ours));
    ASSERT_TRUE(run_until(
        io, [&] { return received.size() == 2; }, kLimit));
    EXPECT_EQ(received, (std::vector<CanFrame>{theirs, ours}));
    EXPECT_EQ(port.stats().echoes_dropped, 1u);
    EXPECT_EQ(port.stats().frames_received, 2u);
}

TEST(SerialPort, EchoesAreDeliveredWhenNotDropped) {
    boost::asio::io_context io;
    PtyPair pty;
    SerialOptions options;
    options.drop_echoes = false;
    SerialPort port(io, pty.slave_path(), options);
    std::vector<CanFrame> received;
    port.set_handler([&](const CanFrame& f) { received.push_back(f); });
    ASSERT_EQ(port.open(), std::nullopt);

    const auto ours = numbered_frame(0x101, 1);
    const auto theirs = numbered_frame(0x202, 1);
    ASSERT_TRUE(send_and_see_on_the_wire(io, port, pty, ours));
    pty.write_master(line(ours) + line(theirs));
    ASSERT_TRUE(run_until(
        io, [&] { return received.size() == 2; }, kLimit));
    EXPECT_EQ(received, (std::vector<CanFrame>{ours, theirs}));
    EXPECT_EQ(port.stats().echoes_dropped, 0u);
}

TEST(SerialPort, DestructionWithPendingWorkCallsNothing) {
    boost::asio::io_context io;
    PtyPair pty;
    bool called = false;
    {
        SerialPort port(io, pty.slave_path());
        port.set_handler([&](const CanFrame&) { called = true; });
        port.set_connection_handler([&](bool, const std::string&) { called = true; });
        ASSERT_EQ(port.open(), std::nullopt);
        port.send(numbered_frame(0x101, 1));
        pty.write_master(line(numbered_frame(0x202, 1)));
    }  // destroyed with a read and a write pending
    run_until(
        io, [] { return false; }, 30ms);
    EXPECT_FALSE(called);
}

// Two ports joined by a null-modem relay, as two programs on two USB adapters of one bus.
class SerialRelay : public ::testing::Test {
protected:
    SerialRelay()
        : relay_(dir_.path() / "relay"),
          a_(io_, relay_.path(PtyRelay::Side::A).string(), fast_reopen()),
          b_(io_, relay_.path(PtyRelay::Side::B).string(), fast_reopen()) {
        a_.set_handler([this](const CanFrame& f) { at_a_.push_back(f); });
        b_.set_handler([this](const CanFrame& f) { at_b_.push_back(f); });
        a_.set_connection_handler([this](bool up, const std::string& reason) {
            a_transitions_.push_back({up, reason});
        });
        b_.set_connection_handler([this](bool up, const std::string& reason) {
            b_transitions_.push_back({up, reason});
        });
    }

    boost::asio::io_context io_;
    TempDir dir_;
    PtyRelay relay_;
    SerialPort a_;
    SerialPort b_;
    std::vector<CanFrame> at_a_;
    std::vector<CanFrame> at_b_;
    std::vector<Transition> a_transitions_;
    std::vector<Transition> b_transitions_;
};

TEST_F(SerialRelay, PortsExchangeFramesBothWays) {
    ASSERT_EQ(a_.open(), std::nullopt);
    ASSERT_EQ(b_.open(), std::nullopt);
    for (std::uint32_t i = 0; i < 50; ++i) a_.send(numbered_frame(0x0AA, i));
    for (std::uint32_t i = 0; i < 30; ++i) b_.send(numbered_frame(0x0BB, i));
    ASSERT_TRUE(run_until(
        io_, [&] { return at_b_.size() == 50 && at_a_.size() == 30; }, kLimit));
    for (std::uint32_t i = 0; i < 50; ++i) EXPECT_EQ(at_b_[i], numbered_frame(0x0AA, i));
    for (std::uint32_t i = 0; i < 30; ++i) EXPECT_EQ(at_a_[i], numbered_frame(0x0BB, i));
    EXPECT_EQ(relay_.bytes_relayed(), 80 * line(numbered_frame(0x0AA, 0)).size());
    EXPECT_EQ(a_.stats().echoes_dropped + b_.stats().echoes_dropped, 0u);
}

TEST_F(SerialRelay, ManualUnplugAndReplug) {
    ASSERT_EQ(a_.open(), std::nullopt);
    ASSERT_EQ(b_.open(), std::nullopt);
    relay_.unplug(PtyRelay::Side::A);
    EXPECT_TRUE(relay_.unplugged(PtyRelay::Side::A));
    EXPECT_FALSE(relay_.unplugged(PtyRelay::Side::B));
    ASSERT_TRUE(run_until(
        io_, [&] { return !a_transitions_.empty(); }, kLimit));
    EXPECT_FALSE(a_transitions_[0].up);
    EXPECT_NE(a_transitions_[0].reason.find(relay_.path(PtyRelay::Side::A).string()),
              std::string::npos);
    EXPECT_TRUE(b_transitions_.empty());
    EXPECT_TRUE(b_.connected());

    relay_.replug(PtyRelay::Side::A);
    ASSERT_TRUE(run_until(
        io_, [&] { return a_.connected(); }, kLimit));
    a_.send(numbered_frame(0x0AA, 7));
    b_.send(numbered_frame(0x0BB, 8));
    ASSERT_TRUE(run_until(
        io_, [&] { return at_a_.size() == 1 && at_b_.size() == 1; }, kLimit));
    EXPECT_EQ(at_b_[0], numbered_frame(0x0AA, 7));
    EXPECT_EQ(at_a_[0], numbered_frame(0x0BB, 8));
}

TEST_F(SerialRelay, ScheduledUnplugHitsTheRightSideAndReplugsAfterTheDowntime) {
    ASSERT_EQ(a_.open(), std::nullopt);
    ASSERT_EQ(b_.open(), std::nullopt);
    const std::size_t frame_bytes = line(numbered_frame(0x0AA, 0)).size();
    relay_.schedule_unplug(PtyRelay::Side::B, 3 * frame_bytes, 150ms);
    for (std::uint32_t i = 0; i < 3; ++i) a_.send(numbered_frame(0x0AA, i));
    ASSERT_TRUE(run_until(
        io_, [&] { return !b_transitions_.empty(); }, kLimit));
    EXPECT_FALSE(b_transitions_[0].up);
    EXPECT_TRUE(relay_.unplugged(PtyRelay::Side::B));
    EXPECT_TRUE(a_transitions_.empty());
    EXPECT_TRUE(a_.connected());
    EXPECT_LE(at_b_.size(), 3u);

    // While B is away, what A sends goes nowhere, and B's own sends are dropped.
    b_.send(numbered_frame(0x0BB, 1));
    EXPECT_EQ(b_.stats().frames_dropped, 1u);

    ASSERT_TRUE(run_until(
        io_, [&] { return b_.connected(); }, kLimit));
    ASSERT_EQ(b_transitions_.size(), 2u);
    EXPECT_TRUE(b_transitions_[1].up);
    EXPECT_FALSE(relay_.unplugged(PtyRelay::Side::B));
    EXPECT_EQ(b_.stats().losses, 1u);
    EXPECT_EQ(b_.stats().opens, 2u);
    EXPECT_EQ(a_.stats().losses, 0u);

    at_b_.clear();
    a_.send(numbered_frame(0x0AA, 10));
    b_.send(numbered_frame(0x0BB, 11));
    ASSERT_TRUE(run_until(
        io_, [&] { return !at_b_.empty() && !at_a_.empty(); }, kLimit));
    EXPECT_EQ(at_b_.back(), numbered_frame(0x0AA, 10));
    EXPECT_EQ(at_a_.back(), numbered_frame(0x0BB, 11));
}

TEST_F(SerialRelay, ScheduledUnplugWithoutReplugStaysDown) {
    ASSERT_EQ(a_.open(), std::nullopt);
    ASSERT_EQ(b_.open(), std::nullopt);
    relay_.schedule_unplug(PtyRelay::Side::A, 1, PtyRelay::kNever);
    b_.send(numbered_frame(0x0BB, 1));
    ASSERT_TRUE(run_until(
        io_, [&] { return !a_transitions_.empty(); }, kLimit));
    run_until(
        io_, [] { return false; }, 100ms);
    EXPECT_FALSE(a_.connected());
    EXPECT_TRUE(relay_.unplugged(PtyRelay::Side::A));
    EXPECT_EQ(a_transitions_.size(), 1u);
    EXPECT_GE(a_.stats().losses, 1u);
    EXPECT_EQ(a_.stats().opens, 1u);
}

}  // namespace
}  // namespace olcb
