#include "simnode/scenario.hpp"

#include <boost/program_options.hpp>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>
#include <unordered_set>

#include "base/bounded_read.hpp"
#include "base/file.hpp"
#include "cdi/parser.hpp"
#include "cdi/schema_validator.hpp"
#include "openlcb/asio.hpp"
#include "openlcb/can_defs.hpp"
#include "openlcb/can_timing.hpp"
#include "simnode/scenario_lookup.hpp"

namespace olcb::simnode {
namespace {

namespace po = boost::program_options;
namespace fs = std::filesystem;

// The fault the process-wide `latency` key gives every node without its own.
constexpr std::string_view kLatency = "latency";

// Keys a node group may set (top level, or a [node.NAME] section).
constexpr std::string_view kNodeKeys[] = {
    "node-id",
    "count",
    "cdi",
    "image-dir",
    "manufacturer",
    "model",
    "hardware-version",
    "software-version",
    "user-name",
    "user-description",
    "fault",
    "watch-variable",
    "streams",
    "memory-config",
    "train-address",
    "train-protocol",
    "fdi",
    "heartbeat",
    "command-station",
    "clock",
};
// Keys of the whole process (top level only).
constexpr std::string_view kProcessKeys[] = {"listen",
                                             "connect",
                                             "socketcan",
                                             "serial",
                                             "baud",
                                             "flow-control",
                                             "trace",
                                             "candump",
                                             "run-for",
                                             "latency",
                                             "bitrate",  // CAN bit timing of the whole segment
                                             "start-on-connect",
                                             "max-clients",
                                             "max-clients-per-address",
                                             "idle-timeout",
                                             "log-max-bytes",
                                             "control",
                                             "control-remote",
                                             "audit",  // the client audit (docs/audit.md)
                                             "audit-junit"};
// A network of this many nodes is already far beyond any real CAN segment.
constexpr std::uint64_t kMaxCount = 100000;
// Faster than any UART a USB-CAN adapter uses; above it a typo is more likely than a rate.
constexpr unsigned long kMaxBaud = 12'000'000;
// The CAN bit rates of real segments: 10 kbit/s (the slowest CiA rate) to 1 Mbit/s (classic
// CAN's top); OpenLCB uses 125 kbit/s.
constexpr std::uint64_t kMinBitrate = 10'000;
constexpr std::uint64_t kMaxBitrate = 1'000'000;
constexpr std::string_view kSectionPrefix = "node.";

bool contains(std::span<const std::string_view> keys, std::string_view key) {
    return std::find(keys.begin(), keys.end(), key) != keys.end();
}

struct Value {
    std::vector<std::string> items;
    fs::path base;  // directory relative paths are resolved against (empty: as given)
};
using Keys = std::map<std::string, Value, std::less<>>;

// Options from one source (file or command line), before merging.
struct Raw {
    Keys top;
    std::vector<std::pair<std::string, Keys>> sections;  // in file order

