#include "openlcb/datagram_transport.hpp"

#include <algorithm>

#include "base/error_codes.hpp"
#include "openlcb/addressed_framing.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/mti.hpp"

namespace olcb {
namespace {

// Addressed reply frame (OK / Rejected) from src to dst with up to 6 extra bytes.
CanFrame addressed_reply(Mti mti, std::uint16_t src, std::uint16_t dst,
                         std::initializer_list<std::uint8_t> extra) {
    CanFrame f;
    f.id = can::message_header(to_u16(mti) & 0xFFF, src);
    f.data[0] = static_cast<std::uint8_t>(dst >> 8 & 0x0F);
    f.data[1] = static_cast<std::uint8_t>(dst & 0xFF);
    std::size_t n = 2;
    for (std::uint8_t b : extra) f.data[n++] = b;
    f.len = static_cast<std::uint8_t>(n);
    return f;
}

template <class T>
std::optional<T> pop(std::deque<T>& q) {
    if (q.empty()) return std::nullopt;
    T v = std::move(q.front());
    q.pop_front();
    return v;
}

}  // namespace

// ---------------- DatagramSender ----------------

std::optional<std::uint32_t> DatagramSender::send(std::uint16_t dest_alias,
                                                  std::span<const std::uint8_t> payload,
                                                  TimePoint now) {
    if (payload.size() > datagram::kMaxSize || alias_ == 0 || dest_alias == 0 ||
        dest_alias > can::kAliasMask || entries_.size() >= config_.max_queued) {
        return std::nullopt;
    }
    const std::uint32_t id = next_id_++;
    const bool busy = outstanding_for(dest_alias).has_value();
    entries_.push_back(Entry{id, dest_alias, {payload.begin(), payload.end()}});
    if (!busy) transmit(entries_.back(), now);
    return id;
}

void DatagramSender::transmit(Entry& e, TimePoint now) {
    Message m;
    m.mti = Mti::kDatagram;
    m.source.alias = alias_;
    m.destination = NodeHandle{NodeId{}, e.dest};
    m.payload = e.payload;
    std::vector<CanFrame> frames;
    encode_message(m, frames);  // cannot fail: sizes and aliases were checked in send()
    outbox_.insert(outbox_.end(), frames.begin(), frames.end());
    e.phase = Phase::kWaitingAck;
    e.deadline = now + config_.ack_timeout;
    ++e.attempts;
}

std::optional<std::size_t> DatagramSender::outstanding_for(std::uint16_t dest) const {
    for (std::size_t i = 0; i < entries_.size(); ++i) {
        if (entries_[i].dest == dest && entries_[i].phase != Phase::kQueued) return i;
    }
    return std::nullopt;
}

void DatagramSender::finish(std::size_t index, DatagramOutcome::Status status, std::uint16_t code,
                            std::uint8_t flags, TimePoint now) {
    const Entry& e = entries_[index];
    const std::uint16_t dest = e.dest;
    outcomes_.push_back(DatagramOutcome{e.id, dest, status, code, flags, e.attempts});
    entries_.erase(entries_.begin() + static_cast<std::ptrdiff_t>(index));
    // The next datagram to the same node may go now.
    for (auto& next : entries_) {
        if (next.dest == dest) {
            transmit(next, now);
            break;
        }
    }
}

bool DatagramSender::on_frame(const CanFrame& frame, TimePoint now) {
    if (!can::is_openlcb_frame(frame) || !can::is_message(frame.id) || alias_ == 0 ||
        can::frame_format(frame.id) != can::FrameFormat::kGlobalAddressed || frame.len < 2) {
        return false;
    }
    const std::uint16_t cmti = can::can_mti(frame.id);
    const bool ok = cmti == (to_u16(Mti::kDatagramReceivedOk) & 0xFFF);
    const bool rejected = cmti == (to_u16(Mti::kDatagramRejected) & 0xFFF);
    const bool oir = cmti == (to_u16(Mti::kOptionalInteractionRejected) & 0xFFF);
    if (!ok && !rejected && !oir) return false;
    if (can::addressed_dest(frame.data[0], frame.data[1]) != alias_) return false;
    if (can::addressed_framing(frame.data[0]) != can::AddressedFraming::kOnly &&
        can::addressed_framing(frame.data[0]) != can::AddressedFraming::kFirst) {
        return false;
    }
    const auto index = outstanding_for(can::source_alias(frame.id));
    if (!index || entries_[*index].phase != Phase::kWaitingAck) return false;
    // Truncated contents read as zero bits (fact sheet 3).
    auto byte = [&](std::size_t i) -> std::uint8_t { return i < frame.len ? frame.data[i] : 0; };
    if (ok) {
        finish(*index, DatagramOutcome::Status::kAccepted, 0, byte(2), now);
        return true;
    }
    const auto code = static_cast<std::uint16_t>(byte(2) << 8 | byte(3));
    if (oir && frame.len >= 6) {
        const auto mti = static_cast<std::uint16_t>(byte(4) << 8 | byte(5));
        if (mti != to_u16(Mti::kDatagram)) return false;  // about some other message of ours
    }
    Entry& e = entries_[*index];
    if (base::is_temporary(code) && e.attempts <= config_.max_resends) {
        if (config_.resend_delay <= Duration::zero()) {
            transmit(e, now);
        } else {
            e.phase = Phase::kWaitingResend;
            e.deadline = now + config_.resend_delay;
        }
        return true;
    }
    finish(*index, DatagramOutcome::Status::kRejected, code, 0, now);
    return true;
}

void DatagramSender::poll(TimePoint now) {
    for (std::size_t i = 0; i < entries_.size();) {
        Entry& e = entries_[i];
        if (e.phase == Phase::kWaitingResend && now >= e.deadline) {
            transmit(e, now);
        } else if (e.phase == Phase::kWaitingAck && now >= e.deadline) {
            // finish() may start a later entry, which sits after i: keep scanning from i.
            finish(i, DatagramOutcome::Status::kTimedOut, base::to_u16(base::ErrorCode::kTimeout),
                   0, now);
            continue;
        }
        ++i;
    }
}

std::optional<TimePoint> DatagramSender::next_deadline() const {
    std::optional<TimePoint> best;
    for (const auto& e : entries_) {
        if (e.phase == Phase::kQueued) continue;
        if (!best || e.deadline < *best) best = e.deadline;
    }
    return best;
}

void DatagramSender::abort_all() {
    for (const auto& e : entries_) {
        outcomes_.push_back(
            DatagramOutcome{e.id, e.dest, DatagramOutcome::Status::kAborted, 0, 0, e.attempts});
    }
    entries_.clear();
}

std::size_t DatagramSender::abort_to(std::uint16_t dest_alias) {
    // Every entry to dest goes, so no later one needs starting (unlike finish()); outcomes keep
    // the send order.
    std::size_t dropped = 0;
    for (auto it = entries_.begin(); it != entries_.end();) {
        if (it->dest != dest_alias) {
            ++it;
            continue;
        }
        outcomes_.push_back(DatagramOutcome{it->id, it->dest, DatagramOutcome::Status::kAborted, 0,
                                            0, it->attempts});
        it = entries_.erase(it);
        ++dropped;
    }
    return dropped;
}

bool DatagramSender::settle(std::uint32_t id, TimePoint now) {
    for (std::size_t i = 0; i < entries_.size(); ++i) {
        if (entries_[i].id != id) continue;
        if (entries_[i].phase != Phase::kWaitingAck) return false;
        finish(i, DatagramOutcome::Status::kUnacknowledged, 0, 0, now);
        return true;
    }
    return false;
}

std::optional<CanFrame> DatagramSender::pop_frame() {
    return pop(outbox_);
}

std::optional<DatagramOutcome> DatagramSender::pop_outcome() {
    return pop(outcomes_);
}

// ---------------- DatagramReceiver ----------------

void DatagramReceiver::set_alias(std::uint16_t alias) {
    if (alias != alias_) reset();
    alias_ = alias;
}

void DatagramReceiver::reset() {
    slots_.clear();
    ready_.clear();
    discarding_.reset();
}

DatagramReceiver::Slot* DatagramReceiver::find(std::uint16_t src) {
    for (auto& s : slots_) {
        if (s.src == src) return &s;
    }
    return nullptr;
}

void DatagramReceiver::erase(std::uint16_t src) {
    std::erase_if(slots_, [&](const Slot& s) { return s.src == src; });
}

void DatagramReceiver::send_reject(std::uint16_t src, std::uint16_t code) {
    ++rejections_;
    outbox_.push_back(addressed_reply(
        Mti::kDatagramRejected, alias_, src,
        {static_cast<std::uint8_t>(code >> 8), static_cast<std::uint8_t>(code & 0xFF)}));
}

void DatagramReceiver::start(std::uint16_t src, const CanFrame& frame, bool complete,
                             TimePoint now) {
    Slot s{src, complete, now, {}};
    s.data.reserve(complete ? frame.len : datagram::kMaxSize);
    s.data.assign(frame.data.begin(), frame.data.begin() + frame.len);
    slots_.push_back(std::move(s));
    if (complete) ready_.push_back(src);
}

void DatagramReceiver::on_frame(const CanFrame& frame, TimePoint now) {
    if (!can::is_openlcb_frame(frame) || !can::is_message(frame.id) || alias_ == 0 ||
        frame.len > 8) {
        return;
    }
    const auto format = can::frame_format(frame.id);
    if (!can::is_datagram_format(format) || can::dest_alias(frame.id) != alias_) return;
    const std::uint16_t src = can::source_alias(frame.id);
    Slot* slot = find(src);
    const bool starts =
        format == can::FrameFormat::kDatagramOnly || format == can::FrameFormat::kDatagramFirst;
    const bool only = format == can::FrameFormat::kDatagramOnly;

    if (starts) {
        on_first_frame(src, slot, frame, only, now);
    } else {
        on_later_frame(src, slot, frame, format == can::FrameFormat::kDatagramLast, now);
    }
}

// Only or First: a new datagram from src, refused while one is unfinished or no buffer is free.
void DatagramReceiver::on_first_frame(std::uint16_t src, const Slot* slot, const CanFrame& frame,
                                      bool only, TimePoint now) {
    discarding_[src] = false;  // whatever was being skipped is over
    std::uint16_t code = 0;
    if (slot && !slot->complete) {
        code = base::to_u16(base::ErrorCode::kFirstBeforePreviousFinished);
        erase(src);
    } else if (slot || slots_.size() >= config_.max_buffers) {
        code = base::to_u16(base::ErrorCode::kBufferUnavailable);
    }
    if (code != 0) {
        send_reject(src, code);
        if (!only) discarding_[src] = true;
        return;
    }
    start(src, frame, only, now);
}

// Middle or Last: appended to src's unfinished datagram; the rest of a refused one is skipped.
void DatagramReceiver::on_later_frame(std::uint16_t src, Slot* slot, const CanFrame& frame,
                                      bool last, TimePoint now) {
    if (discarding_[src]) {
        if (last) discarding_[src] = false;
        return;
    }
    if (!slot || slot->complete) {
        send_reject(src, base::to_u16(base::ErrorCode::kMiddleOrLastWithoutFirst));
        if (!last) discarding_[src] = true;
        return;
    }
    if (slot->data.size() + frame.len > datagram::kMaxSize) {
        erase(src);
        send_reject(src, base::to_u16(base::ErrorCode::kPermanent));
        if (!last) discarding_[src] = true;
        return;
    }
    slot->data.insert(slot->data.end(), frame.data.begin(), frame.data.begin() + frame.len);
    slot->last = now;
    if (last) {
        slot->complete = true;
        ready_.push_back(src);
    }
}

void DatagramReceiver::poll(TimePoint now) {
    const auto before = slots_.size();
    std::erase_if(slots_, [&](const Slot& s) {
        return !s.complete && now - s.last >= config_.reassembly_timeout;
    });
    timeouts_ += before - slots_.size();
}

std::optional<TimePoint> DatagramReceiver::next_deadline() const {
    std::optional<TimePoint> best;
    for (const auto& s : slots_) {
        if (s.complete) continue;
        const TimePoint t = s.last + config_.reassembly_timeout;
        if (!best || t < *best) best = t;
    }
    return best;
}

std::optional<ReceivedDatagram> DatagramReceiver::pop_datagram() {
    while (!ready_.empty()) {
        const std::uint16_t src = ready_.front();
        ready_.pop_front();
        if (Slot* s = find(src); s && s->complete) {
            return ReceivedDatagram{src, alias_, s->data};
        }
    }
    return std::nullopt;
}

bool DatagramReceiver::accept(std::uint16_t source_alias, std::uint8_t flags) {
    outbox_.push_back(addressed_reply(Mti::kDatagramReceivedOk, alias_, source_alias, {flags}));
    Slot* s = find(source_alias);
    const bool held = s && s->complete;
    if (held) erase(source_alias);
    return held;
}

bool DatagramReceiver::reject(std::uint16_t source_alias, std::uint16_t code) {
    outbox_.push_back(addressed_reply(
        Mti::kDatagramRejected, alias_, source_alias,
        {static_cast<std::uint8_t>(code >> 8), static_cast<std::uint8_t>(code & 0xFF)}));
    Slot* s = find(source_alias);
    const bool held = s && s->complete;
    if (held) erase(source_alias);
    return held;
}

bool DatagramReceiver::release(std::uint16_t source_alias) {
    Slot* s = find(source_alias);
    const bool held = s && s->complete;
    if (held) erase(source_alias);
    return held;
}

std::optional<CanFrame> DatagramReceiver::pop_frame() {
    return pop(outbox_);
}

}  // namespace olcb
