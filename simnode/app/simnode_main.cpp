// simnode: runs the nodes of a scenario on one CAN segment (TCP hub, TCP client, SocketCAN,
// serial GridConnect adapter or in-process only) until SIGINT/SIGTERM or --run-for.
#include <signal.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "memory/memory_config_codec.hpp"
#include "memory/memory_config_defs.hpp"
#include "olcb_version.hpp"
#include "openlcb/asio.hpp"
#include "openlcb/in_process_bus.hpp"
#include "openlcb/monitor.hpp"
#include "openlcb/serial_port.hpp"
#include "openlcb/socketcan.hpp"
#include "openlcb/stack_driver.hpp"
#include "openlcb/tcp_client.hpp"
#include "openlcb/tcp_hub_server.hpp"
#include "openlcb/traffic_log.hpp"
#include "simnode/audit/audit_tap.hpp"
#include "simnode/control_client.hpp"
#include "simnode/control_commands.hpp"
#include "simnode/control_server.hpp"
#include "simnode/node_registry.hpp"
#include "simnode/resident_memory.hpp"
#include "simnode/scenario.hpp"
#include "simnode/sim_node.hpp"

namespace {

namespace fs = std::filesystem;
using namespace olcb;
using namespace olcb::simnode;

constexpr int kExitRuntime = 1;
constexpr int kExitUsage = 2;
// How often start-up progress is checked for the "initialized" line.
constexpr auto kStartupPoll = std::chrono::milliseconds(10);
// Output a hub may fall behind by before simnode reconnects (see the --connect client).
constexpr std::size_t kClientQueueBytes = 64u << 20;
// Hub policy: one client's flood is slowed to what every reader takes (docs/scenarios.md).
constexpr std::uint32_t kClientFramesPerSecond = 20000;
// Keeps a flood in the hub's queues, where its backpressure sees it, not in the kernel's.
constexpr std::size_t kHubSendBufferBytes = std::size_t{64} * 1024;

// Where `simnode` without arguments finds scenarios/default.ini: the source tree this binary was
// built from, next to the binary (build tree or install prefix), then the working directory.
std::vector<fs::path> default_scenarios() {
    std::vector<fs::path> out;
    const fs::path source_root = fs::path(__FILE__).parent_path().parent_path().parent_path();
    out.push_back(source_root / "scenarios" / "default.ini");
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        out.push_back(exe.parent_path() / "../../scenarios/default.ini");
        out.push_back(exe.parent_path() / "../share/simnode/scenarios/default.ini");
    }
    out.push_back(fs::path("scenarios") / "default.ini");
    return out;
}

void say(const std::string& line) {
    std::cout << "simnode: " << line << std::endl;  // endl: scripts wait for these lines
}

// Records every frame of the segment: decoded lines (--trace) and candump lines (--candump).
class TrafficTap {
public:
    bool open(const Scenario& s, std::string& error) {
        if (!s.trace.empty()) {
            if (!trace_.open(s.trace.string(), s.log_max_bytes)) {
                error = "cannot open trace file " + s.trace.string();
                return false;
            }
            monitor_.register_datagram_decoder(
                memory::kDatagramType,
                [](std::span<const std::uint8_t> bytes) { return memory::describe(bytes); });
        }
        if (!s.candump.empty() &&
            !log_.add_candump_file(s.candump.string(), s.socketcan.empty() ? "vcan0" : s.socketcan,
                                   s.log_max_bytes)) {
            error = "cannot open candump file " + s.candump.string();
            return false;
        }
        return true;
    }

    void record(const CanFrame& frame) {
        log_.record(frame);
        if (!trace_.is_open()) return;
        if (const auto line = monitor_.decode(frame)) {
            const double t = std::chrono::duration<double>(Clock::now() - start_).count();
            char stamp[32];
            std::snprintf(stamp, sizeof stamp, "%10.6f ", t);
            line_.assign(stamp);
            line_.append(*line);
            line_.push_back('\n');
            trace_.write(line_);
        }
    }

private:
    RotatingFile trace_;  // rotates silently: a message per rotation would flood the console
    std::string line_;
    Monitor monitor_;
    TrafficLog log_;
    TimePoint start_ = Clock::now();
};

