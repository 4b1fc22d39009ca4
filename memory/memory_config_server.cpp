#include "memory/memory_config_server.hpp"

#include <algorithm>
#include <type_traits>
#include <utility>

namespace olcb::memory {
namespace {

constexpr std::uint64_t kNodeIdMask = 0xFFFF'FFFF'FFFFULL;
constexpr std::uint32_t kUniqueIdLimit = 0x10000;  // 16-bit suffix after the 48-bit node ID

std::size_t index(Space space) {
    return to_u8(space);
}

}  // namespace

Decision Decision::reject(ErrorCode code) {
    Decision d;
    d.accepted = false;
    d.reject_error = code;
    return d;
}

Decision Decision::ok() {
    return Decision{};
}

Decision Decision::ok_with_reply(std::optional<Message> reply, std::uint8_t exponent) {
    Decision d;
    d.reply_pending = true;
    d.reply_timeout_exponent = exponent;
    d.reply = std::move(reply);
    return d;
}

std::vector<std::uint8_t> Decision::reply_bytes() const {
    return reply ? encode(*reply) : std::vector<std::uint8_t>{};
}

MemoryConfigServer::MemoryConfigServer(Config config)
    : config_(std::move(config)),
      unique_id_counter_(std::min(config_.unique_id_counter, kUniqueIdLimit)) {}

void MemoryConfigServer::add_space(Space number, MemorySpace& space) {
    spaces_[index(number)] = &space;
}

void MemoryConfigServer::remove_space(Space number) {
    spaces_[index(number)] = nullptr;
}

MemorySpace* MemoryConfigServer::space(Space number) const {
    return spaces_[index(number)];
}

void MemoryConfigServer::reset() {
    lock_holder_ = 0;
}

ConfigOptionsReply MemoryConfigServer::config_options() const {
    ConfigOptionsReply reply;
    reply.available_commands = available_commands::kWriteUnderMask |
                               available_commands::kUnalignedReads |
                               available_commands::kUnalignedWrites;
    if (space(Space::kAcdiManufacturer) != nullptr) {
        reply.available_commands |= available_commands::kAcdiManufacturerRead;
    }
    if (const MemorySpace* user = space(Space::kAcdiUser)) {
        reply.available_commands |= available_commands::kAcdiUserRead;
        if (!user->read_only()) reply.available_commands |= available_commands::kAcdiUserWrite;
    }
    // Stream reads only, as OpenMRN: write_lengths::kStreams would promise stream writes.
    if (config_.streams) reply.available_commands |= available_commands::kStreamReads;
    reply.write_lengths = write_lengths::kRecommended;
    // Over the spaces actually served; with none, the always-defined high spaces.
    reply.highest_space = Space::kCdi;
    reply.lowest_space = Space::kConfig;
    bool any = false;
    for (std::size_t i = 0; i < spaces_.size(); ++i) {
        if (spaces_[i] == nullptr) continue;
        if (!any) reply.lowest_space = static_cast<Space>(i);
        reply.highest_space = static_cast<Space>(i);
        any = true;
    }
    reply.name = config_.name;
    return reply;
}

Decision MemoryConfigServer::with_reply(const Message& reply) const {
    return Decision::ok_with_reply(reply, config_.reply_timeout_exponent);
}

Decision MemoryConfigServer::handle(const Source& source, std::span<const std::uint8_t> payload) {
    return handle(source, decode(payload));
}

Decision MemoryConfigServer::handle(const Source&, const DecodeResult& decoded) {
    if (!decoded.ok()) return Decision::reject(reject_code(decoded.error));

    return std::visit(
        [this](const auto& m) -> Decision {
            using T = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<T, Read>) {
                return on_read(m);
            } else if constexpr (std::is_same_v<T, Write>) {
                return on_write(m.space, m.address, m.form, m.data, nullptr);
            } else if constexpr (std::is_same_v<T, WriteUnderMask>) {
                return on_write(m.space, m.address, m.form, {}, &m.bytes);
            } else if constexpr (std::is_same_v<T, ReadStream>) {
                return on_read_stream(m);
            } else if constexpr (std::is_same_v<T, GetConfigOptions>) {
                return with_reply(config_options());
            } else if constexpr (std::is_same_v<T, GetSpaceInfo>) {
                return on_space_info(m);
            } else if constexpr (std::is_same_v<T, Lock>) {
                return on_lock(m);
            } else if constexpr (std::is_same_v<T, GetUniqueId>) {
                return on_unique_id(m);
            } else if constexpr (std::is_same_v<T, UpdateComplete>) {
                return Decision::ok();
            } else if constexpr (std::is_same_v<T, ResetReboot>) {
                return on_reset_reboot();
            } else if constexpr (std::is_same_v<T, FactoryReset>) {
                return on_factory_reset(m);
            } else if constexpr (std::is_same_v<T, Freeze>) {
                return on_freeze(m);
            } else if constexpr (std::is_same_v<T, Unfreeze>) {
                return on_unfreeze(m);
            } else if constexpr (std::is_same_v<T, EnterBootloader>) {
                return on_enter_bootloader();
            } else {
                // Streams (unsupported) and replies (we are not a client).
                return Decision::reject(ErrorCode::kSubcommandUnknown);
            }
        },
        decoded.message);
}

