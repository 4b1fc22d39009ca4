#include "conformance/link/real_link.hpp"

#include <algorithm>
#include <chrono>

#include "base/timings.hpp"

namespace olcb::conform {

TapTransport::TapTransport(Transport& inner) : inner_(inner) {
    inner_.set_handler([this](const CanFrame& frame) {
        if (observer_) observer_(frame, Clock::now());
        if (handler_) handler_(frame);
    });
}

void TapTransport::send(const CanFrame& frame) {
    if (observer_) observer_(frame, Clock::now());
    inner_.send(frame);
}

void TapTransport::set_handler(FrameHandler handler) {
    handler_ = std::move(handler);
}

namespace {

// On a real link lcc-conform waits 50 ms past the standard's 200 ms between its last CID and
// RID: a hub or node times frames when it gets to them, so CIDs read late (a busy hub, a slow
// accept) would otherwise make a correct wait look short to it. Waiting longer is conformant.
constexpr auto kReservationMargin = std::chrono::milliseconds(50);

NodeStackConfig real_stack_config(NodeId tool_id) {
    NodeStackConfig config = tool_stack_config(tool_id);
    config.alias.reservation_wait = base::kAliasReservationWait + kReservationMargin;
    return config;
}

}  // namespace

RealLink::RealLink(std::unique_ptr<boost::asio::io_context> io, NodeId tool_id)
    : io_(std::move(io)), stack_(real_stack_config(tool_id)) {}

RealLink::~RealLink() {
    detach();
}

void RealLink::detach() {
    driver_.reset();
    if (inner_) inner_->set_handler({});
    inner_ = nullptr;
}

void RealLink::attach(Transport& transport) {
    inner_ = &transport;
    tap_ = std::make_unique<TapTransport>(transport);
    tap_->set_observer([this](const CanFrame& frame, TimePoint at) {
        if (observer_) observer_(frame, at);
    });
    driver_ = std::make_unique<StackDriver>(*io_, *tap_);
    driver_->attach(stack_);
    stack_.start(Clock::now());
    driver_->kick();
}

bool RealLink::run_until(const std::function<bool()>& pred, Duration max) {
    const TimePoint limit = Clock::now() + max;
    for (;;) {
        if (pred && pred()) return true;
        const TimePoint t = Clock::now();
        if (t >= limit) return pred && pred();
        if (io_->stopped()) io_->restart();
        io_->run_one_for(std::min<Duration>(limit - t, std::chrono::milliseconds(20)));
    }
}

void RealLink::send_frame(const CanFrame& frame) {
    if (observer_) observer_(frame, Clock::now());
    if (inner_) inner_->send(frame);
}

void RealLink::set_up(bool up, const std::string& reason) {
    if (up_ && !up) {
        ++losses_;
        loss_reason_ = reason;
    }
    up_ = up;
}

void RealLink::set_frame_observer(FrameObserver observer) {
    observer_ = std::move(observer);
}

}  // namespace olcb::conform
