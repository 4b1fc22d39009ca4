#include "openlcb/monitor.hpp"

#include <algorithm>
#include <string_view>
#include <utility>

#include "base/hex.hpp"
#include "base/node_id.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/datagram_defs.hpp"
#include "openlcb/gridconnect.hpp"
#include "openlcb/mti.hpp"

namespace olcb {

namespace {

constexpr std::uint16_t kDatagramKey = to_u16(Mti::kDatagram);

using base::hex;
using base::hex_bytes;
using base::hex_digits;

// Concatenates by appending: g++ 12 at -O3 warns falsely (-Wrestrict) on "lit" + std::string&&.
std::string concat(std::string_view a, std::string_view b, std::string_view c = {}) {
    std::string out;
    out.reserve(a.size() + b.size() + c.size());
    out.append(a).append(b).append(c);
    return out;
}

std::uint16_t be16(std::span<const std::uint8_t> b) {
    return static_cast<std::uint16_t>(b[0] << 8 | b[1]);
}

std::string mti_text(std::uint16_t mti) {
    const auto name = mti_name(mti);
    if (!name.empty()) return std::string(name);
    return "MTI " + hex(mti, 4);
}

// Payload details of a message whose layout the MTI fixes.
std::string payload_text(std::uint16_t mti, std::span<const std::uint8_t> payload) {
    if (payload.empty()) return {};
    switch (static_cast<Mti>(mti)) {
        case Mti::kInitializationComplete:
        case Mti::kInitializationCompleteSimple:
        case Mti::kVerifyNodeIdGlobal:
        case Mti::kVerifyNodeIdAddressed:
        case Mti::kVerifiedNodeId:
        case Mti::kVerifiedNodeIdSimple:
            if (payload.size() == NodeId::kSize) {
                return concat(" ", NodeId::from_bytes(payload)->to_string());
            }
            break;
        case Mti::kDatagramReceivedOk:
            return " flags " + hex_bytes(payload.first(1));
        case Mti::kDatagramRejected:
        case Mti::kOptionalInteractionRejected:
        case Mti::kTerminateDueToError: {
            if (payload.size() < 2) break;
            std::string out = " error " + hex(be16(payload), 4);
            if (payload.size() >= 4) out += " MTI " + hex(be16(payload.subspan(2)), 4);
            if (payload.size() > 4) out += " [" + hex_bytes(payload.subspan(4)) + "]";
            return out;
        }
        default:
            if (has_event_id(static_cast<Mti>(mti)) && payload.size() == EventId::kSize) {
                return concat(" ", EventId::from_bytes(payload)->to_string());
            }
            break;
    }
    return " [" + hex_bytes(payload) + "]";
}

const char* framing_text(can::AddressedFraming f) {
    switch (f) {
        case can::AddressedFraming::kFirst:
            return " (first frame)";
        case can::AddressedFraming::kMiddle:
            return " (middle frame)";
        case can::AddressedFraming::kLast:
            return " (last frame)";
        case can::AddressedFraming::kOnly:
            break;
    }
    return "";
}

}  // namespace

Monitor::Monitor() = default;

Monitor::Monitor(Options options) : options_(options) {}

void Monitor::register_datagram_decoder(std::uint8_t content_type, DatagramDecoder decoder) {
    decoders_[content_type] = std::move(decoder);
}

std::string Monitor::alias_text(std::uint16_t alias) const {
    std::string out = hex_digits(alias, 3);
    if (options_.show_node_ids) {
        if (auto it = node_ids_.find(alias); it != node_ids_.end()) {
            out += concat("(", NodeId(it->second).to_string(), ")");
        }
    }
    return out;
}

void Monitor::learn_alias(const CanFrame& frame) {
    if (!can::is_control(frame.id)) return;
    const auto kind = can::classify_control(frame.id);
    const auto alias = can::source_alias(frame.id);
    if (kind == can::ControlFrame::kAmd && frame.len >= NodeId::kSize) {
        node_ids_[alias] = NodeId::from_bytes(std::span(frame.data.data(), frame.len))->value();
    } else if (kind == can::ControlFrame::kAmr) {
        node_ids_.erase(alias);
    }
}

std::optional<std::string> Monitor::decode(const CanFrame& frame) {
    std::string prefix;
    if (options_.mode == Mode::kPerFrame) {
        prefix = gridconnect::format(frame);
        prefix.resize(std::max(prefix.size(), gridconnect::kMaxFormattedSize), ' ');
        prefix.push_back(' ');
    }
    if (!frame.extended) return prefix + "standard frame (not OpenLCB)";
    if (frame.remote) return prefix + "remote frame (not OpenLCB)";
    const CanFrame f = [&] {
        CanFrame c = frame;
        c.len = std::min<std::uint8_t>(c.len, 8);
        return c;
    }();
    if (can::is_control(f.id)) {
        std::string line = prefix + decode_control(f);
        learn_alias(f);
        return line;
    }
    std::optional<std::string> body;
    const auto format = can::frame_format(f.id);
    if (can::is_datagram_format(format)) {
        body = decode_datagram(f);
    } else if (format == can::FrameFormat::kGlobalAddressed) {
        body = decode_message(f);
    } else if (format == can::FrameFormat::kStreamData) {
        body = alias_text(can::source_alias(f.id)) + " -> " + alias_text(can::dest_alias(f.id)) +
               " Stream Data Send [" + hex_bytes(std::span(f.data.data(), f.len)) + "]";
    } else {
        body = alias_text(can::source_alias(f.id)) + " reserved frame format " +
               std::to_string(static_cast<int>(format));
    }
    if (!body) return std::nullopt;
    return prefix + *body;
}

std::string Monitor::decode_control(const CanFrame& f) const {
    const auto kind = can::classify_control(f.id);
    std::string line = alias_text(can::source_alias(f.id)) + " ";
    const std::span<const std::uint8_t> data(f.data.data(), f.len);
    switch (kind) {
        case can::ControlFrame::kCid7:
        case can::ControlFrame::kCid6:
        case can::ControlFrame::kCid5:
        case can::ControlFrame::kCid4:
            return line + can::control_name(kind) + " " +
                   hex_digits(can::cid_node_id_bits(f.id), 3);
        case can::ControlFrame::kOther:
            return line + "control frame " + hex(can::content(f.id), 4);
        default:
            line += can::control_name(kind);
            if (data.size() == NodeId::kSize) {
                line += concat(" ", NodeId::from_bytes(data)->to_string());
            } else if (!data.empty()) {
                line += " [" + hex_bytes(data) + "]";
            }
            return line;
    }
}

Monitor::Partial& Monitor::partial(const Key& key) {
    auto it = partials_.find(key);
    if (it == partials_.end()) {
        if (partials_.size() >= kMaxPartials) {
            partials_.erase(std::min_element(
                partials_.begin(), partials_.end(),
                [](const auto& a, const auto& b) { return a.second.serial < b.second.serial; }));
        }
        it = partials_.emplace(key, Partial{}).first;
        it->second.serial = ++serial_;
    }
    return it->second;
}

std::string Monitor::describe_datagram(std::span<const std::uint8_t> bytes) const {
    std::string out = "Datagram " + std::to_string(bytes.size()) + " bytes";
    if (!bytes.empty()) out += ": " + hex_bytes(bytes);
    if (bytes.empty()) return out;
    if (auto it = decoders_.find(bytes[0]); it != decoders_.end() && it->second) {
        try {
            out += " | " + it->second(bytes);
        } catch (...) {
            out += " | (decoder failed)";
        }
    }
    return out;
}

std::optional<std::string> Monitor::decode_datagram(const CanFrame& f) {
    const std::uint16_t src = can::source_alias(f.id);
    const std::uint16_t dst = can::dest_alias(f.id);
    const std::span<const std::uint8_t> data(f.data.data(), f.len);
    const std::string who = alias_text(src) + " -> " + alias_text(dst) + " ";
    const Key key{src, dst, kDatagramKey};
    const bool per_frame = options_.mode == Mode::kPerFrame;
    switch (can::frame_format(f.id)) {
        case can::FrameFormat::kDatagramOnly:
            partials_.erase(key);
            return who + describe_datagram(data);
        case can::FrameFormat::kDatagramFirst: {
            Partial& p = partial(key);
            p.bytes.assign(data.begin(), data.end());
            if (!per_frame) return std::nullopt;
            return who + "Datagram first frame [" + hex_bytes(data) + "]";
        }
        default: {
            const bool last = can::frame_format(f.id) == can::FrameFormat::kDatagramLast;
            const char* kind = last ? "last" : "middle";
            auto it = partials_.find(key);
            if (it == partials_.end()) {
                return who + "Datagram " + kind + " frame without first [" + hex_bytes(data) + "]";
            }
            auto& bytes = it->second.bytes;
            if (bytes.size() + data.size() > datagram::kMaxSize) {
                partials_.erase(it);
                return who + "Datagram longer than 72 bytes, dropped";
            }
            bytes.insert(bytes.end(), data.begin(), data.end());
            std::string line;
            if (per_frame) line = who + "Datagram " + kind + " frame [" + hex_bytes(data) + "]";
            if (!last) {
                if (!per_frame) return std::nullopt;
                return line;
            }
            const std::vector<std::uint8_t> whole = std::move(bytes);
            partials_.erase(it);
            if (per_frame) return line + " => " + describe_datagram(whole);
            return who + describe_datagram(whole);
        }
    }
}

std::optional<std::string> Monitor::decode_message(const CanFrame& f) {
    const std::uint16_t src = can::source_alias(f.id);
    const std::uint16_t mti = can::can_mti(f.id);
    const std::span<const std::uint8_t> data(f.data.data(), f.len);
    if (mti >= can::kCanMtiPcerPayloadLast && mti <= can::kCanMtiPcerPayloadFirst) {
        static constexpr const char* kPart[] = {"last", "middle", "first"};
        return alias_text(src) + " Event Report With Payload (" +
               kPart[mti - can::kCanMtiPcerPayloadLast] + " frame) [" + hex_bytes(data) + "]";
    }
    if (!is_addressed(static_cast<Mti>(mti))) {
        return alias_text(src) + " " + mti_text(mti) + payload_text(mti, data);
    }
    if (data.size() < 2) {
        return alias_text(src) + " " + mti_text(mti) + " (no destination)";
    }
    const std::uint16_t dst = can::addressed_dest(data[0], data[1]);
    const auto framing = can::addressed_framing(data[0]);
    const auto payload = data.subspan(2);
    const std::string who = alias_text(src) + " -> " + alias_text(dst) + " " + mti_text(mti);
    if (options_.mode == Mode::kPerFrame) {
        if (framing == can::AddressedFraming::kOnly) return who + payload_text(mti, payload);
        return who + framing_text(framing) +
               (payload.empty() ? "" : " [" + hex_bytes(payload) + "]");
    }
    const Key key{src, dst, mti};
    switch (framing) {
        case can::AddressedFraming::kOnly:
            return who + payload_text(mti, payload);
        case can::AddressedFraming::kFirst:
            partial(key).bytes.assign(payload.begin(), payload.end());
            return std::nullopt;
        case can::AddressedFraming::kMiddle:
        case can::AddressedFraming::kLast: {
            auto it = partials_.find(key);
            if (it == partials_.end()) {
                return who + framing_text(framing) + " without first [" + hex_bytes(payload) + "]";
            }
            auto& bytes = it->second.bytes;
            if (bytes.size() + payload.size() > kMaxMessageBytes) {
                partials_.erase(it);
                return who + " longer than " + std::to_string(kMaxMessageBytes) + " bytes, dropped";
            }
            bytes.insert(bytes.end(), payload.begin(), payload.end());
            if (framing == can::AddressedFraming::kMiddle) return std::nullopt;
            const std::vector<std::uint8_t> whole = std::move(bytes);
            partials_.erase(it);
            return who + payload_text(mti, whole);
        }
    }
    return std::nullopt;
}

}  // namespace olcb
