#include "memory/memory_config_codec.hpp"

#include <algorithm>
#include <atomic>
#include <type_traits>

#include "base/hex.hpp"
#include "base/node_id.hpp"
#include "memory/snip.hpp"

namespace olcb::memory {
namespace {

constexpr std::size_t kNodeIdBytes = kNodeIdSize;
constexpr std::size_t kEventIdBytes = 8;
constexpr std::size_t kMaxErrorTextChars = kMaxErrorText - 1;
constexpr std::uint8_t kReadCountReservedBit = 0x80;
constexpr std::uint8_t kUniqueIdCountMask = 0x07;

// Bounds-checked big-endian reader; every accessor reports whether the bytes were there.
class Reader {
public:
    explicit Reader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

    std::size_t remaining() const { return bytes_.size() - pos_; }

    bool u8(std::uint8_t& value) {
        if (remaining() < 1) return false;
        value = bytes_[pos_++];
        return true;
    }

    template <typename T>
    bool be(std::size_t size, T& value) {
        if (remaining() < size) return false;
        T result = 0;
        // Integer promotion widens a 16-bit T to int; the result fits T by construction.
        for (std::size_t i = 0; i < size; ++i)
            result = static_cast<T>((result << 8) | bytes_[pos_++]);
        value = result;
        return true;
    }

