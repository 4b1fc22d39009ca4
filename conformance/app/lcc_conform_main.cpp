// lcc-conform: checks an OpenLCB node's CDI, SNIP, ACDI and memory configuration against the
// standards, leaving its memory as it found it.
#include <unistd.h>

#include <boost/program_options.hpp>
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "base/file.hpp"
#include "base/host_port.hpp"
#include "conformance/app/log_decode.hpp"
#include "conformance/checks/check_registry.hpp"
#include "conformance/checks/protocol_checks.hpp"
#include "conformance/link/link.hpp"
#include "conformance/link/session.hpp"
#include "conformance/report/report.hpp"
#include "conformance/report/report_html.hpp"
#include "conformance/run/config_backup.hpp"
#include "conformance/run/runner.hpp"
#include "memory/snip.hpp"
#include "olcb_version.hpp"

namespace po = boost::program_options;
using namespace olcb;
using namespace olcb::conform;

namespace {

constexpr int kUsage = 2;
// The tool's own node IDs: self-assigned IDs of the experimental range 05.01.01.01.3F.01 to
// 05.01.01.01.3F.FE; each run takes one of its own so concurrent runs on one bus don't collide.

// Checked before anything connects, so a mistyped ID is a usage error rather than a run against
// no node; the codec's sentence already quotes the text.
bool check_node_id_option(const std::string& option, const std::string& text, std::string& error) {
    std::string why;
    if (NodeId::parse(text, &why)) return true;
    error = "--" + option + ": " + why;
    return false;
}

NodeId pick_tool_id(const po::variables_map& vm, std::string& error) {
    if (vm.count("tool-id")) {
        auto id = NodeId::parse(vm["tool-id"].as<std::string>(), &error);
        return id ? *id : NodeId{};
    }
    std::seed_seq seed{
        static_cast<unsigned>(::getpid()),
        static_cast<unsigned>(std::chrono::steady_clock::now().time_since_epoch().count())};
    std::mt19937 rng(seed);
    return NodeId(kToolIdBase + 1 + rng() % 0xFE);
}

std::unique_ptr<Link> open_link(const po::variables_map& vm, NodeId tool, std::string& error) {
    if (vm.count("connect")) {
        const auto where =
            base::parse_host_port(vm["connect"].as<std::string>(), error, base::PortZero::kRefused);
        if (!where) {
            error = "--connect " + error;
            return nullptr;
        }
        return connect_tcp(where->host, where->port, tool, error);
    }
    if (vm.count("socketcan"))
        return open_socketcan(vm["socketcan"].as<std::string>(), tool, error);
    if (vm.count("serial")) {
        SerialSettings settings;
        settings.baud = vm["baud"].as<unsigned>();
        const std::string flow = vm["flow-control"].as<std::string>();
        if (flow != "none" && flow != "rtscts") {
            error = "--flow-control wants none or rtscts";
            return nullptr;
        }
        settings.rtscts = flow == "rtscts";
        if (settings.baud == 0) {
            error = "--baud wants a bit rate such as 115200";
            return nullptr;
        }
        return open_serial(vm["serial"].as<std::string>(), settings, tool, error);
    }
    error = "say where the node is: --connect HOST:PORT, --serial DEVICE or --socketcan IF";
    return nullptr;
}

// The transport options as typed, for the "run this to restore later" hint.
std::string transport_arguments(const po::variables_map& vm) {
    std::string out;
    for (const char* key : {"connect", "serial", "socketcan"}) {
        if (vm.count(key)) out += std::string(" --") + key + " " + vm[key].as<std::string>();
    }
    if (vm.count("serial") && vm["baud"].as<unsigned>() != 115200) {
        out += " --baud " + std::to_string(vm["baud"].as<unsigned>());
    }
    return out;
}

po::options_description transport_options() {
    po::options_description o("where the node is");
    o.add_options()("connect", po::value<std::string>(),
                    "GridConnect TCP hub, HOST[:PORT] (12021)")(
        "serial", po::value<std::string>(), "USB/serial GridConnect adapter, e.g. /dev/ttyACM0")(
        "baud", po::value<unsigned>()->default_value(115200), "serial bit rate")(
        "flow-control", po::value<std::string>()->default_value("none"),
        "serial flow control: none or rtscts")("socketcan", po::value<std::string>(),
                                               "SocketCAN interface, e.g. vcan0 or slcan0")(
        "link-wait", po::value<unsigned>()->default_value(60),
        "seconds to wait for a lost link to return before leaving the restore to you")(
        "node", po::value<std::string>(), "node ID to check (default: every node found)")(
        "discover", po::value<double>()->default_value(3.0),
        "seconds to look for nodes (or for --node, one still starting up)")(
        "tool-id", po::value<std::string>(),
        "lcc-conform's own node ID (default: one of 05.01.01.01.3F.01-FE, new each run)");
    return o;
}

po::options_description check_options() {
    po::options_description o("what to check");
    o.add_options()("help,h", "this text")("version", "print the program's version and exit")(
        "list", "list every node with its SNIP names, check nothing")(
        "read-only", "never write (encoding checks are skipped)")(
        "no-stream", "no stream reads: the stream checks SKIP, the CDI is read by datagrams only")(
        "sample", po::value<std::size_t>()->default_value(3),
        "replicas tested per replicated group (0 = all)")("blob", "also write <blob> variables")(
        "reboot", "reset the node and check written values persist")(
        "train-address", po::value<std::uint32_t>()->value_name("N"),
        "the address of the train named with --node: the train search checks search for it")(
        "command-station",
        "the node named with --node is a command station: the train search checks have it "
        "create train nodes (they stay, stopped and released)")(
        "exclude", po::value<std::vector<std::string>>()->composing(),
        "never write variables whose backup key matches GLOB (repeatable), e.g. '*.Internal "
        "data.*'")("only", po::value<std::vector<std::string>>()->composing(),
                   "run only checks matching PATTERN when it starts with a category "
                   "('memory.*', 'frame.collision'); else write only variables whose backup key "
                   "matches it (repeatable)")(
        "skip", po::value<std::vector<std::string>>()->composing(),
        "do not run checks whose ID matches PATTERN (repeatable), e.g. 'frame.capacity'")(
        "thorough", "also run the long and disruptive checks (docs/checks.md, --thorough)")(
        "write-past-end",
        "also write across the end of each writable space (memory.write-past-end): a node "
        "without a bounds check keeps those bytes for good, where no tool can read or restore "
        "them")("list-checks", po::value<std::string>()->implicit_value("text"),
                "print every check (ID, category, section, OlcbChecker checks, summary); "
                "--list-checks=markdown prints docs/checks.md's registry tables")(
        "write-protected",
        "also probe protected settings (read-only hints, 'do not change'), one at a time")(
        "node-wait", po::value<unsigned>()->default_value(30),
        "seconds to wait for a node that stopped answering or restarted")(
        "timeout-scale", po::value<double>()->default_value(1.0),
        "multiply every answer and silence window by F (slow links, loaded machines)")(
        "backup", po::value<std::string>(),
        "safety backup file (default ./lcc-conform-backup-<node>.txt)")(
        "json", po::value<std::string>(), "write the JSON report to FILE (on every exit)")(
        "junit", po::value<std::string>(), "write the JUnit XML report to FILE (on every exit)")(
        "html", po::value<std::string>(),
        "write one self-contained HTML page to FILE: checks, memory map (on every exit)")(
        "no-color", "no colour even on a terminal")(
        "failures-only", "text report: leave out the passes and the unrelated skips")(
        "quiet,q", "text report: only the failures and the summary")(
        "csv", "backup: write CSV rows (key,value,type,space,address,size)")(
        "dry-run", "restore: print what would change (key, node value, file value), write nothing")(
        "allow-unknown",
        "restore: unknown keys and malformed lines are listed but do not make the exit status 1")(
        "force",
        "restore: also write the values the node's CDI forbids (outside <min>/<max>, not in its "
        "<map>, a string too long or not UTF-8), which are otherwise refused; each is listed");
    return o;
}

void print_help(const po::options_description& opts) {
    std::cout
        << "usage: lcc-conform (--connect HOST:PORT | --serial DEVICE | --socketcan IF) "
           "[options]\n"
           "       lcc-conform backup [--node ID] [--csv] FILE\n"
           "                     save every CDI variable (JMRI's key=value format, or CSV)\n"
           "       lcc-conform restore [--node ID] [--dry-run] [--allow-unknown] [--force] FILE\n"
           "                     put a safety, JMRI or CSV backup back (only what differs);\n"
           "                     values the node's CDI forbids are refused (exit 1) unless\n"
           "                     --force; an empty, binary, cut-short or other node type's\n"
           "                     file is refused whole, its cause on the first line\n"
           "       lcc-conform diff A B                  compare two backup files\n"
           "       lcc-conform diff [--node ID] FILE     what restoring FILE would change\n"
           "       lcc-conform decode FILE               read back a CAN log, no link needed\n"
           "                     FILE ('-': standard input) holds candump -L or GridConnect\n"
           "                     lines; one line per frame on stdout:\n"
           "                       SECONDS.MICROS IFACE :X19490343N; 343 Verify Node ID ...\n"
           "                       :X19490343N; 343 Verify Node ID ...   (GridConnect lines)\n"
           "                     other lines (CAN FD, error frames) are skipped, each named on\n"
           "                     stderr, then 'decode: N frames, M lines skipped'; exit 0 once\n"
           "                     read, 2 when FILE cannot be opened (docs/decode.md)\n"
           "Without --node, backup, restore and diff use the node a backup's '# node' line\n"
           "names, else the only node on the bus (several: they are listed). docs/backup.md\n\n"
           "Checks every node found (or --node ID) and prints what failed first (each FAIL\n"
           "and WARN with the checks it left unjudged), then the passes as one block of IDs,\n"
           "then the totals with the IDs that failed.\n"
           "Exit status: 0 every check passed, 1 a check failed, 2 usage or connection "
           "error,\nthe link went down during the run, or a node did not come back (its backup "
           "is kept\nand the restore command printed).\n\n"
        << opts;
}

Duration seconds(double s) {
    return std::chrono::duration_cast<Duration>(std::chrono::duration<double>(s > 0 ? s : 0));
}

// The reports asked for, written on every way out of a check run (exit 2 included).
class Reports {
public:
    Reports(const po::variables_map& vm, int argc, char** argv)
        : started_(std::chrono::system_clock::now()), began_(std::chrono::steady_clock::now()) {
        if (vm.count("json")) json_ = vm["json"].as<std::string>();
        if (vm.count("junit")) junit_ = vm["junit"].as<std::string>();
        if (vm.count("html")) html_ = vm["html"].as<std::string>();
        arguments_.assign(argv, argv + argc);
        for (const char* key : {"connect", "serial", "socketcan"}) {
            if (vm.count(key)) connection_ = std::string(key) + " " + vm[key].as<std::string>();
        }
    }
    // Before anything is written to a node: a report path that cannot be written is a usage
    // error now, not a lost report later.
    bool writable(std::string& error) const {
        for (const std::string& p : {json_, junit_, html_}) {
            if (!p.empty() && !base::write_file(p, "", error)) return false;
        }
        return true;
    }
    int finish(const std::vector<NodeReport>& reports, RunInfo run, int code) const {
        run.started = started_;
        run.elapsed = std::chrono::steady_clock::now() - began_;
        run.arguments = arguments_;
        run.connection = connection_;
        run.exit_code = code;
        std::string error;
        if (!json_.empty() && !base::write_file(json_, to_json(reports, run), error)) {
            std::cerr << "lcc-conform: " << error << "\n";
            return kUsage;
        }
        if (!junit_.empty() && !base::write_file(junit_, to_junit(reports, run), error)) {
            std::cerr << "lcc-conform: " << error << "\n";
            return kUsage;
        }
        if (!html_.empty() && !base::write_file(html_, to_html(reports, run), error)) {
            std::cerr << "lcc-conform: " << error << "\n";
            return kUsage;
        }
        return code;
    }
    int fail(const std::string& why) const {
        std::cerr << "lcc-conform: " << why << "\n";
        RunInfo run;
        run.error = why;
        return finish({}, run, kUsage);
    }

private:
    std::string json_, junit_, html_;
    std::vector<std::string> arguments_;
    std::string connection_;
    std::chrono::system_clock::time_point started_;
    std::chrono::steady_clock::time_point began_;
};

std::vector<NodeInfo> find_nodes(Session& session, const po::variables_map& vm,
                                 std::string& error) {
    const Duration discover = seconds(vm["discover"].as<double>());
    if (!vm.count("node")) {
        auto nodes = session.discover(discover);
        if (nodes.empty()) error = "no node answered Verify Node ID";
        return nodes;
    }
    auto id = NodeId::parse(vm["node"].as<std::string>(), &error);
    if (!id) {
        error = "--node: " + error;
        return {};
    }
    auto found = session.find_node(*id, discover);
    if (!found) {
        error = "node " + id->to_string() + " does not answer";
        return {};
    }
    return {*found};
}

void print_node_line(Session& session, const NodeInfo& n) {
    std::cout << n.id.to_string();
    if (auto p = session.snip_payload(n)) {
        // The node's own bytes: never raw to a terminal.
        const memory::Snip s = memory::decode_snip(*p);
        const auto shown = [](const std::string& text) {
            return show_node_text(text, false, text.size());
        };
        std::cout << "  " << shown(s.manufacturer) << " | " << shown(s.model) << " | "
                  << shown(s.hardware_version) << " | " << shown(s.software_version) << " | "
                  << shown(s.user_name) << " | " << shown(s.user_description);
    }
    std::cout << "\n";
}

int list_nodes(Session& session, std::vector<NodeInfo> nodes) {
    // Nodes that appear while the others are asked for their names are listed too; the session's
    // list is only walked again when it grew, so a segment of thousands stays linear.
    std::set<NodeId> listed;
    for (const NodeInfo& n : nodes) listed.insert(n.id);
    std::size_t walked = session.nodes_seen_count();
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        print_node_line(session, nodes[i]);
        if (session.nodes_seen_count() == walked) continue;
        for (const NodeInfo& seen : session.nodes_seen()) {
            if (listed.insert(seen.id).second) nodes.push_back(seen);
        }
        walked = session.nodes_seen_count();
    }
    return 0;
}

