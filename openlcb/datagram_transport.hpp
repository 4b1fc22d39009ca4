// Datagram transport on CAN (fact sheet 4), sans-I/O: a sender that waits for each datagram's
// OK/Rejected and a receiver that reassembles, rejects protocol violations and hands complete
// datagrams to its owner for the answer.
#pragma once

#include <bitset>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <span>
#include <vector>

#include "base/timings.hpp"
#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"
#include "openlcb/datagram_defs.hpp"

namespace olcb {

/// Tunables of DatagramSender.
struct DatagramSenderConfig {
    /// Wait for OK/Rejected after the last frame before reporting a timeout.
    Duration ack_timeout = base::kDatagramAckTimeout;
    /// Resends after temporary rejections before giving up (so at most 1 + this many sends).
    unsigned max_resends = 3;
    /// Pause before a resend, so a busy receiver gets time to free its buffer.
    Duration resend_delay = std::chrono::milliseconds(100);
    /// Datagrams queued or in flight at once; send() refuses more.
    std::size_t max_queued = 32;
};

/// Final result of one datagram given to DatagramSender::send().
struct DatagramOutcome {
    enum class Status : std::uint8_t {
        kAccepted,  ///< Datagram Received OK; flags hold its flags byte
        kRejected,  ///< Datagram Rejected (or OIR) with a permanent code, or resends exhausted
        kTimedOut,  ///< no answer within ack_timeout (error_code = 0x2010)
        kAborted,   ///< abort_all() or abort_to() dropped it
        /// settle(): the receiver answered it some other way (its reply came) and sends no OK
        kUnacknowledged,
    };
    std::uint32_t id = 0;  ///< what send() returned
    std::uint16_t dest_alias = 0;
    Status status = Status::kAccepted;
    std::uint16_t error_code = 0;  ///< reject code of the last answer, or 0x2010 on timeout
    std::uint8_t flags = 0;        ///< Datagram Received OK flags (Reply Pending, exponent)
    unsigned attempts = 0;         ///< transmissions made
};

/// Sends datagrams: one outstanding per destination (others queue), resends on temporary errors
/// up to a bound, never on permanent ones, reports a timeout after ack_timeout.
class DatagramSender {
public:
    /// Sender with the given limits.
    explicit DatagramSender(DatagramSenderConfig config = {}) : config_(config) {}

    /// Our source alias (0 = none yet: send() refuses).
    void set_alias(std::uint16_t alias) { alias_ = alias; }
    /// Our source alias.
    std::uint16_t alias() const { return alias_; }
    /// Queues a datagram to dest_alias; returns its id, or nullopt when the payload exceeds 72
    /// bytes, an alias is 0 or the queue is full.
    std::optional<std::uint32_t> send(std::uint16_t dest_alias,
                                      std::span<const std::uint8_t> payload, TimePoint now);
    /// Looks at a received frame; returns true when it answered one of our datagrams.
    bool on_frame(const CanFrame& frame, TimePoint now);
    /// Handles timeouts and delayed resends.
    void poll(TimePoint now);
    /// When poll() next has work.
    std::optional<TimePoint> next_deadline() const;
    /// Drops every queued and outstanding datagram, reporting each as kAborted.
    void abort_all();
    /// Drops every queued and outstanding datagram to dest_alias (that node re-initialized, so
    /// no ack will come), reporting each as kAborted; returns how many were dropped.
    std::size_t abort_to(std::uint16_t dest_alias);
    /// Ends datagram id, still waiting for its OK, as kUnacknowledged: the owner knows it was
    /// received (its reply came) from a receiver that never acknowledges, so the next datagram to
    /// that destination goes now instead of after ack_timeout. False when id waits for no OK.
    bool settle(std::uint32_t id, TimePoint now);

    /// Next frame to transmit.
    std::optional<CanFrame> pop_frame();
    /// Next finished datagram.
    std::optional<DatagramOutcome> pop_outcome();
    /// Datagrams queued or in flight.
    std::size_t queued() const { return entries_.size(); }

private:
    enum class Phase : std::uint8_t { kQueued, kWaitingAck, kWaitingResend };
    struct Entry {
        std::uint32_t id;
        std::uint16_t dest;
        std::vector<std::uint8_t> payload;
        Phase phase = Phase::kQueued;
        TimePoint deadline{};
        unsigned attempts = 0;
    };