    std::span<const std::uint8_t> rest() {
        auto out = bytes_.subspan(pos_);
        pos_ = bytes_.size();
        return out;
    }

private:
    std::span<const std::uint8_t> bytes_;
    std::size_t pos_ = 0;
};

template <typename T>
void put_be(std::vector<std::uint8_t>& out, std::size_t size, T value) {
    for (std::size_t i = size; i-- > 0;) {
        out.push_back(static_cast<std::uint8_t>(static_cast<std::uint64_t>(value) >> (8 * i)));
    }
}

// Text runs to the first NUL or the payload end, then is clamped as an encoder would clamp it.
std::string read_text(Reader& reader, std::size_t max_chars) {
    const auto rest = reader.rest();
    const std::string_view raw(reinterpret_cast<const char*>(rest.data()), rest.size());
    return std::string(clamp_utf8(raw, max_chars));
}

void put_text(std::vector<std::uint8_t>& out, std::string_view text, std::size_t max_chars) {
    const std::string_view clamped = clamp_utf8(text, max_chars);
    if (clamped.empty()) return;
    out.insert(out.end(), clamped.begin(), clamped.end());
    out.push_back(0);
}

// Text room left in a datagram after header bytes, keeping one byte for the NUL.
std::size_t text_room(std::size_t header) {
    return header < kMaxDatagram ? kMaxDatagram - header - 1 : 0;
}

struct Header {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    SpaceForm form = SpaceForm::kShort;
};

DecodeResult fail(DecodeError error) {
    return DecodeResult{Message{}, error};
}

template <typename M>
DecodeResult ok(M message) {
    return DecodeResult{Message{std::move(message)}, DecodeError::kNone};
}

template <typename M>
DecodeResult decode_fail_reply(const Header& h, Reader& reader) {
    // Missing error bytes read as 0 ("missing bits = 0"), like OIR/TDE/Datagram Rejected.
    std::uint8_t high = 0;
    std::uint8_t low = 0;
    if (reader.u8(high)) reader.u8(low);
    M message;
    message.space = h.space;
    message.address = h.address;
    message.form = h.form;
    message.error = static_cast<ErrorCode>((high << 8) | low);
    message.text = read_text(reader, kMaxErrorTextChars);
    return ok(std::move(message));
}

DecodeError decode_data(Reader& reader, std::vector<std::uint8_t>& data) {
    const auto rest = reader.rest();
    if (rest.empty()) return DecodeError::kNoData;
    if (rest.size() > kMaxReadWrite) return DecodeError::kTooMuchData;
    data.assign(rest.begin(), rest.end());
    return DecodeError::kNone;
}

bool is_defined_family(std::uint8_t family) {
    switch (static_cast<Command>(family)) {
        case Command::kWrite:
        case Command::kWriteUnderMask:
        case Command::kWriteReply:
        case Command::kWriteReplyFail:
        case Command::kWriteStream:
        case Command::kWriteStreamReply:
        case Command::kWriteStreamReplyFail:
        case Command::kRead:
        case Command::kReadReply:
        case Command::kReadReplyFail:
        case Command::kReadStream:
        case Command::kReadStreamReply:
        case Command::kReadStreamReplyFail:
            return true;
        default:
            return false;
    }
}

// The address, then the space: in the command byte (short form) or in byte 6.
DecodeError decode_header(std::uint8_t command, Reader& reader, Header& h) {
    if (!reader.be(4, h.address)) return DecodeError::kTruncated;
    if (const auto short_space = short_form_space(command)) {
        h.space = *short_space;
        h.form = SpaceForm::kShort;
        return DecodeError::kNone;
    }
    std::uint8_t space = 0;
    if (!reader.u8(space)) return DecodeError::kMissingSpace;
    h.space = static_cast<Space>(space);
    h.form = SpaceForm::kByte6;
    return DecodeError::kNone;
}

DecodeResult decode_read(const Header& h, Reader& reader) {
    std::uint8_t count = 0;
    if (!reader.u8(count)) return fail(DecodeError::kTruncated);
    count &= static_cast<std::uint8_t>(~kReadCountReservedBit);
    if (!is_valid_read_count(count)) return fail(DecodeError::kBadCount);
    return ok(Read{h.space, h.address, count, h.form});
}

// Read Reply and Write: the data bytes follow the header.
template <typename M>
DecodeResult decode_with_data(const Header& h, Reader& reader) {
    M m{h.space, h.address, {}, h.form};
    if (auto e = decode_data(reader, m.data); e != DecodeError::kNone) return fail(e);
    return ok(std::move(m));
}

DecodeResult decode_write_under_mask(const Header& h, Reader& reader) {
    const auto rest = reader.rest();
    if (rest.empty()) return fail(DecodeError::kNoData);
    if (rest.size() % 2 != 0) return fail(DecodeError::kOddMaskData);
    if (rest.size() > kMaxReadWrite) return fail(DecodeError::kTooMuchData);
    WriteUnderMask m{h.space, h.address, {}, h.form};
    for (std::size_t i = 0; i < rest.size(); i += 2) {
        m.bytes.push_back(MaskedByte{rest[i], rest[i + 1]});
    }
    return ok(std::move(m));
}

// Read Stream and its reply: source and destination stream IDs, then the count.
template <typename M>
DecodeResult decode_stream_read(const Header& h, Reader& reader) {
    M m{h.space, h.address, 0, 0, 0, h.form};
    if (!reader.u8(m.source_stream_id) || !reader.u8(m.destination_stream_id) ||
        !reader.be(4, m.count)) {
        return fail(DecodeError::kTruncated);
    }
    return ok(m);
}

DecodeResult decode_write_stream(const Header& h, Reader& reader) {
    WriteStream m{h.space, h.address, 0, h.form};
    if (!reader.u8(m.source_stream_id)) return fail(DecodeError::kTruncated);
    return ok(m);
}

DecodeResult decode_write_stream_reply(const Header& h, Reader& reader) {
    WriteStreamReply m{h.space, h.address, 0, 0, h.form};
    if (!reader.u8(m.source_stream_id) || !reader.u8(m.destination_stream_id)) {
        return fail(DecodeError::kTruncated);
    }
    return ok(m);
}

DecodeResult decode_read_write(std::uint8_t command, Reader& reader) {
    const std::uint8_t family = family_of(command);
    if (!is_defined_family(family)) return fail(DecodeError::kUnknownCommand);
    Header h;
    if (auto e = decode_header(command, reader, h); e != DecodeError::kNone) return fail(e);

    switch (static_cast<Command>(family)) {
        case Command::kRead:
            return decode_read(h, reader);
        case Command::kReadReply:
            return decode_with_data<ReadReply>(h, reader);
        case Command::kWrite:
            return decode_with_data<Write>(h, reader);
        case Command::kWriteUnderMask:
            return decode_write_under_mask(h, reader);
        case Command::kWriteReply:
            return ok(WriteReply{h.space, h.address, h.form});
        case Command::kReadReplyFail:
            return decode_fail_reply<ReadReplyFail>(h, reader);
        case Command::kWriteReplyFail:
            return decode_fail_reply<WriteReplyFail>(h, reader);
        case Command::kReadStreamReplyFail:
            return decode_fail_reply<ReadStreamReplyFail>(h, reader);
        case Command::kWriteStreamReplyFail:
            return decode_fail_reply<WriteStreamReplyFail>(h, reader);
        case Command::kReadStream:
            return decode_stream_read<ReadStream>(h, reader);
        case Command::kReadStreamReply:
            return decode_stream_read<ReadStreamReply>(h, reader);
        case Command::kWriteStream:
            return decode_write_stream(h, reader);
        case Command::kWriteStreamReply:
            return decode_write_stream_reply(h, reader);
        default:
            return fail(DecodeError::kUnknownCommand);
    }
}

DecodeResult decode_space_info(Reader& reader) {
    std::uint8_t space = 0;
    if (!reader.u8(space)) return fail(DecodeError::kMissingSpace);
    SpaceInfoReply m;
    m.space = static_cast<Space>(space);
    if (!reader.be(4, m.highest_address)) return fail(DecodeError::kTruncated);
    std::uint8_t flags = 0;
    reader.u8(flags);  // absent flags read as 0
    m.read_only = (flags & space_flags::kReadOnly) != 0;
    std::size_t header = 8;
    if ((flags & space_flags::kLowAddressPresent) != 0) {
        std::uint32_t low = 0;
        if (!reader.be(4, low)) return fail(DecodeError::kTruncated);
        m.lowest_address = low;
        header += 4;
    }
    m.description = read_text(reader, text_room(header));
    return ok(std::move(m));
}

DecodeResult decode_other(std::uint8_t command, Reader& reader) {
    switch (static_cast<Command>(command)) {
        case Command::kGetConfigOptions:
            return ok(GetConfigOptions{});
        case Command::kGetConfigOptionsReply: {
            ConfigOptionsReply m;
            std::uint8_t highest = 0;
            std::uint8_t lowest = 0;
            if (!reader.be(2, m.available_commands) || !reader.u8(m.write_lengths) ||
                !reader.u8(highest)) {
                return fail(DecodeError::kTruncated);
            }
            reader.u8(lowest);  // absent lowest space reads as 0
            m.highest_space = static_cast<Space>(highest);
            m.lowest_space = static_cast<Space>(lowest);
            m.name = read_text(reader, text_room(7));
            return ok(std::move(m));
        }
        case Command::kGetSpaceInfo:
        case Command::kSpaceInfoNotPresent:
        case Command::kFreeze:
        case Command::kUnfreeze: {
            std::uint8_t byte = 0;
            if (!reader.u8(byte)) return fail(DecodeError::kMissingSpace);
            const auto space = static_cast<Space>(byte);
            switch (static_cast<Command>(command)) {
                case Command::kGetSpaceInfo:
                    return ok(GetSpaceInfo{space});
                case Command::kSpaceInfoNotPresent:
                    return ok(SpaceInfoNotPresent{space});
                case Command::kFreeze:
                    return ok(Freeze{space});
                default:
                    return ok(Unfreeze{space});
            }
        }
        case Command::kSpaceInfoPresent:
            return decode_space_info(reader);
        case Command::kLock:
        case Command::kLockReply:
        case Command::kFactoryReset: {
            std::uint64_t node_id = 0;
            if (!reader.be(kNodeIdBytes, node_id)) return fail(DecodeError::kTruncated);
            if (command == to_u8(Command::kLock)) return ok(Lock{node_id});
            if (command == to_u8(Command::kLockReply)) return ok(LockReply{node_id});
            return ok(FactoryReset{node_id});
        }
        case Command::kGetUniqueId: {
            std::uint8_t count = 0;
            if (!reader.u8(count)) return fail(DecodeError::kTruncated);
            return ok(GetUniqueId{static_cast<std::uint8_t>(count & kUniqueIdCountMask)});
        }
        case Command::kGetUniqueIdReply: {
            if (reader.remaining() % kEventIdBytes != 0) return fail(DecodeError::kBadLength);
            if (reader.remaining() / kEventIdBytes > kMaxUniqueIds) {
                return fail(DecodeError::kBadCount);
            }
            UniqueIdReply m;
            std::uint64_t id = 0;
            while (reader.be(kEventIdBytes, id)) m.event_ids.push_back(id);
            return ok(std::move(m));
        }
        case Command::kUpdateComplete:
            return ok(UpdateComplete{});
        case Command::kResetReboot:
            return ok(ResetReboot{});
        case Command::kEnterBootloader:
            return ok(EnterBootloader{});
        default:
            return fail(DecodeError::kUnknownCommand);
    }
}

// Encoding -------------------------------------------------------------------------------------

class Encoder {
public:
    explicit Encoder(std::vector<std::uint8_t>& out) : out_(out) {}