// One line per node: what it runs, so a developer sees at once which faults are active.
void describe_nodes(const std::vector<std::unique_ptr<SimNode>>& nodes) {
    for (const auto& node : nodes) {
        const NodeConfig& c = node->config();
        std::string faults;
        for (const auto& name : to_names(c.faults)) faults += (faults.empty() ? "" : ",") + name;
        std::cout << "simnode: node " << c.node_id.to_string() << " cdi "
                  << (c.cdi_file.empty() ? std::string("(inline)") : c.cdi_file.string())
                  << " faults " << (faults.empty() ? "none" : faults) << " images "
                  << (c.image_dir.empty() ? std::string("(RAM only)") : c.image_dir.string())
                  << "\n";
    }
    std::cout.flush();
}

// The client audit (--audit, --audit-junit, docs/audit.md); nullptr when none is asked for, or
// with error set when its files cannot be written.
std::unique_ptr<audit::AuditTap> open_audit(boost::asio::io_context& io, const Scenario& s,
                                            const std::vector<std::unique_ptr<SimNode>>& nodes,
                                            std::string& error) {
    if (s.audit.empty() && s.audit_junit.empty()) return nullptr;
    auto tap = audit::AuditTap::open(io, {s.audit, s.audit_junit}, error);
    if (tap) {
        for (const auto& node : nodes) tap->add_node(*node);
    }
    return tap;
}