RunOptions run_options(const po::variables_map& vm) {
    RunOptions ro;
    ro.read_only = vm.count("read-only") > 0;
    ro.sample = vm["sample"].as<std::size_t>();
    ro.blob = vm.count("blob") > 0;
    ro.reboot = vm.count("reboot") > 0;
    if (vm.count("backup")) ro.backup_path = vm["backup"].as<std::string>();
    ro.link_wait = std::chrono::seconds(vm["link-wait"].as<unsigned>());
    ro.node_wait = std::chrono::seconds(vm["node-wait"].as<unsigned>());
    ro.timeout_scale = vm["timeout-scale"].as<double>();
    if (vm.count("exclude")) ro.protection.exclude = vm["exclude"].as<std::vector<std::string>>();
    if (vm.count("only")) {
        // One option for both, as users type it: a check ID pattern starts with a category.
        for (const std::string& p : vm["only"].as<std::vector<std::string>>())
            (is_check_pattern(p) ? ro.selection.only : ro.protection.only).push_back(p);
    }
    if (vm.count("skip")) ro.selection.skip = vm["skip"].as<std::vector<std::string>>();
    ro.selection.thorough = vm.count("thorough") > 0;
    ro.selection.write_past_end = vm.count("write-past-end") > 0;
    ro.protection.write_protected = vm.count("write-protected") > 0;
    ro.restore_command = "lcc-conform" + transport_arguments(vm) + " restore";
    ro.progress = is_terminal(2);
    return ro;
}

