#include "openlcb/stream_defs.hpp"

namespace olcb::stream {
namespace {

void put16(std::vector<std::uint8_t>& out, std::uint16_t v) {
    out.push_back(static_cast<std::uint8_t>(v >> 8));
    out.push_back(static_cast<std::uint8_t>(v & 0xFF));
}

std::uint16_t get16(std::span<const std::uint8_t> p, std::size_t at) {
    return static_cast<std::uint16_t>(p[at] << 8 | p[at + 1]);
}

}  // namespace

std::vector<std::uint8_t> encode(const InitiateRequest& m) {
    std::vector<std::uint8_t> out;
    put16(out, m.max_buffer);
    out.push_back(static_cast<std::uint8_t>(m.content_uid ? m.flags | kFlagCarriesContentUid
                                                          : m.flags & ~kFlagCarriesContentUid));
    out.push_back(m.additional_flags);
    out.push_back(m.source_id);
    out.push_back(m.suggested_dest_id);
    if (m.content_uid) out.insert(out.end(), m.content_uid->begin(), m.content_uid->end());
    return out;
}

std::vector<std::uint8_t> encode(const InitiateReply& m) {
    std::vector<std::uint8_t> out;
    put16(out, m.max_buffer);
    put16(out, m.code);
    out.push_back(m.source_id);
    out.push_back(m.dest_id);
    return out;
}

std::vector<std::uint8_t> encode(const DataProceed& m) {
    return {m.source_id, m.dest_id};
}

std::vector<std::uint8_t> encode(const DataComplete& m) {
    std::vector<std::uint8_t> out{m.source_id, m.dest_id};
    if (m.total_bytes) {
        put16(out, static_cast<std::uint16_t>(*m.total_bytes >> 16));
        put16(out, static_cast<std::uint16_t>(*m.total_bytes & 0xFFFF));
    }
    return out;
}

std::optional<InitiateRequest> decode_initiate_request(std::span<const std::uint8_t> p) {
    if (p.size() < 5) return std::nullopt;
    InitiateRequest m;
    m.max_buffer = get16(p, 0);
    m.flags = p[2];
    m.additional_flags = p[3];
    m.source_id = p[4];
    if (p.size() >= kInitiateSize) m.suggested_dest_id = p[5];
    if ((m.flags & kFlagCarriesContentUid) != 0) {
        if (p.size() < kInitiateSize + kContentUidSize) return std::nullopt;
        std::array<std::uint8_t, kContentUidSize> uid{};
        for (std::size_t i = 0; i < kContentUidSize; ++i) uid[i] = p[kInitiateSize + i];
        m.content_uid = uid;
    }
    return m;
}

std::optional<InitiateReply> decode_initiate_reply(std::span<const std::uint8_t> p) {
    if (p.size() < kInitiateSize) return std::nullopt;
    return InitiateReply{get16(p, 0), get16(p, 2), p[4], p[5]};
}

std::optional<DataProceed> decode_data_proceed(std::span<const std::uint8_t> p) {
    if (p.size() < 2) return std::nullopt;
    return DataProceed{p[0], p[1]};
}

std::optional<DataComplete> decode_data_complete(std::span<const std::uint8_t> p) {
    if (p.size() < 2) return std::nullopt;
    DataComplete m{p[0], p[1], std::nullopt};
    if (p.size() >= 6) {
        m.total_bytes = std::uint32_t{get16(p, 2)} << 16 | get16(p, 4);
    }
    return m;
}

}  // namespace olcb::stream