int run(const Scenario& scenario) {
    boost::asio::io_context io;

    std::vector<std::unique_ptr<SimNode>> nodes;
    nodes.reserve(scenario.nodes.size());
    for (const auto& config : scenario.nodes) {
        std::string error;
        std::error_code ec;
        if (!config.image_dir.empty() && !fs::create_directories(config.image_dir, ec) && ec) {
            std::cerr << "simnode: cannot create image directory " << config.image_dir.string()
                      << ": " << ec.message() << "\n";
            return kExitRuntime;
        }
        auto node = SimNode::create(config, error);
        if (!node) {
            std::cerr << "simnode: node " << config.node_id.to_string() << ": " << error << "\n";
            return kExitRuntime;
        }
        if (!node->cdi_problem().empty()) {
            std::cerr << "simnode: warning: node " << config.node_id.to_string()
                      << " serves a CDI that is not valid: " << node->cdi_problem() << "\n";
        }
        nodes.push_back(std::move(node));
    }

    // The segment: a TCP hub when listening, else an in-process bus. Every other transport
    // is bridged onto it through one more port, so all of them can be combined.
    std::unique_ptr<TcpHubServer> hub;
    std::unique_ptr<InProcessBus> bus;
    const auto add_port = [&](FrameHandler handler) -> Transport& {
        return hub ? hub->add_local_endpoint(std::move(handler))
                   : bus->add_endpoint(std::move(handler));
    };
    if (scenario.listen) {
        TcpHubOptions options;
        options.max_clients = scenario.max_clients;
        options.max_clients_per_address = scenario.max_clients_per_address;
        options.max_client_frames_per_second = kClientFramesPerSecond;
        options.socket_send_buffer_bytes = kHubSendBufferBytes;
        options.idle_timeout = std::chrono::duration_cast<std::chrono::milliseconds>(
            std::chrono::duration<double>(scenario.idle_timeout));
        options.bitrate = scenario.bitrate;
        hub = std::make_unique<TcpHubServer>(io, options);
        hub->set_log_handler([](const std::string& line) { say("hub: " + line); });
        if (const auto ec = hub->listen(scenario.listen->host, scenario.listen->port)) {
            std::cerr << "simnode: cannot listen on " << scenario.listen->to_string() << ": "
                      << ec.message() << "\n";
            return kExitRuntime;
        }
    } else {
        bus = std::make_unique<InProcessBus>(io);
        if (scenario.bitrate > 0) bus->enable_timing(scenario.bitrate);
    }
    Transport& node_port = add_port({});
    std::string audit_error;
    const auto audit = open_audit(io, scenario, nodes, audit_error);
    if (!audit_error.empty()) {
        std::cerr << "simnode: audit: " << audit_error << "\n";
        return kExitRuntime;
    }

    TrafficTap tap;
    std::string error;
    if (!scenario.trace.empty() || !scenario.candump.empty()) {
        if (!tap.open(scenario, error)) {
            std::cerr << "simnode: " << error << "\n";
            return kExitRuntime;
        }
        add_port([&tap](const CanFrame& f) { tap.record(f); });
    }

    std::unique_ptr<TcpClient> client;
    if (scenario.connect) {
        // Hundreds of nodes announce their events in one burst at start-up, faster than any
        // socket drains; the default 256 KiB queue would take that for a stalled hub.
        TcpClientOptions options;
        options.max_queue_bytes = kClientQueueBytes;
        client = std::make_unique<TcpClient>(io, scenario.connect->host, scenario.connect->port,
                                             options);
        Transport& port = add_port([&client](const CanFrame& f) { client->send(f); });
        client->set_handler([&port](const CanFrame& f) { port.send(f); });
    }
    std::unique_ptr<socketcan::SocketCanPort> can;
    if (!scenario.socketcan.empty()) {
        can = std::make_unique<socketcan::SocketCanPort>(io);
        if (const auto failed = can->open(scenario.socketcan)) {
            std::cerr << "simnode: " << failed->message << "\n";
            return kExitRuntime;
        }
        Transport& port = add_port([&can](const CanFrame& f) { can->send(f); });
        can->set_handler([&port](const CanFrame& f) { port.send(f); });
    }

    std::unique_ptr<SerialPort> serial;
    if (!scenario.serial.empty()) {
        SerialOptions options;
        options.baud = scenario.baud;
        options.rtscts = scenario.rtscts;
        serial = std::make_unique<SerialPort>(io, scenario.serial, options);
        if (const auto failed = serial->open()) {
            std::cerr << "simnode: " << *failed << "\n";
            return kExitRuntime;
        }
        // A lost adapter is reported and reopened; the nodes keep running meanwhile.
        serial->set_connection_handler([&serial](bool up, const std::string& reason) {
            if (up) {
                say("serial " + serial->device() + ": open again");
            } else {
                std::cerr << "simnode: " << reason << "; reopening" << std::endl;
            }
        });
        Transport& port = add_port([&serial](const CanFrame& f) { serial->send(f); });
        serial->set_handler([&port](const CanFrame& f) { port.send(f); });
        say("serial " + scenario.serial + " open at " + std::to_string(scenario.baud) + " baud");
    }

    StackDriver driver(io, audit ? audit->attach(node_port, hub.get()) : node_port);
    for (auto& node : nodes) driver.attach(node->stack());
    // Live control (docs/control.md): changes the nodes from the same io_context.
    NodeRegistry registry(nodes, driver);
    ControlCommands commands(registry, scenario);
    commands.set_log_handler(say);
    ControlServer control(io, commands);
    control.set_log_handler(say);
    if (scenario.control) {
        if (const auto ec = control.listen(scenario.control->host, scenario.control->port)) {
            std::cerr << "simnode: cannot listen for control on " << scenario.control->to_string()
                      << ": " << ec.message() << "\n";
            return kExitRuntime;
        }
    }

    // Before the hub closes its clients: what they left open is judged as at the end of the run.
    const auto finish_audit = [&] {
        if (!audit) return;
        std::string failed = audit->finish();  // "" also once it has finished
        if (failed.empty()) return;
        std::cerr << "simnode: audit: " << failed << std::endl;
        audit_error = std::move(failed);
    };
    const auto stop = [&] {
        control.stop();
        finish_audit();
        if (hub) hub->stop();
        if (client) client->stop();
        if (can) can->close();
        if (serial) serial->close();
        io.stop();
    };
    boost::asio::signal_set signals(io, SIGINT, SIGTERM);
    signals.async_wait([&](const boost::system::error_code& ec, int) {
        if (!ec) stop();
    });
    boost::asio::steady_timer run_timer(io);
    if (scenario.run_for) {
        run_timer.expires_after(std::chrono::duration_cast<Clock::duration>(
            std::chrono::duration<double>(*scenario.run_for)));
        run_timer.async_wait([&](const boost::system::error_code& ec) {
            if (!ec) stop();
        });
    }

    describe_nodes(nodes);
    // The bit rate follows the address, without a colon: scripts take the port after the last.
    const std::string paced = scenario.bitrate > 0
                                  ? " (bus paced at " + std::to_string(scenario.bitrate) + " bit/s)"
                                  : "";
    if (hub) {
        say("listening on " + HostPort{scenario.listen->host, hub->port()}.to_string() + paced);
    } else if (!paced.empty()) {
        say("in-process segment" + paced);
    }
    if (scenario.control) {
        say("control on " + HostPort{scenario.control->host, control.port()}.to_string());
    }
    auto started = Clock::now();
    bool nodes_started = false;
    if (scenario.start_on_connect && hub) {
        // As a node that is itself a TCP server: a new client sees every node's login.
        hub->set_connection_handler([&](const std::string& remote) {
            if (!nodes_started) return;
            say("client " + remote + " connected: every node logs in again (start-on-connect)");
            const TimePoint now = Clock::now();
            for (auto& node : nodes) node->relogin(now);
        });
    } else if (scenario.start_on_connect) {
        std::cerr << "simnode: warning: start-on-connect does nothing without listen" << std::endl;
    }
    if (client) {
        // The nodes start once the hub is reached, so the hub's nodes see their alias
        // reservation and can object to a collision.
        const std::string where = scenario.connect->to_string();
        client->set_connection_handler([&, where](bool up) {
            if (!up) {
                std::cerr << "simnode: lost the hub " << where << "; reconnecting" << std::endl;
                return;
            }
            say("connected to hub " + where);
            if (nodes_started) return;
            nodes_started = true;
            started = Clock::now();
            registry.start_all();
        });
        say("connecting to hub " + where);
        client->start();
    } else {
        nodes_started = true;
        registry.start_all();
    }

    // One line once every node holds an alias and sent Initialization Complete: start-up time
    // and memory for scripts and benchmarks.
    boost::asio::steady_timer startup_timer(io);
    std::function<void(const boost::system::error_code&)> check_startup =
        [&](const boost::system::error_code& ec) {
            if (ec) return;
            std::size_t ready = 0;
            for (const auto& node : nodes) ready += node->stack().initialized() ? 1 : 0;
            if (ready == nodes.size()) {
                const auto ms =
                    std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - started)
                        .count();
                say(std::to_string(nodes.size()) + " node(s) initialized in " + std::to_string(ms) +
                    " ms, RSS " + std::to_string(resident_kib() / 1024) + " MiB");
                return;
            }
            startup_timer.expires_after(kStartupPoll);
            startup_timer.async_wait(check_startup);
        };
    startup_timer.expires_after(kStartupPoll);
    startup_timer.async_wait(check_startup);

    io.run();
    finish_audit();
    say("stopped");
    return audit_error.empty() ? 0 : kExitRuntime;
}

}  // namespace

