// Tool side of the download benchmarks: reads a memory space in 64-byte memory-config datagram
// reads, one outstanding, from callbacks; and a transport wrapper tallying the CAN bus time of
// every frame the tool sends and receives.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "memory/memory_config_codec.hpp"
#include "openlcb/can_timing.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/transport.hpp"

namespace olcb::bench {

inline constexpr std::uint8_t kReadSize = 64;

/// Reads space 0xFF (the CDI) in 64-byte reads, one at a time, from the stack's callbacks.
class Reader {
public:
    using Now = std::function<TimePoint()>;

    Reader(NodeStack& stack, Now now) : stack_(stack), now_(std::move(now)) {
        stack_.set_message_handler([](const Message&) { return true; });
        stack_.set_datagram_handler([this](const ReceivedDatagram& d) { on_datagram(d); });
    }

    /// Starts reading count bytes at address (one read), or the whole space (whole = true).
    void start(std::uint16_t node, std::uint32_t address, bool whole) {
        node_ = node;
        whole_ = whole;
        data_.clear();
        done_ = false;
        reads_ = 0;
        address_ = address;
        send();
    }
    bool done() const { return done_; }
    /// When the last reply arrived (valid once done()).
    TimePoint done_at() const { return done_at_; }
    const std::vector<std::uint8_t>& data() const { return data_; }
    std::size_t reads() const { return reads_; }

private:
    void send() {
        memory::Read r;
        r.space = memory::Space::kCdi;
        r.address = address_ + static_cast<std::uint32_t>(data_.size());
        r.count = kReadSize;
        ++reads_;
        if (!stack_.send_datagram(node_, memory::encode(r), now_())) {
            throw std::runtime_error("send_datagram refused");
        }
    }
    void on_datagram(const ReceivedDatagram& d) {
        stack_.accept_datagram(d.source_alias);
        if (d.source_alias != node_ || done_) return;
        const auto decoded = memory::decode(d.payload);
        const auto* reply =
            decoded.ok() ? std::get_if<memory::ReadReply>(&decoded.message) : nullptr;
        if (!reply) {
            finish();
            return;
        }
        data_.insert(data_.end(), reply->data.begin(), reply->data.end());
        if (!whole_ || reply->data.size() < kReadSize) {
            finish();
        } else {
            send();
        }
    }
    void finish() {
        done_ = true;
        done_at_ = now_();
    }

    NodeStack& stack_;
    Now now_;
    std::uint16_t node_ = 0;
    std::uint32_t address_ = 0;
    bool whole_ = false;
    bool done_ = false;
    TimePoint done_at_{};
    std::size_t reads_ = 0;
    std::vector<std::uint8_t> data_;
};

/// A Transport in front of another that adds up can_frame_time() of every frame through it.
/// committed() is the total as of the last frame received: the tool's frames sent after it (its
/// Datagram Received OK of the last reply) were not on the bus within a download that ends there.
class BusTally final : public Transport {
public:
    BusTally(Transport& inner, std::uint32_t bitrate) : inner_(inner), bitrate_(bitrate) {}

    void send(const CanFrame& frame) override {
        total_ += can_frame_time(frame.len, bitrate_);
        ++frames_;
        inner_.send(frame);
    }
    void set_handler(FrameHandler handler) override {
        inner_.set_handler([this, handler = std::move(handler)](const CanFrame& frame) {
            total_ += can_frame_time(frame.len, bitrate_);
            ++frames_;
            committed_ = total_;
            committed_frames_ = frames_;
            last_rx_ = Clock::now();
            if (handler) handler(frame);
        });
    }

    /// Starts a new tally.
    void reset() {
        total_ = committed_ = std::chrono::nanoseconds{0};
        frames_ = committed_frames_ = 0;
    }
    std::chrono::nanoseconds committed() const { return committed_; }
    std::uint64_t committed_frames() const { return committed_frames_; }
    TimePoint last_rx() const { return last_rx_; }

private:
    Transport& inner_;
    std::uint32_t bitrate_;
    std::chrono::nanoseconds total_{0};
    std::chrono::nanoseconds committed_{0};
    std::uint64_t frames_ = 0;
    std::uint64_t committed_frames_ = 0;
    TimePoint last_rx_ = Clock::now();
};

}  // namespace olcb::bench
