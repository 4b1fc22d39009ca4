#include "conformance/checks/check_run.hpp"

#include <algorithm>
#include <set>
#include <variant>

#include "base/hex.hpp"
#include "cdi/validator.hpp"
#include "conformance/report/report.hpp"
#include "memory/acdi.hpp"
#include "memory/memory_config_codec.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform {
namespace {

using memory::Space;

// Most bytes of node-supplied text a message quotes.
constexpr std::size_t kMaxQuote = 80;

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

}  // namespace

std::string hex(unsigned value, int width) {
    return base::hex(value, width);
}

std::string clip(std::string_view text) {
    return show_node_text(text, false, kMaxQuote);
}

std::string quoted(std::string_view text) {
    return show_node_text(text, true, kMaxQuote);
}

std::string describe(const MemResult& r) {
    if (!r.not_sent.empty()) return "not sent by lcc-conform (" + r.not_sent + ")";
    if (r.timed_out) return "no answer";
    if (r.rejected)
        return r.error ? "Datagram Rejected " + hex(r.error)
                       : "Datagram Rejected without an error code";
    if (!r.ok) return r.error ? "error " + hex(r.error) : "failed without an error code";
    return std::to_string(r.data.size()) + " bytes";
}

Refusal judge_refusal(const MemResult& r, const std::string& what, std::uint16_t want) {
    const std::string standard =
        "; it must fail with an error code (" + hex(want) + " recommended)";
    if (r.timed_out) return {Status::kFail, what + ": no answer" + standard, "no answer"};
    if (r.ok) {
        const std::string got = r.data.empty() ? "accepted" : "returned " + describe(r);
        return {Status::kFail, what + " " + got + standard, got};
    }
    const std::string code = r.error ? hex(r.error) : "no error code";
    if (r.error == want) return {Status::kPass, what + " refused with " + code, code};
    return {Status::kWarn,
            what + " refused with " + code + ", not the recommended " + hex(want) +
                " (MemoryConfigurationTN §2.4.3)",
            code};
}

std::string space_suffix(std::uint8_t space) {
    return base::hex_digits(space, 2, base::HexCase::kLower);
}

void Verdict::judge(bool ok, std::string message, std::string expected, std::string seen) {
    add(ok ? Status::kPass : Status::kFail, std::move(message), ok ? "" : std::move(expected),
        ok ? "" : std::move(seen));
}

void Verdict::warn(std::string message, std::vector<std::string> details) {
    add(Status::kWarn, std::move(message), {}, {}, std::move(details));
}

void Verdict::refusal(const Refusal& r, std::string expected) {
    if (r.status == Status::kFail) return fail(r.message, std::move(expected), r.seen);
    add(r.status, r.message, {}, {});
}

void Verdict::skip(std::string why) {
    add(Status::kSkip, std::move(why), {}, {});
}

void Verdict::add(Status status, std::string message, std::string expected, std::string seen,
                  std::vector<std::string> details) {
    CheckResult c;
    c.id = id_;
    c.status = status;
    c.message = std::move(message);
    c.expected = std::move(expected);
    c.seen = std::move(seen);
    c.details = std::move(details);
    run_.add(std::move(c));
}

CheckRun::CheckRun(Session& session, const NodeInfo& node, const ProtocolOptions& options,
                   CheckContext& ctx)
    : s_(session),
      node_(node),
      o_(options),
      ctx_(ctx),
      start_frame_(session.frame_mark()),
      started_(session.link().now()) {}

std::uint16_t CheckRun::alias() const {
    return s_.alias_of(node_);
}

bool CheckRun::from_node(const CanFrame& f) const {
    return f.extended && can::source_alias(f.id) == alias();
}

Verdict CheckRun::out(const CheckSpec& spec) {
    return Verdict(*this, std::string(spec.id));
}