Decision MemoryConfigServer::on_reset_reboot() {
    Decision d = Decision::ok();
    d.effects.reboot = true;
    reset();
    return d;
}

Decision MemoryConfigServer::on_factory_reset(const FactoryReset& request) {
    // The node ID in the command is a safety check against resetting the wrong node.
    if ((request.node_id & kNodeIdMask) != (config_.node_id & kNodeIdMask)) {
        return Decision::reject(ErrorCode::kInvalidArguments);
    }
    Decision d = Decision::ok();
    d.effects.factory_reset = true;
    reset();
    return d;
}

Decision MemoryConfigServer::on_freeze(const Freeze& request) const {
    if (!config_.accept_freeze) return Decision::reject(ErrorCode::kSubcommandUnknown);
    Decision d = Decision::ok();
    d.effects.freeze = request.space;
    return d;
}

Decision MemoryConfigServer::on_unfreeze(const Unfreeze& request) const {
    if (!config_.accept_freeze) return Decision::reject(ErrorCode::kSubcommandUnknown);
    Decision d = Decision::ok();
    d.effects.unfreeze = request.space;
    return d;
}

Decision MemoryConfigServer::on_enter_bootloader() const {
    if (!config_.accept_enter_bootloader) return Decision::reject(ErrorCode::kSubcommandUnknown);
    Decision d = Decision::ok();
    d.effects.enter_bootloader = true;
    return d;
}

Decision MemoryConfigServer::on_read(const Read& read) {
    MemorySpace* s = space(read.space);
    if (s == nullptr) return Decision::reject(ErrorCode::kSpaceUnknown);
    const std::uint32_t size = s->size();
    if (read.address < s->lowest_address() || read.address >= size) {
        return with_reply(
            ReadReplyFail{read.space, read.address, ErrorCode::kOutOfBounds, {}, read.form});
    }
    // A range running past the end is cut short there (fact sheet 5.3).
    const std::size_t wanted = std::min<std::size_t>(read.count, size - read.address);
    std::array<std::uint8_t, kMaxReadWrite> buffer{};
    const std::size_t got =
        std::min(s->read(read.address, std::span(buffer).first(wanted)), wanted);
    if (got == 0) {
        return with_reply(
            ReadReplyFail{read.space, read.address, ErrorCode::kOutOfBounds, {}, read.form});
    }
    return with_reply(ReadReply{read.space, read.address,
                                std::vector<std::uint8_t>(buffer.begin(), buffer.begin() + got),
                                read.form});
}

Decision MemoryConfigServer::on_read_stream(const ReadStream& read) {
    if (!config_.streams) return Decision::reject(ErrorCode::kSubcommandUnknown);
    MemorySpace* s = space(read.space);
    if (s == nullptr) return Decision::reject(ErrorCode::kSpaceUnknown);
    const std::uint32_t size = s->size();
    if (read.address < s->lowest_address() || read.address >= size) {
        return with_reply(
            ReadStreamReplyFail{read.space, read.address, ErrorCode::kOutOfBounds, {}, read.form});
    }
    const std::uint32_t available = size - read.address;
    Decision d = Decision::ok_with_reply(std::nullopt, config_.reply_timeout_exponent);
    d.effects.stream_read =
        StreamRead{read.space,
                   read.address,
                   read.count == 0 ? available : std::min(read.count, available),
                   read.count,
                   read.destination_stream_id,
                   read.form};
    return d;
}

std::vector<std::uint8_t> MemoryConfigServer::stream_reply(const StreamRead& read, std::uint8_t sid,
                                                           std::uint8_t did) {
    return encode(ReadStreamReply{read.space, read.address, sid, did, read.count, read.form});
}

