// What one simnode process runs: its nodes and its transports, read from a scenario .ini file
// and the command line (every .ini key is also an option; docs/scenarios.md lists them all).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "base/host_port.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::simnode {

/// A TCP address as HOST:PORT (base/host_port.hpp); simnode's hosts are numeric addresses.
using base::HostPort;
/// Parses "HOST:PORT", "[V6]:PORT", "HOST" (port 12021) or a bare "PORT" (host 127.0.0.1).
using base::parse_host_port;

/// log-max-bytes when not given: 64 MiB, so about 128 MiB of each log stays on disk.
inline constexpr std::uint64_t kDefaultLogMaxBytes = std::uint64_t{64} * 1024 * 1024;

/// Everything one simnode process runs.
struct Scenario {
    std::vector<NodeConfig> nodes;    ///< every node, in scenario order; IDs are distinct
    std::optional<HostPort> listen;   ///< run a GridConnect TCP hub here
    std::optional<HostPort> connect;  ///< join this GridConnect TCP hub
    std::string socketcan;            ///< join this SocketCAN interface (empty: none)
    std::string serial;               ///< join this serial GridConnect adapter (empty: none)
    unsigned baud = 115200;           ///< the serial adapter's bit rate
    bool rtscts = false;              ///< hardware flow control on the serial adapter
    std::filesystem::path trace;      ///< decoded traffic log (empty: none)
    std::filesystem::path candump;    ///< candump -L traffic log (empty: none)
    /// trace/candump rotate to FILE.1 past this (0 = never); by default a log left running for
    /// days stays bounded.
    std::uint64_t log_max_bytes = kDefaultLogMaxBytes;
    std::optional<double> run_for;             ///< stop after this many seconds
    std::size_t max_clients = 64;              ///< hub connections beyond are refused
    std::size_t max_clients_per_address = 48;  ///< hub connections from one address
    double idle_timeout = 0;                   ///< seconds; a silent client is closed (0 = never)
    std::uint32_t bitrate = 0;  ///< pace the segment at CAN bit timing, bit/s (0 = off)
    /// Every TCP client connecting to the hub makes every node log in again (needs listen).
    bool start_on_connect = false;
    std::filesystem::path scenario_file;  ///< the .ini read (empty: everything inline)
    std::optional<HostPort> control;      ///< take live-control requests here (docs/control.md)
    bool control_remote = false;          ///< control may bind a non-loopback address
    /// Where node groups without image-dir keep their images: the top-level image-dir, else
    /// $TMPDIR/simnode-images/<scenario name>.
    std::filesystem::path image_root;
    std::string latency;  ///< the latency key as given ("" = none); added nodes get it too
    /// The client audit as JSON (empty: none; docs/audit.md).
    std::filesystem::path audit;
    /// The client audit as JUnit XML (empty: none).
    std::filesystem::path audit_junit;
};

/// What the command line asks for.
struct Arguments {
    bool help = false;         ///< --help: print help_text() and exit
    bool list_faults = false;  ///< --list-faults: print fault_names() and exit
    /// --list-faults=FORMAT: "" (one line per fault), "markdown" or "json".
    std::string list_faults_format;
    bool version = false;         ///< --version: print the program's version and exit
    bool list_scenarios = false;  ///< --list-scenarios: print scenario_names() and exit
    Scenario scenario;            ///< filled unless help or list_faults
};

/// The --help text (usage line and every option).
std::string help_text();

/// Parses the command line (args without the program name). The scenario is --scenario, else a
/// positional argument: a path, or a name looked up in scenario_dirs (scenario_lookup.hpp); else
/// (when no node-id is given inline) the name "default". Command-line values override the
/// file's (fault values are added).
std::optional<Arguments> parse_arguments(std::span<const std::string> args,
                                         std::span<const std::filesystem::path> scenario_dirs,
                                         std::string& error);

/// Reads a scenario from .ini text whose relative paths are relative to base_dir, then applies
/// overrides (command-line style arguments, e.g. {"--listen", "127.0.0.1:0"}).
std::optional<Scenario> parse_scenario_text(std::string_view ini,
                                            const std::filesystem::path& base_dir,
                                            std::span<const std::string> overrides,
                                            std::string& error);

/// One node key and its values, as a [node.NAME] section or the command line gives it.
using NodeKey = std::pair<std::string, std::vector<std::string>>;

/// The nodes one group of node keys describes ("node-id", "cdi", "fault", ...; relative paths
/// relative to the working directory) as a node group of the running scenario would be: its
/// image_root and latency apply. nullopt plus a sentence on an unknown key or a bad value.
std::optional<std::vector<NodeConfig>> parse_node_group(std::span<const NodeKey> keys,
                                                        const Scenario& running,
                                                        std::string& error);

}  // namespace olcb::simnode