Verdict CheckRun::out(const CheckSpec& spec, std::uint8_t space) {
    std::string id(spec.id);
    if (id.ends_with(kPerSpace)) id.resize(id.size() - kPerSpace.size());
    return Verdict(*this, id + "." + space_suffix(space));
}

bool CheckRun::space_selected(const CheckSpec& spec, std::uint8_t space) const {
    if (!spec.id.ends_with(kPerSpace)) return true;
    std::string id(spec.id.substr(0, spec.id.size() - kPerSpace.size()));
    return o_.selection.wants_id(id + "." + space_suffix(space));
}

std::vector<std::uint8_t> CheckRun::selected_spaces(const CheckSpec& spec,
                                                    const std::vector<std::uint8_t>& spaces) const {
    std::vector<std::uint8_t> out;
    for (std::uint8_t sp : spaces)
        if (space_selected(spec, sp)) out.push_back(sp);
    return out;
}

void CheckRun::run(const CheckSpec& spec) {
    const std::size_t first = out_.size();
    const std::size_t planned = s_.ledger().entries().size();
    {
        WriteLedger::Origin origin(s_.ledger(), std::string(spec.id));
        if (spec.run) spec.run(*this, spec);
    }
    // A write our own gate kept back proves nothing about the node: the check is not judged.
    const auto& entries = s_.ledger().entries();
    for (std::size_t i = planned; i < entries.size(); ++i) {
        if (entries[i].outcome != WriteOutcome::kNotSent) continue;
        for (std::size_t r = first; r < out_.size(); ++r) {
            out_[r].status = Status::kSkip;
            out_[r].message =
                "not judged: lcc-conform kept a write back (" + entries[i].refused_why + ")";
            out_[r].expected.clear();
            out_[r].seen.clear();
        }
        break;
    }
}

void CheckRun::add(CheckResult result) {
    // The registry is the one source of categories, citations and how strong a verdict may be.
    cite(result);
    out_.push_back(std::move(result));
}

std::optional<NodeId> CheckRun::other_tool() {
    for (const NodeInfo& n : s_.nodes_seen())
        if (is_tool_id(n.id) && n.id != s_.tool_id()) return n.id;
    return std::nullopt;
}

bool CheckRun::others_spoke(std::size_t mark) {
    for (const CanFrame& f : s_.frames_since(mark)) {
        if (!f.extended) continue;  // standard frames: only ours are sent (fr60)
        const std::uint16_t src = can::source_alias(f.id);
        if (src != alias() && src != s_.tool_alias()) return true;
    }
    return false;
}

MemResult CheckRun::note(MemResult r) {
    tally(r);
    return r;
}

void CheckRun::tally(const MemResult& r) {
    if (!r.not_sent.empty()) return;  // the node never saw it
    ctx_.temporary_rejects += r.temporary_rejects;
    // Datagram Rejected is a datagram answer too: the node implements the transport.
    if (!r.timed_out) datagram_answered_ = true;
    if (r.ok || (!r.rejected && !r.timed_out)) memory_works_ = true;
}

