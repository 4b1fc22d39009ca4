#include "conformance/link/session.hpp"

#include <algorithm>
#include <variant>

#include "base/error_codes.hpp"
#include "memory/memory_config_defs.hpp"
#include "memory/snip.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/can_timing.hpp"

namespace olcb::conform {
namespace {

// A run against a chatty node must not grow without bound; beyond these, records are dropped.
constexpr std::size_t kMaxFrames = 1'000'000;
constexpr std::size_t kMaxMessages = 200'000;
constexpr std::size_t kMaxNodes = 10'000;
constexpr std::size_t kMaxShortReads = 100'000;

// CAN-MTIs of the global messages that carry the sender's node ID and so map its alias.
constexpr std::uint16_t kCanMtiInitComplete = 0x100;
constexpr std::uint16_t kCanMtiInitCompleteSimple = 0x101;
constexpr std::uint16_t kCanMtiVerified = 0x170;
constexpr std::uint16_t kCanMtiVerifiedSimple = 0x171;

bool is_verified(const Message& m, NodeId id) {
    return (m.mti == Mti::kVerifiedNodeId || m.mti == Mti::kVerifiedNodeIdSimple) &&
           NodeId::from_bytes(m.payload) == id;
}

bool is_short_form(std::span<const std::uint8_t> payload) {
    return payload.size() >= 2 && payload[1] < 0x80 && (payload[1] & 0x03) != 0;
}

bool is_reply(const memory::Message& m) {
    return std::holds_alternative<memory::ReadReply>(m) ||
           std::holds_alternative<memory::ReadReplyFail>(m) ||
           std::holds_alternative<memory::WriteReply>(m) ||
           std::holds_alternative<memory::WriteReplyFail>(m) ||
           std::holds_alternative<memory::ReadStreamReply>(m) ||
           std::holds_alternative<memory::ReadStreamReplyFail>(m) ||
           std::holds_alternative<memory::WriteStreamReply>(m) ||
           std::holds_alternative<memory::WriteStreamReplyFail>(m) ||
           std::holds_alternative<memory::ConfigOptionsReply>(m) ||
           std::holds_alternative<memory::SpaceInfoReply>(m) ||
           std::holds_alternative<memory::SpaceInfoNotPresent>(m) ||
           std::holds_alternative<memory::LockReply>(m) ||
           std::holds_alternative<memory::UniqueIdReply>(m);
}

// Commands after which the node owes no reply datagram.
bool expects_no_reply(std::span<const std::uint8_t> payload) {
    if (payload.size() < 2 || payload[0] != memory::kDatagramType) return true;
    const std::uint8_t c = payload[1];
    return c == 0xA0 || c == 0xA1 || c == 0xA8 || c == 0xA9 || c == 0xAA || c == 0xAB;
}

bool is_write_command(std::span<const std::uint8_t> payload) {
    return payload.size() >= 2 && (payload[1] & 0xC0) == 0x00;
}

// The write a memory-config payload asks for; nullopt for every other command. A write command
// that does not decode is planned as a stream write: its extent is unknown, so no gate lets it
// out unbacked.
std::optional<PlannedWrite> planned_write(NodeId node, std::span<const std::uint8_t> payload) {
    if (payload.empty() || payload[0] != memory::kDatagramType || !is_write_command(payload))
        return std::nullopt;
    PlannedWrite w;
    w.node = node;
    const memory::DecodeResult d = memory::decode(payload);
    if (const auto* m = std::get_if<memory::Write>(&d.message); d.ok() && m) {
        w.space = memory::to_u8(m->space);
        w.address = m->address;
        w.data = m->data;
    } else if (const auto* u = std::get_if<memory::WriteUnderMask>(&d.message); d.ok() && u) {
        w.space = memory::to_u8(u->space);
        w.address = u->address;
        for (const memory::MaskedByte& b : u->bytes) {
            w.mask.push_back(b.mask);
            w.data.push_back(b.value);
        }
    } else {
        if (const auto* st = std::get_if<memory::WriteStream>(&d.message); d.ok() && st) {
            w.space = memory::to_u8(st->space);
            w.address = st->address;
        }
        w.stream = true;
    }
    return w;
}

WriteOutcome outcome_of_write(const MemResult& r) {
    if (r.ok) return WriteOutcome::kAccepted;
    if (r.timed_out) return WriteOutcome::kNoAnswer;
    return WriteOutcome::kRefused;
}

// How long after Update Complete a restart of the node counts as its doing (it may reset then).
constexpr Duration kUpdateCompleteRestart = std::chrono::seconds(3);

// Fills ok, data and error from a reply datagram.
void take_reply(const memory::Message& reply, MemResult& result) {
    std::visit(
        [&](const auto& m) {
            using T = std::decay_t<decltype(m)>;
            if constexpr (std::is_same_v<T, memory::ReadReply>) {
                result.ok = true;
                result.data = m.data;
            } else if constexpr (std::is_same_v<T, memory::ReadReplyFail> ||
                                 std::is_same_v<T, memory::WriteReplyFail> ||
                                 std::is_same_v<T, memory::ReadStreamReplyFail> ||
                                 std::is_same_v<T, memory::WriteStreamReplyFail>) {
                result.error = memory::to_u16(m.error);
            } else {
                result.ok = true;
            }
        },
        reply);
}

// The first memory-configuration reply datagram from one alias among the recorded messages,
// each scan resuming where the previous one stopped.
struct ReplyScan {
    std::uint16_t alias = 0;
    std::size_t scanned = 0;
    std::optional<std::size_t> index;
    std::optional<memory::Message> decoded;