TextDetail text_detail(const po::variables_map& vm) {
    if (vm.count("quiet")) return TextDetail::kQuiet;
    return vm.count("failures-only") ? TextDetail::kFailuresOnly : TextDetail::kFull;
}

// Nodes seen during the run that were not checked (they appeared later); other lcc-conform
// runs on the segment (the tool's own ID range) are not devices and are left out.
std::vector<std::string> late_nodes(Session& session, const std::vector<NodeInfo>& checked) {
    std::vector<std::string> out;
    for (const NodeInfo& seen : session.nodes_seen()) {
        if (is_tool_id(seen.id)) continue;
        const bool known = std::any_of(checked.begin(), checked.end(),
                                       [&](const NodeInfo& n) { return n.id == seen.id; });
        if (!known) out.push_back(seen.id.to_string());
    }
    return out;
}

// One node a run checks, and how much of it.
struct Target {
    NodeInfo node;
    std::string protocol_only;  // why it gets the protocol checks alone ("" for every check)
};

// Without --node: every configurable node found (PIP Memory Configuration or CDI) gets every
// check; any other node (a throttle, a command station, JMRI's own node) the protocol checks a
// node of any kind owes; nodes of lcc-conform's own ID range are other runs, never checked (two
// runs on one bus testing each other's tool node gave FAILs for not being configurable).
std::vector<Target> choose_targets(Session& session, const std::vector<NodeInfo>& found,
                                   bool chosen, RunInfo& run) {
    std::vector<Target> out;
    for (const NodeInfo& n : found) {
        if (is_tool_id(n.id) && !chosen) {
            run.other_runs.push_back(n.id.to_string());
            continue;
        }
        Target t{n, {}};
        // A node named with --node is judged as what its PIP claims too: a train node is not
        // judged as an I/O board (issue 35: OpenMRN's train got CDI and memory FAILs).
        const auto pip = session.protocol_support(n);
        if (!pip && !chosen)
            t.protocol_only = "no Protocol Support Reply, so not known as a configurable node";
        else if (pip && !pip->has(Protocol::kMemoryConfiguration) && !pip->has(Protocol::kCdi))
            t.protocol_only =
                "not a configurable node (its PIP has neither Memory "
                "Configuration nor CDI)";
        out.push_back(std::move(t));
    }
    return out;
}