const FrameProbe& CheckRun::frame_probe() {
    if (frame_probe_) return *frame_probe_;
    FrameProbe p;
    const std::uint16_t me = s_.tool_alias();
    const std::uint16_t node = alias();
    const std::size_t fmark = s_.frame_mark();
    const std::size_t mmark = s_.message_mark();
    s_.inject(can::make_ame(me));
    s_.inject(can::make_ame(me, node_.id));
    s_.inject(can::make_cid(7, NodeId{kOtherNodeId}, node));
    s_.inject(can::make_frame(can::message_header(kUnknownAddressedMti & 0x0FFF, me),
                              std::array<std::uint8_t, 2>{static_cast<std::uint8_t>(node >> 8),
                                                          static_cast<std::uint8_t>(node & 0xFF)}));
    Message verify;
    verify.mti = Mti::kVerifyNodeIdAddressed;
    verify.destination = NodeHandle{node_.id, node};
    s_.send(verify);
    // Every answer is awaited up to the answer window, and a window more while other nodes'
    // AMDs still came in the last one: on a 1,000-node segment the node's AMD, RID and OIR wait
    // for the bus behind 999 AMDs (a second at 125 kbit/s, longer on a loaded hub). Then the
    // checks judge what came.
    std::size_t frames_seen = fmark, messages_seen = mmark;
    auto count_answers = [&] {
        count_probe_frames(p, frames_seen);
        count_probe_messages(p, messages_seen);
        return p.amd >= 2 && p.rid >= 1 && p.oir.has_value() && p.verified;
    };
    for (int round = 0; round <= kSegmentAnswerRounds; ++round) {
        const std::size_t segment_before = p.segment_amd;
        if (s_.run_until(count_answers, o_.answer_window)) break;
        if (p.segment_amd == segment_before) break;
    }
    count_answers();
    frame_probe_ = p;
    return *frame_probe_;
}

// The node's AMDs (carrying its node ID) and RIDs, and other nodes' AMDs, among the frames
// since seen; seen moves on.
void CheckRun::count_probe_frames(FrameProbe& p, std::size_t& seen) {
    for (const CanFrame& f : s_.frames_since(seen)) {
        if (!can::is_control(f.id)) continue;
        const auto kind = can::classify_control(f.id);
        if (!from_node(f)) {
            if (kind == can::ControlFrame::kAmd) ++p.segment_amd;
            continue;
        }
        if (kind == can::ControlFrame::kAmd && f.len == 6 &&
            NodeId::from_bytes({f.data.data(), 6}) == node_.id)
            ++p.amd;
        if (kind == can::ControlFrame::kRid) ++p.rid;
    }
    seen = s_.frame_mark();
}

// The node's OIR to the unknown addressed MTI and its Verified Node ID among the messages
// since seen; seen moves on.
void CheckRun::count_probe_messages(FrameProbe& p, std::size_t& seen) {
    for (const auto& r : s_.messages_since(seen)) {
        const Message& m = r.message;
        if (m.source.alias != alias()) continue;
        if (m.mti == Mti::kOptionalInteractionRejected && m.payload.size() >= 4 &&
            (m.payload[2] << 8 | m.payload[3]) == kUnknownAddressedMti)
            p.oir = static_cast<std::uint16_t>(m.payload[0] << 8 | m.payload[1]);
        if ((m.mti == Mti::kVerifiedNodeId || m.mti == Mti::kVerifiedNodeIdSimple) &&
            NodeId::from_bytes(m.payload) == node_.id) {
            p.verified = true;
            p.verified_mti = m.mti;
        }
    }
    seen = s_.message_mark();
}

const std::optional<std::vector<std::uint8_t>>& CheckRun::snip_raw() {
    if (!snip_asked_) {
        snip_asked_ = true;
        snip_raw_ = s_.snip_payload(node_);
        if (snip_raw_ && !snip_raw_->empty()) ctx_.snip = memory::decode_snip(*snip_raw_);
    }
    return snip_raw_;
}

const std::optional<ProtocolSet>& CheckRun::pip() {
    if (!pip_asked_) {
        pip_asked_ = true;
        ctx_.pip = s_.protocol_support(node_);
    }
    return ctx_.pip;
}

const MemResult& CheckRun::config_options() {
    if (!options_result_) {
        memory::Message reply;
        MemResult r = s_.command(node_, memory::encode(memory::GetConfigOptions{}), &reply);
        tally(r);
        if (auto* p = std::get_if<memory::ConfigOptionsReply>(&reply); r.ok && p) ctx_.options = *p;
        options_reply_ = r.ok ? memory::describe(memory::encode(reply)) : describe(r);
        options_result_ = std::move(r);
    }
    return *options_result_;
}

