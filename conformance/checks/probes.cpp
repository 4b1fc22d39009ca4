#include "conformance/checks/probes.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <set>
#include <span>
#include <variant>

#include "cdi/validator.hpp"
#include "memory/acdi.hpp"
#include "memory/memory_config_defs.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/event_range.hpp"

namespace olcb::conform {
namespace {

using memory::Space;

// An ACDI block read field by field, each string up to its NUL: some nodes (OpenLcbCLib) serve
// only reads that start at a field and refuse the bytes after a string's NUL, which no tool
// needs. The block comes back whole, each string field padded with zeros after its NUL.
MemResult read_acdi_block(Session& s, const NodeInfo& node, Space space) {
    using namespace memory::acdi;
    struct Field {
        std::size_t offset, size;
    };
    static constexpr Field kManufacturer[] = {{kManufacturerVersionOffset, 1},
                                              {kManufacturerOffset, kManufacturerSize},
                                              {kModelOffset, kModelSize},
                                              {kHardwareVersionOffset, kHardwareVersionSize},
                                              {kSoftwareVersionOffset, kSoftwareVersionSize}};
    static constexpr Field kUser[] = {{kUserVersionOffset, 1},
                                      {kUserNameOffset, kUserNameSize},
                                      {kUserDescriptionOffset, kUserDescriptionSize}};
    const bool user = space == Space::kAcdiUser;
    const std::span<const Field> fields =
        user ? std::span<const Field>(kUser) : std::span<const Field>(kManufacturer);
    MemResult total;
    total.ok = true;
    total.data.assign(user ? kUserBlockSize : kManufacturerBlockSize, 0);
    for (const Field& f : fields) {
        MemResult r = s.read_range(node, space, static_cast<std::uint32_t>(f.offset),
                                   static_cast<std::uint32_t>(f.size), f.size > 1);
        total.temporary_rejects += r.temporary_rejects;
        if (!r.ok || r.data.empty()) {
            r.ok = false;
            return r;
        }
        std::copy_n(r.data.begin(), std::min(r.data.size(), f.size),
                    total.data.begin() + static_cast<std::ptrdiff_t>(f.offset));
    }
    return total;
}

// The node's AMDs (carrying its node ID) and RIDs, and other nodes' AMDs, among the frames
// since seen; seen moves on.
void count_probe_frames(CheckRun& run, FrameProbe& p, std::size_t& seen) {
    Session& s = run.session();
    for (const CanFrame& f : s.frames_since(seen)) {
        if (!can::is_control(f.id)) continue;
        const auto kind = can::classify_control(f.id);
        if (!run.from_node(f)) {
            if (kind == can::ControlFrame::kAmd) ++p.segment_amd;
            continue;
        }
        if (kind == can::ControlFrame::kAmd && f.len == 6 &&
            NodeId::from_bytes({f.data.data(), 6}) == run.node().id)
            ++p.amd;
        if (kind == can::ControlFrame::kRid) ++p.rid;
    }
    seen = s.frame_mark();
}

// The node's OIR to the unknown addressed MTI and its Verified Node ID among the messages
// since seen; seen moves on.
void count_probe_messages(CheckRun& run, FrameProbe& p, std::size_t& seen) {
    Session& s = run.session();
    for (const auto& r : s.messages_since(seen)) {
        const Message& m = r.message;
        if (m.source.alias != run.alias()) continue;
        if (m.mti == Mti::kOptionalInteractionRejected && m.payload.size() >= 4 &&
            (m.payload[2] << 8 | m.payload[3]) == kUnknownAddressedMti)
            p.oir = static_cast<std::uint16_t>(m.payload[0] << 8 | m.payload[1]);
        if ((m.mti == Mti::kVerifiedNodeId || m.mti == Mti::kVerifiedNodeIdSimple) &&
            NodeId::from_bytes(m.payload) == run.node().id) {
            p.verified = true;
            p.verified_mti = m.mti;
        }
    }
    seen = s.message_mark();
}

// Adds what `more`, a later read of the same range, learned about the datagrams to `into`.
void merge_datagram_flags(MemResult& into, const MemResult& more) {
    into.datagram_ok_seen = into.datagram_ok_seen && more.datagram_ok_seen;
    into.reply_pending = into.reply_pending && more.reply_pending;
    into.reply_timeout_exponent =
        std::max(into.reply_timeout_exponent, more.reply_timeout_exponent);
    into.reply_in_request_form = into.reply_in_request_form && more.reply_in_request_form;
    into.reply_latency = std::max(into.reply_latency, more.reply_latency);
    into.temporary_rejects += more.temporary_rejects;
}

// The outcome of a read without its data (a copy of at most the CDI limit, made once).
MemResult without_data(const MemResult& r) {
    MemResult out = r;
    out.data = {};
    return out;
}

// Reads on past Space Info's highest address when the download ended there without a NUL.
void read_past_highest(CheckRun& run, CdiDownload& d, std::uint32_t len) {
    // A highest address below the CDI's end would cut the text short, and every CDI check would
    // fail for one wrong number: read on past it, so the CDI is judged whole and the highest
    // address once (cdi.nul-at-highest).
    MemResult& r = d.result;
    if (!r.ok || r.data.size() != len || (!r.data.empty() && r.data.back() == 0)) return;
    const ProtocolOptions& o = run.options();
    std::function<void(std::size_t)> progress;
    if (o.cdi_progress) progress = [&o, len](std::size_t n) { o.cdi_progress(len + n); };
    MemResult more = run.session().read_range(run.node(), Space::kCdi, len, o.max_cdi_bytes - len,
                                              true, progress);
    run.tally(more);
    if (!more.ok || more.data.empty()) return;
    d.beyond_highest = static_cast<std::uint32_t>(more.data.size());
    r.data.insert(r.data.end(), more.data.begin(), more.data.end());
    merge_datagram_flags(r, more);
}

// The whole CDI by datagram reads (no streams, or the stream read failed).
void download_by_datagrams(CheckRun& run, CdiDownload& d) {
    const ProtocolOptions& o = run.options();
    const SpaceInfo ff = run.probe<SpaceInfoProbe>(0xFF);
    const std::uint32_t len =
        ff.present ? std::min(ff.highest_address + 1, o.max_cdi_bytes) : o.max_cdi_bytes;
    d.result = run.session().read_range(run.node(), Space::kCdi, 0, len, true, o.cdi_progress);
    run.tally(d.result);
    if (ff.present && len < o.max_cdi_bytes) read_past_highest(run, d, len);
    d.datagram = without_data(d.result);
}

// One datagram read of bytes [from, to) of 0xFF, compared with the stream's; false when the read
// failed (d.datagram then says how).
bool sample_by_datagram(CheckRun& run, CdiDownload& d, std::size_t from, std::size_t to) {
    const auto at = static_cast<std::uint32_t>(from);
    const MemResult r = run.session().read_range(run.node(), Space::kCdi, at,
                                                 static_cast<std::uint32_t>(to - from), false);
    run.tally(r);
    // The first sample's outcome, then the second's flags added (or its failure in its place).
    if (!d.sampled.empty() && r.ok) {
        merge_datagram_flags(d.datagram, r);
    } else {
        d.datagram = without_data(r);
    }
    if (!d.sampled.empty()) d.sampled += ", ";
    d.sampled += hex(at, 8) + "-" + hex(static_cast<unsigned>(to - 1), 8);
    if (!r.ok) return false;
    const auto& bytes = d.result.data;
    for (std::size_t i = 0; i < to - from; ++i) {
        const bool have = i < r.data.size();
        if (have && r.data[i] == bytes[from + i]) continue;
        if (d.sample_difference.empty()) {
            d.sample_difference = "at " + hex(static_cast<unsigned>(from + i), 8) + ": stream " +
                                  hex(bytes[from + i], 2) + ", datagram " +
                                  (have ? hex(r.data[i], 2) : std::string("no byte"));
        }
        break;
    }
    return true;
}

// The CDI by the stream read, when the node offers streams and the read brought a NUL; the
// datagram reads then cover the first and last kCdiSampleBytes. False: read it by datagrams.
bool download_by_stream(CheckRun& run, CdiDownload& d) {
    if (!run.probe<StreamSupport>().skip.empty()) return false;
    const CdiStream& stream = run.probe<CdiStream>();
    const auto& bytes = stream.mem.data;
    const auto nul = std::find(bytes.begin(), bytes.end(), std::uint8_t{0});
    // Without its NUL the stream may have been cut short: the datagram download judges the text.
    if (!stream.mem.ok || nul == bytes.end()) return false;
    d.by_stream = true;
    d.result = without_data(stream.mem);
    d.result.data.assign(bytes.begin(), nul + 1);
    const SpaceInfo ff = run.probe<SpaceInfoProbe>(0xFF);
    if (ff.present && d.result.data.size() > ff.highest_address + std::uint64_t{1})
        d.beyond_highest =
            static_cast<std::uint32_t>(d.result.data.size() - (ff.highest_address + 1));
    const std::size_t n = d.result.data.size();
    constexpr std::size_t kCdiSampleBytes = 64;  // one datagram read
    if (!sample_by_datagram(run, d, 0, std::min(n, kCdiSampleBytes))) return true;
    if (n > kCdiSampleBytes)
        sample_by_datagram(run, d, std::max(kCdiSampleBytes, n - kCdiSampleBytes), n);
    return true;
}

}  // namespace

FrameProbe FrameProbe::ask(CheckRun& run) {
    FrameProbe p;
    Session& s = run.session();
    const std::uint16_t me = s.tool_alias();
    const std::uint16_t node = run.alias();
    const std::size_t fmark = s.frame_mark();
    const std::size_t mmark = s.message_mark();
    s.inject(can::make_ame(me));
    s.inject(can::make_ame(me, run.node().id));
    s.inject(can::make_cid(7, NodeId{kOtherNodeId}, node));
    s.inject(can::make_frame(can::message_header(kUnknownAddressedMti & 0x0FFF, me),
                             std::array<std::uint8_t, 2>{static_cast<std::uint8_t>(node >> 8),
                                                         static_cast<std::uint8_t>(node & 0xFF)}));
    Message verify;
    verify.mti = Mti::kVerifyNodeIdAddressed;
    verify.destination = NodeHandle{run.node().id, node};
    s.send(verify);
    // Every answer is awaited up to the answer window, and a window more while other nodes'
    // AMDs still came in the last one: on a 1,000-node segment the node's AMD, RID and OIR wait
    // for the bus behind 999 AMDs (a second at 125 kbit/s, longer on a loaded hub). Then the
    // checks judge what came.
    std::size_t frames_seen = fmark, messages_seen = mmark;
    auto count_answers = [&] {
        count_probe_frames(run, p, frames_seen);
        count_probe_messages(run, p, messages_seen);
        return p.amd >= 2 && p.rid >= 1 && p.oir.has_value() && p.verified;
    };
    for (int round = 0; round <= kSegmentAnswerRounds; ++round) {
        const std::size_t segment_before = p.segment_amd;
        if (s.run_until(count_answers, run.options().answer_window)) break;
        if (p.segment_amd == segment_before) break;
    }
    count_answers();
    return p;
}

SnipProbe SnipProbe::ask(CheckRun& run) {
    SnipProbe p;
    p.raw = run.session().snip_payload(run.node());
    if (p.raw && !p.raw->empty()) p.snip = memory::decode_snip(*p.raw);
    return p;
}

PipProbe PipProbe::ask(CheckRun& run) {
    return {run.session().protocol_support(run.node())};
}

OptionsProbe OptionsProbe::ask(CheckRun& run) {
    OptionsProbe p;
    memory::Message reply;
    p.result =
        run.session().command(run.node(), memory::encode(memory::GetConfigOptions{}), &reply);
    run.tally(p.result);
    if (auto* o = std::get_if<memory::ConfigOptionsReply>(&reply); p.result.ok && o) p.reply = *o;
    p.described = p.result.ok ? memory::describe(memory::encode(reply)) : describe(p.result);
    return p;
}

SpaceInfo ask_space_info(Session& s, const NodeInfo& node, std::uint8_t space, MemResult& outcome) {
    memory::Message reply;
    outcome =
        s.command(node, memory::encode(memory::GetSpaceInfo{static_cast<Space>(space)}), &reply);
    SpaceInfo info;
    if (outcome.ok) {
        if (auto* p = std::get_if<memory::SpaceInfoReply>(&reply)) {
            info = {true, true, p->read_only, p->highest_address, p->lowest_address};
        } else if (std::holds_alternative<memory::SpaceInfoNotPresent>(reply)) {
            info.answered = true;
        }
    }
    return info;
}

SpaceInfoProbe SpaceInfoProbe::ask(CheckRun& run, std::uint8_t space) {
    MemResult outcome;
    SpaceInfoProbe p{ask_space_info(run.session(), run.node(), space, outcome)};
    run.tally(outcome);
    return p;
}

StreamSupport StreamSupport::ask(CheckRun& run) {
    StreamSupport s;
    const auto& pip = run.probe<PipProbe>().reply;
    s.pip = pip && pip->has(Protocol::kStream);
    if (const auto& o = run.probe<OptionsProbe>().reply) {
        s.lengths = (o->write_lengths & memory::write_lengths::kStreams) != 0;
        s.options =
            (o->available_commands & memory::available_commands::kStreamReads) != 0 || s.lengths;
    }
    if (run.options().no_stream) {
        s.skip = "--no-stream";
    } else if (!s.pip || !s.options) {
        s.skip = "node does not advertise streams";
        if (s.pip) s.skip += " reads (PIP Stream, but Options says no stream reads)";
    }
    return s;
}

CdiStream CdiStream::ask(CheckRun& run) {
    const ProtocolOptions& o = run.options();
    StreamReadOptions read;
    read.max_bytes = o.max_cdi_bytes;
    read.progress = o.cdi_progress;
    CdiStream r{run.session().read_stream(run.node(), Space::kCdi, 0, read)};
    run.tally(r.mem);
    return r;
}

CdiDownload CdiDownload::ask(CheckRun& run) {
    CdiDownload d;
    if (!download_by_stream(run, d)) download_by_datagrams(run, d);
    d.read_ok = d.result.ok && !d.result.data.empty();
    d.nul_found = !d.result.data.empty() && d.result.data.back() == 0;
    d.text = d.result.data;
    if (d.nul_found) d.text.pop_back();
    if (d.read_ok) {
        // One validation serves the model the other checks use and the text-only cdi.* rules;
        // the layout points into the document, which stays where it is on the heap.
        const std::string_view text(reinterpret_cast<const char*>(d.text.data()), d.text.size());
        cdi::ValidatedCdi validated = cdi::validate_model(text);
        d.rules = cdi::check_rules(text, validated);
        d.document = std::move(validated.document);
        d.layout = std::move(validated.layout);
    }
    return d;
}

AcdiProbe AcdiProbe::ask(CheckRun& run) {
    AcdiProbe p;
    const CdiDownload& cdi = run.probe<CdiDownload>();
    if (!cdi.document || !cdi.document->acdi) return p;
    p.acdi = cdi.document->acdi;
    p.manufacturer_result = read_acdi_block(run.session(), run.node(), Space::kAcdiManufacturer);
    run.tally(p.manufacturer_result);
    if (p.manufacturer_result.ok) p.manufacturer = p.manufacturer_result.data;
    p.user_result = read_acdi_block(run.session(), run.node(), Space::kAcdiUser);
    run.tally(p.user_result);
    if (p.user_result.ok) p.user = p.user_result.data;
    return p;
}

std::string highest_too_small(CheckRun& run, std::uint8_t space) {
    const SpaceInfo info = run.probe<SpaceInfoProbe>(space);
    if (!info.present) return {};
    const std::string highest = "Space Info's highest address " + hex(info.highest_address, 8);
    const CdiDownload& cdi = run.probe<CdiDownload>();
    if (space == 0xFF && cdi.beyond_highest != 0) {
        return std::string("depends on ") +
               (cdi.nul_found ? "cdi.nul-at-highest" : "cdi.nul-terminated") +
               ": the CDI goes on " + std::to_string(cdi.beyond_highest) + " bytes past " + highest;
    }
    if (cdi.layout) {
        for (const auto& e : cdi.layout->extents()) {
            if (e.space != space || e.end == 0 || info.highest_address + std::uint64_t{1} >= e.end)
                continue;
            return "depends on memory.space-info-layout." + space_suffix(space) +
                   ": the CDI lays out bytes up to " + hex(static_cast<unsigned>(e.end - 1), 8) +
                   ", past " + highest;
        }
    }
    using namespace memory::acdi;
    const bool acdi = cdi.document && cdi.document->acdi;
    const std::size_t block = space == memory::to_u8(kUserSpace)           ? kUserBlockSize
                              : space == memory::to_u8(kManufacturerSpace) ? kManufacturerBlockSize
                                                                           : 0;
    if (acdi && block != 0 && info.highest_address + std::uint64_t{1} < block) {
        return "depends on acdi.space-info: the ACDI block has " + std::to_string(block) +
               " bytes, past " + highest;
    }
    return {};
}

bool memory_works(CheckRun& run) {
    if (!run.heard().memory) run.probe<OptionsProbe>();
    return run.heard().memory;
}

bool datagrams_answered(CheckRun& run) {
    if (!run.heard().datagrams) run.probe<OptionsProbe>();
    return run.heard().datagrams;
}

std::vector<std::uint8_t> layout_spaces(CheckRun& run) {
    const CdiDownload& cdi = run.probe<CdiDownload>();
    std::set<std::uint8_t> spaces;
    if (cdi.layout)
        for (const auto& e : cdi.layout->extents())
            spaces.insert(static_cast<std::uint8_t>(e.space));
    return {spaces.begin(), spaces.end()};
}

void hand_over(CheckRun& run, CheckContext& ctx) {
    if (auto pip = run.release<PipProbe>()) ctx.pip = pip->reply;
    if (auto snip = run.release<SnipProbe>(); snip && snip->snip) ctx.snip = std::move(snip->snip);
    if (auto cdi = run.release<CdiDownload>()) {
        ctx.cdi_bytes = std::move(cdi->text);
        ctx.cdi_nul_found = cdi->nul_found;
        if (cdi->read_ok) {
            // The layout points into the document, whose place on the heap the move keeps.
            ctx.document = std::move(cdi->document);
            ctx.layout = std::move(cdi->layout);
        }
    }
    if (auto acdi = run.release<AcdiProbe>()) {
        if (acdi->manufacturer) ctx.acdi_manufacturer = std::move(acdi->manufacturer);
        if (acdi->user) ctx.acdi_user = std::move(acdi->user);
    }
    if (auto options = run.release<OptionsProbe>(); options && options->reply)
        ctx.options = options->reply;
    for (const auto& [space, info] : run.release_each<SpaceInfoProbe>()) ctx.spaces[space] = info;
    ctx.temporary_rejects += run.heard().temporary_rejects;
}

// ---- Identify Events ----

namespace {

// An Identify Events answer may go on this many answer windows (hundreds of events at CAN speed).
constexpr int kMaxAnswerWindows = 10;

}  // namespace

bool is_identification(Mti m) {
    return is_producer_identified(m) || is_consumer_identified(m) ||
           m == Mti::kProducerRangeIdentified || m == Mti::kConsumerRangeIdentified;
}

bool EventAnswers::produces(std::uint64_t id) const {
    return produced.count(id) ||
           std::any_of(produced_ranges.begin(), produced_ranges.end(),
                       [&](std::uint64_t r) { return in_range(EventId(id), EventId(r)); });
}

bool EventAnswers::consumes(std::uint64_t id) const {
    return consumed.count(id) ||
           std::any_of(consumed_ranges.begin(), consumed_ranges.end(),
                       [&](std::uint64_t r) { return in_range(EventId(id), EventId(r)); });
}

void EventAnswers::add(const Message& m) {
    const auto id = EventId::from_bytes(m.payload);
    if (!id) return;
    ++messages;
    if (is_producer_identified(m.mti)) produced.insert(id->value());
    if (is_consumer_identified(m.mti)) consumed.insert(id->value());
    if (m.mti == Mti::kProducerRangeIdentified) produced_ranges.insert(id->value());
    if (m.mti == Mti::kConsumerRangeIdentified) consumed_ranges.insert(id->value());
}

std::string EventAnswers::describe() const {
    return std::to_string(messages) + " Identified messages (" + std::to_string(produced.size()) +
           " produced, " + std::to_string(consumed.size()) + " consumed, " +
           std::to_string(produced_ranges.size() + consumed_ranges.size()) + " ranges)";
}

std::vector<Message> await_answers(Session& s, std::uint16_t alias, std::size_t mark,
                                   const std::function<bool(const Message&)>& want,
                                   const std::function<bool(const std::vector<Message>&)>& done,
                                   Duration first, const AnswerWindows& w) {
    std::vector<Message> got;
    std::size_t scanned = mark;
    const TimePoint sent = s.link().now();
    const TimePoint stop = sent + w.answer * kMaxAnswerWindows;
    TimePoint last = sent;
    auto scan = [&] {
        bool fresh = false;
        for (const ReceivedMessage& r : s.messages_since(scanned)) {
            if (r.message.source.alias != alias || !want(r.message)) continue;
            got.push_back(r.message);
            last = std::max(last, r.at);
            fresh = true;
        }
        scanned = s.message_mark();
        return fresh;
    };
    s.run_until(
        [&] {
            scan();
            return done(got);
        },
        first);
    for (;;) {
        scan();
        const TimePoint until = std::min(stop, last + w.quiet);
        const TimePoint now = s.link().now();
        if (now >= until) break;
        s.run_until(scan, until - now);
    }
    return got;
}

EventAnswers identify_events(Session& s, const NodeInfo& node, IdentifyTo to, Duration first,
                             const AnswerWindows& w) {
    const bool addressed = to == IdentifyTo::kTheNode;
    const std::uint16_t alias = s.alias_of(node);
    Message m;
    m.mti = addressed ? Mti::kIdentifyEventsAddressed : Mti::kIdentifyEventsGlobal;
    if (addressed) m.destination = NodeHandle{node.id, alias};
    const std::size_t mark = s.message_mark();
    s.send(m);
    const auto got = await_answers(
        s, alias, mark, [](const Message& r) { return is_identification(r.mti); },
        [](const std::vector<Message>& g) { return !g.empty(); }, first, w);
    EventAnswers a;
    for (const Message& r : got) a.add(r);
    return a;
}

}  // namespace olcb::conform
