#include "conformance/checks/protocol_checks.hpp"

#include <algorithm>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <utility>

#include "conformance/checks/check_run.hpp"
#include "conformance/checks/probes.hpp"

namespace olcb::conform {
namespace {

using memory::Space;

// Short replies a FAIL message lists before giving the total.
constexpr std::size_t kShortReadsListed = 3;
// 1-byte reads short_read_checks() makes per space to learn whether a short reply was the end.
constexpr std::size_t kMaxEndProbes = 8;

// Space Info of space: the protocol checks' answer, else asked now (and kept in ctx).
SpaceInfo space_info(Session& s, const NodeInfo& node, std::uint8_t space, CheckContext& ctx) {
    auto known = ctx.spaces.find(space);
    if (known != ctx.spaces.end() && known->second.answered) return known->second;
    MemResult outcome;
    const SpaceInfo info = ask_space_info(s, node, space, outcome);
    if (outcome.not_sent.empty()) ctx.temporary_rejects += outcome.temporary_rejects;
    return ctx.spaces[space] = info;
}

// The short replies of one space that were not the end of it. One that nothing was read after is
// settled by a 1-byte read where it ended (data: not the end; 0x1082: the end), then by Space Info.
std::vector<const ShortRead*> short_reads_inside(Session& s, const NodeInfo& node,
                                                 std::uint8_t space, CheckContext& ctx) {
    auto open = [&](const ShortRead& r) {
        return r.node == node.id && r.space == space && !r.continued && !r.at_end;
    };
    std::optional<SpaceInfo> info;
    auto inside = [&](const ShortRead& r) {
        if (!info) info = space_info(s, node, space, ctx);
        return info->present && r.address + std::uint64_t{r.got} <= info->highest_address;
    };
    std::set<std::uint64_t> probed;
    const std::size_t count = s.short_reads().size();  // the probes below may add more
    for (std::size_t i = 0; i < count && probed.size() < kMaxEndProbes; ++i) {
        const ShortRead r = s.short_reads()[i];
        const std::uint64_t end = r.address + std::uint64_t{r.got};
        if (!open(r) || !inside(r) || !probed.insert(end).second) continue;
        s.read(node, static_cast<Space>(space), static_cast<std::uint32_t>(end), 1);
    }
    std::vector<const ShortRead*> out;
    for (std::size_t i = 0; i < count; ++i) {
        const ShortRead& r = s.short_reads()[i];
        if (r.node != node.id || r.space != space) continue;
        if (r.continued || (open(r) && inside(r))) out.push_back(&r);
    }
    return out;
}

CheckResult short_read_check(Session& s, const NodeInfo& node, std::uint8_t space,
                             CheckContext& ctx) {
    std::string id = "memory.short-read." + space_suffix(space);
    CheckResult c{std::move(id), Category::kMemory, Status::kPass, "", "", "", ""};
    if (const CheckSpec* spec = find_check(c.id)) c.section = std::string(spec->section);
    const std::string name = hex(space, 2);
    const std::uint64_t reads = s.reads(node.id, space);
    const std::vector<const ShortRead*> bad = short_reads_inside(s, node, space, ctx);
    if (bad.empty()) {
        c.message = std::to_string(reads) + " reads of space " + name +
                    " returned the count asked or ended at the end of the space";
        return c;
    }
    std::string list;
    for (std::size_t i = 0; i < bad.size() && i < kShortReadsListed; ++i) {
        list += (i ? "; " : "") + std::string("at ") + hex(bad[i]->address, 8) + " asked " +
                std::to_string(bad[i]->asked) + " got " + std::to_string(bad[i]->got);
    }
    // §4.5 lets a reply be shorter in general and wants a failure only for other reasons: an
    // ambiguity, so a note (a tool reading on copes; one stopping at a short reply loses data).
    c.status = Status::kWarn;
    c.message = "space " + name + ": " + std::to_string(bad.size()) + " of " +
                std::to_string(reads) + " reads returned fewer bytes than asked away from the " +
                "end of the space (" + list + (bad.size() > kShortReadsListed ? "; ..." : "") + ")";
    c.expected = "the count asked: only the end of the space may shorten a Read Reply";
    c.seen = std::to_string(bad.size()) + " short replies, first " + list.substr(0, list.find(';'));
    return c;
}

// True when the node sent any frame since the mark (so it is alive without asking).
bool heard_from(CheckRun& run, std::size_t mark) {
    for (const CanFrame& f : run.session().frames_since(mark))
        if (run.from_node(f)) return true;
    return false;
}

}  // namespace

std::vector<CheckResult> short_read_checks(Session& session, const NodeInfo& node,
                                           CheckContext& ctx) {
    std::vector<CheckResult> out;
    for (unsigned sp = 0; sp <= 0xFF; ++sp) {
        const auto space = static_cast<std::uint8_t>(sp);
        if (session.reads(node.id, space) > 0)
            out.push_back(short_read_check(session, node, space, ctx));
    }
    return out;
}

namespace {

// Why the checks still to come are not run ("" while they are): the node or the link went away.
struct Stop {
    std::string node_after;   // the check after which the node stopped answering
    std::string link_during;  // the check during which the link went down