    Keys& section(const std::string& name) {
        for (auto& [n, keys] : sections) {
            if (n == name) return keys;
        }
        sections.emplace_back(name, Keys{});
        return sections.back().second;
    }
};

bool add_option(Raw& raw, const std::string& key, std::vector<std::string> values,
                const fs::path& base, std::string_view where, std::string& error) {
    Keys* keys = &raw.top;
    std::string field = key;
    if (key.starts_with(kSectionPrefix)) {
        const auto dot = key.rfind('.');
        const std::string name = key.substr(kSectionPrefix.size(), dot - kSectionPrefix.size());
        field = key.substr(dot + 1);
        if (dot < kSectionPrefix.size() || name.empty()) {
            error = std::string(where) + ": '" + key + "' is not a key of a [node.NAME] section";
            return false;
        }
        if (!contains(kNodeKeys, field)) {
            error =
                std::string(where) + ": unknown key '" + field + "' in section [node." + name + "]";
            return false;
        }
        keys = &raw.section(name);
    } else if (!contains(kNodeKeys, key) && !contains(kProcessKeys, key)) {
        error = std::string(where) + ": unknown key '" + key + "'";
        return false;
    }
    if (values.empty()) values.emplace_back();
    auto [it, fresh] = keys->try_emplace(field, Value{{}, base});
    if (!fresh && field != "fault" && field != "clock") {
        error = std::string(where) + ": '" + key + "' is given twice";
        return false;
    }
    for (auto& v : values) it->second.items.push_back(std::move(v));
    return true;
}

po::options_description general_options() {
    po::options_description general("General");
    general.add_options()("help,h", "print this help and exit")(
        "version", "print the program's version and exit")(
        "list-faults", po::value<std::string>()->implicit_value("")->value_name("FORMAT"),
        "print every fault and exit; --list-faults=markdown prints docs/faults.md's table, "
        "=json the declarations")(
        "list-scenarios", "print the name and file of every scenario --scenario finds by name")(
        "scenario", po::value<std::string>()->value_name("FILE|NAME"),
        "scenario .ini file, or the name of one (--list-scenarios; e.g. io-board, "
        "faults/int-byte-order); also accepted as the only positional argument")(
        "run-for", po::value<std::string>()->value_name("SECONDS"),
        "stop cleanly after SECONDS (default: run until SIGINT/SIGTERM)");
    return general;
}

po::options_description node_options() {
    po::options_description node("Node (top level, or a [node.NAME] section)");
    node.add_options()("node-id", po::value<std::string>()->value_name("ID"),
                       "node ID, e.g. 05.01.01.01.22.00 (the first one when count > 1)")(
        "count", po::value<std::string>()->value_name("N"),
        "run N nodes with consecutive node IDs (default 1)")(
        "cdi", po::value<std::string>()->value_name("FILE"), "CDI XML file the node serves")(
        "image-dir", po::value<std::string>()->value_name("DIR"),
        "memory images go to DIR/<node id>/ (default: $TMPDIR/simnode-images/<scenario>)")(
        "manufacturer", po::value<std::string>(), "identity (default: CDI <identification>)")(
        "model", po::value<std::string>(), "identity (default: CDI <identification>)")(
        "hardware-version", po::value<std::string>(), "identity (default: CDI <identification>)")(
        "software-version", po::value<std::string>(), "identity (default: CDI <identification>)")(
        "user-name", po::value<std::string>(),
        "initial user name of a fresh image ({n} = index, {id} = node ID)")(
        "user-description", po::value<std::string>(),
        "initial user description of a fresh image ({n}, {id} as above)")(
        "fault", po::value<std::vector<std::string>>()->value_name("NAME"),
        "misbehave as NAME (repeatable; see --list-faults, docs/faults.md)")(
        "watch-variable", po::value<std::string>()->value_name("NAME"),
        "the variable abort-on-value and factory-reset-on-version-change watch, as "
        "lcc-cdi layout names it (default: the first <int> of space 253)")(
        "memory-config", po::value<std::string>()->value_name("BOOL"),
        "serve Memory Configuration and the CDI (default true; false = a node such as a "
        "throttle: its PIP has neither, memory-config datagrams are rejected 0x1042, the CDI "
        "file gives only SNIP strings and events)")(
        "streams", po::value<std::string>()->value_name("BOOL"),
        "serve memory-config stream reads and accept streams (default true; false = "
        "datagram-only, as a node without stream support)")(
        "train-address", po::value<std::string>()->value_name("N"),
        "make it a train node with this address (the next ones N+1, ... with count): "
        "Traction Control, Is Train, Train Search answered, functions in 0xF9")(
        "train-protocol", po::value<std::string>()->value_name("dcc|dcc-long|dcc-short|native|mm"),
        "the train's track protocol (default dcc: long from address 128 on)")(
        "fdi", po::value<std::string>()->value_name("FILE"),
        "a train's (or a command station's trains') FDI XML, served in 0xFA (PIP FDI bit)")(
        "heartbeat", po::value<std::string>()->value_name("SECONDS"),
        "a train asks its controller for a sign of life after SECONDS of silence while moving, "
        "and stops when none comes in SECONDS (0..255; default 0 = never)")(
        "command-station", po::value<std::string>()->value_name("BOOL"),
        "a command station: an allocating Train Search creates a train node (default false)")(
        "clock", po::value<std::vector<std::string>>()->value_name("SPEC"),
        "run a Broadcast Time clock (repeatable): 'generator|consumer [default-fast|"
        "default-realtime|alternate-1|alternate-2|ID] [rate=R] [time=YYYY-MM-DDTHH:MM|now] "
        "[stopped]' (docs/scenarios.md)");
    return node;
}

po::options_description transport_options() {
    po::options_description transport("Transports and logs (top level)");
    transport.add_options()("listen", po::value<std::string>()->value_name("HOST:PORT"),
                            "run a GridConnect TCP hub (port 0 = any free port; "
                            "a bare PORT binds 127.0.0.1)")(
        "connect", po::value<std::string>()->value_name("HOST:PORT"),
        "join a GridConnect TCP hub (reconnects when it goes away)")(
        "socketcan", po::value<std::string>()->value_name("IF"), "join SocketCAN interface IF")(
        "serial", po::value<std::string>()->value_name("DEVICE"),
        "join the CAN bus behind a GridConnect USB/serial adapter (e.g. /dev/ttyACM0)")(
        "baud", po::value<std::string>()->value_name("N"), "serial bit rate (default 115200)")(
        "flow-control", po::value<std::string>()->value_name("none|rtscts"),
        "serial flow control (default none)")(
        "trace", po::value<std::string>()->value_name("FILE"),
        "write decoded traffic to FILE ('-': standard output)")(
        "candump", po::value<std::string>()->value_name("FILE"),
        "write traffic to FILE as candump -L lines ('-': standard output)")(
        "max-clients", po::value<std::string>()->value_name("N"),
        "hub: refuse connections beyond N (default 64)")(
        "max-clients-per-address", po::value<std::string>()->value_name("N"),
        "hub: refuse connections from one address beyond N (default 48)")(
        "idle-timeout", po::value<std::string>()->value_name("SECONDS"),
        "hub: close a client that sent nothing for SECONDS (default 0 = never)")(
        "log-max-bytes", po::value<std::string>()->value_name("N"),
        "rotate the trace and candump files to FILE.1 before they grow past N bytes "
        "(default 67108864 = 64 MiB; 0 = never)");
    return transport;
}

po::options_description audit_options() {
    po::options_description audit("Client audit (top level, docs/audit.md)");
    audit.add_options()("audit", po::value<std::string>()->value_name("FILE"),
                        "record every protocol violation of the tools talking to the nodes in "
                        "FILE (JSON)")("audit-junit", po::value<std::string>()->value_name("FILE"),
                                       "the same as JUnit XML, one testcase per rule");
    return audit;
}

po::options_description testing_options() {
    po::options_description testing("Test hooks (top level)");
    testing.add_options()("latency", po::value<std::string>()->value_name("MS[:JITTER]"),
                          "every node answers MS ms (plus 0..JITTER ms) late, as the fault "
                          "latency=MS[:JITTER]; a node's own latency fault wins")(
        "bitrate", po::value<std::string>()->value_name("N"),
        "pace the segment (hub or in-process bus) as one CAN bus of N bit/s, "
        "10000..1000000, e.g. 125000 (default 0 = off; 125000 with socketcan)")(
        "start-on-connect", po::value<std::string>()->implicit_value("true")->value_name("BOOL"),
        "with listen: every node logs in again (CID..RID, AMD, Initialization Complete) "
        "whenever a TCP client connects");
    return testing;
}

po::options_description control_options() {
    po::options_description control("Live control (top level; docs/control.md)");
    control.add_options()("control", po::value<std::string>()->value_name("HOST:PORT"),
                          "take JSON-line control requests (list, faults, memory, reboot, add, "
                          "remove nodes) on HOST:PORT; a bare PORT binds 127.0.0.1")(
        "control-remote", po::value<std::string>()->implicit_value("true")->value_name("BOOL"),
        "let control bind an address other machines reach (anyone who connects can change "
        "every node)");
    return control;
}

po::options_description cli_options() {
    po::options_description all;
    all.add(general_options())
        .add(node_options())
        .add(transport_options())
        .add(audit_options())
        .add(testing_options())
        .add(control_options());
    return all;
}

struct CommandLine {
    Raw raw;
    std::optional<std::string> scenario;
    bool help = false;
    bool list_faults = false;
    std::string list_faults_format;
    bool version = false;
    bool list_scenarios = false;
};

std::optional<CommandLine> parse_command_line(std::span<const std::string> args,
                                              std::string& error) {
    CommandLine cl;
    po::positional_options_description positional;
    positional.add("scenario", 1);
    const auto desc = cli_options();
    po::parsed_options parsed(&desc);
    try {
        parsed = po::command_line_parser(std::vector<std::string>(args.begin(), args.end()))
                     .options(desc)
                     .positional(positional)
                     .allow_unregistered()
                     .run();
    } catch (const po::error& e) {
        error = e.what();
        return std::nullopt;
    }
    for (const auto& opt : parsed.options) {
        if (opt.string_key == "help") {
            cl.help = true;
        } else if (opt.string_key == "list-faults") {
            cl.list_faults = true;
            cl.list_faults_format = opt.value.empty() ? std::string() : opt.value.front();
        } else if (opt.string_key == "version") {
            cl.version = true;
        } else if (opt.string_key == "list-scenarios") {
            cl.list_scenarios = true;
        } else if (opt.string_key == "scenario") {
            if (cl.scenario) {
                error = "more than one scenario file given";
                return std::nullopt;
            }
            cl.scenario = opt.value.empty() ? std::string() : opt.value.front();
        } else if (opt.unregistered && !opt.string_key.starts_with(kSectionPrefix)) {
            error = "unknown option '" +
                    (opt.original_tokens.empty() ? opt.string_key : opt.original_tokens.front()) +
                    "' (see --help)";
            return std::nullopt;
        } else if (!add_option(cl.raw, opt.string_key, opt.value, {}, "command line", error)) {
            return std::nullopt;
        }
    }
    return cl;
}

std::optional<Raw> parse_ini(std::string_view text, const fs::path& base, std::string_view where,
                             std::string& error) {
    Raw raw;
    const po::options_description none;
    std::istringstream in{std::string(text)};
    po::parsed_options parsed(&none);
    try {
        parsed = po::parse_config_file(in, none, true);
    } catch (const po::error& e) {
        error = std::string(where) + ": " + e.what();
        return std::nullopt;
    }
    for (const auto& opt : parsed.options) {
        if (!add_option(raw, opt.string_key, opt.value, base, where, error)) return std::nullopt;
    }
    return raw;
}

// The command line replaces a file's values key by key; faults accumulate.
void merge_keys(Keys& into, const Keys& over) {
    for (const auto& [key, value] : over) {
        auto [it, fresh] = into.try_emplace(key, value);
        if (fresh) continue;
        if (key == "fault") {
            it->second.items.insert(it->second.items.end(), value.items.begin(), value.items.end());
        } else {
            it->second = value;
        }
    }
}

const std::string* single(const Keys& keys, std::string_view key) {
    const auto it = keys.find(key);
    if (it == keys.end() || it->second.items.empty()) return nullptr;
    return &it->second.items.back();
}

fs::path path_of(const Keys& keys, std::string_view key) {
    const auto it = keys.find(key);
    if (it == keys.end() || it->second.items.empty()) return {};
    fs::path p = it->second.items.back();
    if (p == "-") return p;  // standard output (--trace -, --candump -), not a file named "-"
    if (p.is_relative() && !it->second.base.empty()) p = it->second.base / p;
    return p.lexically_normal();
}

std::string expand(std::string text, std::uint64_t index, NodeId id) {
    const auto replace_all = [&text](std::string_view what, const std::string& with) {
        for (auto pos = text.find(what); pos != std::string::npos;
             pos = text.find(what, pos + with.size())) {
            text.replace(pos, what.size(), with);
        }
    };
    replace_all("{n}", std::to_string(index));
    replace_all("{id}", id.to_string());
    return text;
}

std::optional<std::uint64_t> parse_count(const std::string& text) {
    std::uint64_t v = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || ptr != text.data() + text.size() || v == 0 || v > kMaxCount) {
        return std::nullopt;
    }
    return v;
}

// A byte count, 0 allowed (no upper bound beyond 64 bits: any file size is plausible).
std::optional<std::uint64_t> parse_bytes(const std::string& text) {
    std::uint64_t v = 0;
    const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc() || ptr != text.data() + text.size()) return std::nullopt;
    return v;
}

