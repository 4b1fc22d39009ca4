#include "openlcb/addressed_framing.hpp"

#include <algorithm>

#include "openlcb/can_defs.hpp"
#include "openlcb/datagram_defs.hpp"

namespace olcb {
namespace {

CanFrame frame_of(std::uint32_t id, const std::uint8_t* bytes, std::size_t count) {
    CanFrame f;
    f.id = id;
    f.len = static_cast<std::uint8_t>(count);
    std::copy_n(bytes, count, f.data.begin());
    return f;
}

Message make_message(Mti mti, std::uint16_t src, std::optional<std::uint16_t> dst,
                     std::vector<std::uint8_t> payload) {
    Message m;
    m.mti = mti;
    m.source.alias = src;
    if (dst) m.destination = NodeHandle{NodeId{}, *dst};
    m.payload = std::move(payload);
    return m;
}

void encode_addressed(const Message& msg, std::uint16_t dst, std::vector<CanFrame>& out) {
    const std::uint32_t id = can::message_header(to_u16(msg.mti) & 0xFFF, msg.source.alias);
    const std::size_t size = msg.payload.size();
    const std::size_t frames =
        size == 0 ? 1 : (size + kAddressedBytesPerFrame - 1) / kAddressedBytesPerFrame;
    for (std::size_t i = 0; i < frames; ++i) {
        can::AddressedFraming framing = can::AddressedFraming::kOnly;
        if (frames > 1) {
            framing = i == 0            ? can::AddressedFraming::kFirst
                      : i + 1 == frames ? can::AddressedFraming::kLast
                                        : can::AddressedFraming::kMiddle;
        }
        std::uint8_t buf[8];
        buf[0] = static_cast<std::uint8_t>(static_cast<std::uint8_t>(framing) | (dst >> 8 & 0xF));
        buf[1] = static_cast<std::uint8_t>(dst & 0xFF);
        const std::size_t start = i * kAddressedBytesPerFrame;
        const std::size_t n = std::min(kAddressedBytesPerFrame, size - start);
        std::copy_n(msg.payload.data() + start, n, buf + 2);
        out.push_back(frame_of(id, buf, 2 + n));
    }
}

void encode_datagram(const Message& msg, std::uint16_t dst, std::vector<CanFrame>& out) {
    const std::size_t size = msg.payload.size();
    const std::uint8_t* data = msg.payload.data();
    const std::uint16_t src = msg.source.alias;
    if (size <= 8) {
        out.push_back(
            frame_of(can::addressed_header(can::FrameFormat::kDatagramOnly, dst, src), data, size));
        return;
    }
    for (std::size_t start = 0; start < size; start += 8) {
        const std::size_t n = std::min<std::size_t>(8, size - start);
        const auto format = start == 0          ? can::FrameFormat::kDatagramFirst
                            : start + n == size ? can::FrameFormat::kDatagramLast
                                                : can::FrameFormat::kDatagramMiddle;
        out.push_back(frame_of(can::addressed_header(format, dst, src), data + start, n));
    }
}

void encode_pcer_payload(const Message& msg, std::vector<CanFrame>& out) {
    const std::size_t size = msg.payload.size();
    const std::uint16_t src = msg.source.alias;
    for (std::size_t start = 0; start < size; start += 8) {
        const std::size_t n = std::min<std::size_t>(8, size - start);
        const std::uint16_t mti = start == 0          ? can::kCanMtiPcerPayloadFirst
                                  : start + n == size ? can::kCanMtiPcerPayloadLast
                                                      : can::kCanMtiPcerPayloadMiddle;
        out.push_back(frame_of(can::message_header(mti, src), msg.payload.data() + start, n));
    }
}

}  // namespace

std::string_view framing_error_text(FramingError error) {
    switch (error) {
        case FramingError::kNone:
            return "ok";
        case FramingError::kMissingSourceAlias:
            return "message has no source alias";
        case FramingError::kMissingDestinationAlias:
            return "addressed message has no destination alias";
        case FramingError::kBadPayloadLength:
            return "payload length not allowed for this MTI";
    }
    return "unknown framing error";
}

FramingError encode_message(const Message& msg, std::vector<CanFrame>& out) {
    if ((msg.source.alias & can::kAliasMask) == 0 || msg.source.alias > can::kAliasMask) {
        return FramingError::kMissingSourceAlias;
    }
    const std::size_t size = msg.payload.size();
    const bool needs_dest = is_addressed(msg.mti) || is_stream_or_datagram(msg.mti);
    std::uint16_t dst = 0;
    if (needs_dest) {
        if (!msg.destination || msg.destination->alias == 0 ||
            msg.destination->alias > can::kAliasMask) {
            return FramingError::kMissingDestinationAlias;
        }
        dst = msg.destination->alias;
    }
    if (is_datagram(msg.mti)) {
        if (size > datagram::kMaxSize) return FramingError::kBadPayloadLength;
        encode_datagram(msg, dst, out);
    } else if (is_stream_data(msg.mti)) {
        if (size > 8) return FramingError::kBadPayloadLength;
        out.push_back(
            frame_of(can::addressed_header(can::FrameFormat::kStreamData, dst, msg.source.alias),
                     msg.payload.data(), size));
    } else if (is_stream_or_datagram(msg.mti)) {
        return FramingError::kBadPayloadLength;  // no CAN mapping for other bit-12 MTIs
    } else if (is_addressed(msg.mti)) {
        encode_addressed(msg, dst, out);
    } else if (msg.mti == Mti::kEventReportWithPayload) {
        // Event ID plus at least one payload byte; the last frame must not be empty.
        if (size <= 8 || size > kMaxPcerPayload) return FramingError::kBadPayloadLength;
        encode_pcer_payload(msg, out);
    } else {
        if (size > 8) return FramingError::kBadPayloadLength;
        out.push_back(frame_of(can::message_header(to_u16(msg.mti) & 0xFFF, msg.source.alias),
                               msg.payload.data(), size));
    }
    return FramingError::kNone;
}

std::optional<Message> MessageAssembler::on_frame(const CanFrame& frame, TimePoint now) {
    if (!can::is_openlcb_frame(frame) || !can::is_message(frame.id) || frame.len > 8) {
        return std::nullopt;
    }
    const std::uint16_t src = can::source_alias(frame.id);
    switch (can::frame_format(frame.id)) {
        case can::FrameFormat::kGlobalAddressed: {
            const std::uint16_t cmti = can::can_mti(frame.id);
            if (cmti == can::kCanMtiPcerPayloadFirst || cmti == can::kCanMtiPcerPayloadMiddle ||
                cmti == can::kCanMtiPcerPayloadLast) {
                return on_pcer_payload(frame, now);
            }
            if (is_addressed(static_cast<Mti>(cmti))) return on_addressed(frame, now);
            return make_message(static_cast<Mti>(cmti), src, std::nullopt,
                                {frame.data.begin(), frame.data.begin() + frame.len});
        }
        case can::FrameFormat::kDatagramOnly:
        case can::FrameFormat::kDatagramFirst:
        case can::FrameFormat::kDatagramMiddle:
        case can::FrameFormat::kDatagramLast:
            if (!config_.datagrams) return std::nullopt;
            return on_datagram(frame, now);
        case can::FrameFormat::kStreamData:
            return make_message(Mti::kStreamDataSend, src, can::dest_alias(frame.id),
                                {frame.data.begin(), frame.data.begin() + frame.len});
        default:
            return std::nullopt;
    }
}

std::optional<Message> MessageAssembler::on_addressed(const CanFrame& frame, TimePoint now) {
    if (frame.len < 2) {
        ++errors_;
        return std::nullopt;
    }
    const auto framing = can::addressed_framing(frame.data[0]);
    const bool first =
        framing == can::AddressedFraming::kOnly || framing == can::AddressedFraming::kFirst;
    const bool last =
        framing == can::AddressedFraming::kOnly || framing == can::AddressedFraming::kLast;
    return step(can::source_alias(frame.id), can::addressed_dest(frame.data[0], frame.data[1]),
                static_cast<Mti>(can::can_mti(frame.id)), first, last, frame.data.data() + 2,
                frame.len - 2u, config_.max_payload, now);
}

std::optional<Message> MessageAssembler::on_pcer_payload(const CanFrame& frame, TimePoint now) {
    const std::uint16_t cmti = can::can_mti(frame.id);
    return step(can::source_alias(frame.id), 0, Mti::kEventReportWithPayload,
                cmti == can::kCanMtiPcerPayloadFirst, cmti == can::kCanMtiPcerPayloadLast,
                frame.data.data(), frame.len, std::min(config_.max_payload, kMaxPcerPayload), now);
}

std::optional<Message> MessageAssembler::on_datagram(const CanFrame& frame, TimePoint now) {
    const auto format = can::frame_format(frame.id);
    const bool first =
        format == can::FrameFormat::kDatagramOnly || format == can::FrameFormat::kDatagramFirst;
    const bool last =
        format == can::FrameFormat::kDatagramOnly || format == can::FrameFormat::kDatagramLast;
    return step(can::source_alias(frame.id), can::dest_alias(frame.id), Mti::kDatagram, first, last,
                frame.data.data(), frame.len, datagram::kMaxSize, now);
}

std::optional<Message> MessageAssembler::step(std::uint16_t src, std::uint16_t dst, Mti mti,
                                              bool first, bool last, const std::uint8_t* bytes,
                                              std::size_t count, std::size_t limit, TimePoint now) {
    Partial* p = find(src, dst, mti);
    const std::optional<std::uint16_t> dest =
        mti == Mti::kEventReportWithPayload ? std::nullopt : std::optional(dst);
    if (first) {
        if (p) {
            ++errors_;  // the previous message never finished
            erase(p);
        }
        if (last) return make_message(mti, src, dest, {bytes, bytes + count});
        if (count > limit) {
            ++errors_;
            return std::nullopt;
        }
        if (partials_.size() >= config_.max_in_progress) {
            if (partials_.empty()) {
                ++errors_;
                return std::nullopt;
            }
            auto oldest = std::min_element(
                partials_.begin(), partials_.end(),
                [](const Partial& a, const Partial& b) { return a.last < b.last; });
            ++errors_;
            partials_.erase(oldest);
        }
        partials_.push_back(Partial{src, dst, mti, now, {bytes, bytes + count}});
        return std::nullopt;
    }
    if (!p) {
        ++errors_;  // middle or last without first
        return std::nullopt;
    }
    if (p->data.size() + count > limit) {
        ++errors_;
        erase(p);
        return std::nullopt;
    }
    p->data.insert(p->data.end(), bytes, bytes + count);
    p->last = now;
    if (!last) return std::nullopt;
    Message m = make_message(mti, src, dest, std::move(p->data));
    erase(p);
    return m;
}

MessageAssembler::Partial* MessageAssembler::find(std::uint16_t src, std::uint16_t dst, Mti mti) {
    for (auto& p : partials_) {
        if (p.src == src && p.dst == dst && p.mti == mti) return &p;
    }
    return nullptr;
}

void MessageAssembler::erase(Partial* p) {
    partials_.erase(partials_.begin() + (p - partials_.data()));
}

void MessageAssembler::poll(TimePoint now) {
    const auto before = partials_.size();
    std::erase_if(partials_, [&](const Partial& p) { return now - p.last >= config_.timeout; });
    errors_ += before - partials_.size();
}

std::optional<TimePoint> MessageAssembler::next_deadline() const {
    std::optional<TimePoint> best;
    for (const auto& p : partials_) {
        const TimePoint t = p.last + config_.timeout;
        if (!best || t < *best) best = t;
    }
    return best;
}

}  // namespace olcb