const SpaceInfo& CheckRun::space_info(std::uint8_t space) {
    auto known = ctx_.spaces.find(space);
    if (known != ctx_.spaces.end() && known->second.answered) return known->second;
    memory::Message reply;
    const auto payload = memory::encode(memory::GetSpaceInfo{static_cast<Space>(space)});
    const MemResult& r = note(s_.command(node_, payload, &reply));
    SpaceInfo info;
    if (r.ok) {
        if (auto* p = std::get_if<memory::SpaceInfoReply>(&reply)) {
            info = {true, true, p->read_only, p->highest_address, p->lowest_address};
        } else if (std::holds_alternative<memory::SpaceInfoNotPresent>(reply)) {
            info.answered = true;
        }
    }
    ctx_.spaces[space] = info;
    return ctx_.spaces[space];
}

const CdiDownload& CheckRun::cdi() {
    if (cdi_) return *cdi_;
    const SpaceInfo ff = space_info(0xFF);
    const std::uint32_t len =
        ff.present ? std::min(ff.highest_address + 1, o_.max_cdi_bytes) : o_.max_cdi_bytes;
    CdiDownload d;
    d.result = s_.read_range(node_, Space::kCdi, 0, len, true, ctx_.cdi_progress);
    tally(d.result);
    if (ff.present && len < o_.max_cdi_bytes) read_past_highest(d, len);
    d.read_ok = d.result.ok && !d.result.data.empty();
    ctx_.cdi_nul_found = !d.result.data.empty() && d.result.data.back() == 0;
    ctx_.cdi_bytes = d.result.data;
    if (ctx_.cdi_nul_found) ctx_.cdi_bytes.pop_back();
    const std::string_view text(reinterpret_cast<const char*>(ctx_.cdi_bytes.data()),
                                ctx_.cdi_bytes.size());
    if (d.read_ok) {
        // One validation serves the model the other checks use and the text-only cdi.* rules;
        // the layout points into the document, which stays where it is on the heap.
        cdi::ValidatedCdi validated = cdi::validate_model(text);
        rules_ = cdi::check_rules(text, validated);
        ctx_.document = std::move(validated.document);
        ctx_.layout = std::move(validated.layout);
    }
    cdi_ = std::move(d);
    return *cdi_;
}

void CheckRun::read_past_highest(CdiDownload& d, std::uint32_t len) {
    // A highest address below the CDI's end would cut the text short, and every CDI check would
    // fail for one wrong number: read on past it, so the CDI is judged whole and the highest
    // address once (cdi.nul-at-highest).
    MemResult& r = d.result;
    if (!r.ok || r.data.size() != len || (!r.data.empty() && r.data.back() == 0)) return;
    std::function<void(std::size_t)> progress;
    if (ctx_.cdi_progress) progress = [this, len](std::size_t n) { ctx_.cdi_progress(len + n); };
    MemResult more = s_.read_range(node_, Space::kCdi, len, o_.max_cdi_bytes - len, true, progress);
    tally(more);
    if (!more.ok || more.data.empty()) return;
    d.beyond_highest = static_cast<std::uint32_t>(more.data.size());
    r.data.insert(r.data.end(), more.data.begin(), more.data.end());
    r.datagram_ok_seen = r.datagram_ok_seen && more.datagram_ok_seen;
    r.reply_pending = r.reply_pending && more.reply_pending;
    r.reply_in_request_form = r.reply_in_request_form && more.reply_in_request_form;
    r.reply_latency = std::max(r.reply_latency, more.reply_latency);
    r.temporary_rejects += more.temporary_rejects;
}