// "05.01.01.01.22.00  configurable  97 passed, 0 failed, 1 warning, 2 skipped": one line per
// node at the end of a run over several.
void print_node_summaries(const std::vector<NodeReport>& reports, const RunInfo& run) {
    std::cout << "summary of " << reports.size() << " node(s):\n";
    for (const NodeReport& r : reports) {
        const Summary s = summarize({r});
        std::cout << "  " << r.node_id << "  "
                  << (r.scope == "configurable" ? "configurable" : "protocol only") << "  "
                  << s.pass << " passed, " << s.fail << " failed, " << s.warn << " warnings, "
                  << s.skip << " skipped" << (r.incomplete ? "  INCOMPLETE" : "") << "\n";
    }
    for (const std::string& id : run.other_runs)
        std::cout << "  " << id << "  another lcc-conform run (not checked)\n";
}

// The protocol checks' options of the command line (the selection is the node's own).
ProtocolOptions protocol_options(const po::variables_map& vm, const RunOptions& ro) {
    ProtocolOptions o;
    o.read_only = ro.read_only;
    o.reboot = ro.reboot;
    o.no_stream = vm.count("no-stream") > 0;
    o.named = vm.count("node") > 0;
    o.command_station = vm.count("command-station") > 0;
    if (vm.count("train-address")) o.train_address = vm["train-address"].as<std::uint32_t>();
    return o;
}