std::optional<double> parse_seconds(const std::string& text) {
    double seconds = -1;
    try {
        std::size_t used = 0;
        seconds = std::stod(text, &used);
        if (used != text.size()) return std::nullopt;
    } catch (const std::exception&) {
        return std::nullopt;
    }
    if (!(seconds >= 0) || !std::isfinite(seconds)) return std::nullopt;
    return seconds;
}

std::optional<bool> parse_bool(const std::string& text) {
    if (text.empty()) return true;  // a bare --start-on-connect
    if (text == "true" || text == "yes" || text == "on" || text == "1") return true;
    if (text == "false" || text == "no" || text == "off" || text == "0") return false;
    return std::nullopt;
}

class Builder {
public:
    Builder(Scenario& scenario, std::string& error) : scenario_(scenario), error_(error) {}

    bool group(const std::string& name, const Keys& keys, const fs::path& default_root) {
        const std::string where = name.empty() ? "node" : "[node." + name + "]";
        Group g;
        if (!ids_of(keys, where, g) || !cdi_of(keys, where, g)) return false;
        g.root = path_of(keys, "image-dir");
        if (g.root.empty()) g.root = default_root;
        if (single(keys, "manufacturer") || single(keys, "model") ||
            single(keys, "hardware-version") || single(keys, "software-version")) {
            g.identity = identity_of(*g.cdi, keys);
        }
        return faults_of(keys, where, g) && train_of(keys, where, g) && add_nodes(keys, where, g);
    }

