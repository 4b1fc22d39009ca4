#include "openlcb/in_process_bus.hpp"

#include "openlcb/asio.hpp"
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

struct InProcessBus::Timer {
    explicit Timer(boost::asio::io_context& io) : timer(io) {}
    boost::asio::steady_timer timer;
};

InProcessBus::InProcessBus() = default;

InProcessBus::InProcessBus(boost::asio::io_context& io)
    : io_(&io), timer_(std::make_unique<Timer>(io)), epoch_(std::chrono::steady_clock::now()) {}

InProcessBus::~InProcessBus() = default;

Transport& InProcessBus::add_endpoint(FrameHandler handler) {
    ports_.push_back(std::make_unique<Port>(*this, ports_.size(), std::move(handler)));
    return *ports_.back();
}

void InProcessBus::enable_timing(std::uint32_t bitrate) {
    pacer_.emplace(bitrate);
}

InProcessBus::Duration InProcessBus::now() const {
    if (io_) return std::chrono::steady_clock::now() - epoch_;
    return now_;
}

std::size_t InProcessBus::pending() const {
    return fifo_.size() + (pacer_ ? pacer_->pending() : 0);
}

void InProcessBus::enqueue(std::size_t sender, const CanFrame& frame) {
    if (pacer_) {
        pacer_->push(sender, frame, now());
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
    if (pacer_) return advance_to(now(), max_frames);
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

std::optional<InProcessBus::Duration> InProcessBus::next_completion() {
    if (!pacer_) return std::nullopt;
    return pacer_->next_completion();
}

std::size_t InProcessBus::advance_to(Duration t, std::size_t max_frames) {
    if (delivering_) return 0;
    if (!pacer_) {
        if (!io_) now_ = std::max(now_, t);
        return deliver(max_frames);
    }
    FlagGuard guard(delivering_);
    std::size_t count = 0;
    while (count < max_frames) {
        const auto done = pacer_->pop(t);
        if (!done) break;
        // Handlers see the bus clock at the frame's completion, so their replies queue from then.
        if (!io_) now_ = std::max(now_, done->completed_at);
        fan_out(static_cast<std::size_t>(done->source), done->frame);
        ++count;
    }
    if (!io_) now_ = std::max(now_, t);
    return count;
}

std::size_t InProcessBus::run_until_idle(std::size_t max_frames) {
    std::size_t count = 0;
    while (count < max_frames) {
        if (!pacer_) {
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
    if (!pacer_) {
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
    timer_->timer.expires_at(epoch_ + *next);
    timer_->timer.async_wait([alive, this](const boost::system::error_code& ec) {
        if (ec || alive.expired()) return;
        on_io_wakeup();
    });
}

void InProcessBus::on_io_wakeup() {
    if (!pacer_) {
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