std::string CheckRun::highest_too_small(std::uint8_t space) {
    const SpaceInfo info = space_info(space);
    if (!info.present) return {};
    const std::string highest = "Space Info's highest address " + hex(info.highest_address, 8);
    if (space == 0xFF && cdi().beyond_highest != 0) {
        return std::string("depends on ") +
               (ctx_.cdi_nul_found ? "cdi.nul-at-highest" : "cdi.nul-terminated") +
               ": the CDI goes on " + std::to_string(cdi_->beyond_highest) + " bytes past " +
               highest;
    }
    cdi();
    if (ctx_.layout) {
        for (const auto& e : ctx_.layout->extents()) {
            if (e.space != space || e.end == 0 || info.highest_address + std::uint64_t{1} >= e.end)
                continue;
            return "depends on memory.space-info-layout." + space_suffix(space) +
                   ": the CDI lays out bytes up to " + hex(static_cast<unsigned>(e.end - 1), 8) +
                   ", past " + highest;
        }
    }
    using namespace memory::acdi;
    const bool acdi = ctx_.document && ctx_.document->acdi;
    const std::size_t block = space == memory::to_u8(kUserSpace)           ? kUserBlockSize
                              : space == memory::to_u8(kManufacturerSpace) ? kManufacturerBlockSize
                                                                           : 0;
    if (acdi && block != 0 && info.highest_address + std::uint64_t{1} < block) {
        return "depends on acdi.space-info: the ACDI block has " + std::to_string(block) +
               " bytes, past " + highest;
    }
    return {};
}

const std::vector<cdi::RuleFinding>& CheckRun::rules() {
    if (!rules_) {
        cdi();
        const auto& b = ctx_.cdi_bytes;
        rules_ = cdi::check_rules({reinterpret_cast<const char*>(b.data()), b.size()});
    }
    return *rules_;
}

const FormProbe& CheckRun::form_probe() {
    if (form_probe_) return *form_probe_;
    FormProbe p;
    p.space = data_space();
    const auto space = static_cast<Space>(p.space);
    p.byte6 = note(s_.read(node_, space, 0, 8, memory::SpaceForm::kByte6));
    if (p.space >= 0xFD)
        p.short_form = note(s_.read(node_, space, 0, 8, memory::SpaceForm::kShort));
    form_probe_ = std::move(p);
    return *form_probe_;
}

bool CheckRun::acdi_blocks() {
    if (acdi_read_) return *acdi_read_;
    cdi();
    acdi_read_ = false;
    if (!ctx_.document || !ctx_.document->acdi) return false;
    MemResult m = read_acdi_block(s_, node_, Space::kAcdiManufacturer);
    tally(m);
    if (m.ok) ctx_.acdi_manufacturer = m.data;
    MemResult u = read_acdi_block(s_, node_, Space::kAcdiUser);
    tally(u);
    if (u.ok) ctx_.acdi_user = u.data;
    acdi_manufacturer_result_ = std::move(m);
    acdi_user_result_ = std::move(u);
    acdi_read_ = true;
    return true;
}

bool CheckRun::memory_works() {
    if (!memory_works_) config_options();
    return memory_works_;
}

bool CheckRun::datagrams_answered() {
    if (!datagram_answered_) config_options();
    return datagram_answered_;
}

std::vector<std::uint8_t> CheckRun::layout_spaces() {
    cdi();
    std::set<std::uint8_t> spaces;
    if (ctx_.layout)
        for (const auto& e : ctx_.layout->extents())
            spaces.insert(static_cast<std::uint8_t>(e.space));
    return {spaces.begin(), spaces.end()};
}

std::uint8_t CheckRun::data_space() {
    std::optional<std::uint8_t> best;
    // Prefer a space with both forms, so the form check covers the short one.
    for (std::uint8_t sp : layout_spaces())
        if (!best || (sp >= 0xFD && *best < 0xFD)) best = sp;
    return best.value_or(0xFF);
}

void CheckRun::share_duration(std::size_t first, Duration spent) {
    if (first >= out_.size()) return;
    const auto n = static_cast<long>(out_.size() - first);
    for (std::size_t i = first; i < out_.size(); ++i) out_[i].duration = spent / n;
}

}  // namespace olcb::conform