    bool process(const Keys& keys) {
        using Read = bool (Builder::*)(const std::string& value, const Keys& keys);
        // In the order they are checked: the first bad key is the one reported. control-remote
        // comes before control, which needs it.
        static constexpr std::pair<std::string_view, Read> kReaders[] = {
            {"listen", &Builder::read_listen},
            {"connect", &Builder::read_connect},
            {"socketcan", &Builder::read_socketcan},
            {"serial", &Builder::read_serial},
            {"baud", &Builder::read_baud},
            {"flow-control", &Builder::read_flow_control},
            {"max-clients", &Builder::read_max_clients},
            {"max-clients-per-address", &Builder::read_max_clients_per_address},
            {"idle-timeout", &Builder::read_idle_timeout},
            {"latency", &Builder::read_latency},
            {"control-remote", &Builder::read_control_remote},
            {"control", &Builder::read_control},
            {"bitrate", &Builder::read_bitrate},
            {"start-on-connect", &Builder::read_start_on_connect},
            {"trace", &Builder::read_trace},
            {"candump", &Builder::read_candump},
            {"audit", &Builder::read_audit},
            {"audit-junit", &Builder::read_audit_junit},
            {"log-max-bytes", &Builder::read_log_max_bytes},
            {"run-for", &Builder::read_run_for},
        };
        for (const auto& [key, read] : kReaders) {
            if (const auto* v = single(keys, key); v && !(this->*read)(*v, keys)) return false;
        }
        return true;
    }

private:
    // The process keys' readers (see process()): each one has its key's value.
    bool read_listen(const std::string& v, const Keys&) {
        std::string why;
        scenario_.listen = parse_host_port(v, why);
        return scenario_.listen || fail("listen: " + why);
    }

    bool read_connect(const std::string& v, const Keys&) {
        std::string why;
        scenario_.connect = parse_host_port(v, why);
        if (!scenario_.connect) return fail("connect: " + why);
        return scenario_.connect->port != 0 || fail("connect: port 0 is not a port");
    }