    void operator()(const Read& m) {
        header(Command::kRead, m.space, m.address, m.form);
        out_.push_back(m.count);
    }
    void operator()(const ReadReply& m) {
        header(Command::kReadReply, m.space, m.address, m.form);
        data(m.data);
    }
    void operator()(const ReadReplyFail& m) { fail_reply(Command::kReadReplyFail, m); }
    void operator()(const Write& m) {
        header(Command::kWrite, m.space, m.address, m.form);
        data(m.data);
    }
    void operator()(const WriteUnderMask& m) {
        header(Command::kWriteUnderMask, m.space, m.address, m.form);
        const std::size_t pairs = std::min(m.bytes.size(), kMaxReadWrite / 2);
        for (std::size_t i = 0; i < pairs; ++i) {
            out_.push_back(m.bytes[i].mask);
            out_.push_back(m.bytes[i].value);
        }
    }
    void operator()(const WriteReply& m) {
        header(Command::kWriteReply, m.space, m.address, m.form);
    }
    void operator()(const WriteReplyFail& m) { fail_reply(Command::kWriteReplyFail, m); }
    void operator()(const ReadStream& m) {
        header(Command::kReadStream, m.space, m.address, m.form);
        out_.push_back(m.source_stream_id);
        out_.push_back(m.destination_stream_id);
        put_be(out_, 4, m.count);
    }
    void operator()(const ReadStreamReply& m) {
        header(Command::kReadStreamReply, m.space, m.address, m.form);
        out_.push_back(m.source_stream_id);
        out_.push_back(m.destination_stream_id);
        put_be(out_, 4, m.count);
    }
    void operator()(const ReadStreamReplyFail& m) { fail_reply(Command::kReadStreamReplyFail, m); }
    void operator()(const WriteStream& m) {
        header(Command::kWriteStream, m.space, m.address, m.form);
        out_.push_back(m.source_stream_id);
    }
    void operator()(const WriteStreamReply& m) {
        header(Command::kWriteStreamReply, m.space, m.address, m.form);
        out_.push_back(m.source_stream_id);
        out_.push_back(m.destination_stream_id);
    }
    void operator()(const WriteStreamReplyFail& m) {
        fail_reply(Command::kWriteStreamReplyFail, m);
    }
    void operator()(const GetConfigOptions&) { command(Command::kGetConfigOptions); }
    void operator()(const ConfigOptionsReply& m) {
        command(Command::kGetConfigOptionsReply);
        put_be(out_, 2, m.available_commands);
        out_.push_back(m.write_lengths);
        out_.push_back(to_u8(m.highest_space));
        out_.push_back(to_u8(m.lowest_space));
        put_text(out_, m.name, text_room(out_.size()));
    }
    void operator()(const GetSpaceInfo& m) { command_space(Command::kGetSpaceInfo, m.space); }
    void operator()(const SpaceInfoReply& m) {
        command_space(Command::kSpaceInfoPresent, m.space);
        put_be(out_, 4, m.highest_address);
        std::uint8_t flags = m.read_only ? space_flags::kReadOnly : 0;
        if (m.lowest_address) flags |= space_flags::kLowAddressPresent;
        out_.push_back(flags);
        if (m.lowest_address) put_be(out_, 4, *m.lowest_address);
        put_text(out_, m.description, text_room(out_.size()));
    }
    void operator()(const SpaceInfoNotPresent& m) {
        command_space(Command::kSpaceInfoNotPresent, m.space);
    }
    void operator()(const Lock& m) { command_node(Command::kLock, m.node_id); }
    void operator()(const LockReply& m) { command_node(Command::kLockReply, m.node_id); }
    void operator()(const GetUniqueId& m) {
        command(Command::kGetUniqueId);
        out_.push_back(m.count);
    }
    void operator()(const UniqueIdReply& m) {
        command(Command::kGetUniqueIdReply);
        const std::size_t count = std::min(m.event_ids.size(), kMaxUniqueIds);
        for (std::size_t i = 0; i < count; ++i) put_be(out_, kEventIdBytes, m.event_ids[i]);
    }
    void operator()(const Freeze& m) { command_space(Command::kFreeze, m.space); }
    void operator()(const Unfreeze& m) { command_space(Command::kUnfreeze, m.space); }
    void operator()(const UpdateComplete&) { command(Command::kUpdateComplete); }
    void operator()(const ResetReboot&) { command(Command::kResetReboot); }
    void operator()(const FactoryReset& m) { command_node(Command::kFactoryReset, m.node_id); }
    void operator()(const EnterBootloader&) { command(Command::kEnterBootloader); }

private:
    void command(Command c) {
        out_.push_back(kDatagramType);
        out_.push_back(to_u8(c));
    }
    void command_space(Command c, Space space) {
        command(c);
        out_.push_back(to_u8(space));
    }
    void command_node(Command c, std::uint64_t node_id) {
        command(c);
        put_be(out_, kNodeIdBytes, node_id & 0xFFFF'FFFF'FFFFULL);
    }
    void header(Command family, Space space, std::uint32_t address, SpaceForm form) {
        const bool short_form = resolve_form(space, form) == SpaceForm::kShort;
        out_.push_back(kDatagramType);
        out_.push_back(to_u8(family) | (short_form ? short_form_bits(space) : 0));
        put_be(out_, 4, address);
        if (!short_form) out_.push_back(to_u8(space));
    }
    void data(const std::vector<std::uint8_t>& bytes) {
        const std::size_t n = std::min(bytes.size(), kMaxReadWrite);
        out_.insert(out_.end(), bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(n));
    }
    template <typename M>
    void fail_reply(Command family, const M& m) {
        header(family, m.space, m.address, m.form);
        put_be(out_, 2, to_u16(m.error));
        put_text(out_, m.text, kMaxErrorTextChars);
    }

