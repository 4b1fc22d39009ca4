// Session::read_stream: the client side of a memory-config stream read, on the link's stack with
// the stream transport on (see tool_stack_config).
#include <algorithm>

#include "base/error_codes.hpp"
#include "conformance/link/session.hpp"
#include "openlcb/datagram_defs.hpp"

namespace olcb::conform {

// The state of one read while it runs.
struct Session::StreamWait {
    NodeId node;
    std::uint16_t alias = 0;
    std::uint8_t did = 0;
    std::uint32_t request = 0;  // datagram id of the Read Stream command
    std::size_t message_mark = 0;
    std::size_t event_mark = 0;
    std::optional<std::uint32_t> stream;  // our handle of the incoming stream
    bool window_full = false;
    bool failed = false;
    bool reply_done = false;  // Read Stream Reply (OK or Fail) seen
    TimePoint last_progress{};
    StreamReadOptions options;
    StreamReadResult result;
};

void Session::stream_event(StreamWait& w, const StreamEvent& e) {
    if (e.outgoing || e.remote.alias != w.alias) return;
    if (e.kind == StreamEvent::Kind::kOpened && !w.stream && e.dest_id == w.did) {
        w.stream = e.id;
        w.result.initiated = true;
        w.result.granted = e.buffer;
        if (auto info = link_.stack().streams().info(e.id)) w.result.proposed = info->proposed;
        return;
    }
    if (!w.stream || e.id != *w.stream) return;
    switch (e.kind) {
        case StreamEvent::Kind::kData:
            w.result.mem.data.insert(w.result.mem.data.end(), e.data.begin(), e.data.end());
            if (w.result.mem.data.size() > w.options.max_bytes) {
                w.result.mem.data.resize(w.options.max_bytes);
                w.result.cut = true;
                w.failed = true;
            }
            break;
        case StreamEvent::Kind::kWindowFull:
            w.window_full = true;
            break;
        case StreamEvent::Kind::kCompleted:
            w.result.completed = true;
            w.result.complete_count = e.count;
            break;
        case StreamEvent::Kind::kTerminated:
        case StreamEvent::Kind::kTimedOut:
            w.failed = true;
            w.result.mem.error = e.code != 0 ? e.code : base::to_u16(base::ErrorCode::kTimeout);
            break;
        default:
            break;
    }
}

bool Session::stream_progress(StreamWait& w) {
    const std::size_t before = w.result.mem.data.size();
    for (; w.event_mark < stream_events_.size(); ++w.event_mark) {
        stream_event(w, stream_events_[w.event_mark]);
    }
    for (; !w.reply_done && w.message_mark < messages_.size(); ++w.message_mark) {
        const Message& m = messages_[w.message_mark].message;
        if (m.mti != Mti::kDatagram || m.source.alias != w.alias) continue;
        const auto d = memory::decode(m.payload);
        if (const auto* ok = std::get_if<memory::ReadStreamReply>(&d.message); d.ok() && ok) {
            w.result.reply = *ok;
            w.reply_done = true;
        } else if (const auto* fail = std::get_if<memory::ReadStreamReplyFail>(&d.message);
                   d.ok() && fail) {
            w.result.mem.error = memory::to_u16(fail->error);
            w.reply_done = true;
            w.failed = true;
        }
    }
    if (w.reply_done) replied(w.request, w.node);
    if (auto it = outcomes_.find(w.request); it != outcomes_.end()) {
        const DatagramOutcome& o = it->second.outcome;
        w.result.mem.datagram_ok_seen = o.status == DatagramOutcome::Status::kAccepted;
        w.result.mem.reply_pending = datagram::is_reply_pending(o.flags);
        // A Read Stream answered by its reply but never acknowledged is noted (on_outcome) and
        // read on: the stream and its reply show the node took it.
        const bool answered_unacked =
            w.reply_done && (o.status == DatagramOutcome::Status::kTimedOut ||
                             o.status == DatagramOutcome::Status::kUnacknowledged);
        if (o.status != DatagramOutcome::Status::kAccepted && !answered_unacked) {
            w.result.mem.rejected = o.status == DatagramOutcome::Status::kRejected;
            w.result.mem.timed_out = o.status == DatagramOutcome::Status::kTimedOut;
            w.result.mem.error = o.error_code;
            w.failed = true;
        }
    }
    if (w.result.mem.data.size() != before || w.window_full) w.last_progress = link_.now();
    if (w.result.mem.data.size() != before && w.options.progress)
        w.options.progress(w.result.mem.data.size());
    return w.failed || w.window_full || (w.result.completed && w.reply_done);
}

void Session::stream_hold(StreamWait& w) {
    // A source must wait for our Proceed: whatever comes meanwhile overran the buffer.
    const std::size_t at_full = w.result.mem.data.size();
    link_.run_until([] { return false; }, w.options.hold);
    stream_progress(w);
    w.result.during_hold += w.result.mem.data.size() - at_full;
    w.window_full = false;
    if (w.stream) link_.stack().proceed_stream(*w.stream);
    w.last_progress = link_.now();
}

StreamReadResult Session::read_stream(const NodeInfo& node, memory::Space space,
                                      std::uint32_t address, const StreamReadOptions& options) {
    StreamWait w;
    w.node = node.id;
    w.alias = alias_of(node);
    w.did = next_stream_id_;
    next_stream_id_ =
        static_cast<std::uint8_t>(next_stream_id_ == 0xFE ? 0x40 : next_stream_id_ + 1);
    w.options = options;
    const auto payload = memory::encode(
        memory::ReadStream{space, address, 0xFF, w.did, options.count, options.form});
    link_.stack().expect_stream(w.alias, w.did, options.buffer, options.hold.count() == 0);
    auto id = send_datagram_after(w.alias, payload);
    // Marked after the wait for an earlier datagram: what came meanwhile answers other requests.
    w.message_mark = messages_.size();
    w.event_mark = stream_events_.size();
    const TimePoint sent_at = link_.now();
    if (!id) {
        w.result.mem.error = base::to_u16(base::ErrorCode::kTemporary);
        w.result.mem.rejected = true;
        return w.result;
    }
    w.request = *id;
    w.last_progress = sent_at;
    const Duration patience = std::max(options.idle_timeout, reply_timeout_);
    while (true) {
        link_.run_until([&] { return stream_progress(w); }, std::chrono::milliseconds(250));
        if (w.window_full) {
            stream_hold(w);
            continue;
        }
        if (w.failed || (w.result.completed && w.reply_done)) break;
        if (link_.now() - w.last_progress > patience) {
            w.result.mem.timed_out = true;
            if (w.result.mem.error == 0)
                w.result.mem.error = base::to_u16(base::ErrorCode::kTimeout);
            break;
        }
    }
    if (w.stream) {
        if (auto info = link_.stack().streams().info(*w.stream)) {
            w.result.max_in_window = info->max_in_window;
            w.result.data_frames = info->data_frames;
            w.result.proceeds = info->proceeds;
        }
        if (!w.result.completed) link_.stack().streams().drop(*w.stream);
    }
    w.result.mem.ok = !w.failed && w.result.completed && w.result.reply.has_value();
    w.result.elapsed = link_.now() - sent_at;
    return w.result;
}

}  // namespace olcb::conform