    bool read_socketcan(const std::string& v, const Keys&) {
        scenario_.socketcan = v;
        return true;
    }

    bool read_serial(const std::string& v, const Keys&) {
        scenario_.serial = v;
        return true;
    }

    bool read_baud(const std::string& v, const Keys&) {
        unsigned long baud = 0;
        const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), baud);
        if (ec != std::errc() || end != v.data() + v.size() || baud == 0 || baud > kMaxBaud) {
            return fail("baud '" + v + "' must be a bit rate such as 115200");
        }
        scenario_.baud = static_cast<unsigned>(baud);
        return true;
    }

    bool read_flow_control(const std::string& v, const Keys&) {
        if (v != "none" && v != "rtscts")
            return fail("flow-control '" + v + "' must be none or rtscts");
        scenario_.rtscts = v == "rtscts";
        return true;
    }

    bool read_client_limit(std::string_view key, const std::string& v, std::size_t& field) {
        const auto n = parse_count(v);
        if (!n) return fail(std::string(key) + " '" + v + "' must be a whole number >= 1");
        field = static_cast<std::size_t>(*n);
        return true;
    }

    bool read_max_clients(const std::string& v, const Keys&) {
        return read_client_limit("max-clients", v, scenario_.max_clients);
    }

    bool read_max_clients_per_address(const std::string& v, const Keys&) {
        return read_client_limit("max-clients-per-address", v, scenario_.max_clients_per_address);
    }

    bool read_idle_timeout(const std::string& v, const Keys&) {
        const auto seconds = parse_seconds(v);
        if (!seconds) return fail("idle-timeout '" + v + "' must be a number of seconds >= 0");
        scenario_.idle_timeout = *seconds;
        return true;
    }

    bool read_latency(const std::string& v, const Keys&) {
        std::string why;
        const auto parsed = parse_faults({std::string(kLatency) + "=" + v}, why);
        if (!parsed) return fail("latency '" + v + "' must be MS or MS:JITTER (milliseconds)");
        latency_ = *parsed;
        scenario_.latency = v;
        return true;
    }

    bool read_control_remote(const std::string& v, const Keys&) {
        const auto on = parse_bool(v);
        if (!on) return fail("control-remote '" + v + "' must be true or false");
        scenario_.control_remote = *on;
        return true;
    }

    // Control changes every node: it listens where other machines reach it only when told so.
    bool read_control(const std::string& v, const Keys&) {
        std::string why;
        scenario_.control = parse_host_port(v, why);
        if (!scenario_.control) return fail("control: " + why);
        boost::system::error_code ec;
        const auto ip = boost::asio::ip::make_address(scenario_.control->host, ec);
        if (ec) return fail("control: '" + scenario_.control->host + "' is not a numeric address");
        if (!ip.is_loopback() && !scenario_.control_remote) {
            return fail("control: " + scenario_.control->host +
                        " is not a loopback address; give control-remote = true "
                        "(--control-remote) to let other machines change the nodes");
        }
        return true;
    }

    bool read_bitrate(const std::string& v, const Keys&) {
        const auto n = parse_bytes(v);
        if (!n || (*n != 0 && (*n < kMinBitrate || *n > kMaxBitrate))) {
            return fail("bitrate '" + v + "' must be 0 (off) or 10000..1000000 bit/s");
        }
        scenario_.bitrate = static_cast<std::uint32_t>(*n);
        return true;
    }

    bool read_start_on_connect(const std::string& v, const Keys&) {
        const auto on = parse_bool(v);
        if (!on) return fail("start-on-connect '" + v + "' must be true or false");
        scenario_.start_on_connect = *on;
        return true;
    }

    // Paths are resolved against the directory of the file that gave them.
    bool read_trace(const std::string&, const Keys& keys) {
        scenario_.trace = path_of(keys, "trace");
        return true;
    }

    bool read_candump(const std::string&, const Keys& keys) {
        scenario_.candump = path_of(keys, "candump");
        return true;
    }

    bool read_audit(const std::string&, const Keys& keys) {
        scenario_.audit = path_of(keys, "audit");
        return true;
    }

    bool read_audit_junit(const std::string&, const Keys& keys) {
        scenario_.audit_junit = path_of(keys, "audit-junit");
        return true;
    }

    bool read_log_max_bytes(const std::string& v, const Keys&) {
        const auto n = parse_bytes(v);
        if (!n) return fail("log-max-bytes '" + v + "' must be a whole number of bytes >= 0");
        scenario_.log_max_bytes = *n;
        return true;
    }

    bool read_run_for(const std::string& v, const Keys&) {
        const auto seconds = parse_seconds(v);
        if (!seconds) return fail("run-for '" + v + "' must be a number of seconds >= 0");
        scenario_.run_for = seconds;
        return true;
    }

    // What a node group's keys say, shared by each of its nodes.
    struct Group {
        NodeId base;
        std::uint64_t count = 1;
        fs::path cdi_path;
        const std::string* cdi = nullptr;
        fs::path root;  // where the nodes' image directories go
        std::optional<Identity> identity;
        FaultSet faults;
        std::optional<TrainConfig> train;            // train-address given
        std::optional<TrainConfig> command_station;  // command-station = true
    };

    // node-id and count: the group's first node ID and how many follow it.
    bool ids_of(const Keys& keys, const std::string& where, Group& g) {
        const std::string* id_text = single(keys, "node-id");
        if (!id_text) return fail(where + ": node-id is missing");
        std::string why;
        const auto base = NodeId::parse(*id_text, &why);
        if (!base || base->is_zero()) {
            return fail(where + ": node-id '" + *id_text +
                        "': " + (why.empty() ? "must not be zero" : why));
        }
        g.base = *base;
        if (const auto* c = single(keys, "count")) {
            const auto v = parse_count(*c);
            if (!v) {
                return fail(where + ": count '" + *c + "' must be a whole number 1.." +
                            std::to_string(kMaxCount));
            }
            g.count = *v;
        }
        if (g.base.value() + (g.count - 1) > NodeId::kMask) {
            return fail(where + ": node IDs run past FF.FF.FF.FF.FF.FF");
        }
        return true;
    }

    bool cdi_of(const Keys& keys, const std::string& where, Group& g) {
        g.cdi_path = path_of(keys, "cdi");
        if (g.cdi_path.empty()) return fail(where + ": cdi is missing");
        std::string why;
        g.cdi = read_cdi(g.cdi_path, why);
        return g.cdi || fail(where + ": CDI file: " + why);
    }

    // The group's faults; without a latency of its own it takes the process-wide one.
    bool faults_of(const Keys& keys, const std::string& where, Group& g) {
        std::vector<std::string> fault_list;
        if (const auto it = keys.find("fault"); it != keys.end()) {
            for (const auto& f : it->second.items) {
                if (!f.empty()) fault_list.push_back(f);
            }
        }
        std::string fault_error;
        auto faults = parse_faults(fault_list, fault_error);
        if (!faults) return fail(where + ": " + fault_error);
        if (faults->value(kLatency) == FaultValue{} && latency_.value(kLatency) != FaultValue{}) {
            faults->by_name.emplace(kLatency, latency_.value(kLatency));
        }
        g.faults = *faults;
        return true;
    }

    // train-protocol's value: the protocol and whether the address is a long one (nullopt: from
    // the address).
    static std::optional<std::pair<train_search::TrackProtocol, std::optional<bool>>> protocol_of(
        const std::string& v) {
        using P = train_search::TrackProtocol;
        if (v == "dcc") return std::pair{P::kDcc, std::optional<bool>{}};
        if (v == "dcc-long") return std::pair{P::kDcc, std::optional<bool>{true}};
        if (v == "dcc-short") return std::pair{P::kDcc, std::optional<bool>{false}};
        if (v == "native") return std::pair{P::kNative, std::optional<bool>{}};
        if (v == "mm") return std::pair{P::kMarklinMotorola, std::optional<bool>{}};
        return std::nullopt;
    }

    // The train keys: train-address, train-protocol, fdi, heartbeat, command-station.
    bool train_of(const Keys& keys, const std::string& where, Group& g) {
        TrainConfig train;
        if (const auto* v = single(keys, "heartbeat")) {
            const auto n = parse_bytes(*v);
            if (!n || *n > 255) return fail(where + ": heartbeat '" + *v + "' must be 0..255 s");
            train.heartbeat = static_cast<std::uint8_t>(*n);
        }
        train.fdi_file = path_of(keys, "fdi");
        if (!train.fdi_file.empty()) {
            std::string why;
            auto text = base::read_bounded_file(train.fdi_file, cdi::kMaxCdiBytes,
                                                base::Streams::kRefuse, why);
            if (!text) return fail(where + ": FDI file: " + why);
            train.fdi = std::move(*text);
        }
        const std::string* station = single(keys, "command-station");
        const auto station_on = station ? parse_bool(*station) : std::optional<bool>(false);
        if (!station_on)
            return fail(where + ": command-station '" + *station + "' must be true or false");
        const std::string* address = single(keys, "train-address");
        if (*station_on && address)
            return fail(where +
                        ": a command station is no train: give train-address to its "
                        "trains, not to it");
        if (*station_on) g.command_station = train;
        if (!address) return true;
        const auto a = parse_bytes(*address);
        if (!a || *a > 999999)
            return fail(where + ": train-address '" + *address +
                        "' must be a whole number 0..999999");
        train.identity.address = static_cast<std::uint32_t>(*a);
        std::optional<bool> long_form;
        if (const auto* p = single(keys, "train-protocol")) {
            const auto proto = protocol_of(*p);
            if (!proto)
                return fail(where + ": train-protocol '" + *p +
                            "' must be dcc, dcc-long, dcc-short, native or mm");
            train.identity.protocol = proto->first;
            long_form = proto->second;
        }
        train.identity.long_address = long_form.value_or(*a >= 128);
        g.train = train;
        return true;
    }

    bool add_nodes(const Keys& keys, const std::string& where, const Group& g) {
        const std::string* user_name = single(keys, "user-name");
        const std::string* user_description = single(keys, "user-description");
        const std::string* watch = single(keys, "watch-variable");
        const std::string* streams = single(keys, "streams");
        const auto streams_on = streams ? parse_bool(*streams) : std::optional<bool>(true);
        if (!streams_on) return fail(where + ": streams '" + *streams + "' must be true or false");
        const std::string* memory = single(keys, "memory-config");
        const auto memory_on = memory ? parse_bool(*memory) : std::optional<bool>(true);
        if (!memory_on)
            return fail(where + ": memory-config '" + *memory + "' must be true or false");
        std::vector<ClockConfig> clocks;
        if (const auto it = keys.find("clock"); it != keys.end()) {
            const auto wall =
                std::chrono::floor<std::chrono::minutes>(std::chrono::system_clock::now());
            for (const auto& spec : it->second.items) {
                std::string why;
                auto c = parse_clock_config(spec, FastTime{wall}, why);
                if (!c) return fail(std::string(where).append(": ").append(why));
                clocks.push_back(*c);
            }
        }
        // More would contend for an alias for ever (issue 32: 5,000 nodes never started).
        if (const std::uint64_t total = scenario_.nodes.size() + g.count;
            total > can::kAliasCount) {
            return fail(where + ": " + std::to_string(total) + " nodes on one segment, more than " +
                        "its " + std::to_string(can::kAliasCount) + " aliases (one per node)");
        }
        for (std::uint64_t k = 0; k < g.count; ++k) {
            NodeConfig config;
            config.node_id = NodeId(g.base.value() + k);
            if (!ids_.insert(config.node_id).second) {
                return fail(where + ": node ID " + config.node_id.to_string() +
                            " is used by another node");
            }
            config.cdi = *g.cdi;
            config.cdi_file = g.cdi_path;
            config.image_dir = g.root / config.node_id.to_string();
            config.identity = g.identity;
            if (user_name) config.user_name = expand(*user_name, k + 1, config.node_id);
            if (user_description) {
                config.user_description = expand(*user_description, k + 1, config.node_id);
            }
            config.faults = g.faults;
            if (watch) config.watch_variable = *watch;
            config.streams = *streams_on && *memory_on;
            config.memory_config = *memory_on;
            if (g.train) {
                config.train = g.train;
                config.train->identity.address += static_cast<std::uint32_t>(k);
            }
            config.command_station = g.command_station;
            config.clocks = clocks;
            scenario_.nodes.push_back(std::move(config));
        }
        return true;
    }

    bool fail(std::string message) {
        error_ = std::move(message);
        return false;
    }

    const std::string* read_cdi(const fs::path& path, std::string& error) {
        const auto key = path.string();
        if (const auto it = cdis_.find(key); it != cdis_.end()) return &it->second;
        // A control request names the file too: a FIFO or /dev/zero must not stall or fill the
        // io thread, so only a regular file is read, and never past the limit.
        auto text = base::read_bounded_file(path, cdi::kMaxCdiBytes, base::Streams::kRefuse, error);
        if (!text) return nullptr;
        return &cdis_.emplace(key, std::move(*text)).first->second;
    }

    // Identity keys given override the CDI's <identification>; the rest come from it.
    static Identity identity_of(const std::string& cdi, const Keys& keys) {
        Identity id;
        if (const auto parsed = cdi::parse(cdi);
            parsed.document && parsed.document->identification) {
            const auto& ident = *parsed.document->identification;
            id.manufacturer = ident.manufacturer;
            id.model = ident.model;
            id.hardware_version = ident.hardware_version;
            id.software_version = ident.software_version;
        }
        if (const auto* v = single(keys, "manufacturer")) id.manufacturer = *v;
        if (const auto* v = single(keys, "model")) id.model = *v;
        if (const auto* v = single(keys, "hardware-version")) id.hardware_version = *v;
        if (const auto* v = single(keys, "software-version")) id.software_version = *v;
        return id;
    }

    Scenario& scenario_;
    std::string& error_;
    FaultSet latency_;  // the process-wide latency key; only the latency fault is set
    std::map<std::string, std::string> cdis_;
    std::unordered_set<NodeId> ids_;
};

