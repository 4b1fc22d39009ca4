#include "conformance/runner.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <ostream>

#include "cdi/layout.hpp"
#include "cdi/parser.hpp"
#include "conformance/encoding_checks.hpp"
#include "conformance/report.hpp"
#include "conformance/session_memory.hpp"
#include "memory/snip.hpp"

namespace olcb::conform {
namespace {

volatile std::sig_atomic_t g_stop = 0;

extern "C" void on_stop_signal(int) {
    g_stop = 1;
}

// A CDI larger than this is not downloaded for the encoding checks (protocol checks judge it).
constexpr std::uint32_t kMaxCdi = 4u << 20;

// One FAIL naming the loss when the transport went away during this node's run.
void add_link_check(NodeReport& report, Link& link, std::uint64_t losses_before) {
    if (link.losses() == losses_before && link.up()) return;
    std::string message = "the link went down during the run";
    if (!link.loss_reason().empty()) message += ": " + link.loss_reason();
    message += link.up() ? " (it came back)" : " (still down)";
    report.checks.push_back(
        CheckResult{"link.lost", Category::kLink, Status::kFail, message, "", "", ""});
}

// After a loss, waits (bounded) until the transport is back and the node answers again, so the
// restore can run; says what it is waiting for.
void wait_for_link(Session& session, const NodeInfo& node, const RunOptions& options,
                   std::ostream& progress) {
    Link& link = session.link();
    progress << "lcc-conform: the link went down"
             << (link.loss_reason().empty() ? "" : " (" + link.loss_reason() + ")")
             << "; waiting up to " << options.link_wait.count()
             << " s for it to return to restore the node" << std::endl;
    // The link's clock: simulated in tests, steady on real transports.
    const TimePoint deadline = link.now() + options.link_wait;
    while (!stop_requested() && link.now() < deadline) {
        const Duration left = deadline - link.now();
        if (!link.up() && !link.run_until([&] { return link.up() || stop_requested(); }, left)) {
            continue;
        }
        if (stop_requested()) return;
        // Up again: the node must answer before its memory is trusted to the restore.
        if (session.find_node(node.id)) {
            progress << "lcc-conform: link back; restoring" << std::endl;
            return;
        }
    }
}

}  // namespace

namespace {

// losses_before: the link's loss count when this node's run began.
NodeReport run_node_checks(Session& session, const NodeInfo& node, const RunOptions& options,
                           const ProtocolChecks& protocol_checks, std::ostream& progress,
                           std::uint64_t losses_before) {
    NodeReport report;
    report.node_id = node.id.to_string();
    Link& link = session.link();
    const auto link_lost = [&] { return link.losses() != losses_before || !link.up(); };
    if (auto snip = session.snip_payload(node)) {
        memory::Snip s = memory::decode_snip(*snip);
        report.name = s.manufacturer + " " + s.model;
        if (!s.user_name.empty()) report.name += " \"" + s.user_name + "\"";
    }
    // The protocol checks download and lay out the CDI; the encoding checks reuse both.
    ProgressBar bar(progress, options.progress);
    auto wall = [] { return std::chrono::steady_clock::now(); };
    CheckContext ctx;
    ctx.cdi_progress = [&](std::size_t n) { bar.update(n, wall()); };
    if (protocol_checks) {
        bar.start("protocol checks, reading CDI", 0, wall());
        report.checks = protocol_checks(session, node, ctx);
        bar.finish();
    }
    if (options.read_only) {
        for (auto& c : skipped_encoding_checks("--read-only: no write")) report.checks.push_back(c);
        report.restore_summary = "nothing written (--read-only)";
        return report;
    }
    if (stop_requested()) {
        for (auto& c : skipped_encoding_checks("interrupted")) report.checks.push_back(c);
        report.restore_summary = "nothing written (interrupted)";
        return report;
    }

    // Without the protocol checks' layout (none ran, or their read stopped at a wrong highest
    // address), the CDI is read here up to its NUL.
    if (!ctx.document || !ctx.layout) {
        bar.start("reading CDI", 0, wall());
        MemResult cdi_bytes = session.read_range(node, memory::Space::kCdi, 0, kMaxCdi, true,
                                                 [&](std::size_t n) { bar.update(n, wall()); });
        bar.finish();
        std::string xml(cdi_bytes.data.begin(), cdi_bytes.data.end());
        if (auto nul = xml.find('\0'); nul != std::string::npos) xml.resize(nul);
        auto parsed = cdi::parse(xml);
        ctx.layout.reset();
        ctx.document.reset();
        if (cdi_bytes.ok && parsed.document) {
            ctx.document = std::make_unique<cdi::Document>(std::move(*parsed.document));
            ctx.layout = cdi::build_layout(*ctx.document).layout;
        }
    }
    if (!ctx.document || !ctx.layout) {
        for (auto& c : skipped_encoding_checks("no usable CDI layout (see the cdi checks)")) {
            report.checks.push_back(c);
        }
        report.restore_summary = "nothing written";
        return report;
    }

    EncodingOptions eo;
    eo.sample = options.sample;
    eo.blob = options.blob;
    eo.reboot = options.reboot;
    eo.acdi_user = ctx.document->acdi.has_value();
    std::vector<Probe> probes = plan_encoding(*ctx.layout, eo);
    // Spaces the standard makes read-only (CDI, ACDI manufacturer) are never written, even when
    // a CDI lays variables there: cdi.acdi-spaces reports such a CDI.
    const std::size_t planned = probes.size();
    std::erase_if(probes, [](const Probe& p) { return p.space == 0xFF || p.space == 0xFC; });
    const std::size_t read_only_skipped = planned - probes.size();

    SessionMemory memory(session, node);
    SafetyBackup backup(
        options.backup_path.empty() ? default_backup_path(report.node_id) : options.backup_path,
        report.node_id);
    std::string error;
    if (!backup.capture(memory, ranges_to_backup(probes, eo), error)) {
        for (auto& c : skipped_encoding_checks("no safety backup, nothing written: " + error)) {
            report.checks.push_back(c);
        }
        report.restore_summary = "nothing written (" + error + ")";
        return report;
    }

    EncodingHooks hooks;
    hooks.stop = [&] { return stop_requested() || link_lost(); };
    hooks.reboot = [&] {
        std::size_t mark = session.message_mark();
        const std::uint8_t reset[] = {0x20, 0xA9};
        session.command(node, reset);
        auto is_init = [&](const Message& m) {
            return (m.mti == Mti::kInitializationComplete ||
                    m.mti == Mti::kInitializationCompleteSimple) &&
                   m.source.id == node.id;
        };
        for (const auto& r : session.messages_since(mark)) {
            if (is_init(r.message)) return true;
        }
        return session.wait_for(is_init, std::chrono::seconds(3)).has_value();
    };
    hooks.snip_user_name = [&]() -> std::optional<std::string> {
        auto payload = session.snip_payload(node);
        if (!payload) return std::nullopt;
        return memory::decode_snip(*payload).user_name;
    };
    bar.start("encoding checks", 0, wall());
    hooks.progress = [&](std::size_t done, std::size_t total) {
        (void)total;
        bar.update(done, wall());
    };
    auto results = run_encoding_checks(probes, memory, eo, hooks);
    bar.finish();
    report.checks.insert(report.checks.end(), results.begin(), results.end());
    if (read_only_skipped != 0) {
        report.checks.push_back(CheckResult{
            "encoding.read-only-spaces", Category::kEncoding, Status::kSkip,
            std::to_string(read_only_skipped) +
                " variables in the read-only spaces 252/255 not written (see cdi.acdi-spaces)",
            "MemoryConfigurationS 4.2", "", ""});
    }

    if (link_lost()) {
        // What ran after the loss measured the link, not the node.
        for (CheckResult& c : report.checks) {
            if (c.category == Category::kEncoding || c.id == "snip.follows-acdi-user-write") {
                c.status = Status::kSkip;
                c.message = "not judged: the link went down mid-run";
                c.expected.clear();
                c.seen.clear();
            }
        }
        wait_for_link(session, node, options, progress);
    }

    RestoreOutcome outcome;
    if (link.up()) {
        outcome = restore(backup, memory);
    } else {
        outcome.differences.push_back("not restored, the link is still down");
    }
    report.restore_summary = outcome.summary();
    CheckResult restored{"encoding.restore",
                         Category::kEncoding,
                         outcome.identical ? Status::kPass : Status::kFail,
                         outcome.summary(),
                         "lcc-conform safety rule",
                         "",
                         ""};
    if (outcome.identical) {
        backup.remove_file();
    } else {
        restored.message += "; backup kept in " + backup.path() +
                            "; when the node is reachable again run: " + options.restore_command +
                            " " + backup.path();
    }
    report.checks.push_back(std::move(restored));
    return report;
}

}  // namespace

NodeReport run_node(Session& session, const NodeInfo& node, const RunOptions& options,
                    const ProtocolChecks& protocol_checks, std::ostream& progress) {
    Link& link = session.link();
    const std::uint64_t losses_before = link.losses();
    NodeReport report =
        run_node_checks(session, node, options, protocol_checks, progress, losses_before);
    add_link_check(report, link, losses_before);
    return report;
}

std::optional<RestoreOutcome> restore_file(Session& session, const std::string& path,
                                           std::string& error) {
    auto backup = SafetyBackup::load(path, error);
    if (!backup) return std::nullopt;
    auto id = NodeId::parse(backup->node_id(), &error);
    if (!id) return std::nullopt;
    auto node = session.find_node(*id);
    if (!node) {
        error = "node " + backup->node_id() + " does not answer";
        return std::nullopt;
    }
    SessionMemory memory(session, *node);
    return restore(*backup, memory);
}

int exit_code(const std::vector<NodeReport>& reports) {
    for (const NodeReport& r : reports) {
        if (r.count(Status::kFail) > 0) return 1;
    }
    return 0;
}

void install_stop_handlers() {
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, nullptr);
    sigaction(SIGTERM, &sa, nullptr);
}

bool stop_requested() {
    return g_stop != 0;
}

void request_stop(bool on) {
    g_stop = on ? 1 : 0;
}

}  // namespace olcb::conform
