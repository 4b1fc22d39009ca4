#include "conformance/run/config_backup.hpp"

#include <cstring>
#include <ostream>
#include <sstream>

#include "base/file.hpp"
#include "base/hex.hpp"
#include "base/utf8.hpp"
#include "cdi/parser.hpp"
#include "conformance/backup/backup_csv.hpp"
#include "conformance/link/session.hpp"
#include "conformance/link/session_memory.hpp"
#include "conformance/report/report.hpp"
#include "conformance/run/runner.hpp"

namespace olcb::conform {

namespace {

constexpr std::uint32_t kMaxCdiBytes = 1u << 24;

std::optional<NodeInfo> find(Session& session, const std::string& id_text, std::ostream& err) {
    std::string error;
    auto id = NodeId::parse(id_text, &error);
    if (!id) {
        err << base::printable("lcc-conform: node ID '" + id_text + "': " + error) << "\n";
        return std::nullopt;
    }
    auto node = session.find_node(*id);
    if (!node) err << "lcc-conform: node " << id->to_string() << " does not answer\n";
    return node;
}

// The node and its laid-out CDI; false after saying why on err.
bool open_node(Session& session, const std::string& node_id,
               const std::optional<std::string>& file_node, NodeInfo& node, NodeConfig& config,
               std::ostream& out, std::ostream& err) {
    auto chosen = choose_node(session, node_id, file_node, out, err);
    if (!chosen) return false;
    node = *chosen;
    std::string error;
    if (!load_node_config(session, node, config, error)) {
        err << "lcc-conform: node " << node.id.to_string() << ": " << error << "\n";
        return false;
    }
    return true;
}

// The node a file goes to, its CDI and variables, and what restoring the file onto it would
// change (the node's values read now): what restore and diff share. The plan points into
// entries, which point into config: they live together.
struct NodePlan {
    NodeInfo node;
    NodeConfig config;
    std::vector<ConfigEntry> entries;
    RestorePlan plan;
};

bool plan_on_node(Session& session, const std::string& node_id, const BackupFile& file, NodePlan& p,
                  std::ostream& out, std::ostream& err) {
    if (!open_node(session, node_id, file.node, p.node, p.config, out, err)) return false;
    SessionMemory memory(session, p.node);
    p.entries = config_entries(*p.config.layout);
    p.plan = plan_restore(p.entries, file, read_config_values(p.entries, memory));
    return true;
}

bool read_text_file(const std::string& path, std::string& text, std::ostream& err) {
    std::string error;
    auto bytes = read_backup_text(path, error);
    if (!bytes) {
        err << "lcc-conform: " << base::printable(error) << "\n";
        return false;
    }
    text = std::move(*bytes);
    return true;
}

// A file whose keys are mostly not the node's: the cause, then the first unknown keys.
UnusableBackup another_node_type(const RestorePlan& plan, const NodeInfo& node) {
    UnusableBackup u;
    u.cause = "is for another node type: it matches " + std::to_string(plan.matched) + " of the " +
              std::to_string(plan.node_keys) + " keys of node " + node.id.to_string() + ", and " +
              std::to_string(plan.unknown_keys.size()) + " of its keys are not the node's";
    for (const std::string& k : plan.unknown_keys) u.add(k);
    return u;
}

int restore_safety_backup(Session& session, const RestoreOptions& o, std::ostream& out,
                          std::ostream& err) {
    if (o.dry_run) {
        err << "lcc-conform: " << o.path << " is a safety backup; --dry-run applies to "
            << "configuration backups only\n";
        return 2;
    }
    std::string error;
    auto outcome = restore_file(session, o.path, error);
    if (!outcome) {
        err << "lcc-conform: " << error << "\n";
        return 2;
    }
    out << "restore: " << outcome->summary() << "\n";
    return outcome->identical ? 0 : 1;
}

// The problems of a plan that --allow-unknown accepts, as one sentence (empty when none).
std::string problems(const RestorePlan& plan) {
    if (plan.unknown_keys.empty() && plan.file_errors.empty()) return {};
    std::ostringstream s;
    s << plan.unknown_keys.size() << " unknown key(s) and " << plan.file_errors.size()
      << " malformed line(s) skipped";
    return s.str();
}

// The refused values' count lines: what was kept back, and what --force wrote anyway; the
// number of refused values not written (each makes the exit status 1).
std::size_t report_refused(const RestorePlan& plan, bool dry_run, bool force, std::ostream& out) {
    const std::size_t forced = force ? plan.forcible() : 0;
    const std::size_t kept_back = plan.refused.size() - forced;
    if (kept_back != 0) {
        out << "restore: " << kept_back
            << " value(s) refused (the node's CDI forbids them, or they are no value of their "
               "variable), so nothing "
            << (dry_run ? "would be" : "was") << " written for them";
        const std::size_t could = plan.forcible() - forced;
        if (could != 0) out << "; --force writes the " << could << " that have bytes anyway";
        out << "\n";
    }
    if (forced != 0) {
        out << "restore: " << forced << " value(s) the node's CDI forbids "
            << (dry_run ? "would be written" : "written") << " anyway (--force)\n";
    }
    return kept_back;
}

int report_restore(const RestorePlan& plan, const ConfigRestoreOutcome* done,
                   const RestoreOptions& o, const NodeInfo& node, std::ostream& out) {
    const std::string id = node.id.to_string();
    const std::size_t forced = o.force ? plan.forcible() : 0;
    std::string refused;
    if (forced != 0) refused += ", " + std::to_string(forced) + " forced";
    if (plan.refused.size() > forced) {
        refused += ", " + std::to_string(plan.refused.size() - forced) + " refused";
    }
    if (done == nullptr) {
        out << "restore --dry-run: " << plan.changes.size() << " change(s) to node " << id << ", "
            << plan.unchanged << " value(s) already equal" << refused << "; nothing written\n";
    } else {
        out << "restore: " << done->written << " variable(s) written to node " << id << ", "
            << plan.unchanged << " already equal" << refused << "\n";
    }
    print_plan(plan, false, out, o.force);
    if (done != nullptr) {
        for (const std::string& e : done->errors) {
            out << "  error      " << base::printable(e) << "\n";
        }
    }
    const std::size_t kept_back = report_refused(plan, done == nullptr, o.force, out);
    const std::string skipped = problems(plan);
    if (!skipped.empty()) {
        out << "restore: " << skipped
            << (o.allow_unknown ? " (--allow-unknown)\n" : "; --allow-unknown accepts them\n");
    }
    const bool failed = done != nullptr && !done->ok();
    return failed || kept_back != 0 || (!skipped.empty() && !o.allow_unknown) ? 1 : 0;
}

}  // namespace

std::string make_config_backup(const cdi::Layout& layout, MemoryAccess& memory,
                               const std::string& node_id, std::vector<std::string>& errors) {
    const std::vector<ConfigEntry> entries = config_entries(layout);
    const std::vector<ConfigValue> values = read_config_values(entries, memory);
    for (std::size_t i = 0; i < entries.size(); ++i) {
        if (!values[i].text) errors.push_back(entries[i].key + ": " + values[i].error);
    }
    return backup_text(entries, values, node_id);
}

bool load_node_config(Session& session, const NodeInfo& node, NodeConfig& config,
                      std::string& error) {
    MemResult cdi = session.read_range(node, memory::Space::kCdi, 0, kMaxCdiBytes, true);
    if (cdi.data.empty()) {
        error = "could not read the CDI (space 0xFF, error " + base::hex(cdi.error) + ")";
        return false;
    }
    std::string_view xml(reinterpret_cast<const char*>(cdi.data.data()), cdi.data.size());
    if (auto nul = xml.find('\0'); nul != std::string_view::npos) xml = xml.substr(0, nul);
    cdi::ParseResult parsed = cdi::parse(xml);
    if (!parsed.document) {
        error = "the CDI does not parse";
        return false;
    }
    config.document = std::make_unique<cdi::Document>(std::move(*parsed.document));
    cdi::LayoutResult laid = cdi::build_layout(*config.document);
    if (!laid.layout) {
        error = "the CDI has no valid address layout";
        return false;
    }
    config.layout.emplace(std::move(*laid.layout));
    return true;
}

std::optional<NodeInfo> choose_node(Session& session, const std::string& node_id,
                                    const std::optional<std::string>& file_node, std::ostream& out,
                                    std::ostream& err) {
    if (!node_id.empty()) return find(session, node_id, err);
    if (file_node) return find(session, *file_node, err);
    const std::vector<NodeInfo> nodes = session.discover();
    if (nodes.size() == 1) {
        out << "lcc-conform: using node " << nodes[0].id.to_string()
            << ", the only node on the bus\n";
        return nodes[0];
    }
    if (nodes.empty()) {
        err << "lcc-conform: no node answered Verify Node ID\n";
    } else {
        err << "lcc-conform: " << nodes.size() << " nodes answer; say which with --node ID:\n";
        for (const NodeInfo& n : nodes) err << "  " << n.id.to_string() << "\n";
    }
    return std::nullopt;
}

int run_config_backup(Session& session, const BackupOptions& o, std::ostream& out,
                      std::ostream& err) {
    NodeInfo node;
    NodeConfig config;
    if (!open_node(session, o.node_id, std::nullopt, node, config, out, err)) return 2;
    SessionMemory memory(session, node);
    const std::vector<ConfigEntry> entries = config_entries(*config.layout);
    const std::vector<ConfigValue> values = read_config_values(entries, memory);
    const std::string id = node.id.to_string();
    const std::string text = o.csv ? backup_csv(entries, values) : backup_text(entries, values, id);
    std::string error;
    if (!base::write_file(o.path, text, error)) {
        err << "lcc-conform: " << error << "\n";
        return 2;
    }
    std::size_t saved = 0;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        if (values[i].text) {
            ++saved;
        } else {
            err << "backup: " << entries[i].key << ": " << values[i].error << "\n";
        }
    }
    out << "backup: " << saved << " variable(s) of node " << id << " written to " << o.path
        << (o.csv ? " (CSV)" : "") << "\n";
    return saved == entries.size() ? 0 : 1;
}