    std::string why() const {
        if (!link_during.empty()) return "the link went down during " + link_during;
        if (!node_after.empty()) return "the node stopped answering after " + node_after;
        return {};
    }
};

// A check not run: a SKIP saying why (per-space checks have no result of their own).
void not_run(CheckRun& run, const CheckSpec& spec, const std::string& why) {
    if (!spec.id.ends_with(kPerSpace))
        run.add(
            {std::string(spec.id), spec.category, Status::kSkip, "not run: " + why, "", "", ""});
}

// Why a check that needs a protocol the node does not claim is not run ("" when it runs).
std::string unclaimed(CheckRun& run, const CheckSpec& spec) {
    if (!spec.needs) return {};
    const std::string name(protocol_name(*spec.needs));
    const auto& pip = run.probe<PipProbe>().reply;
    if (!pip) return "no Protocol Support Reply, so " + name + " is not known";
    return pip->has(*spec.needs) ? "" : "the node's PIP does not claim " + name;
}

ProtocolOptions widened(const ProtocolOptions& options, const CheckContext& ctx) {
    // The node's measured latency widens every window; none gets shorter than asked.
    ProtocolOptions o = options;
    if (ctx.timing) {
        o.window = std::max(o.window, ctx.timing->silence);
        o.answer_window = std::max(o.answer_window, ctx.timing->answer);
        o.quiet_window = std::max(o.quiet_window, ctx.timing->quiet);
    }
    o.cdi_progress = ctx.cdi_progress;
    return o;
}

}  // namespace

std::vector<CheckResult> run_protocol_checks(Session& session, const NodeInfo& node,
                                             const ProtocolOptions& options, CheckContext& ctx) {
    const ProtocolOptions o = widened(options, ctx);
    CheckRun run(session, node, o);
    Stop stop;
    const std::uint64_t losses = session.link().losses();
    for (const CheckSpec& spec : check_registry()) {
        if (!spec.run || !o.selection.wants(spec)) continue;
        if (const std::string why = stop.why(); !why.empty()) {
            // A dead node or link would cost every later check its full timeout, for nothing.
            ++ctx.not_run;
            not_run(run, spec, why);
            continue;
        }
        if (const std::string why = unclaimed(run, spec); !why.empty()) {
            not_run(run, spec, why);
            continue;
        }
        if (spec.exclusive) {
            if (auto other = run.other_tool()) {
                not_run(run, spec,
                        "another lcc-conform run (" + other->to_string() +
                            ") is on the segment, and this check needs the bus to itself");
                continue;
            }
        }
        if (ctx.check_started) ctx.check_started(spec.id);
        const std::size_t mark = session.frame_mark();
        const std::size_t first = run.result_count();
        const auto since = std::chrono::steady_clock::now();
        run.run(spec);
        run.share_duration(first, std::chrono::steady_clock::now() - since);
        // A silent link says nothing about the node (CheckRun left this check not judged).
        if (session.link().losses() != losses || !session.link().up()) {
            stop.link_during = spec.id;
        } else if (!heard_from(run, mark) && !session.ping(node, o.answer_window)) {
            stop.node_after = spec.id;
        }
    }
    hand_over(run, ctx);
    ctx.lost_after = stop.node_after;
    ctx.link_lost_during = stop.link_during;
    std::vector<CheckResult> out = run.take();
    std::erase_if(out, [&](const CheckResult& c) { return !o.selection.wants_id(c.id); });
    return out;
}

}  // namespace olcb::conform