static int main_checked(int argc, char** argv) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (!args.empty() && args.front() == "ctl") {
        return run_ctl(std::span(args).subspan(1), std::cout, std::cerr);
    }
    const auto defaults = default_scenarios();
    std::string error;
    const auto parsed = parse_arguments(args, defaults, error);
    if (!parsed) {
        std::cerr << "simnode: " << error << "\n";
        return kExitUsage;
    }
    if (parsed->help) {
        std::cout << help_text();
        return 0;
    }
    if (parsed->version) {
        std::cout << "simnode " << olcb::kVersion << "\n";
        return 0;
    }
    if (parsed->list_faults) {
        // The name first: scripts take the first word of each line.
        for (const auto& f : fault_catalog()) {
            std::string name(f.name);
            name.resize(std::max<std::size_t>(name.size() + 1, 32), ' ');
            std::cout << name << f.summary;
            if (!f.parameter.empty()) std::cout << " (parameter " << f.parameter << ")";
            std::cout << "\n";
        }
        return 0;
    }
    // A peer closing its socket must not kill the process.
    ::signal(SIGPIPE, SIG_IGN);
    return run(parsed->scenario);
}

int main(int argc, char** argv) {
    try {
        return main_checked(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "simnode: internal error: " << e.what() << "\n";
        return kExitRuntime;
    }
}
