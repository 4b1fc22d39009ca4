// Memory Configuration Protocol server, sans-I/O: one datagram payload in, one Decision out.
//
// The Decision is a plain value the owner turns into Datagram Received OK / Datagram Rejected and
// an optional reply datagram; an owner injecting faults may rewrite it before sending, or wrap a
// MemorySpace (see ForwardingSpace), so no fault needs a copy of this class.
//
// Documented choices (fact sheet 5 and 11):
//  * read count 0 or > 64, truncated or malformed commands, factory reset naming another node:
//    Datagram Rejected 0x1080; unknown command, write streams, read streams unless enabled,
//    replies sent to us, and freeze / unfreeze / enter bootloader unless enabled: Datagram
//    Rejected 0x1041;
//  * Read Stream: the same spaces and bounds as Read (at/after the end: Reply Pending + Read
//    Stream Reply Fail 0x1082), count 0 = to the end of the space; the owner opens the stream
//    (SideEffects::stream_read) and sends the reply once the requester accepted it;
//  * unknown space: Datagram Rejected 0x1081 (no reply); write to a read-only space, or one the
//    space refuses as read-only (a read-only byte inside it, as 251's version byte): 0x1083;
//  * read starting at/after the end: Read Reply Fail 0x1082; read running past the end: short
//    Read Reply; write not fitting the space: Write Reply Fail 0x1082 and nothing written;
//    storage failure: Write Reply Fail 0x1000;
//  * Get Unique ID: event ID = node ID (48 bits) then a 16-bit counter the owner persists;
//    once 65536 are used up: Datagram Rejected 0x1000. Lock: test-and-set, zeros release it
//    whoever holds it (advisory), cleared by reset(), Reset/Reboot and Factory Reset;
//  * replies use the same form (short FD/FE/FF or byte 6) as the request;
//  * successful writes answer Reply Pending + Write Reply OK (like OpenMRN) unless
//    Config::write_reply_pending is false (plain Datagram OK); a failed write always gets
//    Reply Pending + Write Reply Fail.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "memory/memory_config_codec.hpp"
#include "memory/memory_config_defs.hpp"
#include "memory/memory_space.hpp"

namespace olcb::memory {

/// Sender of a datagram (opaque to the server; available to policies layered around it).
struct Source {
    std::uint64_t node_id = 0;  ///< 48 bits used; 0 when unknown
    std::uint16_t alias = 0;    ///< CAN alias; 0 on other transports
};

/// A range of a space that a write command stored.
struct WrittenRange {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    std::uint32_t length = 0;
    bool changed = false;  ///< at least one byte differs from before
    friend bool operator==(const WrittenRange&, const WrittenRange&) = default;
};

/// A Read Stream the owner must serve: open a stream to the requester (suggesting
/// destination_stream_id), then send stream_reply() (or stream_fail() when the stream was
/// refused) and the bytes of [address, address + length) of the space.
struct StreamRead {
    Space space = Space::kConfig;
    std::uint32_t address = 0;
    std::uint32_t length = 0;  ///< bytes to send (count 0 = to the end, cut at the end)
    std::uint32_t count = 0;   ///< count as requested (echoed in the reply)
    std::uint8_t destination_stream_id = 0xFF;
    SpaceForm form = SpaceForm::kAuto;
    friend bool operator==(const StreamRead&, const StreamRead&) = default;
};

/// What the owner must do once the acknowledgement (and any reply) is sent.
struct SideEffects {
    bool reboot = false;                  ///< restart as after power-up
    bool factory_reset = false;           ///< restore factory content (then restart)
    bool identification_changed = false;  ///< ACDI user data changed: Initialization Complete again
    std::optional<WrittenRange> written;  ///< a space was written (e.g. re-advertise events)
    /// New value of the Get Unique ID counter: persist it before sending the reply.
    std::optional<std::uint32_t> unique_id_counter;
    std::optional<Space> freeze;            ///< Freeze accepted for this space
    std::optional<Space> unfreeze;          ///< Unfreeze accepted for this space
    bool enter_bootloader = false;          ///< Enter Bootloader accepted
    std::optional<StreamRead> stream_read;  ///< Read Stream accepted: serve it (see StreamRead)
    /// A write the space could not store (I/O error): refused, worth a log line.
    std::optional<WrittenRange> not_stored;
    friend bool operator==(const SideEffects&, const SideEffects&) = default;
};

/// The server's answer to one datagram; a plain value the owner may rewrite before sending.
struct Decision {
    bool accepted = true;                       ///< Datagram Received OK, else Datagram Rejected
    ErrorCode reject_error = ErrorCode::kNone;  ///< code of the Datagram Rejected
    bool reply_pending = false;                 ///< OK flag: a reply datagram follows
    std::uint8_t reply_timeout_exponent = 0;    ///< OK flag: reply within 2^N s (0 = unstated)
    /// The reply datagram, typed: encoded once, where the owner sends it, so an owner that
    /// changes it (simnode's faults) changes fields, never bytes; none = no reply.
    std::optional<Message> reply;
    SideEffects effects;  ///< actions for the owner

