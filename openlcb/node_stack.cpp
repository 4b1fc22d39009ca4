#include "openlcb/node_stack.hpp"
#include "openlcb/flag_guard.hpp"

#include <algorithm>
#include <utility>

#include "base/error_codes.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/datagram_defs.hpp"
#include "openlcb/mti.hpp"

namespace olcb {
namespace {

constexpr std::uint16_t cmti_of(Mti mti) {
    return to_u16(mti) & 0xFFF;
}

// AMDs this soon after an AME are taken as its answers, not as a node re-initializing: a
// re-initializing node sends Initialization Complete right after its AMD anyway.
constexpr Duration kAmeAnswerWindow = std::chrono::seconds(1);

// Bounds the skipping of generator states that fold to the alias the node had before.
constexpr int kMaxSameAliasSkips = 16;

// Stream data is framed only while fewer frames than this wait in the output, so a large window
// never overflows max_output_frames; the rest follows as the driver drains the output.
constexpr std::size_t kStreamOutputBudget = 256;

std::optional<TimePoint> earliest(std::optional<TimePoint> a, std::optional<TimePoint> b) {
    if (!a) return b;
    if (!b) return a;
    return std::min(*a, *b);
}

}  // namespace

NodeStack::NodeStack(NodeStackConfig config)
    : config_(config),
      alias_(config_.node_id, config_.alias),
      assembler_([this] {
          MessageAssemblerConfig c = config_.assembler;
          c.datagrams = false;  // datagrams belong to the DatagramReceiver
          return c;
      }()),
      sender_(config_.datagram_sender),
      receiver_(config_.datagram_receiver),
      streams_(config_.stream) {}

bool NodeStack::never_rejected(std::uint16_t mti) {
    switch (static_cast<Mti>(mti)) {
        case Mti::kOptionalInteractionRejected:
        case Mti::kTerminateDueToError:
        case Mti::kProtocolSupportReply:
        case Mti::kSnipReply:
        case Mti::kDatagramReceivedOk:
        case Mti::kDatagramRejected:
        case Mti::kStreamInitiateReply:
        case Mti::kStreamDataProceed:
        case Mti::kStreamDataComplete:
        case Mti::kStreamDataSend:
        case Mti::kTractionControlReply:
            return true;
        default:
            return false;
    }
}

// ---------------- lifecycle ----------------

void NodeStack::start(TimePoint now) {
    now_ = now;
    if (started_ || silent_) return;
    started_ = true;
    alias_.start(now);
    collect();
}

void NodeStack::restart(TimePoint now) {
    drop_state();
    silent_ = false;
    start(now);
}

void NodeStack::go_silent(TimePoint now) {
    now_ = now;
    drop_state();
    silent_ = true;
}

void NodeStack::release(TimePoint now) {
    alias_.release();
    // drop_state() replaces the allocator: take its AMR first.
    take_frames(alias_);
    go_silent(now);
}

void NodeStack::drop_state() {
    if (alias() != 0) previous_alias_ = alias();
    std::shared_ptr<const AliasCache> shared = alias_.shared_cache();
    if (config_.new_alias_on_restart) {
        // Two generator states can fold to the same 12 bits: step past any that would hand the
        // node the alias it just had, so it really comes back on another one.
        AliasGenerator generator = alias_.generator();
        for (int i = 0; i < kMaxSameAliasSkips; ++i) {
            AliasGenerator peek = generator;
            if (peek.next() != previous_alias_) break;
            generator = peek;
        }
        alias_ = AliasAllocator(config_.node_id, config_.alias, generator);
    } else {
        // A fresh allocator: a rebooted node forgets its cache and starts from the first alias.
        alias_ = AliasAllocator(config_.node_id, config_.alias);
    }
    alias_.share_cache(std::move(shared));  // the segment's, not the node's to forget
    assembler_.clear();
    receiver_.set_alias(0);
    receiver_.reset();
    sender_.abort_all();
    sender_.set_alias(0);
    streams_.reset();
    pending_.clear();
    initialized_ = false;
    started_ = false;
}

void NodeStack::share_alias_cache(std::shared_ptr<const AliasCache> cache) {
    alias_.share_cache(std::move(cache));
}

void NodeStack::set_global_messages(std::optional<std::vector<Mti>> mtis) {
    global_can_mtis_.reset();
    if (!mtis) return;
    global_can_mtis_.emplace();
    for (const Mti mti : *mtis) {
        if (mti == Mti::kEventReportWithPayload) {
            // Carried by frames of three CAN-MTIs of its own.
            global_can_mtis_->insert(global_can_mtis_->end(),
                                     {can::kCanMtiPcerPayloadFirst, can::kCanMtiPcerPayloadMiddle,
                                      can::kCanMtiPcerPayloadLast});
        } else {
            global_can_mtis_->push_back(cmti_of(mti));
        }
    }
}

bool NodeStack::takes_global(std::uint16_t can_mti) const {
    return !global_can_mtis_ || std::find(global_can_mtis_->begin(), global_can_mtis_->end(),
                                          can_mti) != global_can_mtis_->end();
}

void NodeStack::reinitialize(TimePoint now) {
    now_ = now;
    if (!initialized()) return;
    assembler_.clear();
    receiver_.reset();
    send_initialization_complete();
    if (on_initialized_) on_initialized_();
    collect();
}

void NodeStack::send_initialization_complete() {
    const Mti mti = config_.protocols.has(Protocol::kSimpleProtocol)
                        ? Mti::kInitializationCompleteSimple
                        : Mti::kInitializationComplete;
    push_frame(
        can::make_node_id_frame(can::message_header(cmti_of(mti), alias()), config_.node_id));
    ++initializations_;
}

void NodeStack::handle_alias_event(const AliasEvent& event) {
    if (on_alias_event_) on_alias_event_(event);
    switch (event.kind) {
        case AliasEvent::Kind::kPermitted:
            enter_permitted();
            break;
        case AliasEvent::Kind::kAliasLost:
            // Everything addressed to the old alias is void; outstanding datagrams cannot be
            // acknowledged any more, so they end now instead of timing out later.
            receiver_.set_alias(0);
            sender_.abort_all();
            sender_.set_alias(0);
            assembler_.clear();
            break;
        case AliasEvent::Kind::kDuplicateNodeId:
            announce_duplicate();
            break;
        default:
            break;
    }
}

void NodeStack::announce_duplicate() {
    // halt_on_duplicate has sent its own PCER already.
    if (!config_.builtins.duplicate_id_pcer || !initialized() || halted()) return;
    // A flood of duplicates (or an echoing hub) must not turn into a flood of reports.
    if (last_duplicate_pcer_ && now_ - *last_duplicate_pcer_ < kDuplicatePcerInterval) return;
    last_duplicate_pcer_ = now_;
    push_frame(can::make_frame(can::message_header(cmti_of(Mti::kEventReport), alias()),
                               kDuplicateNodeIdEvent.to_bytes()));
}

void NodeStack::enter_permitted() {
    const std::uint16_t a = alias();
    receiver_.set_alias(a);
    sender_.set_alias(a);
    if (!initialized_ || config_.reinitialize_after_alias_change) {
        send_initialization_complete();
        logged_in_at_ = now_;
        initialized_ = true;
        flush_pending();
        if (on_initialized_) on_initialized_();
    } else {
        flush_pending();
    }
}

void NodeStack::flush_pending() {
    std::vector<Message> pending;
    pending.swap(pending_);
    for (auto& m : pending) frame_message(m);
}

// ---------------- input ----------------

void NodeStack::on_frame(const CanFrame& frame, TimePoint now) {
    now_ = now;
    if (silent_) return;
    const FrameRoute route = inbound_filter_ ? inbound_filter_(frame, now) : FrameRoute{};
    if (!can::is_openlcb_frame(frame) || frame.len > 8) return;
    if (route.alias) alias_.on_frame(frame, now);
    // The allocator reports nothing without queueing a frame, except a duplicate node ID (an
    // AMD or Verified Node ID carrying our ID): skipping collect() otherwise keeps 1,000 stacks
    // per bus cheap.
    const bool control = can::is_control(frame.id);
    if (!alias_.pending_frames().empty() || alias_.has_events() ||
        (control && can::classify_control(frame.id) == can::ControlFrame::kAmd)) {
        collect();
    }
    if (control && can::classify_control(frame.id) == can::ControlFrame::kAme) last_ame_ = now;
    if (sender_.queued() != 0 && announces_reinitialization(frame, control, now)) {
        // Its new run will never ack what the old one was sent: waiting out the ack timeout
        // would only delay the next datagram to it (memconfig_utils re-runs on the same alias).
        sender_.abort_to(can::source_alias(frame.id));
        collect();
    }
    if (control || !initialized() || !route.messages) return;
    route_message_frame(frame, now);
}

// A message frame of an initialized node, to the handler of its format if it is for us.
void NodeStack::route_message_frame(const CanFrame& frame, TimePoint now) {
    const std::uint16_t me = alias();
    switch (can::frame_format(frame.id)) {
        case can::FrameFormat::kGlobalAddressed: {
            if (!is_addressed(static_cast<Mti>(can::can_mti(frame.id)))) {
                on_global_frame(frame, now);
            } else if (frame.len >= 2 && can::addressed_dest(frame.data[0], frame.data[1]) == me) {
                on_addressed_frame(frame, now);
            }
            break;
        }
        case can::FrameFormat::kDatagramOnly:
        case can::FrameFormat::kDatagramFirst:
        case can::FrameFormat::kDatagramMiddle:
        case can::FrameFormat::kDatagramLast:
            if (can::dest_alias(frame.id) == me) on_datagram_frame(frame, now);
            break;
        case can::FrameFormat::kStreamData:
            if (can::dest_alias(frame.id) == me) {
                if (auto msg = assembler_.on_frame(frame, now)) dispatch(*msg);
            }
            break;
        default:
            break;
    }
}

bool NodeStack::announces_reinitialization(const CanFrame& frame, bool control,
                                           TimePoint now) const {
    if (control) {
        return can::classify_control(frame.id) == can::ControlFrame::kAmd &&
               !(last_ame_ && now - *last_ame_ < kAmeAnswerWindow);
    }
    if (can::frame_format(frame.id) != can::FrameFormat::kGlobalAddressed) return false;
    const std::uint16_t cmti = can::can_mti(frame.id);
    return cmti == cmti_of(Mti::kInitializationComplete) ||
           cmti == cmti_of(Mti::kInitializationCompleteSimple);
}

void NodeStack::on_global_frame(const CanFrame& frame, TimePoint now) {
    const std::uint16_t cmti = can::can_mti(frame.id);
    const bool taken = on_message_ && takes_global(cmti);
    if (cmti == can::kCanMtiPcerPayloadFirst || cmti == can::kCanMtiPcerPayloadMiddle ||
        cmti == can::kCanMtiPcerPayloadLast) {
        if (!taken) return;  // no built-in uses it: do not reassemble for nobody
        if (auto msg = assembler_.on_frame(frame, now)) dispatch(*msg);
        return;
    }
    const bool builtin =
        cmti == cmti_of(Mti::kVerifyNodeIdGlobal) && config_.builtins.verify_node_id;
    if (!builtin && !taken) return;  // nobody would look at it: stay cheap
    const std::uint16_t src = can::source_alias(frame.id);
    scratch_.mti = static_cast<Mti>(cmti);
    scratch_.source = NodeHandle{alias_.cache().node_of(src).value_or(NodeId{}), src};
    scratch_.destination.reset();
    scratch_.payload.assign(frame.data.begin(), frame.data.begin() + frame.len);
    dispatch(scratch_);
}

void NodeStack::on_addressed_frame(const CanFrame& frame, TimePoint now) {
    const std::uint16_t cmti = can::can_mti(frame.id);
    if (cmti == cmti_of(Mti::kDatagramReceivedOk) || cmti == cmti_of(Mti::kDatagramRejected) ||
        cmti == cmti_of(Mti::kOptionalInteractionRejected)) {
        if (sender_.on_frame(frame, now)) {
            collect();
            return;
        }
    }
    auto msg = assembler_.on_frame(frame, now);
    if (!msg) return;
    msg->source.id = alias_.cache().node_of(msg->source.alias).value_or(NodeId{});
    if (msg->destination) msg->destination->id = config_.node_id;
    dispatch(*msg);
}

void NodeStack::on_datagram_frame(const CanFrame& frame, TimePoint now) {
    const std::uint16_t src = can::source_alias(frame.id);
    if (!on_datagram_) {
        // No datagram support: answer each datagram once, on its closing frame (fact sheet 4.2).
        const auto format = can::frame_format(frame.id);
        if (config_.builtins.reject_datagrams_without_handler &&
            (format == can::FrameFormat::kDatagramOnly ||
             format == can::FrameFormat::kDatagramLast)) {
            send_oir(src, base::to_u16(base::ErrorCode::kUnknownMtiOrTransport),
                     to_u16(Mti::kDatagram));
        }
        return;
    }
    receiver_.on_frame(frame, now);
    while (auto d = receiver_.pop_datagram()) {
        if (on_datagram_) {
            on_datagram_(*d);
        } else {
            receiver_.reject(d->source_alias,
                             base::to_u16(base::ErrorCode::kUnknownMtiOrTransport));
        }
    }
    take_frames(receiver_);  // owner calls made inside the handler collected for themselves
}

void NodeStack::dispatch(const Message& msg) {
    if (handle_builtin(msg)) return;
    if (config_.streams && msg.destination && StreamTransport::handles(msg.mti) &&
        streams_.on_message(msg, now_)) {
        if (on_message_) on_message_(msg);  // owners may watch stream traffic; it is answered
        collect();
        return;
    }
    const bool handled = on_message_ && on_message_(msg);
    if (!handled && msg.destination && config_.builtins.reject_unknown_addressed &&
        !never_rejected(to_u16(msg.mti))) {
        send_oir(msg.source.alias, base::to_u16(base::ErrorCode::kUnknownMtiOrTransport),
                 to_u16(msg.mti));
    }
    collect();
}

void NodeStack::push_verified_node_id() {
    const Mti verified = config_.protocols.has(Protocol::kSimpleProtocol)
                             ? Mti::kVerifiedNodeIdSimple
                             : Mti::kVerifiedNodeId;
    push_frame(
        can::make_node_id_frame(can::message_header(cmti_of(verified), alias()), config_.node_id));
}

bool NodeStack::handle_builtin(const Message& msg) {
    const std::uint16_t src = msg.source.alias;
    switch (msg.mti) {
        case Mti::kVerifyNodeIdGlobal: {
            if (!config_.builtins.verify_node_id) return false;
            // Answer when empty or carrying our ID; another ID (or a malformed one) is not for us.
            const auto asked = NodeId::from_bytes(msg.payload);
            if (msg.payload.empty() || (asked && *asked == config_.node_id)) {
                push_verified_node_id();
            }
            return true;
        }
        case Mti::kVerifyNodeIdAddressed:
            if (!config_.builtins.verify_node_id) return false;
            push_verified_node_id();
            return true;
        case Mti::kProtocolSupportInquiry: {
            if (!config_.builtins.protocol_support) return false;
            const auto flags = config_.protocols.encode();
            CanFrame f;
            f.id = can::message_header(cmti_of(Mti::kProtocolSupportReply), alias());
            f.data[0] = static_cast<std::uint8_t>(src >> 8 & 0x0F);
            f.data[1] = static_cast<std::uint8_t>(src & 0xFF);
            std::copy(flags.begin(), flags.end(), f.data.begin() + 2);
            f.len = 8;
            push_frame(f);
            return true;
        }
        default:
            return false;
    }
}

void NodeStack::send_oir(std::uint16_t dest, std::uint16_t code, std::uint16_t mti) {
    if (!initialized()) return;  // an owner callback may have restarted the node meanwhile
    CanFrame f;
    f.id = can::message_header(cmti_of(Mti::kOptionalInteractionRejected), alias());
    f.data = {static_cast<std::uint8_t>(dest >> 8 & 0x0F),
              static_cast<std::uint8_t>(dest & 0xFF),
              static_cast<std::uint8_t>(code >> 8),
              static_cast<std::uint8_t>(code & 0xFF),
              static_cast<std::uint8_t>(mti >> 8),
              static_cast<std::uint8_t>(mti & 0xFF),
              0,
              0};
    f.len = 6;
    push_frame(f);
}

void NodeStack::poll(TimePoint now) {
    now_ = now;
    alias_.poll(now);
    assembler_.poll(now);
    receiver_.poll(now);
    sender_.poll(now);
    streams_.poll(now);
    collect();
    run_timers(now);
}

std::optional<TimePoint> NodeStack::next_deadline() const {
    const std::optional<TimePoint> timer =
        timers_.empty() ? std::nullopt : std::optional<TimePoint>(timers_.begin()->first);
    // Stream data held back by the output budget goes out at the next poll.
    const std::optional<TimePoint> streams =
        streams_.has_output() ? std::optional<TimePoint>(now_) : streams_.next_deadline();
    return earliest(earliest(earliest(alias_.next_deadline(), assembler_.next_deadline()),
                             earliest(receiver_.next_deadline(), sender_.next_deadline())),
                    earliest(timer, streams));
}

void NodeStack::schedule(TimePoint at, TimerHandler fn) {
    if (!fn) return;
    timers_.emplace(at, std::move(fn));  // equal keys keep insertion order
    // A new deadline without output: tell the driver too, so it re-arms its timer.
    if (on_output_) on_output_();
}

void NodeStack::run_timers(TimePoint now) {
    // Only timers due before this call run now: one that re-arms itself for `now` waits for the
    // next poll() instead of looping here forever.
    std::vector<TimerHandler> due;
    while (!timers_.empty() && timers_.begin()->first <= now) {
        due.push_back(std::move(timers_.begin()->second));
        timers_.erase(timers_.begin());
    }
    for (auto& fn : due) fn(now);
    collect();
}

void NodeStack::on_transmit_error(TimePoint now) {
    alias_.on_transmit_error(now);
    collect();
}

// ---------------- output ----------------

SendStatus NodeStack::send_message(Message msg) {
    if (halted()) return SendStatus::kHalted;
    if (silent_) return SendStatus::kSilent;
    msg.source = NodeHandle{config_.node_id, alias()};
    if (is_addressed(msg.mti) || is_stream_or_datagram(msg.mti)) {
        if (!msg.destination) return SendStatus::kUnknownDestination;
        NodeHandle& dest = *msg.destination;
        if (dest.alias == 0) {
            const auto known = dest.id.is_zero() ? std::nullopt : alias_.cache().alias_of(dest.id);
            if (!known) return SendStatus::kUnknownDestination;
            dest.alias = *known;
        }
    }
    if (initialized()) return frame_message(msg);
    // Check the framing now so a bad message is refused at once, not dropped later.
    msg.source.alias = 1;
    encode_buf_.clear();
    if (encode_message(msg, encode_buf_) != FramingError::kNone) return SendStatus::kFramingError;
    if (pending_.size() >= config_.max_pending_messages) return SendStatus::kQueueFull;
    pending_.push_back(std::move(msg));
    return SendStatus::kQueued;
}

SendStatus NodeStack::frame_message(Message& msg) {
    msg.source.alias = alias();
    // A message the owner's filter drops counts as sent: for the sender it went on the wire.
    if (outbound_filter_ && !outbound_filter_(msg)) return SendStatus::kSent;
    encode_buf_.clear();
    if (encode_message(msg, encode_buf_) != FramingError::kNone) return SendStatus::kFramingError;
    for (const auto& f : encode_buf_) push_frame(f);
    return SendStatus::kSent;
}

std::optional<std::uint32_t> NodeStack::send_datagram(std::uint16_t dest_alias,
                                                      std::span<const std::uint8_t> payload,
                                                      TimePoint now) {
    if (!initialized()) return std::nullopt;
    auto id = sender_.send(dest_alias, payload, now);
    take_frames(sender_);  // send() reports no outcome by itself
    return id;
}

bool NodeStack::accept_datagram(std::uint16_t src, std::uint8_t flags) {
    if (receiver_.alias() == 0 || !initialized()) return false;
    const bool held = receiver_.accept(src, flags);
    take_frames(receiver_);
    return held;
}

bool NodeStack::reject_datagram(std::uint16_t src, std::uint16_t code) {
    if (receiver_.alias() == 0 || !initialized()) return false;
    const bool held = receiver_.reject(src, code);
    take_frames(receiver_);
    return held;
}

bool NodeStack::release_datagram(std::uint16_t src) {
    return receiver_.release(src);
}

bool NodeStack::settle_datagram(std::uint32_t id, TimePoint now) {
    const bool settled = sender_.settle(id, now);
    collect();  // the outcome now (its owner waits on it), and the next datagram to that node
    return settled;
}

void NodeStack::push_frame(const CanFrame& frame) {
    if (out_.size() - out_head_ >= config_.max_output_frames) {
        ++dropped_frames_;
        return;
    }
    const bool was_empty = !has_output();
    if (out_head_ > 64 && out_head_ * 2 > out_.size()) {
        out_.erase(out_.begin(), out_.begin() + static_cast<std::ptrdiff_t>(out_head_));
        out_head_ = 0;
    }
    out_.push_back(frame);
    if (was_empty && on_output_) on_output_();
}

std::optional<CanFrame> NodeStack::pop_frame() {
    if (out_head_ >= out_.size()) return std::nullopt;
    const CanFrame f = out_[out_head_++];
    if (out_head_ == out_.size()) {
        out_.clear();  // keeps the capacity: no allocation in steady state
        out_head_ = 0;
    }
    return f;
}

std::size_t NodeStack::drain(std::vector<CanFrame>& out) {
    const std::size_t n = out_.size() - out_head_;
    out.insert(out.end(), out_.begin() + static_cast<std::ptrdiff_t>(out_head_), out_.end());
    out_.clear();
    out_head_ = 0;
    return n;
}

void NodeStack::collect() {
    if (collecting_) return;  // a callback re-entered: the outer loop picks everything up
    FlagGuard guard(collecting_);
    for (bool progress = true; progress;) {
        progress = false;
        while (auto f = alias_.pop_frame()) {
            push_frame(*f);
            progress = true;
        }
        while (auto e = alias_.pop_event()) {
            handle_alias_event(*e);
            progress = true;
        }
        while (auto f = receiver_.pop_frame()) {
            push_frame(*f);
            progress = true;
        }
        while (auto f = sender_.pop_frame()) {
            push_frame(*f);
            progress = true;
        }
        while (auto o = sender_.pop_outcome()) {
            if (on_outcome_) on_outcome_(*o);
            progress = true;
        }
        if (collect_streams()) progress = true;
    }
}

bool NodeStack::collect_streams() {
    bool progress = false;
    while (initialized() && out_.size() - out_head_ < kStreamOutputBudget) {
        auto m = streams_.pop_message();
        if (!m) break;
        m->source = NodeHandle{config_.node_id, alias()};
        frame_message(*m);
        progress = true;
    }
    while (auto e = streams_.pop_event()) {
        if (on_stream_) on_stream_(*e);
        progress = true;
    }
    return progress;
}

std::optional<std::uint32_t> NodeStack::open_stream(NodeHandle dest, std::uint16_t buffer,
                                                    std::uint8_t suggested_dest_id) {
    if (!config_.streams || !initialized() || dest.alias == 0) return std::nullopt;
    auto id = streams_.open(dest, buffer, suggested_dest_id, now_);
    collect();
    return id;
}

bool NodeStack::write_stream(std::uint32_t id, std::span<const std::uint8_t> data) {
    const bool ok = streams_.write(id, data);
    collect();
    return ok;
}

bool NodeStack::close_stream(std::uint32_t id) {
    const bool ok = streams_.close(id);
    collect();
    return ok;
}

void NodeStack::expect_stream(std::uint16_t remote_alias, std::uint8_t dest_id,
                              std::uint16_t max_buffer, bool auto_proceed) {
    streams_.expect(remote_alias, dest_id, max_buffer, auto_proceed);
}

bool NodeStack::proceed_stream(std::uint32_t id) {
    const bool ok = streams_.proceed(id);
    collect();
    return ok;
}

}  // namespace olcb