int run_restore(Session& session, const RestoreOptions& o, std::ostream& out, std::ostream& err) {
    std::string text;
    if (!read_text_file(o.path, text, err)) return 2;
    if (SafetyBackup::is_safety_backup(text)) return restore_safety_backup(session, o, out, err);
    const BackupFile file = parse_backup_file(text);
    if (file.unusable) {
        print_unusable(o.path, *file.unusable, "; nothing written", err);
        return 2;
    }
    NodePlan p;
    if (!plan_on_node(session, o.node_id, file, p, out, err)) return 2;
    const NodeInfo& node = p.node;
    const RestorePlan& plan = p.plan;
    if (plan.for_another_node()) {
        print_unusable(o.path, another_node_type(plan, node), "; nothing written", err);
        return 1;
    }
    if (o.dry_run) return report_restore(plan, nullptr, o, node, out);
    SessionMemory memory(session, node);
    const ConfigRestoreOutcome done = apply_restore(plan, memory, o.force);
    return report_restore(plan, &done, o, node, out);
}

int run_diff_files(const std::string& a, const std::string& b, std::ostream& out,
                   std::ostream& err) {
    BackupFile fa;
    BackupFile fb;
    std::string error;
    if (!load_backup_file(a, fa, error) || !load_backup_file(b, fb, error)) {
        err << "lcc-conform: " << base::printable(error) << "\n";
        return 2;
    }
    for (const auto* f : {&fa, &fb}) {
        if (!f->unusable) continue;
        print_unusable(f == &fa ? a : b, *f->unusable, "", err);
        return 2;
    }
    for (const auto* f : {&fa, &fb}) {
        for (const std::string& e : f->errors)
            err << "diff: " << base::printable(f == &fa ? a : b) << ": " << base::printable(e)
                << "\n";
    }
    const std::vector<BackupDifference> diffs = diff_backups(fa, fb);
    std::size_t only_b = 0;
    for (const BackupDifference& d : diffs) only_b += !d.a;
    out << "diff: A = " << base::printable(a) << ", B = " << base::printable(b) << "\n";
    print_differences(diffs, fa.records.size() + only_b, out);
    return diffs.empty() ? 0 : 1;
}

int run_diff_node(Session& session, const DiffOptions& o, std::ostream& out, std::ostream& err) {
    BackupFile file;
    std::string error;
    if (!load_backup_file(o.path, file, error)) {
        err << "lcc-conform: " << base::printable(error) << "\n";
        return 2;
    }
    if (file.unusable) {
        print_unusable(o.path, *file.unusable, "", err);
        return 2;
    }
    NodePlan p;
    if (!plan_on_node(session, o.node_id, file, p, out, err)) return 2;
    const NodeInfo& node = p.node;
    const RestorePlan& plan = p.plan;
    if (plan.for_another_node()) {
        print_unusable(o.path, another_node_type(plan, node), "; a restore writes nothing", err);
        return 1;
    }
    out << "diff: node " << node.id.to_string() << " -> " << base::printable(o.path) << ": "
        << plan.changes.size() << " change(s) a restore would write, " << plan.refused.size()
        << " refused by the node's CDI, " << plan.unchanged << " equal, " << plan.missing.size()
        << " key(s) of the node not in the file\n";
    print_plan(plan, true, out);
    return plan.changes.empty() && plan.clean() ? 0 : 1;
}

}  // namespace olcb::conform
