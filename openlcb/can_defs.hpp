// The 29-bit OpenLCB-CAN header (fact sheet 1.1, 1.2, 2.2, 2.3): field codec, control frames,
// builders and classifiers. Pure functions only.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "base/node_id.hpp"
#include "openlcb/can_frame.hpp"

namespace olcb::can {

/// Bit 28: always sent as 1, ignored on receipt.
inline constexpr std::uint32_t kReservedBit = 0x1000'0000;
/// Bit 27: 1 = OpenLCB message, 0 = CAN control frame.
inline constexpr std::uint32_t kMessageBit = 0x0800'0000;
/// Mask of the 29 valid header bits.
inline constexpr std::uint32_t kHeaderMask = 0x1FFF'FFFF;
/// Mask of the 12-bit alias fields.
inline constexpr std::uint16_t kAliasMask = 0x0FFF;
/// Aliases a segment has (0x001-0xFFF; 0 is none): the most nodes one CAN segment holds.
inline constexpr std::size_t kAliasCount = kAliasMask;

/// CAN frame format of an OpenLCB message (bits 26-24).
enum class FrameFormat : std::uint8_t {
    kReserved0 = 0,
    kGlobalAddressed = 1,  ///< CAN-MTI in bits 23-12
    kDatagramOnly = 2,
    kDatagramFirst = 3,
    kDatagramMiddle = 4,
    kDatagramLast = 5,
    kReserved6 = 6,
    kStreamData = 7,
};

/// Kind of a CAN control frame (bit 27 = 0).
enum class ControlFrame : std::uint8_t {
    kCid7,
    kCid6,
    kCid5,
    kCid4,
    kRid,
    kAmd,
    kAme,
    kAmr,
    kErrorInfo0,
    kErrorInfo1,
    kErrorInfo2,
    kErrorInfo3,
    kOther,  ///< CID3-1 or a reserved content value: ignore
};

/// Control-frame content values (15-bit field) of the fixed frames.
namespace control_content {
inline constexpr std::uint16_t kRid = 0x0700;
inline constexpr std::uint16_t kAmd = 0x0701;
inline constexpr std::uint16_t kAme = 0x0702;
inline constexpr std::uint16_t kAmr = 0x0703;
inline constexpr std::uint16_t kErrorInfo0 = 0x0710;
}  // namespace control_content

/// Framing nibble of an addressed message's first data byte (fact sheet 2.3).
enum class AddressedFraming : std::uint8_t {
    kOnly = 0x00,
    kFirst = 0x10,
    kLast = 0x20,
    kMiddle = 0x30,
};

/// CAN-MTIs of Event Report With Payload, which uses its own multi-frame scheme.
inline constexpr std::uint16_t kCanMtiPcerPayloadFirst = 0xF16;
inline constexpr std::uint16_t kCanMtiPcerPayloadMiddle = 0xF15;
inline constexpr std::uint16_t kCanMtiPcerPayloadLast = 0xF14;

// ---- field extraction ----

/// Source alias (bits 11-0).
constexpr std::uint16_t source_alias(std::uint32_t id) {
    return id & kAliasMask;
}
/// True for OpenLCB message frames (bit 27 set).
constexpr bool is_message(std::uint32_t id) {
    return (id & kMessageBit) != 0;
}
/// True for CAN control frames (bit 27 clear).
constexpr bool is_control(std::uint32_t id) {
    return (id & kMessageBit) == 0;
}
/// The 15-bit content field (bits 26-12).
constexpr std::uint16_t content(std::uint32_t id) {
    return (id >> 12) & 0x7FFF;
}
/// Frame format of a message frame (bits 26-24).
constexpr FrameFormat frame_format(std::uint32_t id) {
    return static_cast<FrameFormat>((id >> 24) & 0x7);
}
/// CAN-MTI of a format-1 frame (bits 23-12).
constexpr std::uint16_t can_mti(std::uint32_t id) {
    return (id >> 12) & 0xFFF;
}
/// Destination alias of a datagram or stream frame (bits 23-12).
constexpr std::uint16_t dest_alias(std::uint32_t id) {
    return (id >> 12) & 0xFFF;
}
/// True for datagram formats 2-5.
constexpr bool is_datagram_format(FrameFormat f) {
    return f >= FrameFormat::kDatagramOnly && f <= FrameFormat::kDatagramLast;
}
/// True when the frame is one an OpenLCB node must look at: extended, not remote.
constexpr bool is_openlcb_frame(const CanFrame& f) {
    return f.extended && !f.remote;
}

/// Classifies a control-frame header (result is meaningless for message frames).
constexpr ControlFrame classify_control(std::uint32_t id) {
    const std::uint16_t c = content(id);
    switch (c >> 12) {
        case 7:
            return ControlFrame::kCid7;
        case 6:
            return ControlFrame::kCid6;
        case 5:
            return ControlFrame::kCid5;
        case 4:
            return ControlFrame::kCid4;
        default:
            break;
    }
    switch (c) {
        case control_content::kRid:
            return ControlFrame::kRid;
        case control_content::kAmd:
            return ControlFrame::kAmd;
        case control_content::kAme:
            return ControlFrame::kAme;
        case control_content::kAmr:
            return ControlFrame::kAmr;
        case control_content::kErrorInfo0:
            return ControlFrame::kErrorInfo0;
        case control_content::kErrorInfo0 + 1:
            return ControlFrame::kErrorInfo1;
        case control_content::kErrorInfo0 + 2:
            return ControlFrame::kErrorInfo2;
        case control_content::kErrorInfo0 + 3:
            return ControlFrame::kErrorInfo3;
        default:
            return ControlFrame::kOther;
    }
}
/// True for CID7..CID4 headers.
constexpr bool is_cid(std::uint32_t id) {
    return is_control(id) && (content(id) >> 12) >= 4 && (content(id) >> 12) <= 7;
}
/// The 12 node-ID bits a CID frame carries (bits 23-12).
constexpr std::uint16_t cid_node_id_bits(std::uint32_t id) {
    return (id >> 12) & 0xFFF;
}
/// Short name of a control frame kind ("CID7", "AMD", ...).
constexpr const char* control_name(ControlFrame c) {
    constexpr const char* kNames[] = {"CID7", "CID6", "CID5", "CID4", "RID",  "AMD",     "AME",
                                      "AMR",  "EIR0", "EIR1", "EIR2", "EIR3", "control?"};
    return kNames[static_cast<int>(c)];
}

/// Framing nibble of an addressed frame's first data byte.
constexpr AddressedFraming addressed_framing(std::uint8_t byte0) {
    return static_cast<AddressedFraming>(byte0 & 0x30);
}
/// Destination alias from an addressed frame's first two data bytes (fddd).
constexpr std::uint16_t addressed_dest(std::uint8_t byte0, std::uint8_t byte1) {
    return static_cast<std::uint16_t>((byte0 & 0x0F) << 8 | byte1);
}

// ---- header builders ----

/// Header of a format-1 message (global or addressed) from src with the 12-bit CAN-MTI.
constexpr std::uint32_t message_header(std::uint16_t can_mti_value, std::uint16_t src) {
    return kReservedBit | kMessageBit | std::uint32_t{1} << 24 |
           std::uint32_t{can_mti_value & 0xFFFu} << 12 | (src & kAliasMask);
}
/// Header of a datagram (formats 2-5) or stream (format 7) frame.
constexpr std::uint32_t addressed_header(FrameFormat format, std::uint16_t dst, std::uint16_t src) {
    return kReservedBit | kMessageBit | std::uint32_t{static_cast<std::uint8_t>(format)} << 24 |
           (std::uint32_t{dst} & kAliasMask) << 12 | (src & kAliasMask);
}
/// Header of a control frame with the given 15-bit content.
constexpr std::uint32_t control_header(std::uint16_t content_value, std::uint16_t src) {
    return kReservedBit | std::uint32_t{content_value & 0x7FFFu} << 12 | (src & kAliasMask);
}
/// Header of CID n (4..7) carrying the matching 12-bit slice of node.
constexpr std::uint32_t cid_header(int n, NodeId node, std::uint16_t src) {
    const auto slice = static_cast<std::uint16_t>((node.value() >> (12 * (n - 4))) & 0xFFF);
    return control_header(static_cast<std::uint16_t>(n << 12 | slice), src);
}

// ---- frame builders ----

/// A frame with the given header and up to 8 data bytes (extra bytes are dropped).
inline CanFrame make_frame(std::uint32_t id, std::span<const std::uint8_t> data = {}) {
    CanFrame f;
    f.id = id & kHeaderMask;
    f.len = static_cast<std::uint8_t>(data.size() > 8 ? 8 : data.size());
    std::copy_n(data.begin(), f.len, f.data.begin());
    return f;
}
/// A frame with the given header carrying a node ID (AMD, AMR, AME, Verified Node ID, ...).
inline CanFrame make_node_id_frame(std::uint32_t id, NodeId node) {
    const auto bytes = node.to_bytes();
    return make_frame(id, bytes);
}
/// CID n (4..7) for node using tentative alias src.
inline CanFrame make_cid(int n, NodeId node, std::uint16_t src) {
    return make_frame(cid_header(n, node, src));
}
/// Reserve ID frame.
inline CanFrame make_rid(std::uint16_t src) {
    return make_frame(control_header(control_content::kRid, src));
}
/// Alias Map Definition frame.
inline CanFrame make_amd(std::uint16_t src, NodeId node) {
    return make_node_id_frame(control_header(control_content::kAmd, src), node);
}
/// Alias Mapping Enquiry: global when node is nullopt, else for that node ID.
inline CanFrame make_ame(std::uint16_t src, std::optional<NodeId> node = std::nullopt) {
    const std::uint32_t id = control_header(control_content::kAme, src);
    return node ? make_node_id_frame(id, *node) : make_frame(id);
}
/// Alias Map Reset frame.
inline CanFrame make_amr(std::uint16_t src, NodeId node) {
    return make_node_id_frame(control_header(control_content::kAmr, src), node);
}

}  // namespace olcb::can