int check_nodes(Session& session, Link& link, const std::vector<NodeInfo>& nodes,
                const po::variables_map& vm, const Reports& out) {
    const RunOptions ro = run_options(vm);
    RunInfo run;
    const std::vector<Target> targets = choose_targets(session, nodes, vm.count("node") > 0, run);
    for (const std::string& id : run.other_runs)
        std::cerr << "lcc-conform: node " << id << " is another lcc-conform run: not checked\n";
    if (targets.empty()) {
        run.error = "no node to check: only other lcc-conform runs answered";
        std::cerr << "lcc-conform: " << run.error << "\n";
        return out.finish({}, run, kUsage);
    }
    const TextStyle style{is_terminal(1) && !vm.count("no-color"), text_detail(vm)};
    // The selection of the node being run (a protocol-only node's is narrower).
    CheckSelection selection = ro.selection;
    ProtocolChecks protocol = [&](Session& s, const NodeInfo& n, CheckContext& ctx) {
        ProtocolOptions po_opts = protocol_options(vm, ro);
        po_opts.selection = selection;
        return run_protocol_checks(s, n, po_opts, ctx);
    };
    install_stop_handlers();
    if (ro.selection.write_past_end && !ro.read_only) {
        std::cerr << "lcc-conform: warning: --write-past-end writes across the end of every "
                     "writable space; a node without a bounds check (OpenMRN's file-backed "
                     "spaces) keeps those bytes for good, where no tool can read them back or "
                     "restore them\n";
    }
    std::vector<NodeReport> reports;
    for (std::size_t k = 0; k < targets.size(); ++k) {
        const Target& t = targets[k];
        RunOptions one = ro;
        if (targets.size() > 1 && !ro.backup_path.empty()) {
            one.backup_path = ro.backup_path + "." + t.node.id.to_string();
        }
        one.protocol_only = t.protocol_only;
        if (!t.protocol_only.empty()) {
            one.selection.categories = {Category::kFrame,  Category::kMessage, Category::kSnip,
                                        Category::kPip,    Category::kEvents,  Category::kTrain,
                                        Category::kSearch, Category::kFdi,     Category::kClock};
        }
        selection = one.selection;
        if (targets.size() > 1) {
            std::cerr << "lcc-conform: node " << k + 1 << " of " << targets.size() << ": "
                      << t.node.id.to_string()
                      << (t.protocol_only.empty() ? "" : " (" + t.protocol_only + ")") << "\n";
        }
        reports.push_back(run_node(session, t.node, one, protocol, std::cerr));
        write_text(std::cout, reports.back(), style);
        if (stop_requested() || !link.up()) break;  // the next node cannot be reached either
    }
    if (targets.size() > 1 || !run.other_runs.empty()) print_node_summaries(reports, run);
    // With --node the user chose one node of a segment they know: the others, which answer the
    // frame probe's global AME, did not appear late and are not news.
    if (!vm.count("node")) run.late_nodes = late_nodes(session, nodes);
    for (const std::string& id : run.late_nodes) {
        std::cout << "node " << id << " appeared during the run (not checked)\n";
    }
    if (stop_requested()) {
        std::cerr << "lcc-conform: interrupted; node memory restored (see the restore line)\n";
        run.error = "interrupted";
        return out.finish(reports, run, kUsage);
    }
    if (link.losses() != 0) {
        run.error = "the link went down during the run (" + link.loss_reason() + ")";
        std::cerr << "lcc-conform: " << run.error
                  << "; the results are incomplete (see link.lost)\n";
        return out.finish(reports, run, kUsage);
    }
    return out.finish(reports, run, exit_code(reports));
}