std::vector<std::uint8_t> MemoryConfigServer::stream_fail(const StreamRead& read, ErrorCode code) {
    return encode(ReadStreamReplyFail{read.space, read.address, code, {}, read.form});
}

std::vector<std::uint8_t> MemoryConfigServer::stream_data(const StreamRead& read) const {
    std::vector<std::uint8_t> out(read.length);
    MemorySpace* s = space(read.space);
    const std::size_t got = s == nullptr ? 0 : s->read(read.address, out);
    out.resize(std::min<std::size_t>(got, read.length));
    return out;
}

Decision MemoryConfigServer::on_write(Space number, std::uint32_t address, SpaceForm form,
                                      std::span<const std::uint8_t> data,
                                      const std::vector<MaskedByte>* mask) {
    MemorySpace* s = space(number);
    if (s == nullptr) return Decision::reject(ErrorCode::kSpaceUnknown);
    if (s->read_only()) return Decision::reject(ErrorCode::kReadOnly);
    const std::size_t length = mask != nullptr ? mask->size() : data.size();
    const auto fail = [&](ErrorCode code) {
        return with_reply(WriteReplyFail{number, address, code, {}, form});
    };
    if (address < s->lowest_address() || !fits(s->size(), address, length)) {
        return fail(ErrorCode::kOutOfBounds);
    }

    std::array<std::uint8_t, kMaxReadWrite> before{};
    std::array<std::uint8_t, kMaxReadWrite> after{};
    const bool have_before = s->read(address, std::span(before).first(length)) == length;
    for (std::size_t i = 0; i < length; ++i) {
        if (mask != nullptr) {
            const MaskedByte& b = (*mask)[i];
            after[i] = static_cast<std::uint8_t>((before[i] & ~b.mask) | (b.value & b.mask));
        } else {
            after[i] = data[i];
        }
    }
    if (mask != nullptr && !have_before) return fail(ErrorCode::kPermanent);

    // The space persists the bytes before returning, so acknowledging after this is safe.
    switch (s->write(address, std::span(after).first(length))) {
        case WriteStatus::kOk:
            break;
        case WriteStatus::kReadOnly:
            // A space read-only in part (251's version byte) refuses as a read-only space does.
            return Decision::reject(ErrorCode::kReadOnly);
        case WriteStatus::kOutOfBounds:
            return fail(ErrorCode::kOutOfBounds);
        case WriteStatus::kIoError: {
            Decision d = fail(ErrorCode::kPermanent);
            d.effects.not_stored =
                WrittenRange{number, address, static_cast<std::uint32_t>(length), false};
            return d;
        }
    }

    Decision d = config_.write_reply_pending ? with_reply(WriteReply{number, address, form})
                                             : Decision::ok();
    const bool changed =
        !have_before || !std::equal(before.begin(), before.begin() + length, after.begin());
    d.effects.written = WrittenRange{number, address, static_cast<std::uint32_t>(length), changed};
    d.effects.identification_changed = changed && number == Space::kAcdiUser;
    return d;
}

Decision MemoryConfigServer::on_space_info(const GetSpaceInfo& request) const {
    const MemorySpace* s = space(request.space);
    if (s == nullptr) return with_reply(SpaceInfoNotPresent{request.space});
    SpaceInfoReply reply;
    reply.space = request.space;
    reply.highest_address = s->size() == 0 ? 0 : s->size() - 1;
    reply.read_only = s->read_only();
    // Omitted when 0 so the reply fits one CAN frame.
    if (s->lowest_address() != 0) reply.lowest_address = s->lowest_address();
    reply.description = std::string(s->description());
    return with_reply(reply);
}

Decision MemoryConfigServer::on_lock(const Lock& request) {
    const std::uint64_t requester = request.node_id & kNodeIdMask;
    if (requester == 0) {
        lock_holder_ = 0;
    } else if (lock_holder_ == 0) {
        lock_holder_ = requester;
    }
    return with_reply(LockReply{lock_holder_});
}

Decision MemoryConfigServer::on_unique_id(const GetUniqueId& request) {
    if (unique_id_counter_ + request.count > kUniqueIdLimit) {
        return Decision::reject(ErrorCode::kPermanent);
    }
    UniqueIdReply reply;
    for (std::uint8_t i = 0; i < request.count; ++i) {
        reply.event_ids.push_back(((config_.node_id & kNodeIdMask) << 16) | unique_id_counter_++);
    }
    Decision d = with_reply(reply);
    d.effects.unique_id_counter = unique_id_counter_;
    return d;
}

}  // namespace olcb::memory