    std::vector<std::uint8_t>& out_;
};

// Description ----------------------------------------------------------------------------------

using base::hex;
using base::hex_digits;

std::string node_id_text(std::uint64_t id) {
    return base::NodeId(id).to_string();
}

// Control bytes are escaped so a description always stays on one line.
std::string quoted(std::string_view text) {
    std::string out = " \"";
    for (const char c : text) {
        const auto byte = static_cast<unsigned char>(c);
        if (byte < 0x20 || byte == 0x7F || c == '"' || c == '\\') {
            out += "\\x" + hex_digits(byte, 2);
        } else {
            out += c;
        }
    }
    return out + '"';
}

std::string error_text(ErrorCode error) {
    std::string out = " " + hex(to_u16(error), 4);
    const std::string_view name = error_name(error);
    if (!name.empty()) out += " " + std::string(name);
    return out;
}

std::string where(Space space, std::uint32_t address) {
    return " " + hex_digits(to_u8(space), 2) + " @" + hex(address, 8);
}

std::string form_note(Space space, SpaceForm form) {
    return form == SpaceForm::kByte6 && has_short_form(space) ? " (byte-6 form)" : "";
}

class Describer {
public:
    std::string operator()(const Read& m) const {
        return "read" + where(m.space, m.address) + " x" + std::to_string(m.count) +
               form_note(m.space, m.form);
    }
    std::string operator()(const ReadReply& m) const {
        return "read-reply" + where(m.space, m.address) + " x" + std::to_string(m.data.size()) +
               form_note(m.space, m.form);
    }
    std::string operator()(const ReadReplyFail& m) const { return failed("read-reply-fail", m); }
    std::string operator()(const Write& m) const {
        return "write" + where(m.space, m.address) + " x" + std::to_string(m.data.size()) +
               form_note(m.space, m.form);
    }
    std::string operator()(const WriteUnderMask& m) const {
        return "write-under-mask" + where(m.space, m.address) + " x" +
               std::to_string(m.bytes.size()) + form_note(m.space, m.form);
    }
    std::string operator()(const WriteReply& m) const {
        return "write-reply" + where(m.space, m.address) + form_note(m.space, m.form);
    }
    std::string operator()(const WriteReplyFail& m) const { return failed("write-reply-fail", m); }
    std::string operator()(const ReadStream& m) const {
        return "read-stream" + where(m.space, m.address) + streams(m.source_stream_id) + " dst " +
               hex(m.destination_stream_id, 2) + " x" + std::to_string(m.count) +
               form_note(m.space, m.form);
    }
    std::string operator()(const ReadStreamReply& m) const {
        return "read-stream-reply" + where(m.space, m.address) + streams(m.source_stream_id) +
               " dst " + hex(m.destination_stream_id, 2) + " x" + std::to_string(m.count) +
               form_note(m.space, m.form);
    }
    std::string operator()(const ReadStreamReplyFail& m) const {
        return failed("read-stream-reply-fail", m);
    }
    std::string operator()(const WriteStream& m) const {
        return "write-stream" + where(m.space, m.address) + streams(m.source_stream_id) +
               form_note(m.space, m.form);
    }
    std::string operator()(const WriteStreamReply& m) const {
        return "write-stream-reply" + where(m.space, m.address) + streams(m.source_stream_id) +
               " dst " + hex(m.destination_stream_id, 2) + form_note(m.space, m.form);
    }
    std::string operator()(const WriteStreamReplyFail& m) const {
        return failed("write-stream-reply-fail", m);
    }
    std::string operator()(const GetConfigOptions&) const { return "get-config-options"; }
    std::string operator()(const ConfigOptionsReply& m) const {
        std::string out = "config-options cmds " + hex(m.available_commands, 4) + " lengths " +
                          hex(m.write_lengths, 2) + " spaces " +
                          hex_digits(to_u8(m.highest_space), 2) + ".." +
                          hex_digits(to_u8(m.lowest_space), 2);
        if (!m.name.empty()) out += quoted(m.name);
        return out;
    }
    std::string operator()(const GetSpaceInfo& m) const {
        return "get-space-info " + hex_digits(to_u8(m.space), 2);
    }
    std::string operator()(const SpaceInfoReply& m) const {
        std::string out = "space-info " + hex_digits(to_u8(m.space), 2) + " present hi " +
                          hex(m.highest_address, 8) + (m.read_only ? " ro" : " rw");
        if (m.lowest_address) out += " lo " + hex(*m.lowest_address, 8);
        if (!m.description.empty()) out += quoted(m.description);
        return out;
    }
    std::string operator()(const SpaceInfoNotPresent& m) const {
        return "space-info " + hex_digits(to_u8(m.space), 2) + " not present";
    }
    std::string operator()(const Lock& m) const {
        return "lock " + node_id_text(m.node_id) + (m.node_id == 0 ? " (release)" : "");
    }
    std::string operator()(const LockReply& m) const {
        return "lock-reply " + node_id_text(m.node_id);
    }
    std::string operator()(const GetUniqueId& m) const {
        return "get-unique-id x" + std::to_string(m.count);
    }
    std::string operator()(const UniqueIdReply& m) const {
        return "unique-id-reply x" + std::to_string(m.event_ids.size());
    }
    std::string operator()(const Freeze& m) const {
        return "freeze " + hex_digits(to_u8(m.space), 2);
    }
    std::string operator()(const Unfreeze& m) const {
        return "unfreeze " + hex_digits(to_u8(m.space), 2);
    }
    std::string operator()(const UpdateComplete&) const { return "update-complete"; }
    std::string operator()(const ResetReboot&) const { return "reset-reboot"; }
    std::string operator()(const FactoryReset& m) const {
        return "factory-reset " + node_id_text(m.node_id);
    }
    std::string operator()(const EnterBootloader&) const { return "enter-bootloader"; }

private:
    static std::string streams(std::uint8_t source) { return " src " + hex(source, 2); }