// `backup`, `restore` and `diff --node`: the configuration-backup commands (docs/backup.md).
int backup_command(Session& session, const std::string& command,
                   const std::vector<std::string>& args, const po::variables_map& vm) {
    const std::string node_arg = vm.count("node") ? vm["node"].as<std::string>() : "";
    if (command == "backup") {
        BackupOptions o;
        o.node_id = node_arg;
        o.path = args[1];
        o.csv = vm.count("csv") > 0;
        return run_config_backup(session, o, std::cout, std::cerr);
    }
    if (command == "restore") {
        RestoreOptions o;
        o.path = args[1];
        o.node_id = node_arg;
        o.dry_run = vm.count("dry-run") > 0;
        o.allow_unknown = vm.count("allow-unknown") > 0;
        o.force = vm.count("force") > 0;
        return run_restore(session, o, std::cout, std::cerr);
    }
    DiffOptions o;  // diff --node ID FILE
    o.node_id = node_arg;
    o.path = args[1];
    return run_diff_node(session, o, std::cout, std::cerr);
}

// --help, --version and --list-checks: printed, with the exit status; nullopt for a run.
std::optional<int> answer_without_a_run(const po::variables_map& vm,
                                        const po::options_description& opts) {
    if (vm.count("help")) {
        print_help(opts);
        return 0;
    }
    if (vm.count("version")) {
        std::cout << "lcc-conform " << kVersion << "\n";
        return 0;
    }
    if (vm.count("list-checks")) {
        const std::string form = vm["list-checks"].as<std::string>();
        if (form != "text" && form != "markdown") {
            std::cerr << "lcc-conform: --list-checks takes text or markdown\n";
            return kUsage;
        }
        std::cout << (form == "markdown" ? format_check_markdown() : format_check_list());
        return 0;
    }
    return std::nullopt;
}

