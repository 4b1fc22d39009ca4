// Stream transport (StreamTransportS/TN) wire constants and payload codecs, in one place. The
// payloads are the message contents after the CAN `fddd` bytes (or, for Stream Data Send, the
// whole format-7 frame: destination stream ID, then up to 7 data bytes).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace olcb::stream {

/// Not a valid stream ID: "none assigned yet" in an Initiate Request's suggested DID.
inline constexpr std::uint8_t kInvalidStreamId = 0xFF;
/// Largest buffer (window) size: the field is 16 bits.
inline constexpr std::uint16_t kMaxBufferSize = 0xFFFF;
/// Data bytes one CAN frame carries after the destination stream ID.
inline constexpr std::size_t kMaxDataPerFrame = 7;
/// Bytes of an Initiate Request/Reply without the optional content UID.
inline constexpr std::size_t kInitiateSize = 6;
/// Bytes of the content UID an Initiate Request may carry (flag kFlagCarriesContentUid).
inline constexpr std::size_t kContentUidSize = 6;

/// Initiate Request flags byte (byte 2).
inline constexpr std::uint8_t kFlagCarriesContentUid = 0x01;  ///< a 6-byte content UID follows

/// Initiate Reply code: stream accepted.
inline constexpr std::uint16_t kAccept = 0x8000;
/// Initiate Reply code: invalid request (e.g. a proposed buffer of 0).
inline constexpr std::uint16_t kRejectInvalid = 0x1080;
/// Initiate Reply code: content not known here (an unknown content UID, OlcbChecker st40).
inline constexpr std::uint16_t kRejectUnimplemented = 0x1040;
/// Initiate Reply code: no free stream (temporary, retry later).
inline constexpr std::uint16_t kRejectBufferFull = 0x2020;
/// Initiate Reply code: the node takes no streams from us (permanent).
inline constexpr std::uint16_t kRejectNotAccepted = 0x1043;

/// True when an Initiate Reply code accepts the stream (bit 15; OpenMRN tests only it).
constexpr bool is_accept(std::uint16_t code) {
    return (code & kAccept) != 0;
}

/// Stream Initiate Request (MTI 0x0CC8).
struct InitiateRequest {
    std::uint16_t max_buffer = 0;                       ///< proposed window size
    std::uint8_t flags = 0;                             ///< kFlagCarriesContentUid
    std::uint8_t additional_flags = 0;                  ///< reserved, 0
    std::uint8_t source_id = 0;                         ///< SID chosen by the source
    std::uint8_t suggested_dest_id = kInvalidStreamId;  ///< DID the sink may take (0xFF: none)
    std::optional<std::array<std::uint8_t, kContentUidSize>> content_uid;
    friend bool operator==(const InitiateRequest&, const InitiateRequest&) = default;
};

/// Stream Initiate Reply (MTI 0x0868).
struct InitiateReply {
    std::uint16_t max_buffer = 0;  ///< granted window (0 when rejected)
    std::uint16_t code = kAccept;  ///< kAccept or an error code
    std::uint8_t source_id = 0;    ///< the request's SID, echoed
    std::uint8_t dest_id = 0;      ///< DID assigned by the sink
    friend bool operator==(const InitiateReply&, const InitiateReply&) = default;
};

/// Stream Data Proceed (MTI 0x0888).
struct DataProceed {
    std::uint8_t source_id = 0;
    std::uint8_t dest_id = 0;
    friend bool operator==(const DataProceed&, const DataProceed&) = default;
};

/// Stream Data Complete (MTI 0x08A8), optionally with the total byte count.
struct DataComplete {
    std::uint8_t source_id = 0;
    std::uint8_t dest_id = 0;
    std::optional<std::uint32_t> total_bytes;
    friend bool operator==(const DataComplete&, const DataComplete&) = default;
};

/// Encodes an Initiate Request (6 bytes, 12 with a content UID).
std::vector<std::uint8_t> encode(const InitiateRequest& m);
/// Encodes an Initiate Reply (6 bytes).
std::vector<std::uint8_t> encode(const InitiateReply& m);
/// Encodes a Data Proceed (2 bytes).
std::vector<std::uint8_t> encode(const DataProceed& m);
/// Encodes a Data Complete (2 bytes, 6 with the count).
std::vector<std::uint8_t> encode(const DataComplete& m);

/// Decodes an Initiate Request; nullopt when shorter than 5 bytes (a missing suggested DID
/// reads as 0xFF) or the content UID is announced but truncated.
std::optional<InitiateRequest> decode_initiate_request(std::span<const std::uint8_t> p);
/// Decodes an Initiate Reply; nullopt when shorter than 6 bytes.
std::optional<InitiateReply> decode_initiate_reply(std::span<const std::uint8_t> p);
/// Decodes a Data Proceed; nullopt when shorter than 2 bytes.
std::optional<DataProceed> decode_data_proceed(std::span<const std::uint8_t> p);
/// Decodes a Data Complete; nullopt when shorter than 2 bytes (2..5 bytes: no count).
std::optional<DataComplete> decode_data_complete(std::span<const std::uint8_t> p);

/// The buffer a sink grants: the smaller of proposed and acceptable (0 only if either is 0).
constexpr std::uint16_t negotiate_buffer(std::uint16_t proposed, std::uint16_t acceptable) {
    return proposed < acceptable ? proposed : acceptable;
}

/// Data Send frames needed for n bytes with buffer b (frames end at every buffer boundary).
constexpr std::uint64_t data_frames(std::uint64_t n, std::uint16_t b) {
    if (b == 0) return 0;
    const std::uint64_t full = n / b;
    const std::uint64_t rest = n % b;
    const std::uint64_t per_buffer = (b + kMaxDataPerFrame - 1) / kMaxDataPerFrame;
    return full * per_buffer + (rest + kMaxDataPerFrame - 1) / kMaxDataPerFrame;
}

}  // namespace olcb::stream