std::optional<Scenario> build(const Raw& file, const Raw& cli, const fs::path& scenario_file,
                              std::string& error) {
    Raw merged = file;
    // A tool developer pointing a hub scenario at another hub wants a client, not a second hub.
    if (cli.top.contains("connect") && !cli.top.contains("listen")) merged.top.erase("listen");
    merge_keys(merged.top, cli.top);
    for (const auto& [name, keys] : cli.sections) merge_keys(merged.section(name), keys);

    Scenario scenario;
    scenario.scenario_file = scenario_file;
    const std::string stem = scenario_file.empty() ? "inline" : scenario_file.stem().string();
    std::error_code ec;
    fs::path tmp = fs::temp_directory_path(ec);
    if (ec) tmp = "/tmp";
    const fs::path default_root = tmp / "simnode-images" / stem;

    const fs::path top_image_dir = path_of(merged.top, "image-dir");
    scenario.image_root = top_image_dir.empty() ? default_root : top_image_dir;
    Builder builder(scenario, error);
    if (!builder.process(merged.top)) return std::nullopt;
    // A vcan carries frames as fast as they are written, far faster than any CAN bus; a reader
    // with the kernel's default receive queue (OpenMRN's hub -s vcan0) then loses the frames of a
    // stream. On SocketCAN the segment runs at LCC's bit rate unless bitrate says otherwise.
    if (!scenario.socketcan.empty() && !merged.top.contains("bitrate")) {
        scenario.bitrate = kLccBitrate;
    }
    if (merged.sections.empty()) {
        if (!builder.group("", merged.top, default_root)) return std::nullopt;
    } else {
        // Top-level node keys are defaults of every section.
        for (const auto& [name, keys] : merged.sections) {
            Keys group;
            for (const auto& [key, value] : merged.top) {
                if (contains(kNodeKeys, key)) group.emplace(key, value);
            }
            merge_keys(group, keys);
            if (!builder.group(name, group, default_root)) return std::nullopt;
        }
    }
    return scenario;
}