    template <typename M>
    static std::string failed(std::string_view name, const M& m) {
        std::string out = std::string(name) + where(m.space, m.address) + error_text(m.error);
        if (!m.text.empty()) out += quoted(m.text);
        return out + form_note(m.space, m.form);
    }
};

}  // namespace

std::string_view to_string(DecodeError error) {
    switch (error) {
        case DecodeError::kNone:
            return "ok";
        case DecodeError::kEmpty:
            return "empty payload";
        case DecodeError::kTooLong:
            return "payload longer than 72 bytes";
        case DecodeError::kNotMemoryConfig:
            return "not a memory-config payload";
        case DecodeError::kTruncated:
            return "truncated";
        case DecodeError::kMissingSpace:
            return "missing space byte";
        case DecodeError::kUnknownCommand:
            return "unknown command";
        case DecodeError::kBadCount:
            return "count out of range";
        case DecodeError::kNoData:
            return "no data";
        case DecodeError::kTooMuchData:
            return "more than 64 data bytes";
        case DecodeError::kOddMaskData:
            return "odd number of mask/data bytes";
        case DecodeError::kBadLength:
            return "length not a whole number of IDs";
    }
    return "unknown decode error";
}

ErrorCode reject_code(DecodeError error) {
    switch (error) {
        case DecodeError::kNone:
            return ErrorCode::kNone;
        case DecodeError::kNotMemoryConfig:
            return ErrorCode::kCommandUnknown;
        case DecodeError::kUnknownCommand:
            return ErrorCode::kSubcommandUnknown;
        default:
            return ErrorCode::kInvalidArguments;
    }
}

SpaceForm resolve_form(Space space, SpaceForm requested) {
    if (requested == SpaceForm::kByte6 || !has_short_form(space)) return SpaceForm::kByte6;
    return SpaceForm::kShort;
}

namespace {
// Relaxed: only counts, read by tests after the work they count.
std::atomic<std::uint64_t> g_decoded{0};
std::atomic<std::uint64_t> g_encoded{0};
}  // namespace

CodecCounts codec_counts() {
    return {g_decoded.load(std::memory_order_relaxed), g_encoded.load(std::memory_order_relaxed)};
}

DecodeResult decode(std::span<const std::uint8_t> payload) {
    g_decoded.fetch_add(1, std::memory_order_relaxed);
    if (payload.empty()) return fail(DecodeError::kEmpty);
    if (payload.size() > kMaxDatagram) return fail(DecodeError::kTooLong);
    Reader reader(payload);
    std::uint8_t type = 0;
    std::uint8_t command = 0;
    reader.u8(type);
    if (type != kDatagramType) return fail(DecodeError::kNotMemoryConfig);
    if (!reader.u8(command)) return fail(DecodeError::kTruncated);
    return is_read_write_family(command) ? decode_read_write(command, reader)
                                         : decode_other(command, reader);
}

std::vector<std::uint8_t> encode(const Message& message) {
    g_encoded.fetch_add(1, std::memory_order_relaxed);
    std::vector<std::uint8_t> out;
    out.reserve(kMaxDatagram);
    std::visit(Encoder(out), message);
    return out;
}

std::string describe(std::span<const std::uint8_t> payload) {
    const DecodeResult result = decode(payload);
    if (result.ok()) return std::visit(Describer{}, result.message);
    std::string out = "invalid memory-config payload: " + std::string(to_string(result.error));
    out += " [";
    const std::size_t shown = std::min<std::size_t>(payload.size(), 8);
    out += base::hex_bytes(payload.first(shown));
    if (payload.size() > shown) out += " ...";
    return out + "]";
}

}  // namespace olcb::memory
