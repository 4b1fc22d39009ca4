// Fixture of the simnode tests: a SimNode on a SimNetwork and a raw GridConnect client port
// (alias 0x12C, the fact sheet's runner) that frames datagrams, acknowledges the node's reply
// datagrams and collects SNIP replies; simulated clock only.
#pragma once

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "openlcb/can_defs.hpp"
#include "openlcb/gridconnect.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/sim_network.hpp"
#include "simnode/sim_node.hpp"
#include "support/temp_files.hpp"

namespace olcb::simnode::test {

using namespace std::chrono_literals;

/// The fact sheet's node ID (first alias 0x343).
inline constexpr NodeId kNodeId{0x05'01'01'01'22'00ull};
/// The runner's node ID and alias.
inline constexpr NodeId kClientId{0x02'01'0D'00'00'01ull};
inline constexpr std::uint16_t kClientAlias = 0x12C;

/// The faults parse_faults() makes of names (a test failure when they do not parse).
inline FaultSet faults_of(const std::vector<std::string>& names) {
    std::string error;
    auto parsed = parse_faults(names, error);
    EXPECT_TRUE(parsed) << error;
    return parsed.value_or(FaultSet{});
}

/// Contents of a file below the source tree.
inline std::string read_source_file(const std::string& relative) {
    std::ifstream in(std::string(OLCB_SOURCE_DIR) + "/" + relative, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// scenarios/default.xml: every variable type and <acdi/>.
inline const std::string& default_cdi() {
    static const std::string text = read_source_file("scenarios/default.xml");
    return text;
}

using test_support::TempDir;

/// What the node answered to one datagram.
struct Answer {
    bool ok = false;                                 ///< Datagram Received OK seen
    std::uint8_t ok_flags = 0;                       ///< its flags byte
    bool rejected = false;                           ///< Datagram Rejected seen
    std::uint16_t code = 0;                          ///< its error code
    std::optional<std::vector<std::uint8_t>> reply;  ///< reply datagram, if any
    TimePoint ok_at{};                               ///< when the OK arrived
    TimePoint reply_at{};                            ///< when the reply datagram was complete
    std::size_t ok_index = 0;     ///< position of the OK in the client's frame log
    std::size_t reply_index = 0;  ///< position of the reply's first frame in that log
};

/// Node plus client on one simulated segment.
class SimNodeTest : public ::testing::Test {
protected:
    SimNodeTest()
        : port_(net_.add_endpoint([this](const CanFrame& f, TimePoint t) { on_frame(f, t); })) {}

    /// A config for the default CDI, RAM-only.
    static NodeConfig default_config() {
        NodeConfig c;
        c.node_id = kNodeId;
        c.cdi = default_cdi();
        c.user_name = "Test node";
        c.user_description = "Bench";
        return c;
    }

    /// Creates the node, attaches and starts it, runs until it is initialized.
    void start(NodeConfig config) {
        std::string error;
        node_ = SimNode::create(std::move(config), error);
        ASSERT_TRUE(node_) << error;
        net_.add_stack(node_->stack());
        node_->stack().start(net_.now());
        ASSERT_TRUE(net_.run_until([this] { return node_->stack().initialized(); }, 1s));
        net_.run_for(10ms);
    }
    /// Starts a node with the default config plus faults.
    void start_with(const std::vector<std::string>& faults) {
        NodeConfig c = default_config();
        c.faults = faults_of(faults);
        start(std::move(c));
    }

    std::uint16_t alias() const { return node_->stack().alias(); }

    /// Sends one frame given as GridConnect text.
    void send_text(const std::string& text) {
        auto f = gridconnect::parse_frame(text);
        ASSERT_TRUE(f) << text;
        port_.send(*f);
    }
    /// Sends an addressed message (MTI's CAN-MTI) to the node with payload after fddd.
    void send_addressed(std::uint16_t mti, std::vector<std::uint8_t> payload = {}) {
        CanFrame f;
        f.id = can::message_header(mti & 0xFFF, kClientAlias);
        f.data[0] = static_cast<std::uint8_t>(alias() >> 8);
        f.data[1] = static_cast<std::uint8_t>(alias() & 0xFF);
        for (std::size_t i = 0; i < payload.size() && i < 6; ++i) f.data[2 + i] = payload[i];
        f.len = static_cast<std::uint8_t>(2 + std::min<std::size_t>(payload.size(), 6));
        port_.send(f);
    }
    /// Sends a global message.
    void send_global(std::uint16_t mti, std::vector<std::uint8_t> payload = {}) {
        port_.send(can::make_frame(can::message_header(mti & 0xFFF, kClientAlias), payload));
    }
    /// Sends a datagram to the node, framed as 1A or 1B/1C../1D.
    void send_datagram(const std::vector<std::uint8_t>& payload) {
        const std::uint16_t dst = alias();
        if (payload.size() <= 8) {
            port_.send(can::make_frame(
                can::addressed_header(can::FrameFormat::kDatagramOnly, dst, kClientAlias),
                payload));
            return;
        }
        for (std::size_t i = 0; i < payload.size(); i += 8) {
            const std::size_t n = std::min<std::size_t>(8, payload.size() - i);
            const auto format = i == 0                    ? can::FrameFormat::kDatagramFirst
                                : i + n >= payload.size() ? can::FrameFormat::kDatagramLast
                                                          : can::FrameFormat::kDatagramMiddle;
            port_.send(can::make_frame(can::addressed_header(format, dst, kClientAlias),
                                       std::span(payload).subspan(i, n)));
        }
    }

    /// Sends a datagram and runs until the exchange ends (reject, OK without reply pending, or
    /// the reply datagram), at most max of simulated time.
    Answer exchange(const std::vector<std::uint8_t>& payload, Duration max = 3s) {
        answer_ = Answer{};
        waiting_ = true;
        send_datagram(payload);
        net_.run_until(
            [this] {
                return answer_.rejected || answer_.reply ||
                       (answer_.ok && (answer_.ok_flags & 0x80) == 0);
            },
            max);
        net_.run_for(1ms);  // let our acknowledgement of the reply go out
        waiting_ = false;
        return answer_;
    }
    /// Data of a successful read (empty when it failed), asserting nothing.
    std::vector<std::uint8_t> read(std::uint8_t space, std::uint32_t address, std::uint8_t count) {
        auto a = exchange(read_cmd(space, address, count));
        if (!a.reply || a.reply->size() < 7) return {};
        const std::size_t header = ((*a.reply)[1] & 3) == 0 ? 7 : 6;
        if (((*a.reply)[1] & 0xF8) != 0x50) return {};
        return std::vector<std::uint8_t>(a.reply->begin() + static_cast<std::ptrdiff_t>(header),
                                         a.reply->end());
    }
    /// Space 0xFF read in 64-byte steps up to the first short reply (the CDI as served).
    std::vector<std::uint8_t> served_cdi() {
        std::vector<std::uint8_t> got;
        for (std::uint32_t a = 0;; a += 64) {
            auto part = read(0xFF, a, 64);
            got.insert(got.end(), part.begin(), part.end());
            if (part.size() < 64) break;
        }
        return got;
    }
    /// Read command in the form the fact sheet recommends (short for FD..FF).
    static std::vector<std::uint8_t> read_cmd(std::uint8_t space, std::uint32_t address,
                                              std::uint8_t count) {
        std::vector<std::uint8_t> p{
            0x20, 0x40, addr(address, 0), addr(address, 1), addr(address, 2), addr(address, 3)};
        if (space >= 0xFD) {
            p[1] = static_cast<std::uint8_t>(0x40 | (space - 0xFC));
        } else {
            p.push_back(space);
        }
        p.push_back(count);
        return p;
    }
    /// Write command (short form for FD..FF).
    static std::vector<std::uint8_t> write_cmd(std::uint8_t space, std::uint32_t address,
                                               const std::vector<std::uint8_t>& data) {
        std::vector<std::uint8_t> p{
            0x20, 0x00, addr(address, 0), addr(address, 1), addr(address, 2), addr(address, 3)};
        if (space >= 0xFD) {
            p[1] = static_cast<std::uint8_t>(space - 0xFC);
        } else {
            p.push_back(space);
        }
        p.insert(p.end(), data.begin(), data.end());
        return p;
    }
    /// Writes and asserts a Write Reply OK.
    void write_ok(std::uint8_t space, std::uint32_t address,
                  const std::vector<std::uint8_t>& data) {
        auto a = exchange(write_cmd(space, address, data));
        ASSERT_TRUE(a.ok) << "write not acknowledged";
        ASSERT_TRUE(a.reply);
        EXPECT_EQ((*a.reply)[1] & 0xF8, 0x10) << "not a Write Reply OK";
    }
    static std::uint8_t addr(std::uint32_t a, int byte) {
        return static_cast<std::uint8_t>(a >> (24 - 8 * byte));
    }

    /// Requests SNIP and returns the reassembled reply payload.
    std::vector<std::uint8_t> request_snip() {
        snip_.clear();
        snip_done_ = false;
        send_addressed(0xDE8);
        net_.run_until([this] { return snip_done_; }, 1s);
        return snip_;
    }

    /// Frames the node sent since the last call, as GridConnect text.
    std::vector<std::string> take() { return std::exchange(texts_, {}); }
    /// Count of frames in texts whose header starts with prefix (e.g. ":X19490").
    static std::size_t count_prefix(const std::vector<std::string>& texts, std::string_view p) {
        std::size_t n = 0;
        for (const auto& t : texts) n += t.rfind(p, 0) == 0 ? 1 : 0;
        return n;
    }

    SimNetwork net_;
    Transport& port_;
    std::unique_ptr<SimNode> node_;
    std::vector<std::string> texts_;  // every frame the client saw
    std::size_t seen_ = 0;
    bool auto_ack_ = true;

private:
    void on_frame(const CanFrame& f, TimePoint t) {
        texts_.push_back(gridconnect::format(f));
        const std::size_t index = seen_++;
        if (!can::is_message(f.id)) return;
        const auto format = can::frame_format(f.id);
        if (can::is_datagram_format(format)) {
            if (can::dest_alias(f.id) == kClientAlias) on_datagram_frame(f, format, t, index);
            return;
        }
        if (format != can::FrameFormat::kGlobalAddressed || f.len < 2) return;
        if (can::addressed_dest(f.data[0], f.data[1]) != kClientAlias) return;
        on_addressed(f, t, index);
    }

    // A datagram frame to the client: collected, and once whole the answer awaited (and acked).
    void on_datagram_frame(const CanFrame& f, can::FrameFormat format, TimePoint t,
                           std::size_t index) {
        if (format == can::FrameFormat::kDatagramOnly ||
            format == can::FrameFormat::kDatagramFirst) {
            partial_.clear();
            partial_index_ = index;
        }
        partial_.insert(partial_.end(), f.data.begin(), f.data.begin() + f.len);
        if (format != can::FrameFormat::kDatagramOnly &&
            format != can::FrameFormat::kDatagramLast) {
            return;
        }
        if (waiting_ && !answer_.reply) {
            answer_.reply = partial_;
            answer_.reply_at = t;
            answer_.reply_index = partial_index_;
        }
        if (auto_ack_) {
            const std::uint16_t src = can::source_alias(f.id);
            port_.send(can::make_frame(
                can::message_header(0xA28, kClientAlias),
                std::vector<std::uint8_t>{static_cast<std::uint8_t>(src >> 8),
                                          static_cast<std::uint8_t>(src & 0xFF), 0}));
        }
    }

    // An addressed message to the client: Datagram Received OK, Datagram Rejected, SNIP reply.
    void on_addressed(const CanFrame& f, TimePoint t, std::size_t index) {
        const std::uint16_t mti = can::can_mti(f.id);
        if (mti == 0xA28 && waiting_ && !answer_.ok) {
            answer_.ok = true;
            answer_.ok_flags = f.len > 2 ? f.data[2] : 0;
            answer_.ok_at = t;
            answer_.ok_index = index;
        } else if (mti == 0xA48 && waiting_) {
            answer_.rejected = true;
            answer_.code = static_cast<std::uint16_t>(f.len >= 4 ? f.data[2] << 8 | f.data[3] : 0);
        } else if (mti == 0xA08) {
            snip_.insert(snip_.end(), f.data.begin() + 2, f.data.begin() + f.len);
            if ((f.data[0] & 0x30) == 0x00 || (f.data[0] & 0x30) == 0x20) snip_done_ = true;
        }
    }

    Answer answer_;
    bool waiting_ = false;
    std::vector<std::uint8_t> partial_;
    std::size_t partial_index_ = 0;
    std::vector<std::uint8_t> snip_;
    bool snip_done_ = false;
};

/// Bytes of a string.
inline std::vector<std::uint8_t> bytes_of(std::string_view s) {
    return std::vector<std::uint8_t>(s.begin(), s.end());
}

/// Offsets in space 253 of scenarios/default.xml: "Enabled" (the version the restart faults
/// watch), "Trim", "Delay (ms)", "Scale", "Label" and port 0's two event IDs.
inline constexpr std::uint32_t kVersion = 0, kTrim = 1, kDelay = 3, kScale = 22, kLabel = 30,
                               kPort0On = 62, kPort0Off = 70;
/// "Delay (ms)"'s default, 250.
inline const std::vector<std::uint8_t> kDefaultDelay{0, 0, 0, 0xFA};

inline constexpr std::uint32_t kConfigSize = 179;  // scenarios/default.xml space 253: 0..178
inline constexpr std::uint32_t kUserSize = 128;    // space 251: 0..127

// An event ID of the default node's CDI: node ID + ordinal (docs/faults.md).
inline std::vector<std::uint8_t> default_event(std::uint8_t ordinal) {
    return {0x05, 0x01, 0x01, 0x01, 0x22, 0x00, 0x00, ordinal};
}

inline const std::vector<std::uint8_t> kNewEvent{1, 2, 3, 4, 5, 6, 7, 8};

/// The default node checked against the rules OlcbChecker tests: space information, Read/Write
/// Reply Fail codes, event identification, restarts and bursts of frames.
class SimNodeRulesTest : public SimNodeTest {
protected:
    std::uint32_t highest(std::uint8_t space) {
        const auto r = exchange({0x20, 0x84, space}).reply;
        if (!r || r->size() < 7 || (*r)[1] != 0x87) return 0;
        return static_cast<std::uint32_t>((*r)[3]) << 24 | (*r)[4] << 16 | (*r)[5] << 8 | (*r)[6];
    }
    // The error code of a Read/Write Reply Fail (0 when the reply is no failure).
    static std::uint16_t fail_code(const Answer& a) {
        if (!a.reply || a.reply->size() < 8) return 0;
        const auto& r = *a.reply;
        if ((r[1] & 0x08) == 0) return 0;  // the fail bit of read/write replies
        const std::size_t at = (r[1] & 3) == 0 ? 7 : 6;
        return static_cast<std::uint16_t>(r[at] << 8 | r[at + 1]);
    }
    // Identify Consumer (or Producer) for id; the frames the node answered.
    std::vector<std::string> identify(const std::vector<std::uint8_t>& id, bool producer = false) {
        take();
        send_global(producer ? 0x914 : 0x8F4, id);
        net_.run_for(10ms);
        return take();
    }
    std::vector<std::string> identify_events_global() {
        take();
        send_global(0x970);
        net_.run_for(10ms);
        return take();
    }
    static std::string consumer_identified(const std::vector<std::uint8_t>& id) {
        std::string text = ":X194C7343N";
        static constexpr char kHex[] = "0123456789ABCDEF";
        for (const auto b : id) {
            text += kHex[b >> 4];
            text += kHex[b & 0xF];
        }
        return text + ";";
    }
    void reboot() {
        EXPECT_TRUE(exchange({0x20, 0xA9}).ok);
        net_.run_for(1s);
        ASSERT_TRUE(node_->stack().initialized());
    }
    // Sends an addressed Verify Node ID among n frames of noise, all at one instant.
    void verify_in_burst(std::size_t n, const std::function<void(std::size_t)>& noise) {
        for (std::size_t i = 0; i < n / 2; ++i) noise(i);
        send_addressed(0x488);
        for (std::size_t i = n / 2; i < n; ++i) noise(i);
    }
};

inline constexpr NodeId kReaderId{0x02'01'0D'00'00'02ull};
inline constexpr std::uint8_t kDid = 0x21;

/// A second NodeStack with the stream transport on (the way lcc-conform reads) reading the
/// node's memory by stream, on the same simulated bus.
class StreamReadTest : public SimNodeTest {
protected:
    StreamReadTest() : reader_(reader_config()) {
        reader_.set_datagram_handler([this](const ReceivedDatagram& d) {
            replies_.push_back(d.payload);
            reader_.accept_datagram(d.source_alias);
        });
        reader_.set_outcome_handler([this](const DatagramOutcome& o) { outcomes_.push_back(o); });
        reader_.set_stream_handler([this](const StreamEvent& e) {
            if (e.kind == StreamEvent::Kind::kData) {
                data_.insert(data_.end(), e.data.begin(), e.data.end());
            }
            if (e.kind == StreamEvent::Kind::kOpened) stream_ = e.id;
            if (e.kind == StreamEvent::Kind::kCompleted) completed_ = e;
        });
    }
    static NodeStackConfig reader_config() {
        NodeStackConfig c;
        c.node_id = kReaderId;
        c.protocols = {Protocol::kDatagram, Protocol::kStream};
        c.streams = true;
        return c;
    }
    void boot(NodeConfig config) {
        start(std::move(config));
        net_.add_stack(reader_);
        reader_.start(net_.now());
        ASSERT_TRUE(net_.run_until([this] { return reader_.initialized(); }, 1s));
    }
    // Reads the CDI by stream (count 0 = to the end) with our buffer `buffer`.
    void read_cdi(std::uint16_t buffer, Duration max = 5s) {
        reader_.expect_stream(alias(), kDid, buffer);
        const std::vector<std::uint8_t> cmd{0x20, 0x63, 0, 0, 0, 0, 0xFF, kDid, 0, 0, 0, 0};
        ASSERT_TRUE(reader_.send_datagram(alias(), cmd, net_.now()));
        net_.run_until([this] { return completed_.has_value(); }, max);
    }
    std::vector<std::uint8_t> cdi_bytes() {
        memory::MemorySpace* s = node_->memory().space(0xFF);
        std::vector<std::uint8_t> out(s->size());
        out.resize(s->read(0, out));
        return out;
    }
    std::optional<StreamInfo> info() { return reader_.streams().info(stream_); }

    NodeStack reader_;
    std::vector<std::vector<std::uint8_t>> replies_;
    std::vector<DatagramOutcome> outcomes_;
    std::vector<std::uint8_t> data_;
    std::uint32_t stream_ = 0;
    std::optional<StreamEvent> completed_;
};

}  // namespace olcb::simnode::test