// The scenario file the command line names: a path, or a name under scenario_dirs (so
// `simnode faults/int-byte-order` works from anywhere, installed or built); "default" when it
// names none and gives no node inline. Empty without error: everything is inline.
std::optional<fs::path> scenario_file(const CommandLine& cl, std::span<const fs::path> dirs,
                                      std::string& error) {
    if (!cl.scenario && (cl.raw.top.contains("node-id") || !cl.raw.sections.empty())) {
        return fs::path();
    }
    const std::string given = cl.scenario.value_or("default");
    if (auto found = find_scenario(given, dirs)) return found;
    if (cl.scenario) {
        error = "no scenario '" + given + "': no such file, nor a name of --list-scenarios";
    } else {
        error = "no scenario: give a scenario file, or --node-id and --cdi (see --help)";
    }
    return std::nullopt;
}

}  // namespace

std::string help_text() {
    std::ostringstream out;
    out << "usage: simnode [--scenario] [FILE.ini] [OPTIONS]\n"
           "       simnode ctl HOST:PORT COMMAND [ARGS...]   (live control; simnode ctl --help)\n"
           "Runs simulated OpenLCB nodes. Without a scenario and without --node-id it runs the\n"
           "scenario named default. Every option is also a key of the .ini file; keys of a\n"
           "[node.NAME] section are given on the command line as --node.NAME.KEY=VALUE.\n"
           "See docs/scenarios.md.\n";
    out << cli_options();
    return out.str();
}

