#include "openlcb/stack_driver.hpp"
#include "openlcb/flag_guard.hpp"

#include <utility>

namespace olcb {
namespace {

// Frames handled in one go before yielding to other io_context work (bounds a ping-pong).
constexpr std::size_t kMaxFramesPerBatch = 100'000;

}  // namespace

StackDriver::StackDriver(boost::asio::io_context& io, Transport& transport)
    : io_(io), transport_(transport), timer_(io) {
    transport_.set_handler([this](const CanFrame& f) { on_transport_frame(f); });
}

StackDriver::~StackDriver() {
    // Attached stacks may already be gone: their output handlers check alive_ instead.
    transport_.set_handler({});
}

void StackDriver::attach(NodeStack& stack) {
    const std::size_t index = slots_.size();
    slots_.push_back({&stack, false});
    ++count_;
    stack.set_output_handler([this, index, alive = std::weak_ptr<bool>(alive_)] {
        if (!alive.expired()) mark_dirty(index);
    });
    if (stack.has_output()) mark_dirty(index);
    schedule();
}

void StackDriver::detach(NodeStack& stack) {
    for (auto& s : slots_) {
        if (s.stack == &stack) {
            stack.set_output_handler({});
            s.stack = nullptr;  // a tombstone keeps the other indices valid
            --count_;
        }
    }
}

void StackDriver::start_all() {
    const TimePoint now = Clock::now();
    for (auto& s : slots_) {
        if (s.stack) s.stack->start(now);
    }
}

void StackDriver::kick() {
    schedule();
}

void StackDriver::flush() {
    process();
}

void StackDriver::mark_dirty(std::size_t index) {
    Slot& s = slots_[index];
    if (s.dirty) return;
    s.dirty = true;
    dirty_.push_back(index);
    if (!busy_) schedule();  // output made outside a driver callback: flush it soon
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
    std::size_t handled = 0;
    while (handled < kMaxFramesPerBatch) {
        if (!incoming_.empty()) {
            const CanFrame f = incoming_.front();
            incoming_.pop_front();
            for (auto& s : slots_) {
                if (s.stack) s.stack->on_frame(f, now);
            }
            ++handled;
            continue;
        }
        if (dirty_.empty()) break;
        handled += drain_dirty(now);
    }
    if (!incoming_.empty() || !dirty_.empty()) {
        schedule();  // more work than one batch: continue after other handlers ran
        return;
    }
    post_rearm();
}

// Sends the output of every dirty stack to the transport and the other stacks; returns the
// frames sent.
std::size_t StackDriver::drain_dirty(TimePoint now) {
    std::size_t sent = 0;
    // Index loop: delivering to the other stacks may append to dirty_.
    for (std::size_t d = 0; d < dirty_.size(); ++d) {
        const std::size_t i = dirty_[d];
        slots_[i].dirty = false;
        if (!slots_[i].stack) continue;
        scratch_.clear();
        slots_[i].stack->drain(scratch_);
        for (const CanFrame& f : scratch_) {
            ++stats_.frames_out;
            ++sent;
            transport_.send(f);
            for (std::size_t j = 0; j < slots_.size(); ++j) {
                if (j != i && slots_[j].stack) slots_[j].stack->on_frame(f, now);
            }
        }
    }
    dirty_.clear();
    return sent;
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

// The deadline minimum is O(stacks): recompute once per burst, not per frame.
void StackDriver::post_rearm() {
    post_once(rearm_posted_, &StackDriver::rearm);
}

void StackDriver::schedule() {
    post_once(posted_, &StackDriver::process);
}

void StackDriver::rearm() {
    std::optional<TimePoint> best;
    for (const auto& s : slots_) {
        if (!s.stack) continue;
        if (auto d = s.stack->next_deadline(); d && (!best || *d < *best)) best = d;
    }
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
    const TimePoint now = Clock::now();
    {
        FlagGuard guard(busy_);  // output made by poll() is flushed by process() below
        for (auto& s : slots_) {
            if (!s.stack) continue;
            if (auto d = s.stack->next_deadline(); d && *d <= now) {
                s.stack->poll(now);
                ++stats_.polls;
            }
        }
    }
    process();
}

}  // namespace olcb
