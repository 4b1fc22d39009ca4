#include "openlcb/alias_allocator.hpp"

#include <utility>

#include "openlcb/can_defs.hpp"
#include "openlcb/mti.hpp"

namespace olcb {
namespace {

// Bounds the (already unlikely) search for an alias not known to be in use.
constexpr int kMaxAliasSkips = 4096;
// Bounds the events an owner that never drains them can pile up.
constexpr std::size_t kMaxQueuedEvents = 256;

}  // namespace

AliasAllocator::AliasAllocator(NodeId node, AliasAllocatorConfig config)
    : node_(node), config_(config), generator_(node) {}

AliasAllocator::AliasAllocator(NodeId node, AliasAllocatorConfig config, AliasGenerator generator)
    : node_(node), config_(config), generator_(generator) {}

void AliasAllocator::start(TimePoint now) {
    if (state_ == State::kIdle || state_ == State::kHalted) begin_reservation(now);
}

void AliasAllocator::share_cache(std::shared_ptr<const AliasCache> cache) {
    shared_ = std::move(cache);
    cache_.clear();
}

void AliasAllocator::begin_reservation(TimePoint now) {
    // A shared cache also holds this node's own mapping, which is no reason to skip its alias.
    const auto taken = [this](std::uint16_t alias) {
        const auto holder = cache().node_of(alias);
        return holder && *holder != node_;
    };
    std::uint16_t alias = generator_.next();
    for (int i = 0; i < kMaxAliasSkips && taken(alias); ++i) alias = generator_.next();
    alias_ = alias;
    ++attempts_;
    for (int n = 7; n >= 4; --n) send(can::make_cid(n, node_, alias_));
    state_ = State::kChecking;
    deadline_ = now + config_.reservation_wait;
}

void AliasAllocator::on_frame(const CanFrame& frame, TimePoint now) {
    if (!can::is_openlcb_frame(frame) || state_ == State::kHalted) return;
    const std::uint16_t src = can::source_alias(frame.id);
    const bool control = can::is_control(frame.id);
    if (alias_ != 0 && src == alias_ && state_ != State::kIdle) {
        handle_own_alias_hit(frame, control && can::is_cid(frame.id), now);
    }
    if (control) {
        handle_control(frame);
    } else {
        learn_from_message(frame);
    }
}

void AliasAllocator::handle_own_alias_hit(const CanFrame& frame, bool is_cid, TimePoint now) {
    (void)frame;
    switch (state_) {
        case State::kChecking:
            // Someone else uses or contends for the tentative alias: try the next one.
            report(AliasEvent::Kind::kConflictRestart);
            begin_reservation(now);
            break;
        case State::kReserved:
            if (is_cid) {
                send(can::make_rid(alias_));
            } else {
                report(AliasEvent::Kind::kConflictRestart);
                begin_reservation(now);
            }
            break;
        case State::kPermitted:
            if (is_cid) {
                send(can::make_rid(alias_));
            } else {
                send(can::make_amr(alias_, node_));
                report(AliasEvent::Kind::kAliasLost);
                begin_reservation(now);
            }
            break;
        case State::kIdle:
        case State::kHalted:
            break;
    }
}

void AliasAllocator::handle_control(const CanFrame& frame) {
    const std::uint16_t src = can::source_alias(frame.id);
    const auto carried = NodeId::from_bytes(std::span(frame.data.data(), frame.len));
    switch (can::classify_control(frame.id)) {
        case can::ControlFrame::kAmd:
            if (!carried) return;
            if (*carried == node_) {
                on_duplicate();
                return;
            }
            if (!shared_) cache_.add(src, *carried);
            break;
        case can::ControlFrame::kAmr:
            if (!shared_) cache_.remove_alias(src);
            break;
        case can::ControlFrame::kAme:
            if (frame.len == 0) {
                if (!shared_) cache_.clear();
                if (state_ == State::kPermitted) send(can::make_amd(alias_, node_));
            } else if (carried && *carried == node_ && state_ == State::kPermitted) {
                send(can::make_amd(alias_, node_));
            }
            break;
        default:
            break;
    }
}

void AliasAllocator::on_duplicate() {
    report(AliasEvent::Kind::kDuplicateNodeId);
    if (!config_.halt_on_duplicate) return;
    if (state_ == State::kPermitted) {
        const auto event = kDuplicateNodeIdEvent.to_bytes();
        send(
            can::make_frame(can::message_header(to_u16(Mti::kEventReport) & 0xFFF, alias_), event));
    }
    state_ = State::kHalted;
}

void AliasAllocator::learn_from_message(const CanFrame& frame) {
    if (can::frame_format(frame.id) != can::FrameFormat::kGlobalAddressed) return;
    switch (can::can_mti(frame.id)) {
        case to_u16(Mti::kInitializationComplete):
        case to_u16(Mti::kInitializationCompleteSimple):
        case to_u16(Mti::kVerifiedNodeId):
        case to_u16(Mti::kVerifiedNodeIdSimple):
            if (auto id = NodeId::from_bytes(std::span(frame.data.data(), frame.len))) {
                const std::uint16_t src = can::source_alias(frame.id);
                if (*id != node_) {
                    if (!shared_) cache_.add(src, *id);
                } else if (can::can_mti(frame.id) != to_u16(Mti::kInitializationComplete) &&
                           can::can_mti(frame.id) != to_u16(Mti::kInitializationCompleteSimple) &&
                           src != alias_ && state_ == State::kPermitted) {
                    // Another node answers a Verify with our ID: the same duplicate as an AMD.
                    on_duplicate();
                }
            }
            break;
        default:
            break;
    }
}

void AliasAllocator::poll(TimePoint now) {
    if (state_ != State::kChecking || now < deadline_) return;
    send(can::make_rid(alias_));
    state_ = State::kReserved;
    if (config_.auto_permit) {
        permit();
    } else {
        report(AliasEvent::Kind::kReserved);
    }
}

std::optional<TimePoint> AliasAllocator::next_deadline() const {
    if (state_ == State::kChecking) return deadline_;
    return std::nullopt;
}

void AliasAllocator::on_transmit_error(TimePoint now) {
    if (state_ == State::kChecking) {
        report(AliasEvent::Kind::kConflictRestart);
        begin_reservation(now);
    }
}

void AliasAllocator::report(AliasEvent::Kind kind) {
    if (events_.size() >= kMaxQueuedEvents) events_.pop_front();
    events_.push_back({kind, alias_});
}

void AliasAllocator::permit() {
    if (state_ != State::kReserved) return;
    send(can::make_amd(alias_, node_));
    state_ = State::kPermitted;
    report(AliasEvent::Kind::kPermitted);
}

void AliasAllocator::release() {
    if (state_ == State::kPermitted) send(can::make_amr(alias_, node_));
    state_ = State::kIdle;
    alias_ = 0;
}

std::optional<CanFrame> AliasAllocator::pop_frame() {
    if (outbox_.empty()) return std::nullopt;
    CanFrame f = outbox_.front();
    outbox_.pop_front();
    return f;
}

std::optional<AliasEvent> AliasAllocator::pop_event() {
    if (events_.empty()) return std::nullopt;
    AliasEvent e = events_.front();
    events_.pop_front();
    return e;
}

}  // namespace olcb