    void transmit(Entry& e, TimePoint now);
    void finish(std::size_t index, DatagramOutcome::Status status, std::uint16_t code,
                std::uint8_t flags, TimePoint now);
    std::optional<std::size_t> outstanding_for(std::uint16_t dest) const;

    DatagramSenderConfig config_;
    std::uint16_t alias_ = 0;
    std::uint32_t next_id_ = 1;
    std::deque<Entry> entries_;
    std::deque<CanFrame> outbox_;
    std::deque<DatagramOutcome> outcomes_;
};

/// Tunables of DatagramReceiver.
struct DatagramReceiverConfig {
    /// Datagrams held at once: being reassembled or delivered and not yet answered. A new
    /// datagram beyond this is rejected with 0x2020 (buffer unavailable).
    std::size_t max_buffers = 4;
    /// A partial datagram idle this long is abandoned silently (the sender times out).
    Duration reassembly_timeout = base::kDatagramAckTimeout;
};

/// A complete datagram waiting for its owner's accept() or reject().
struct ReceivedDatagram {
    std::uint16_t source_alias = 0;
    std::uint16_t dest_alias = 0;
    std::vector<std::uint8_t> payload;  ///< 0..72 bytes, content type first
};

/// Reassembles datagrams addressed to our alias, one per source; rejects: middle/last without
/// first 0x2041, first while one is in progress 0x2042, more than 72 bytes 0x1000 (permanent, as
/// OpenMRN), no free buffer 0x2020. One reject per broken datagram: its remaining frames are
/// then ignored up to its last frame.
class DatagramReceiver {
public:
    /// Receiver with the given limits.
    explicit DatagramReceiver(DatagramReceiverConfig config = {}) : config_(config) {}

    /// Our alias; frames to other aliases are ignored. Changing it abandons all state.
    void set_alias(std::uint16_t alias);
    /// Our alias.
    std::uint16_t alias() const { return alias_; }
    /// Processes a received frame (non-datagram frames are ignored).
    void on_frame(const CanFrame& frame, TimePoint now);
    /// Abandons stale partial datagrams.
    void poll(TimePoint now);
    /// When poll() next has work.
    std::optional<TimePoint> next_deadline() const;
    /// Forgets every partial and unanswered datagram (node re-initialised).
    void reset();

    /// Next complete datagram for the owner, who must answer it with accept() or reject().
    std::optional<ReceivedDatagram> pop_datagram();
    /// Sends Datagram Received OK with flags (see datagram::ok_flags) to source_alias and frees
    /// its buffer; returns false when no datagram from it was waiting (the OK is still sent).
    bool accept(std::uint16_t source_alias, std::uint8_t flags = 0);
    /// Sends Datagram Rejected with code to source_alias and frees its buffer; returns false when
    /// no datagram from it was waiting (the reject is still sent).
    bool reject(std::uint16_t source_alias, std::uint16_t code);
    /// Frees the buffer of a delivered datagram from source_alias without answering it (the
    /// owner answers by other means, or not at all); false when none from it was waiting.
    bool release(std::uint16_t source_alias);

    /// Next frame to transmit.
    std::optional<CanFrame> pop_frame();
    /// Buffers in use (reassembling or awaiting an answer).
    std::size_t buffers_in_use() const { return slots_.size(); }
    /// Rejections sent by the receiver itself (protocol violations, no buffer).
    std::uint64_t rejections() const { return rejections_; }
    /// Partial datagrams abandoned after the reassembly timeout.
    std::uint64_t timeouts() const { return timeouts_; }

private:
    struct Slot {
        std::uint16_t src;
        bool complete = false;
        TimePoint last{};
        std::vector<std::uint8_t> data;
    };

    Slot* find(std::uint16_t src);
    void erase(std::uint16_t src);
    void send_reject(std::uint16_t src, std::uint16_t code);
    void start(std::uint16_t src, const CanFrame& frame, bool complete, TimePoint now);
    void on_first_frame(std::uint16_t src, const Slot* slot, const CanFrame& frame, bool only,
                        TimePoint now);
    void on_later_frame(std::uint16_t src, Slot* slot, const CanFrame& frame, bool last,
                        TimePoint now);

    DatagramReceiverConfig config_;
    std::uint16_t alias_ = 0;
    std::vector<Slot> slots_;
    std::deque<std::uint16_t> ready_;
    std::bitset<4096> discarding_;  // sources whose current datagram was rejected mid-way
    std::deque<CanFrame> outbox_;
    std::uint64_t rejections_ = 0;
    std::uint64_t timeouts_ = 0;
};

}  // namespace olcb