    template <class Events>
    bool found(const Events& messages) {
        for (; !index && scanned < messages.size(); ++scanned) {
            const Message& m = messages[scanned].message;
            if (m.mti != Mti::kDatagram || m.source.alias != alias) continue;
            auto d = memory::decode(m.payload);
            if (!d.ok() || !is_reply(d.message)) continue;
            index = scanned;
            decoded = d.message;
        }
        return index.has_value();
    }
};

}  // namespace

Session::Session(Link& link) : link_(link) {
    NodeStack& stack = link_.stack();
    stack.set_message_handler([this](const Message& msg) {
        if (messages_.size() < kMaxMessages) messages_.push_back({msg, link_.now(), ++seq_});
        return true;  // a tool answers nothing it did not ask for
    });
    stack.set_datagram_handler([this](const ReceivedDatagram& d) {
        Message msg;
        msg.mti = Mti::kDatagram;
        msg.source = NodeHandle{NodeId{}, d.source_alias};
        msg.destination = NodeHandle{link_.stack().node_id(), d.dest_alias};
        msg.payload = d.payload;
        if (messages_.size() < kMaxMessages) messages_.push_back({msg, link_.now(), ++seq_});
        link_.stack().accept_datagram(d.source_alias);
    });
    stack.set_outcome_handler([this](const DatagramOutcome& o) { on_outcome(o); });
    stack.set_stream_handler([this](const StreamEvent& e) {
        if (stream_events_.size() < kMaxMessages) stream_events_.push_back(e);
    });
    link_.set_frame_observer([this](const CanFrame& f, TimePoint at) {
        if (frames_.size() < kMaxFrames) frames_.push_back(f);
        if (injecting_ || (f.extended && can::source_alias(f.id) == link_.stack().alias()))
            queue_on_wire(f, at);
        if (!injecting_) observe(f, at);
    });
}

void Session::queue_on_wire(const CanFrame& f, TimePoint at) {
    // Each of our frames occupies the bus for its worst-case length after the frames ahead of
    // it: on a real or paced segment, an answer cannot come before they are through.
    const std::uint32_t bitrate = link_.bus_bitrate();
    if (bitrate == 0) return;
    backlog_end_ = std::max(backlog_end_, at) + can_frame_time(f.len, bitrate);
}

void Session::backlog_through() {
    // The node answered the last frame we queued, so every frame before it has left the bus
    // (frames from one sender keep their order): no modelled backlog is left to wait out. On a
    // TCP link, whose bus speed is only assumed, this is what ends a wait after a burst.
    backlog_end_ = std::min(backlog_end_, link_.now());
}

Duration Session::backlog() {
    const TimePoint now = link_.now();
    return backlog_end_ > now ? backlog_end_ - now : Duration::zero();
}

bool Session::run_until(const std::function<bool()>& pred, Duration window) {
    return link_.run_until(pred, window + backlog());
}

void Session::inject(const CanFrame& frame) {
    injecting_ = true;
    link_.send_frame(frame);
    injecting_ = false;
}

NodeTrack* Session::track_for(NodeId id) {
    auto it = tracks_.find(id);
    if (it != tracks_.end()) return &it->second;
    if (tracks_.size() >= kMaxNodes) return nullptr;
    return &tracks_[id];
}

void Session::set_alias(NodeId id, std::uint16_t alias) {
    NodeTrack* t = track_for(id);
    if (!t) return;
    if (t->alias != 0 && t->alias != alias) {
        auto old = aliases_.find(t->alias);
        if (old != aliases_.end() && old->second.owner == id) old->second.owner.reset();
    }
    AliasState& a = aliases_[alias];
    // The alias moved to another node: the previous owner no longer has it.
    if (a.owner && *a.owner != id) {
        auto prev = tracks_.find(*a.owner);
        if (prev != tracks_.end() && prev->second.alias == alias) prev->second.alias = 0;
    }
    a.owner = id;
    t->alias = alias;
}

void Session::observe_control(const CanFrame& f, TimePoint at) {
    const std::uint16_t src = can::source_alias(f.id);
    switch (can::classify_control(f.id)) {
        case can::ControlFrame::kCid7:
        case can::ControlFrame::kCid6:
        case can::ControlFrame::kCid5:
        case can::ControlFrame::kCid4: {
            const int n = 7 - static_cast<int>(can::classify_control(f.id)) +
                          static_cast<int>(can::ControlFrame::kCid7);
            AliasState& a = aliases_[src];
            const std::uint64_t bits = (f.id >> 12) & 0xFFF;
            const int shift = (n - 4) * 12;
            a.cid_bits = (a.cid_bits & ~(std::uint64_t{0xFFF} << shift)) | bits << shift;
            a.cid_parts |= static_cast<std::uint8_t>(1u << (n - 4));
            break;
        }
        case can::ControlFrame::kRid: {
            // Only a RID after all four CIDs of one node ID ends a reservation: a RID that
            // defends an alias (against a probe of ours or another tool's) follows one CID.
            AliasState& a = aliases_[src];
            if (a.cid_parts == 0x0F) a.rid_pending = NodeId(a.cid_bits);
            a.cid_parts = 0;
            break;
        }
        case can::ControlFrame::kAmd: {
            if (f.len != 6) break;
            auto id = NodeId::from_bytes({f.data.data(), 6});
            if (!id) break;
            AliasState& a = aliases_[src];
            const bool reserved = a.rid_pending && *a.rid_pending == *id;
            a.rid_pending.reset();
            a.cid_parts = 0;
            set_alias(*id, src);
            // A restart that Update Complete may cause (MemoryConfigurationS §4.23) is allowed.
            const auto excused = excused_until_.find(*id);
            const bool allowed = excused != excused_until_.end() && at <= excused->second;
            if (NodeTrack* t = track_for(*id); t && reserved && !allowed) ++t->reservations;
            break;
        }
        default:
            break;
    }
}

void Session::observe(const CanFrame& f, TimePoint at) {
    if (!can::is_openlcb_frame(f)) return;
    const std::uint16_t src = can::source_alias(f.id);
    if (can::is_control(f.id)) {
        observe_control(f, at);
    } else if (can::frame_format(f.id) == can::FrameFormat::kGlobalAddressed && f.len == 6) {
        const std::uint16_t mti = can::can_mti(f.id);
        const bool init = mti == kCanMtiInitComplete || mti == kCanMtiInitCompleteSimple;
        if (init || mti == kCanMtiVerified || mti == kCanMtiVerifiedSimple) {
            if (auto id = NodeId::from_bytes({f.data.data(), 6})) {
                set_alias(*id, src);
                if (NodeTrack* t = track_for(*id); t && init) ++t->initializations;
            }
        }
    }
    auto it = aliases_.find(src);
    if (it == aliases_.end() || !it->second.owner) return;
    auto t = tracks_.find(*it->second.owner);
    if (t != tracks_.end() && t->second.alias == src) t->second.last_heard = at;
}

NodeTrack Session::track(NodeId id) const {
    auto it = tracks_.find(id);
    return it == tracks_.end() ? NodeTrack{} : it->second;
}

void Session::excuse_reservations(NodeId id, std::uint32_t n) {
    auto it = tracks_.find(id);
    if (it != tracks_.end()) it->second.reservations -= std::min(n, it->second.reservations);
}

std::uint16_t Session::alias_of(const NodeInfo& node) const {
    auto it = tracks_.find(node.id);
    return it != tracks_.end() && it->second.alias != 0 ? it->second.alias : node.alias;
}

bool Session::ping(const NodeInfo& node, Duration timeout) {
    if (round_trip(node, timeout / 2)) return true;
    // The alias may have changed unseen: the global form reaches the node on any alias.
    return find_node(node.id, timeout - timeout / 2).has_value();
}

std::uint64_t Session::reads(NodeId node, std::uint8_t space) const {
    auto it = reads_.find({node.value(), space});
    return it == reads_.end() ? 0 : it->second;
}

void Session::record_read(const NodeInfo& node, std::uint8_t space, std::uint32_t address,
                          std::uint8_t count, const MemResult& r) {
    if (r.timed_out) return;
    // A rejected read (an unknown space) says nothing about reply lengths.
    if (!r.rejected) ++reads_[{node.id.value(), space}];
    const bool data = r.ok && !r.data.empty();
    const bool end =
        (r.ok && r.data.empty()) ||
        (!r.ok && !r.rejected && r.error == base::to_u16(base::ErrorCode::kOutOfBounds));
    if (data || end) {
        // A short reply that ended here: this read tells whether the space really ended.
        auto [first, last] = open_short_reads_.equal_range({node.id.value(), space, address});
        for (auto it = first; it != last; ++it) {
            short_reads_[it->second].continued = data;
            short_reads_[it->second].at_end = end;
        }
        open_short_reads_.erase(first, last);
    }
    const std::size_t got = std::min<std::size_t>(r.data.size(), count);
    if (!r.ok || got >= count || short_reads_.size() >= kMaxShortReads) return;
    short_reads_.push_back({node.id, space, address, count, got, false, false});
    open_short_reads_.emplace(
        ReadKey{node.id.value(), space, address + static_cast<std::uint32_t>(got)},
        short_reads_.size() - 1);
}

bool Session::start(Duration timeout) {
    return link_.run_until([this] { return link_.stack().initialized(); }, timeout);
}

std::vector<NodeInfo> Session::nodes_seen() const {
    std::vector<NodeInfo> out;
    const NodeId me = link_.stack().node_id();
    for (const auto& [id, t] : tracks_) {
        if (id != me && t.alias != 0) out.push_back({id, t.alias});
    }
    return out;  // a std::map: already sorted by node ID
}

std::optional<NodeId> Session::other_tool() const {
    for (const auto& [id, t] : tracks_)
        if (t.alias != 0 && is_tool_id(id) && id != link_.stack().node_id()) return id;
    return std::nullopt;
}

std::size_t Session::nodes_seen_count() const {
    const NodeId me = link_.stack().node_id();
    return static_cast<std::size_t>(
        std::count_if(tracks_.begin(), tracks_.end(),
                      [&](const auto& t) { return t.first != me && t.second.alias != 0; }));
}

std::vector<NodeInfo> Session::discover(Duration max, Duration quiet) {
    Message verify;
    verify.mti = Mti::kVerifyNodeIdGlobal;
    const TimePoint deadline = link_.now() + max;
    send(verify);
    // Every Verified Node ID, Initialization Complete and AMD counts (the session tracks them).
    // Done when no new node appeared for `quiet`; with none at all, ask again until `max`: on a
    // busy machine or a big segment the first answers can take longer than any quiet period.
    std::size_t known = nodes_seen_count();
    while (link_.now() < deadline) {
        const Duration left = deadline - link_.now();
        const bool grew =
            link_.run_until([&] { return nodes_seen_count() != known; }, std::min(quiet, left));
        if (grew) {
            known = nodes_seen_count();
            continue;
        }
        if (known != 0) break;
        send(verify);
    }
    return nodes_seen();
}

std::optional<NodeInfo> Session::find_node(NodeId id, Duration timeout) {
    Message msg;
    msg.mti = Mti::kVerifyNodeIdGlobal;
    auto bytes = id.to_bytes();
    msg.payload.assign(bytes.begin(), bytes.end());
    const std::size_t mark = messages_.size();
    const std::uint32_t inits_before = track(id).initializations;
    std::optional<NodeInfo> found;
    auto answered = [&] {
        for (std::size_t i = mark; i < messages_.size(); ++i) {
            if (is_verified(messages_[i].message, id)) {
                found = NodeInfo{id, messages_[i].message.source.alias};
                return true;
            }
        }
        // A node finishing its alias reservation announces itself instead of answering.
        if (const NodeTrack t = track(id);
            t.alias != 0 && t.initializations != 0 && t.initializations != inits_before) {
            found = NodeInfo{id, t.alias};
            return true;
        }
        return false;
    };
    // Asked again every half second: a node still reserving its alias (just powered up, or a
    // TCP-server node logging in when we connect) ignores a Verify sent before it is Permitted.
    const TimePoint deadline = link_.now() + timeout;
    while (link_.now() < deadline) {
        send(msg);
        const Duration left = deadline - link_.now();
        if (link_.run_until(answered, std::min<Duration>(left, std::chrono::milliseconds(500))))
            return found;
    }
    return found;
}

std::optional<Duration> Session::round_trip(const NodeInfo& node, Duration timeout) {
    const std::size_t mark = messages_.size();
    std::size_t scanned = mark;
    auto answered = [&] {
        for (; scanned < messages_.size(); ++scanned)
            if (is_verified(messages_[scanned].message, node.id)) return true;
        return false;
    };
    Message addressed;
    addressed.mti = Mti::kVerifyNodeIdAddressed;
    addressed.destination = NodeHandle{node.id, alias_of(node)};
    const TimePoint sent = link_.now();
    send(addressed);
    if (!run_until(answered, timeout)) return std::nullopt;
    backlog_through();
    return link_.now() - sent;
}

SendStatus Session::send(Message msg) {
    return link_.stack().send_message(std::move(msg));
}

std::vector<Message> Session::collect(const std::function<bool(const Message&)>& match,
                                      Duration window) {
    const std::size_t mark = messages_.size();
    wait(window);
    std::vector<Message> out;
    for (std::size_t i = mark; i < messages_.size(); ++i) {
        if (!match || match(messages_[i].message)) out.push_back(messages_[i].message);
    }
    return out;
}

std::optional<Message> Session::wait_for(const std::function<bool(const Message&)>& match,
                                         Duration timeout) {
    const std::size_t mark = messages_.size();
    std::size_t scanned = mark;
    std::optional<Message> found;
    run_until(
        [&] {
            for (; scanned < messages_.size(); ++scanned) {
                if (!match || match(messages_[scanned].message)) {
                    found = messages_[scanned].message;
                    return true;
                }
            }
            return false;
        },
        timeout);
    return found;
}

std::vector<CanFrame> Session::frames_since(std::size_t mark) const {
    if (mark >= frames_.size()) return {};
    return {frames_.begin() + static_cast<std::ptrdiff_t>(mark), frames_.end()};
}

std::vector<std::pair<std::uint16_t, std::optional<NodeId>>> Session::datagram_senders_to(
    std::uint16_t to) const {
    std::vector<std::pair<std::uint16_t, std::optional<NodeId>>> out;
    const std::uint16_t me = link_.stack().alias();
    for (const CanFrame& f : frames_) {
        if (!can::is_openlcb_frame(f) || can::is_control(f.id) ||
            !can::is_datagram_format(can::frame_format(f.id)) || can::dest_alias(f.id) != to)
            continue;
        const std::uint16_t from = can::source_alias(f.id);
        if (from == me ||
            std::any_of(out.begin(), out.end(), [&](const auto& s) { return s.first == from; }))
            continue;
        const auto a = aliases_.find(from);
        out.emplace_back(from, a == aliases_.end() ? std::nullopt : a->second.owner);
    }
    return out;
}

std::vector<ReceivedMessage> Session::messages_since(std::size_t mark) const {
    std::vector<ReceivedMessage> out;
    for (std::size_t i = mark; i < messages_.size(); ++i) {
        out.push_back({messages_[i].message, messages_[i].at});
    }
    return out;
}

std::optional<ProtocolSet> Session::protocol_support(const NodeInfo& node) {
    Message msg;
    msg.mti = Mti::kProtocolSupportInquiry;
    const std::uint16_t alias = alias_of(node);
    msg.destination = NodeHandle{node.id, alias};
    auto reply = [&](const Message& m) {
        return m.mti == Mti::kProtocolSupportReply && m.source.alias == alias;
    };
    const std::size_t mark = messages_.size();
    if (send(msg) != SendStatus::kSent) return std::nullopt;
    std::size_t scanned = mark;
    std::optional<ProtocolSet> out;
    run_until(
        [&] {
            for (; scanned < messages_.size(); ++scanned) {
                if (reply(messages_[scanned].message)) {
                    out = ProtocolSet::decode(messages_[scanned].message.payload);
                    return true;
                }
            }
            return false;
        },
        answer_timeout_);
    return out;
}

std::optional<std::vector<std::uint8_t>> Session::snip_payload(const NodeInfo& node) {
    Message msg;
    msg.mti = Mti::kSnipRequest;
    const std::uint16_t alias = alias_of(node);
    msg.destination = NodeHandle{node.id, alias};
    const std::size_t mark = messages_.size();
    if (send(msg) != SendStatus::kSent) return std::nullopt;
    std::vector<std::uint8_t> bytes;
    bool any = false;
    std::size_t scanned = mark;
    // Legacy nodes send each frame as its own message: concatenate until six NULs are in.
    run_until(
        [&] {
            for (; scanned < messages_.size(); ++scanned) {
                const Message& m = messages_[scanned].message;
                if (m.mti != Mti::kSnipReply || m.source.alias != alias) continue;
                any = true;
                bytes.insert(bytes.end(), m.payload.begin(), m.payload.end());
                if (bytes.size() > memory::kSnipMaxPayload * 2) return true;
            }
            return any && memory::is_complete_snip(bytes);
        },
        answer_timeout_);
    if (!any) return std::nullopt;
    return bytes;
}

MemResult Session::exchange(const NodeInfo& node, std::span<const std::uint8_t> payload,
                            bool always_reply, memory::Message* reply) {
    // Every write goes through the ledger first: recorded, and sent only when its gate (the
    // safety backup) has what it may change.
    std::optional<PlannedWrite> write = planned_write(node.id, payload);
    if (!write) return send_exchange(node, payload, always_reply, reply);
    // A restart after this write is not the earlier Update Complete's doing.
    excused_until_.erase(node.id);
    std::string why;
    const std::optional<std::size_t> entry = ledger_.open(std::move(*write), why);
    if (!entry) {
        MemResult kept;
        kept.not_sent = why.empty() ? std::string("kept back") : why;
        return kept;
    }
    MemResult result = send_exchange(node, payload, always_reply, reply);
    ledger_.close(*entry, outcome_of_write(result));
    return result;
}

namespace {

// Reset/Reboot and Factory Reset: the node may restart before its acknowledgement goes out.
bool restarts_node(std::span<const std::uint8_t> payload) {
    using memory::Command;
    return payload.size() >= 2 && payload[0] == memory::kDatagramType &&
           (payload[1] == memory::to_u8(Command::kResetReboot) ||
            payload[1] == memory::to_u8(Command::kFactoryReset));
}

}  // namespace

MemResult Session::send_exchange(const NodeInfo& node, std::span<const std::uint8_t> payload,
                                 bool always_reply, memory::Message* reply) {
    MemResult result;
    const bool request_short = is_short_form(payload);
    const std::uint16_t alias = alias_of(node);
    auto id = send_datagram_after(alias, payload);
    const std::size_t mark = messages_.size();
    const TimePoint sent_at = link_.now();
    if (!id) {
        result.error = base::to_u16(base::ErrorCode::kTemporary);
        result.rejected = true;
        return result;
    }
    ReplyScan scan{alias, mark, std::nullopt, std::nullopt};
    auto find_reply = [&] { return scan.found(messages_); };
    // The ack may sit behind an earlier unacknowledged datagram to the same node (sender timeout).
    const Duration ack_wait =
        link_.stack().config().datagram_sender.ack_timeout * 2 + std::chrono::milliseconds(500);
    // A transport that goes away mid-exchange ends the wait at once: no reply can come.
    const std::uint64_t losses = link_.losses();
    auto lost = [&] { return link_.losses() != losses; };
    // A node that restarts without acknowledging a command (a Reset performed at once,
    // OpenLcbCLib) may come back on another alias, where nothing aborts the datagram sent to the
    // old one. Only commands that want no reply end there: a reply arriving after an early end
    // would be taken for the next request's.
    const std::uint32_t inits = track(node.id).initializations;
    auto restarted = [&] { return !always_reply && came_back_elsewhere(node.id, inits, alias); };
    // A node noted as never acknowledging sends no OK to wait for: only its reply or a reject.
    const bool never_acks = track(node.id).never_acks;
    run_until([&] { return outcome_of(*id) != nullptr || find_reply() || lost() || restarted(); },
              never_acks && !always_reply ? answer_timeout_ : ack_wait);
    if (never_acks && !always_reply && !scan.index && !lost() && !restarted() &&
        no_answer_settled(*id))
        return unacknowledged_result();
    const OutcomeRecord* oc = outcome_of(*id);
    if (oc && oc->outcome.attempts > 1) result.temporary_rejects = oc->outcome.attempts - 1;
    if (!scan.index && ended_unanswered(oc, payload, restarted(), result)) return result;
    if (oc && oc->outcome.status == DatagramOutcome::Status::kAccepted) {
        result.reply_pending = datagram::is_reply_pending(oc->outcome.flags);
        result.reply_timeout_exponent = datagram::timeout_exponent(oc->outcome.flags);
        const bool reply_expected = always_reply || result.reply_pending;
        if (!reply_expected && !find_reply()) {
            result.ok = true;
            return result;
        }
    }
    if (!scan.index && !lost()) {
        run_until([&] { return find_reply() || lost(); }, reply_timeout_);
    }
    if (!scan.index) {
        result.timed_out = true;
        result.error = base::to_u16(base::ErrorCode::kTimeout);
        // Accepted and then silent differs from never answered (memory.unknown-command).
        result.datagram_ok_seen = oc && oc->outcome.status == DatagramOutcome::Status::kAccepted;
        return result;
    }
    replied(*id, node.id);
    const Event& ev = messages_[*scan.index];
    time_reply(outcome_of(*id), ev, sent_at, result);
    result.reply_in_request_form = is_short_form(ev.message.payload) == request_short;
    if (reply) *reply = *scan.decoded;
    take_reply(*scan.decoded, result);
    return result;
}

void Session::time_reply(const OutcomeRecord* oc, const Event& reply, TimePoint sent_at,
                         MemResult& result) const {
    result.datagram_ok_seen =
        oc && oc->outcome.status == DatagramOutcome::Status::kAccepted && oc->seq < reply.seq;
    if (oc && oc->outcome.attempts > 1) result.temporary_rejects = oc->outcome.attempts - 1;
    result.reply_latency = reply.at - sent_at;
}

MemResult Session::unacknowledged_result() {
    MemResult result;
    result.unacknowledged = true;
    result.timed_out = true;
    result.error = base::to_u16(base::ErrorCode::kTimeout);
    return result;
}

bool Session::ended_unanswered(const OutcomeRecord* oc, std::span<const std::uint8_t> payload,
                               bool back_elsewhere, MemResult& result) const {
    if (oc && oc->outcome.status == DatagramOutcome::Status::kRejected) {
        result.rejected = true;
        result.error = oc->outcome.error_code;
        return true;
    }
    // The node came back on another alias before acknowledging, or ended a Reset's datagram by
    // restarting: its new run answers nothing the old one was sent. (Other requests ended as
    // kAborted by a re-initialization on the same alias may still be answered: that wait stays.)
    const bool aborted = oc && oc->outcome.status == DatagramOutcome::Status::kAborted;
    if (back_elsewhere || (aborted && restarts_node(payload))) {
        result.restarted = true;
        return true;
    }
    return false;
}

bool Session::came_back_elsewhere(NodeId id, std::uint32_t initializations,
                                  std::uint16_t alias) const {
    const NodeTrack t = track(id);
    return t.initializations != initializations && t.alias != alias;
}

void Session::on_outcome(const DatagramOutcome& o) {
    outcomes_[o.id] = OutcomeRecord{o, link_.now(), ++seq_};
    auto it = replied_unacked_.find(o.id);
    if (it == replied_unacked_.end()) return;
    // Its reply came and its OK never did: every later datagram to this node would wait the
    // whole timeout behind the one before (DatagramTransportS: one outstanding per destination).
    if (o.status == DatagramOutcome::Status::kTimedOut) {
        if (NodeTrack* t = track_for(it->second)) {
            t->never_acks = true;
            ++t->unacknowledged;
        }
    }
    replied_unacked_.erase(it);
}

std::optional<std::uint32_t> Session::send_datagram_after(std::uint16_t alias,
                                                          std::span<const std::uint8_t> payload) {
    // Queued behind an unanswered one, a datagram would leave up to the ack timeout later than
    // asked, and its reply would look that slow.
    if (auto last = last_datagram_.find(alias); last != last_datagram_.end()) {
        const std::uint32_t before = last->second;
        const std::uint64_t losses = link_.losses();
        link_.run_until(
            [&] { return outcome_of(before) || link_.losses() != losses; },
            link_.stack().config().datagram_sender.ack_timeout + std::chrono::milliseconds(500));
    }
    auto id = link_.stack().send_datagram(alias, payload, link_.now());
    if (id) last_datagram_[alias] = *id;
    return id;
}

bool Session::no_answer_settled(std::uint32_t datagram_id) {
    if (const OutcomeRecord* oc = outcome_of(datagram_id))
        return oc->outcome.status == DatagramOutcome::Status::kTimedOut;
    return link_.stack().settle_datagram(datagram_id, link_.now());
}

void Session::replied(std::uint32_t datagram_id, NodeId node) {
    if (outcome_of(datagram_id) || replied_unacked_.contains(datagram_id)) return;
    NodeTrack* t = track_for(node);
    if (t && t->never_acks) {
        if (link_.stack().settle_datagram(datagram_id, link_.now())) ++t->unacknowledged;
        return;
    }
    replied_unacked_[datagram_id] = node;
}

const Session::OutcomeRecord* Session::outcome_of(std::uint32_t datagram_id) const {
    auto it = outcomes_.find(datagram_id);
    return it == outcomes_.end() ? nullptr : &it->second;
}

MemResult Session::read(const NodeInfo& node, memory::Space space, std::uint32_t address,
                        std::uint8_t count, memory::SpaceForm form) {
    const auto payload = memory::encode(memory::Read{space, address, count, form});
    MemResult r = exchange(node, payload, true, nullptr);
    record_read(node, memory::to_u8(space), address, count, r);
    return r;
}

MemResult Session::write(const NodeInfo& node, memory::Space space, std::uint32_t address,
                         std::span<const std::uint8_t> data, memory::SpaceForm form) {
    memory::Write w{space, address, {data.begin(), data.end()}, form};
    const auto payload = memory::encode(w);
    return exchange(node, payload, false, nullptr);
}

MemResult Session::command(const NodeInfo& node, std::span<const std::uint8_t> payload,
                           memory::Message* reply) {
    if (payload.size() >= 2 && payload[0] == memory::kDatagramType &&
        payload[1] == memory::to_u8(memory::Command::kUpdateComplete))
        excused_until_[node.id] = link_.now() + kUpdateCompleteRestart + backlog();
    const bool always = !expects_no_reply(payload) && !is_write_command(payload);
    return exchange(node, payload, always, reply);
}

MemResult Session::read_range(const NodeInfo& node, memory::Space space, std::uint32_t address,
                              std::uint32_t length, bool stop_at_nul,
                              const std::function<void(std::size_t)>& progress) {
    MemResult total;
    total.ok = true;
    total.datagram_ok_seen = true;
    total.reply_pending = true;
    std::uint32_t done = 0;
    // Every pass adds at least one byte or ends the loop, so `length` passes are enough.
    for (std::uint64_t pass = 0; done < length && pass < length; ++pass) {
        const auto count = static_cast<std::uint8_t>(std::min<std::uint32_t>(length - done, 64));
        MemResult r = read(node, space, address + done, count);
        total.temporary_rejects += r.temporary_rejects;
        total.reply_latency = std::max(total.reply_latency, r.reply_latency);
        if (!r.ok) {
            if (!r.rejected && !r.timed_out &&
                r.error == base::to_u16(base::ErrorCode::kOutOfBounds))
                break;
            total.ok = false;
            total.error = r.error;
            total.rejected = r.rejected;
            total.timed_out = r.timed_out;
            break;
        }
        total.datagram_ok_seen = total.datagram_ok_seen && r.datagram_ok_seen;
        total.reply_pending = total.reply_pending && r.reply_pending;
        total.reply_timeout_exponent =
            std::max(total.reply_timeout_exponent, r.reply_timeout_exponent);
        total.reply_in_request_form = total.reply_in_request_form && r.reply_in_request_form;
        if (r.data.size() > count) r.data.resize(count);  // never trust the node's length
        if (r.data.empty()) break;                        // the end of the space
        bool nul = false;
        if (stop_at_nul) {
            auto it = std::find(r.data.begin(), r.data.end(), std::uint8_t{0});
            if (it != r.data.end()) {
                r.data.erase(it + 1, r.data.end());
                nul = true;
            }
        }
        total.data.insert(total.data.end(), r.data.begin(), r.data.end());
        done += static_cast<std::uint32_t>(r.data.size());
        if (progress) progress(total.data.size());
        if (nul) break;
    }
    return total;
}

}  // namespace olcb::conform