std::optional<Arguments> parse_arguments(std::span<const std::string> args,
                                         std::span<const fs::path> scenario_dirs,
                                         std::string& error) {
    auto cl = parse_command_line(args, error);
    if (!cl) return std::nullopt;
    Arguments result;
    result.help = cl->help;
    result.list_faults = cl->list_faults;
    result.list_faults_format = cl->list_faults_format;
    result.version = cl->version;
    result.list_scenarios = cl->list_scenarios;
    if (result.help || result.list_faults || result.version || result.list_scenarios) {
        return result;
    }

    const auto found = scenario_file(*cl, scenario_dirs, error);
    if (!found) return std::nullopt;
    const fs::path& file = *found;
    Raw file_raw;
    if (!file.empty()) {
        const auto text = base::read_file(file, error);
        if (!text) {
            error = "scenario file: " + error;
            return std::nullopt;
        }
        std::error_code ec;
        const fs::path dir = fs::absolute(file, ec).parent_path();
        auto raw = parse_ini(*text, dir, file.string(), error);
        if (!raw) return std::nullopt;
        file_raw = std::move(*raw);
    }
    auto scenario = build(file_raw, cl->raw, file, error);
    if (!scenario) return std::nullopt;
    result.scenario = std::move(*scenario);
    return result;
}

std::optional<Scenario> parse_scenario_text(std::string_view ini, const fs::path& base_dir,
                                            std::span<const std::string> overrides,
                                            std::string& error) {
    auto raw = parse_ini(ini, base_dir, "scenario", error);
    if (!raw) return std::nullopt;
    auto cl = parse_command_line(overrides, error);
    if (!cl) return std::nullopt;
    return build(*raw, cl->raw, {}, error);
}

std::optional<std::vector<NodeConfig>> parse_node_group(std::span<const NodeKey> keys,
                                                        const Scenario& running,
                                                        std::string& error) {
    Raw raw;
    for (const auto& [key, values] : keys) {
        if (!contains(kNodeKeys, key)) {
            error = "'" + key + "' is not a node key (see docs/scenarios.md)";
            return std::nullopt;
        }
        if (!add_option(raw, key, values, {}, "node", error)) return std::nullopt;
    }
    Scenario out;
    Builder builder(out, error);
    if (!running.latency.empty()) {
        Keys process;
        process.emplace("latency", Value{{running.latency}, {}});
        if (!builder.process(process)) return std::nullopt;
    }
    if (!builder.group("", raw.top, running.image_root)) return std::nullopt;
    return std::move(out.nodes);
}

}  // namespace olcb::simnode
