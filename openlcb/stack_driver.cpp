#include "openlcb/stack_driver.hpp"
#include "openlcb/flag_guard.hpp"

#include <utility>

namespace olcb {
namespace {

// Frames handled in one go before yielding to other io_context work (bounds a ping-pong).
constexpr std::size_t kMaxFramesPerBatch = 100'000;

}  // namespace

StackDriver::StackDriver(boost::asio::io_context& io, Transport& transport,
                         StackGroupOptions options)
    : io_(io), transport_(transport), timer_(io), group_(options) {
    transport_.set_handler([this](const CanFrame& f) { on_transport_frame(f); });
    // Output made outside a driver callback is flushed soon; inside one, the batch takes it.
    group_.set_notice([this] {
        if (!busy_) schedule();
    });
}

StackDriver::~StackDriver() {
    // Attached stacks may already be gone: their output handlers check the group's token.
    transport_.set_handler({});
}

StackDriver::Stats StackDriver::stats() const {
    Stats s = stats_;
    s.frames_out = group_.stats().frames_out;
    s.polls = group_.stats().polls;
    s.deliveries = group_.stats().deliveries;
    return s;
}

void StackDriver::attach(NodeStack& stack) {
    group_.attach(stack);
    schedule();
}

void StackDriver::detach(NodeStack& stack) {
    group_.detach(stack);
}

void StackDriver::start_all() {
    group_.start_all(Clock::now());
}

void StackDriver::kick() {
    schedule();
}

void StackDriver::flush() {
    process();
}

void StackDriver::on_transport_frame(const CanFrame& frame) {
    ++stats_.frames_in;
    incoming_.push_back(frame);
    if (!busy_) process();
}

void StackDriver::process() {
    if (busy_) return;
    FlagGuard guard(busy_);
    const TimePoint now = Clock::now();
    const auto send = [this](const CanFrame& f) { transport_.send(f); };
    std::size_t handled = 0;
    while (handled < kMaxFramesPerBatch) {
        if (!incoming_.empty()) {
            const CanFrame f = incoming_.front();
            incoming_.pop_front();
            group_.deliver(f, now);
            ++handled;
            continue;
        }
        if (!group_.has_output()) break;
        handled += group_.flush(now, send, kMaxFramesPerBatch - handled);
    }
    if (!incoming_.empty() || group_.has_output()) {
        schedule();  // more work than one batch: continue after other handlers ran
        return;
    }
    post_rearm();
}

// One post however often this is asked before it runs, so a burst costs one step; a driver
// destroyed meanwhile is not touched (pending is its member).
void StackDriver::post_once(bool& pending, void (StackDriver::*step)()) {
    if (pending) return;
    pending = true;
    std::weak_ptr<bool> alive = alive_;
    boost::asio::post(io_, [alive, this, &pending, step] {
        if (alive.expired()) return;
        pending = false;
        (this->*step)();
    });
}

// Once per burst, not per frame: the group's deadline heap drops its stale entries here.
void StackDriver::post_rearm() {
    post_once(rearm_posted_, &StackDriver::rearm);
}

void StackDriver::schedule() {
    post_once(posted_, &StackDriver::process);
}

void StackDriver::rearm() {
    const std::optional<TimePoint> best = group_.next_deadline();
    if (best == armed_at_) return;
    armed_at_ = best;
    if (!best) {
        timer_.cancel();
        return;
    }
    ++stats_.timer_arms;
    timer_.expires_at(*best);
    std::weak_ptr<bool> alive = alive_;
    timer_.async_wait([alive, this](const boost::system::error_code& ec) {
        if (ec || alive.expired()) return;
        on_timer();
    });
}

void StackDriver::on_timer() {
    armed_at_.reset();
    {
        FlagGuard guard(busy_);  // output made by poll() is flushed by process() below
        group_.poll(Clock::now());
    }
    process();
}

}  // namespace olcb