    /// Datagram Rejected with code, nothing else.
    static Decision reject(ErrorCode code);
    /// Plain Datagram Received OK, no reply.
    static Decision ok();
    /// Datagram Received OK with Reply Pending, then reply.
    static Decision ok_with_reply(std::optional<Message> reply, std::uint8_t exponent = 0);
    /// The reply's datagram payload; empty when there is none.
    std::vector<std::uint8_t> reply_bytes() const;
    friend bool operator==(const Decision&, const Decision&) = default;
};

/// Memory Configuration server over registered spaces.
class MemoryConfigServer {
public:
    /// Fixed behaviour of a server.
    struct Config {
        std::uint64_t node_id = 0;                ///< our node ID (factory reset check, unique IDs)
        bool write_reply_pending = true;          ///< false: successful writes get a plain OK
        std::uint8_t reply_timeout_exponent = 0;  ///< N in Reply Pending flags (0 = unstated)
        std::string name;                         ///< optional name in Get Configuration Options
        bool accept_freeze = false;               ///< Freeze/Unfreeze get OK instead of 0x1041
        bool accept_enter_bootloader = false;     ///< Enter Bootloader gets OK instead of 0x1041
        /// Read Stream is served (Options says "stream reads", 0x1000, as OpenMRN); false
        /// rejects stream commands 0x1041 as a datagram-only node.
        bool streams = false;
        /// First Get Unique ID suffix, 0..65536 (persisted by the owner across runs).
        std::uint32_t unique_id_counter = 0;
    };

    /// A server with no spaces.
    explicit MemoryConfigServer(Config config);

    /// Serves space as number; space must outlive the server (or be removed first).
    void add_space(Space number, MemorySpace& space);
    /// Stops serving a space.
    void remove_space(Space number);
    /// The space served as number, or null.
    MemorySpace* space(Space number) const;

    /// Decides how to answer one datagram payload (content type 0x20 first).
    Decision handle(const Source& source, std::span<const std::uint8_t> payload);
    /// Decides how to answer a datagram its owner decoded already (and may have changed).
    Decision handle(const Source& source, const DecodeResult& request);

    /// Forgets volatile state as at power-up (the lock).
    void reset();
    /// Node holding the Lock/Reserve (0 = free).
    std::uint64_t lock_holder() const { return lock_holder_; }
    /// Suffix the next Get Unique ID will use (65536 = all used up).
    std::uint32_t unique_id_counter() const { return unique_id_counter_; }
    /// The Get Configuration Options reply for the registered spaces.
    ConfigOptionsReply config_options() const;
    /// Fixed behaviour.
    const Config& config() const { return config_; }
    /// Serves Read Stream or not (see Config::streams).
    void set_streams(bool on) { config_.streams = on; }
    /// The Read Stream Reply datagram for a read served with stream IDs sid/did.
    static std::vector<std::uint8_t> stream_reply(const StreamRead& read, std::uint8_t sid,
                                                  std::uint8_t did);
    /// The Read Stream Reply Fail datagram (the stream could not be opened: code).
    static std::vector<std::uint8_t> stream_fail(const StreamRead& read, ErrorCode code);
    /// The bytes a StreamRead sends, read from its space now (fewer if the space shrank).
    std::vector<std::uint8_t> stream_data(const StreamRead& read) const;

private:
    Decision on_read(const Read& read);
    Decision on_read_stream(const ReadStream& read);
    Decision on_write(Space number, std::uint32_t address, SpaceForm form,
                      std::span<const std::uint8_t> data, const std::vector<MaskedByte>* mask);
    Decision on_space_info(const GetSpaceInfo& request) const;
    Decision on_lock(const Lock& request);
    Decision on_unique_id(const GetUniqueId& request);
    Decision on_reset_reboot();
    Decision on_factory_reset(const FactoryReset& request);
    Decision on_freeze(const Freeze& request) const;
    Decision on_unfreeze(const Unfreeze& request) const;
    Decision on_enter_bootloader() const;
    Decision with_reply(const Message& reply) const;

    Config config_;
    std::array<MemorySpace*, 256> spaces_{};
    std::uint64_t lock_holder_ = 0;
    std::uint32_t unique_id_counter_ = 0;
};

}  // namespace olcb::memory