// Options no run can start with: false after saying why (before anything is connected).
bool options_usable(const po::variables_map& vm) {
    for (const char* option : {"node", "tool-id"}) {
        std::string error;
        if (vm.count(option) &&
            !check_node_id_option(option, vm[option].as<std::string>(), error)) {
            std::cerr << "lcc-conform: " << error << "\n";
            return false;
        }
    }
    for (const char* option : {"command-station", "train-address"}) {
        if (!vm.count(option) || vm.count("node")) continue;
        std::cerr << "lcc-conform: --" << option
                  << " says what the node of --node is: give "
                     "--node too\n";
        return false;
    }
    if (vm.count("train-address") && vm["train-address"].as<std::uint32_t>() > 999999) {
        std::cerr << "lcc-conform: --train-address takes 0..999999 (six digits, TrainSearchS)\n";
        return false;
    }
    if (!vm.count("skip")) return true;
    for (const std::string& p : vm["skip"].as<std::vector<std::string>>()) {
        if (is_check_pattern(p)) continue;
        std::cerr << "lcc-conform: --skip '" << p
                  << "': not a check ID pattern (it starts with a category, e.g. "
                     "'memory.*'); to leave variables alone use --exclude\n";
        return false;
    }
    return true;
}

// The command and its FILEs (args[0] is the command): false after saying what is wrong.
bool command_usable(const std::string& command, const std::vector<std::string>& args,
                    const po::variables_map& vm) {
    if (command != "check" && command != "restore" && command != "backup" && command != "diff" &&
        command != "decode") {
        std::cerr << "lcc-conform: unknown command '" << command << "' (see --help)\n";
        return false;
    }
    if ((command == "restore" || command == "backup") && args.size() != 2) {
        std::cerr << "lcc-conform: " << command << " wants exactly one FILE\n";
        return false;
    }
    if (command == "diff" &&
        (args.size() < 2 || args.size() > 3 || (args.size() == 3 && vm.count("node")))) {
        std::cerr << "lcc-conform: diff wants two FILEs, or --node ID and one FILE\n";
        return false;
    }
    if (command == "decode" && args.size() != 2) {
        std::cerr << "lcc-conform: decode wants exactly one FILE ('-' for standard input)\n";
        return false;
    }
    return true;
}

int main_checked(int argc, char** argv) {
    po::options_description opts("options");
    opts.add(transport_options()).add(check_options());
    po::options_description hidden;
    hidden.add_options()("args", po::value<std::vector<std::string>>(), "subcommand and file");
    po::options_description all;
    all.add(opts).add(hidden);
    po::positional_options_description pos;
    pos.add("args", -1);
    po::variables_map vm;
    try {
        po::store(po::command_line_parser(argc, argv).options(all).positional(pos).run(), vm);
        po::notify(vm);
    } catch (const std::exception& e) {
        std::cerr << "lcc-conform: " << e.what() << "\n";
        return kUsage;
    }
    if (auto answered = answer_without_a_run(vm, opts)) return *answered;
    if (!options_usable(vm)) return kUsage;
    std::vector<std::string> args;
    if (vm.count("args")) args = vm["args"].as<std::vector<std::string>>();
    const std::string command = args.empty() ? "check" : args[0];
    if (!command_usable(command, args, vm)) return kUsage;
    if (command == "decode") {
        return run_decode(args[1], std::cin, std::cout, std::cerr);  // needs no link
    }
    if (command == "diff" && args.size() == 3) {
        return run_diff_files(args[1], args[2], std::cout, std::cerr);  // needs no link
    }
    const Reports reports(vm, argc, argv);
    std::string error;
    if (command == "check" && !reports.writable(error)) {
        // Said once: the reports cannot be written, so none is tried again.
        std::cerr << "lcc-conform: " << error << "\n";
        return kUsage;
    }
    const NodeId tool = pick_tool_id(vm, error);
    if (tool.is_zero()) return reports.fail("--tool-id: " + error);
    auto link = open_link(vm, tool, error);
    if (!link) return reports.fail(error);
    Session session(*link);
    if (!session.start()) return reports.fail("could not join the network (no alias)");

    if (command != "check") return backup_command(session, command, args, vm);
    auto nodes = find_nodes(session, vm, error);
    if (nodes.empty()) return reports.fail(error);
    if (vm.count("list")) return list_nodes(session, nodes);
    return check_nodes(session, *link, nodes, vm, reports);
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return main_checked(argc, argv);
    } catch (const std::exception& e) {
        // Never a silent abort: the user must know the node may hold test values (the safety
        // backup file says what to restore).
        std::cerr << "lcc-conform: internal error: " << e.what() << "\n";
        return kUsage;
    }
}
