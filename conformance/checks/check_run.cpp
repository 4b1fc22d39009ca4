#include "conformance/checks/check_run.hpp"

#include "base/hex.hpp"
#include "conformance/report/report.hpp"
#include "openlcb/can_defs.hpp"

namespace olcb::conform {
namespace {

// Most bytes of node-supplied text a message quotes.
constexpr std::size_t kMaxQuote = 80;

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
    if (r.restarted) return "the node restarted before answering";
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

CheckRun::CheckRun(Session& session, const NodeInfo& node, const ProtocolOptions& options)
    : s_(session),
      node_(node),
      o_(options),
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
    const std::uint64_t losses = s_.link().losses();
    {
        WriteLedger::Origin origin(s_.ledger(), std::string(spec.id));
        if (spec.run) spec.run(*this, spec);
    }
    // What the link lost is no evidence about the node.
    if (s_.link().losses() != losses || !s_.link().up())
        return not_judged(first, "not judged: the link went down during this check");
    // A write our own gate kept back proves nothing about the node: the check is not judged.
    const auto& entries = s_.ledger().entries();
    for (std::size_t i = planned; i < entries.size(); ++i) {
        if (entries[i].outcome != WriteOutcome::kNotSent) continue;
        return not_judged(
            first, "not judged: lcc-conform kept a write back (" + entries[i].refused_why + ")");
    }
}

void CheckRun::not_judged(std::size_t first, const std::string& why) {
    for (std::size_t r = first; r < out_.size(); ++r) {
        out_[r].status = Status::kSkip;
        out_[r].message = why;
        out_[r].expected.clear();
        out_[r].seen.clear();
    }
}

void CheckRun::add(CheckResult result) {
    // The registry is the one source of categories, citations and how strong a verdict may be.
    cite(result);
    out_.push_back(std::move(result));
}

std::optional<NodeId> CheckRun::other_tool() {
    return s_.other_tool();
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

Duration reply_limit(const ProtocolOptions& options, unsigned exponent) {
    return exponent == 0 ? options.max_reply_latency
                         : Duration(std::chrono::seconds(1u << exponent));
}

void CheckRun::tally(const MemResult& r) {
    if (!r.not_sent.empty()) return;  // the node never saw it
    heard_.temporary_rejects += r.temporary_rejects;
    // Datagram Rejected is a datagram answer too: the node implements the transport.
    if (!r.timed_out) heard_.datagrams = true;
    if (r.ok || (!r.rejected && !r.timed_out)) heard_.memory = true;
    // No reply came, or the time includes our waits before resending a rejected request.
    if (r.reply_latency == Duration::zero() || r.temporary_rejects != 0) return;
    const auto over = [this](Duration latency, std::uint8_t n) {
        return latency - reply_limit(o_, n);
    };
    if (!heard_.slowest_reply || over(r.reply_latency, r.reply_timeout_exponent) >
                                     over(*heard_.slowest_reply, heard_.slowest_exponent)) {
        heard_.slowest_reply = r.reply_latency;
        heard_.slowest_exponent = r.reply_timeout_exponent;
    }
}

void CheckRun::share_duration(std::size_t first, Duration spent) {
    if (first >= out_.size()) return;
    const auto n = static_cast<long>(out_.size() - first);
    for (std::size_t i = first; i < out_.size(); ++i) out_[i].duration = spent / n;
}

}  // namespace olcb::conform
