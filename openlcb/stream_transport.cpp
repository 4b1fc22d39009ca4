#include "openlcb/stream_transport.hpp"

#include <algorithm>
#include <utility>

#include "openlcb/mti.hpp"

namespace olcb {
namespace {

// Ended streams kept for info() before the oldest are forgotten.
constexpr std::size_t kKeptClosed = 32;

std::uint16_t u16_at(const std::vector<std::uint8_t>& p, std::size_t at) {
    return p.size() >= at + 2 ? static_cast<std::uint16_t>(p[at] << 8 | p[at + 1]) : 0;
}

}  // namespace

bool StreamTransport::handles(Mti mti) {
    switch (mti) {
        case Mti::kStreamInitiateRequest:
        case Mti::kStreamInitiateReply:
        case Mti::kStreamDataSend:
        case Mti::kStreamDataProceed:
        case Mti::kStreamDataComplete:
        case Mti::kOptionalInteractionRejected:
        case Mti::kTerminateDueToError:
            return true;
        default:
            return false;
    }
}

bool StreamTransport::on_message(const Message& msg, TimePoint now) {
    now_ = now;
    switch (msg.mti) {
        case Mti::kStreamInitiateRequest:
            on_initiate_request(msg, now);
            return true;
        case Mti::kStreamInitiateReply:
            return on_initiate_reply(msg, now);
        case Mti::kStreamDataSend:
            return on_data(msg, now);
        case Mti::kStreamDataProceed:
            return on_proceed(msg, now);
        case Mti::kStreamDataComplete:
            return on_complete(msg, now);
        case Mti::kOptionalInteractionRejected:
        case Mti::kTerminateDueToError:
            return on_reject(msg);
        default:
            return false;
    }
}

void StreamTransport::reset() {
    streams_.clear();
    expected_.clear();
    control_.clear();
    events_.clear();
}

// ---------------- source ----------------

std::optional<std::uint32_t> StreamTransport::open(NodeHandle dest, std::uint16_t buffer,
                                                   std::uint8_t suggested_dest_id, TimePoint now) {
    now_ = now;
    if (open_streams() >= config_.max_streams) return std::nullopt;
    const std::uint32_t id = next_id_++;
    Stream s;
    s.info.outgoing = true;
    s.info.remote = dest;
    s.info.source_id = free_source_id(dest.alias);
    s.info.dest_id = suggested_dest_id;
    s.info.proposed = buffer == 0 ? config_.source_buffer : buffer;
    s.deadline = now + config_.initiate_timeout;
    stream::InitiateRequest req;
    req.max_buffer = s.info.proposed;
    req.source_id = s.info.source_id;
    req.suggested_dest_id = suggested_dest_id;
    send(Mti::kStreamInitiateRequest, dest, stream::encode(req));
    streams_.emplace(id, std::move(s));
    return id;
}

bool StreamTransport::write(std::uint32_t id, std::span<const std::uint8_t> data) {
    auto it = streams_.find(id);
    if (it == streams_.end() || !it->second.info.outgoing || it->second.state == State::kClosed ||
        it->second.closing) {
        return false;
    }
    it->second.queue.insert(it->second.queue.end(), data.begin(), data.end());
    return true;
}

bool StreamTransport::close(std::uint32_t id) {
    auto it = streams_.find(id);
    if (it == streams_.end() || !it->second.info.outgoing || it->second.state == State::kClosed) {
        return false;
    }
    it->second.closing = true;
    maybe_complete(it->second);
    return true;
}

void StreamTransport::maybe_complete(Stream& s) {
    if (s.state != State::kOpen || !s.closing || !s.queue.empty()) return;
    s.state = State::kClosed;
    s.info.open = false;
    s.deadline = {};
    send(Mti::kStreamDataComplete, s.info.remote,
         stream::encode(stream::DataComplete{s.info.source_id, s.info.dest_id,
                                             static_cast<std::uint32_t>(s.info.bytes)}));
    for (auto& [id, other] : streams_) {
        if (&other == &s) emit(StreamEvent::Kind::kCompleted, id, s);
    }
}

bool StreamTransport::ready_to_send(const Stream& s) const {
    return s.info.outgoing && s.state == State::kOpen && !s.queue.empty() && s.window > 0;
}

std::uint64_t StreamTransport::grant(std::uint16_t buffer) const {
    return window_policy_ ? std::min(window_policy_(buffer), kUnlimitedWindow) : buffer;
}

std::optional<Message> StreamTransport::next_data() {
    // Round robin over the streams, one frame each, so concurrent streams share the bus.
    auto it = streams_.upper_bound(round_robin_);
    for (std::size_t n = 0; n < streams_.size(); ++n, ++it) {
        if (it == streams_.end()) it = streams_.begin();
        Stream& s = it->second;
        if (!ready_to_send(s)) continue;
        round_robin_ = it->first;
        std::size_t len = std::min(stream::kMaxDataPerFrame, s.queue.size());
        len = static_cast<std::size_t>(std::min<std::uint64_t>(len, s.window));
        std::vector<std::uint8_t> payload{s.info.dest_id};
        payload.insert(payload.end(), s.queue.begin(),
                       s.queue.begin() + static_cast<std::ptrdiff_t>(len));
        s.queue.erase(s.queue.begin(), s.queue.begin() + static_cast<std::ptrdiff_t>(len));
        s.window -= std::min<std::uint64_t>(s.window, len);
        s.info.bytes += len;
        ++s.info.data_frames;
        Message m{Mti::kStreamDataSend, {}, s.info.remote, std::move(payload)};
        if (s.window == 0 && !s.queue.empty()) {
            s.deadline = now_ + config_.proceed_timeout;
        }
        maybe_complete(s);
        return m;
    }
    return std::nullopt;
}

bool StreamTransport::on_initiate_reply(const Message& msg, TimePoint now) {
    const auto reply = stream::decode_initiate_reply(msg.payload);
    if (!reply) return false;
    Stream* s = find_outgoing(msg.source.alias, reply->source_id);
    if (s == nullptr || s->state != State::kInitiating) return false;
    s->deadline = {};
    std::uint32_t id = 0;
    for (const auto& [key, other] : streams_) {
        if (&other == s) id = key;
    }
    if (!stream::is_accept(reply->code) || reply->max_buffer == 0) {
        s->state = State::kClosed;
        emit(StreamEvent::Kind::kRejected, id, *s);
        events_.back().code = stream::is_accept(reply->code) ? stream::kRejectInvalid : reply->code;
        return true;
    }
    s->state = State::kOpen;
    s->info.open = true;
    s->info.dest_id = reply->dest_id;
    // A sink granting more than proposed gets only what we proposed.
    s->info.buffer = std::min(reply->max_buffer, s->info.proposed);
    s->window = grant(s->info.buffer);
    now_ = now;
    emit(StreamEvent::Kind::kOpened, id, *s);
    maybe_complete(*s);
    return true;
}

bool StreamTransport::on_proceed(const Message& msg, TimePoint now) {
    const auto p = stream::decode_data_proceed(msg.payload);
    if (!p) return false;
    Stream* s = find_outgoing(msg.source.alias, p->source_id);
    if (s == nullptr || s->state != State::kOpen) return false;
    ++s->info.proceeds;
    // An early Proceed extends the window (as OpenMRN).
    s->window = std::min(s->window + grant(s->info.buffer), kUnlimitedWindow);
    s->deadline = {};
    now_ = now;
    return true;
}

// ---------------- sink ----------------

void StreamTransport::expect(std::uint16_t remote_alias, std::uint8_t dest_id,
                             std::uint16_t max_buffer, bool auto_proceed) {
    expected_.push_back({remote_alias, dest_id, max_buffer, auto_proceed});
}

void StreamTransport::on_initiate_request(const Message& msg, TimePoint now) {
    const auto req = stream::decode_initiate_request(msg.payload);
    stream::InitiateReply reply;
    reply.max_buffer = 0;
    reply.source_id = msg.payload.size() > 4 ? msg.payload[4] : 0;
    reply.dest_id = 0;
    const auto reject = [&](std::uint16_t code) {
        reply.code = code;
        send(Mti::kStreamInitiateReply, msg.source, stream::encode(reply));
    };
    if (!req || req->max_buffer == 0) return reject(stream::kRejectInvalid);
    const std::uint16_t remote = msg.source.alias;
    auto match = std::find_if(expected_.begin(), expected_.end(), [&](const Expectation& e) {
        return e.remote == remote &&
               (e.dest_id == stream::kInvalidStreamId || e.dest_id == req->suggested_dest_id ||
                req->suggested_dest_id == stream::kInvalidStreamId);
    });
    std::uint16_t acceptable = config_.sink_max_buffer;
    bool auto_proceed = true;
    if (match != expected_.end()) {
        acceptable = match->max_buffer;
        auto_proceed = match->auto_proceed;
        expected_.erase(match);
    } else if (!config_.accept_unsolicited) {
        return reject(stream::kRejectNotAccepted);
    }
    // A repeated request for a SID still open: the source started over.
    for (auto& [id, s] : streams_) {
        if (!s.info.outgoing && s.info.remote.alias == remote &&
            s.info.source_id == req->source_id && s.state == State::kOpen) {
            s.state = State::kClosed;
            s.info.open = false;
        }
    }
    if (open_streams() >= config_.max_streams) return reject(stream::kRejectBufferFull);
    Stream s;
    s.info.remote = msg.source;
    s.info.source_id = req->source_id;
    s.info.dest_id = free_dest_id(remote, req->suggested_dest_id);
    s.info.proposed = req->max_buffer;
    s.info.buffer = stream::negotiate_buffer(req->max_buffer, acceptable);
    s.info.open = true;
    s.state = State::kOpen;
    s.auto_proceed = auto_proceed;
    s.deadline = now + config_.idle_timeout;
    reply.max_buffer = s.info.buffer;
    reply.code = stream::kAccept;
    reply.dest_id = s.info.dest_id;
    send(Mti::kStreamInitiateReply, msg.source, stream::encode(reply));
    const std::uint32_t id = next_id_++;
    auto [it, inserted] = streams_.emplace(id, std::move(s));
    emit(StreamEvent::Kind::kOpened, id, it->second);
    prune();
}

bool StreamTransport::on_data(const Message& msg, TimePoint now) {
    if (msg.payload.empty()) return false;
    const std::uint16_t remote = msg.source.alias;
    for (auto& [id, s] : streams_) {
        if (s.info.outgoing || s.state != State::kOpen || s.info.remote.alias != remote ||
            s.info.dest_id != msg.payload[0]) {
            continue;
        }
        const std::size_t n = msg.payload.size() - 1;
        s.info.bytes += n;
        ++s.info.data_frames;
        s.in_window += n;
        s.info.max_in_window = std::max(s.info.max_in_window, s.in_window);
        s.deadline = now + config_.idle_timeout;
        if (n > 0) {
            emit(StreamEvent::Kind::kData, id, s);
            events_.back().data.assign(msg.payload.begin() + 1, msg.payload.end());
        }
        if (s.in_window >= s.info.buffer && s.in_window - n < s.info.buffer) {
            if (s.auto_proceed) {
                proceed(id);
            } else {
                emit(StreamEvent::Kind::kWindowFull, id, s);
            }
        }
        return true;
    }
    return false;
}

bool StreamTransport::proceed(std::uint32_t id) {
    auto it = streams_.find(id);
    if (it == streams_.end() || it->second.info.outgoing || it->second.state != State::kOpen) {
        return false;
    }
    Stream& s = it->second;
    s.in_window = s.in_window > s.info.buffer ? s.in_window - s.info.buffer : 0;
    ++s.info.proceeds;
    send(Mti::kStreamDataProceed, s.info.remote,
         stream::encode(stream::DataProceed{s.info.source_id, s.info.dest_id}));
    return true;
}

bool StreamTransport::on_complete(const Message& msg, TimePoint) {
    const auto c = stream::decode_data_complete(msg.payload);
    if (!c) return false;
    Stream* s = find_incoming(msg.source.alias, c->dest_id);
    if (s == nullptr || s->info.source_id != c->source_id) return false;
    s->state = State::kClosed;
    s->info.open = false;
    s->deadline = {};
    for (auto& [id, other] : streams_) {
        if (&other != s) continue;
        emit(StreamEvent::Kind::kCompleted, id, *s);
        events_.back().count = c->total_bytes;
        break;
    }
    prune();
    return true;
}

bool StreamTransport::on_reject(const Message& msg) {
    const std::uint16_t code = u16_at(msg.payload, 0);
    const std::uint16_t mti = u16_at(msg.payload, 2);
    const bool oir = msg.mti == Mti::kOptionalInteractionRejected;
    bool any = false;
    for (auto& [id, s] : streams_) {
        if (s.state == State::kClosed || s.info.remote.alias != msg.source.alias) continue;
        // An OIR answers our Initiate Request; a TDE ends whatever streams we share.
        if (oir && !(s.state == State::kInitiating && mti == to_u16(Mti::kStreamInitiateRequest))) {
            continue;
        }
        const bool initiating = s.state == State::kInitiating;
        s.state = State::kClosed;
        s.info.open = false;
        s.deadline = {};
        emit(initiating ? StreamEvent::Kind::kRejected : StreamEvent::Kind::kTerminated, id, s);
        events_.back().code = code;
        any = true;
    }
    return any;
}

void StreamTransport::drop(std::uint32_t id) {
    auto it = streams_.find(id);
    if (it == streams_.end()) return;
    it->second.state = State::kClosed;
    it->second.info.open = false;
    it->second.deadline = {};
    it->second.queue.clear();
}

// ---------------- time ----------------

void StreamTransport::poll(TimePoint now) {
    now_ = now;
    for (auto& [id, s] : streams_) {
        if (s.state == State::kClosed || s.deadline == TimePoint{} || now < s.deadline) continue;
        s.state = State::kClosed;
        s.info.open = false;
        s.deadline = {};
        s.queue.clear();
        emit(StreamEvent::Kind::kTimedOut, id, s);
    }
    prune();
}

std::optional<TimePoint> StreamTransport::next_deadline() const {
    std::optional<TimePoint> best;
    for (const auto& [id, s] : streams_) {
        if (s.state == State::kClosed || s.deadline == TimePoint{}) continue;
        if (!best || s.deadline < *best) best = s.deadline;
    }
    return best;
}

// ---------------- output and lookup ----------------

std::optional<Message> StreamTransport::pop_message() {
    if (!control_.empty()) {
        Message m = std::move(control_.front());
        control_.pop_front();
        return m;
    }
    return next_data();
}

bool StreamTransport::has_output() const {
    if (!control_.empty()) return true;
    return std::any_of(streams_.begin(), streams_.end(),
                       [this](const auto& kv) { return ready_to_send(kv.second); });
}

std::optional<StreamEvent> StreamTransport::pop_event() {
    if (events_.empty()) return std::nullopt;
    StreamEvent e = std::move(events_.front());
    events_.pop_front();
    return e;
}

std::optional<StreamInfo> StreamTransport::info(std::uint32_t id) const {
    auto it = streams_.find(id);
    if (it == streams_.end()) return std::nullopt;
    return it->second.info;
}

std::size_t StreamTransport::open_streams() const {
    return static_cast<std::size_t>(
        std::count_if(streams_.begin(), streams_.end(),
                      [](const auto& kv) { return kv.second.state != State::kClosed; }));
}

StreamTransport::Stream* StreamTransport::find_outgoing(std::uint16_t remote, std::uint8_t sid) {
    for (auto& [id, s] : streams_) {
        if (s.info.outgoing && s.state != State::kClosed && s.info.remote.alias == remote &&
            s.info.source_id == sid) {
            return &s;
        }
    }
    return nullptr;
}

StreamTransport::Stream* StreamTransport::find_incoming(std::uint16_t remote, std::uint8_t did) {
    for (auto& [id, s] : streams_) {
        if (!s.info.outgoing && s.state != State::kClosed && s.info.remote.alias == remote &&
            s.info.dest_id == did) {
            return &s;
        }
    }
    return nullptr;
}

std::uint8_t StreamTransport::free_dest_id(std::uint16_t remote, std::uint8_t suggested) const {
    const auto used = [&](std::uint8_t did) {
        return std::any_of(streams_.begin(), streams_.end(), [&](const auto& kv) {
            const Stream& s = kv.second;
            return !s.info.outgoing && s.state != State::kClosed && s.info.remote.alias == remote &&
                   s.info.dest_id == did;
        });
    };
    if (suggested != stream::kInvalidStreamId && !used(suggested)) return suggested;
    for (std::uint8_t did = 0; did < stream::kInvalidStreamId; ++did) {
        if (!used(did)) return did;
    }
    return 0;
}

std::uint8_t StreamTransport::free_source_id(std::uint16_t remote) {
    for (int tries = 0; tries < stream::kInvalidStreamId; ++tries) {
        const std::uint8_t sid = next_sid_;
        next_sid_ = static_cast<std::uint8_t>(next_sid_ % 0xFE + 1);  // 1..0xFE, never 0xFF
        if (find_outgoing(remote, sid) == nullptr) return sid;
    }
    return next_sid_;
}

void StreamTransport::send(Mti mti, const NodeHandle& to, std::vector<std::uint8_t> payload) {
    control_.push_back(Message{mti, {}, to, std::move(payload)});
}

void StreamTransport::emit(StreamEvent::Kind kind, std::uint32_t id, const Stream& s) {
    StreamEvent e;
    e.kind = kind;
    e.id = id;
    e.outgoing = s.info.outgoing;
    e.remote = s.info.remote;
    e.source_id = s.info.source_id;
    e.dest_id = s.info.dest_id;
    e.buffer = s.info.buffer;
    e.bytes = s.info.bytes;
    events_.push_back(std::move(e));
}

void StreamTransport::prune() {
    std::size_t closed = 0;
    for (const auto& kv : streams_) closed += kv.second.state == State::kClosed ? 1 : 0;
    for (auto it = streams_.begin(); closed > kKeptClosed && it != streams_.end();) {
        if (it->second.state == State::kClosed) {
            it = streams_.erase(it);
            --closed;
        } else {
            ++it;
        }
    }
}

}  // namespace olcb
