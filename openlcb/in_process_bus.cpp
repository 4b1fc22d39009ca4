#include "openlcb/in_process_bus.hpp"
#include "openlcb/flag_guard.hpp"

#include <algorithm>
#include <utility>

namespace olcb {

class InProcessBus::Port final : public Transport {
public:
    Port(InProcessBus& bus, std::size_t index, FrameHandler handler) : bus_(bus), index_(index) {
        handler_.set(std::move(handler));
    }
    void send(const CanFrame& frame) override { bus_.enqueue(index_, frame); }
    void set_handler(FrameHandler handler) override { handler_.set(std::move(handler)); }
    void receive(const CanFrame& frame) { handler_(frame); }

private:
    InProcessBus& bus_;
    std::size_t index_;
    HandlerSlot handler_;
};

namespace {}  // namespace

InProcessBus::InProcessBus() = default;

InProcessBus::InProcessBus(boost::asio::io_context& io)
    : io_(&io), timer_(std::in_place, io), epoch_(std::chrono::steady_clock::now()) {}

InProcessBus::~InProcessBus() = default;

Transport& InProcessBus::add_endpoint(FrameHandler handler) {
    ports_.push_back(std::make_unique<Port>(*this, ports_.size(), std::move(handler)));
    waiting_.emplace_back();
    return *ports_.back();
}

void InProcessBus::enable_timing(std::uint32_t bitrate) {
    bitrate_ = bitrate == 0 ? 1 : bitrate;
}

InProcessBus::Duration InProcessBus::now() const {
    if (io_) return std::chrono::steady_clock::now() - epoch_;
    return now_;
}

std::size_t InProcessBus::pending() const {
    std::size_t n = fifo_.size() + (on_wire_ ? 1 : 0);
    for (const auto& q : waiting_) n += q.size();
    return n;
}

void InProcessBus::enqueue(std::size_t sender, const CanFrame& frame) {
    if (bitrate_) {
        waiting_[sender].push_back({frame, now()});
    } else {
        fifo_.emplace_back(sender, frame);
    }
    if (io_) schedule_io();
}

void InProcessBus::fan_out(std::size_t sender, const CanFrame& frame) {
    ++frames_delivered_;
    // Index loop: a handler may add ports while we iterate.
    for (std::size_t i = 0; i < ports_.size(); ++i) {
        if (i != sender) ports_[i]->receive(frame);
    }
}

std::size_t InProcessBus::deliver(std::size_t max_frames) {
    if (bitrate_) return advance_to(now(), max_frames);
    if (delivering_) return 0;
    FlagGuard guard(delivering_);
    std::size_t count = 0;
    while (!fifo_.empty() && count < max_frames) {
        auto [sender, frame] = fifo_.front();
        fifo_.pop_front();
        fan_out(sender, frame);
        ++count;
    }
    return count;
}

bool InProcessBus::start_next_frame() {
    if (on_wire_) return true;
    std::optional<Duration> earliest;
    for (const auto& q : waiting_) {
        if (!q.empty() && (!earliest || q.front().sent_at < *earliest))
            earliest = q.front().sent_at;
    }
    if (!earliest) return false;
    const Duration start = std::max(bus_free_at_, *earliest);
    // Arbitration among every port that had a frame ready when the bus became free.
    std::size_t winner = waiting_.size();
    for (std::size_t i = 0; i < waiting_.size(); ++i) {
        const auto& q = waiting_[i];
        if (q.empty() || q.front().sent_at > start) continue;
        if (winner == waiting_.size() || q.front().frame.id < waiting_[winner].front().frame.id) {
            winner = i;
        }
    }
    const CanFrame frame = waiting_[winner].front().frame;
    waiting_[winner].pop_front();
    const Duration length = can_frame_time(frame.len, *bitrate_);
    on_wire_ = OnWire{frame, winner, start + length};
    bus_free_at_ = start + length;
    busy_time_ += length;
    bits_on_wire_ += can_frame_bits(frame.len);
    return true;
}

std::optional<InProcessBus::Duration> InProcessBus::next_completion() {
    if (!bitrate_ || !start_next_frame()) return std::nullopt;
    return on_wire_->completes_at;
}

std::size_t InProcessBus::advance_to(Duration t, std::size_t max_frames) {
    if (delivering_) return 0;
    if (!bitrate_) {
        if (!io_) now_ = std::max(now_, t);
        return deliver(max_frames);
    }
    FlagGuard guard(delivering_);
    std::size_t count = 0;
    while (count < max_frames && start_next_frame() && on_wire_->completes_at <= t) {
        const OnWire done = *on_wire_;
        on_wire_.reset();
        // Handlers see the bus clock at the frame's completion, so their replies queue from then.
        if (!io_) now_ = std::max(now_, done.completes_at);
        fan_out(done.sender, done.frame);
        ++count;
    }
    if (!io_) now_ = std::max(now_, t);
    return count;
}

std::size_t InProcessBus::run_until_idle(std::size_t max_frames) {
    std::size_t count = 0;
    while (count < max_frames) {
        if (!bitrate_) {
            const std::size_t n = deliver(max_frames - count);
            count += n;
            if (n == 0) break;
            continue;
        }
        const auto next = next_completion();
        if (!next) break;
        const std::size_t n = advance_to(std::max(*next, now_), max_frames - count);
        count += n;
        if (n == 0) break;
    }
    return count;
}

void InProcessBus::schedule_io() {
    std::weak_ptr<bool> alive = alive_;
    if (!bitrate_) {
        if (wakeup_posted_) return;
        wakeup_posted_ = true;
        boost::asio::post(*io_, [alive, this] {
            if (alive.expired()) return;
            on_io_wakeup();
        });
        return;
    }
    const auto next = next_completion();
    if (!next) return;
    timer_->expires_at(epoch_ + *next);
    timer_->async_wait([alive, this](const boost::system::error_code& ec) {
        if (ec || alive.expired()) return;
        on_io_wakeup();
    });
}

void InProcessBus::on_io_wakeup() {
    if (!bitrate_) {
        wakeup_posted_ = false;
        // Deliver only what was queued before this wakeup so endless ping-pong cannot starve the
        // io_context; frames sent meanwhile already posted the next wakeup.
        deliver(fifo_.size());
        return;
    }
    advance_to(now());
    schedule_io();
}

}  // namespace olcb
