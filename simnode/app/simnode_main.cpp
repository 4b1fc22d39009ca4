// simnode: runs the nodes of a scenario on one CAN segment (TCP hub, TCP client, SocketCAN,
// serial GridConnect adapter or in-process only) until SIGINT/SIGTERM or --run-for.
#include <signal.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
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
#include "simnode/faults/fault_catalog.hpp"
#include "simnode/fd_budget.hpp"
#include "simnode/node_registry.hpp"
#include "simnode/resident_memory.hpp"
#include "simnode/scenario.hpp"
#include "simnode/scenario_lookup.hpp"
#include "simnode/sim_node.hpp"

namespace {

namespace fs = std::filesystem;
using namespace olcb;
using namespace olcb::simnode;

constexpr int kExitRuntime = 1;
constexpr int kExitUsage = 2;
// How long --connect waits for the hub at start-up before giving up with exit status 2.
constexpr std::chrono::seconds kFirstConnectWait{3};
// How often start-up progress is checked for the "initialized" line.
constexpr auto kStartupPoll = std::chrono::milliseconds(10);
// Output a hub may fall behind by before simnode reconnects (see the --connect client).
constexpr std::size_t kClientQueueBytes = 64u << 20;
// Hub policy: one client's flood is slowed to what every reader takes (docs/scenarios.md).
constexpr std::uint32_t kClientFramesPerSecond = 20000;
// Keeps a flood in the hub's queues, where its backpressure sees it, not in the kernel's.
constexpr std::size_t kHubSendBufferBytes = std::size_t{64} * 1024;

// Where this binary finds scenarios by name (scenario_lookup.hpp): the source tree from its
// build tree, the installed data beside it (or where it was to be installed) otherwise.
std::vector<fs::path> this_scenario_dirs() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return scenario_dirs(ec ? fs::path() : exe, built_scenario_places());
}

void say(const std::string& line) {
    std::cout << "simnode: " << line << '\n' << std::flush;  // scripts wait for these lines
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

// One run of a scenario: the nodes, the segment and every transport bridged onto it, live
// control and the stop conditions, built in that order (and destroyed in reverse).
class Runner {
public:
    explicit Runner(const Scenario& scenario)
        : scenario_(scenario), run_timer_(io_), startup_timer_(io_) {}

    int run() {
        if (!fits_fd_limit()) return kExitUsage;
        if (!create_nodes() || !open_segment()) return kExitRuntime;
        node_port_ = &add_port({});
        if (!start_audit() || !open_tap()) return kExitRuntime;
        open_client();
        if (!open_socketcan() || !open_serial()) return kExitRuntime;
        // One alias cache for all nodes, as one interface's virtual nodes have: a cache per
        // node, each taught every node's announcement, made start-up N^2 (issue 32).
        driver_.emplace(io_, audit_ ? audit_->attach(*node_port_, hub_.get()) : *node_port_,
                        StackGroupOptions{.share_alias_cache = true});
        for (auto& node : nodes_) driver_->attach(node->stack());
        // Live control (docs/control.md): changes the nodes from the same io_context.
        registry_.emplace(nodes_, *driver_);
        registry_->set_fd_budget(fd_budget_);
        if (audit_) registry_->set_added_handler([this](const SimNode& n) { audit_->add_node(n); });
        registry_->set_log_handler(say);
        commands_.emplace(*registry_, scenario_);
        commands_->set_log_handler(say);
        control_.emplace(io_, *commands_);
        control_->set_log_handler(say);
        if (!start_control()) return kExitRuntime;
        arm_stop();
        announce();
        if (!start_nodes()) return kExitUsage;
        watch_startup();
        io_.run();
        finish_audit();
        say("stopped");
        return audit_error_.empty() ? 0 : kExitRuntime;
    }

private:
    // Before anything opens: a scenario over the limit would stop at whichever node or client
    // came first, so it is refused with the numbers instead.
    bool fits_fd_limit() {
        fd_budget_ = {fixed_fds(scenario_), fd_limit()};
        const std::string shortage =
            fd_shortage("scenario", fd_budget_.fixed + node_fds(scenario_.nodes), fd_budget_);
        if (shortage.empty()) return true;
        std::cerr << "simnode: " << shortage << "; raise the limit or run fewer nodes\n";
        return false;
    }

    bool create_nodes() {
        nodes_.reserve(scenario_.nodes.size());
        for (const auto& config : scenario_.nodes) {
            std::string error;
            std::error_code ec;
            if (!config.image_dir.empty() && !fs::create_directories(config.image_dir, ec) && ec) {
                std::cerr << "simnode: cannot create image directory " << config.image_dir.string()
                          << ": " << ec.message() << "\n";
                return false;
            }
            auto node = SimNode::create(config, error);
            if (!node) {
                std::cerr << "simnode: node " << config.node_id.to_string() << ": " << error
                          << "\n";
                return false;
            }
            if (!node->cdi_problem().empty()) {
                std::cerr << "simnode: warning: node " << config.node_id.to_string()
                          << " serves a CDI that is not valid: " << node->cdi_problem() << "\n";
            }
            nodes_.push_back(std::move(node));
        }
        return true;
    }

    // The segment: a TCP hub when listening, else an in-process bus. Every other transport
    // is bridged onto it through one more port, so all of them can be combined.
    bool open_segment() {
        if (!scenario_.listen) {
            bus_ = std::make_unique<InProcessBus>(io_);
            if (scenario_.bitrate > 0) bus_->enable_timing(scenario_.bitrate);
            return true;
        }
        TcpHubOptions options;
        options.max_clients = scenario_.max_clients;
        options.max_clients_per_address = scenario_.max_clients_per_address;
        options.max_client_frames_per_second = kClientFramesPerSecond;
        options.socket_send_buffer_bytes = kHubSendBufferBytes;
        options.idle_timeout = std::chrono::duration_cast<std::chrono::milliseconds>(
            std::chrono::duration<double>(scenario_.idle_timeout));
        options.bitrate = scenario_.bitrate;
        hub_ = std::make_unique<TcpHubServer>(io_, options);
        hub_->set_log_handler([](const std::string& line) { say("hub: " + line); });
        if (const auto ec = hub_->listen(scenario_.listen->host, scenario_.listen->port)) {
            std::cerr << "simnode: cannot listen on " << scenario_.listen->to_string() << ": "
                      << ec.message() << "\n";
            return false;
        }
        return true;
    }

    Transport& add_port(FrameHandler handler) {
        return hub_ ? hub_->add_local_endpoint(std::move(handler))
                    : bus_->add_endpoint(std::move(handler));
    }

    bool start_audit() {
        audit_ = open_audit(io_, scenario_, nodes_, audit_error_);
        if (audit_error_.empty()) return true;
        std::cerr << "simnode: audit: " << audit_error_ << "\n";
        return false;
    }

    bool open_tap() {
        if (scenario_.trace.empty() && scenario_.candump.empty()) return true;
        std::string error;
        if (!tap_.open(scenario_, error)) {
            std::cerr << "simnode: " << error << "\n";
            return false;
        }
        add_port([this](const CanFrame& f) { tap_.record(f); });
        return true;
    }

    void open_client() {
        if (!scenario_.connect) return;
        // Hundreds of nodes announce their events in one burst at start-up, faster than any
        // socket drains; the default 256 KiB queue would take that for a stalled hub.
        TcpClientOptions options;
        options.max_queue_bytes = kClientQueueBytes;
        client_ = std::make_unique<TcpClient>(io_, scenario_.connect->host, scenario_.connect->port,
                                              options);
        Transport& port = add_port([this](const CanFrame& f) { client_->send(f); });
        client_->set_handler([&port](const CanFrame& f) { port.send(f); });
    }

    bool open_socketcan() {
        if (scenario_.socketcan.empty()) return true;
        can_ = std::make_unique<socketcan::SocketCanPort>(io_);
        if (const auto failed = can_->open(scenario_.socketcan)) {
            std::cerr << "simnode: " << failed->message << "\n";
            return false;
        }
        // The nodes keep running while the interface is down, as on a bus whose cable is out.
        can_->set_connection_handler([this](bool up, const std::string& reason) {
            if (up) {
                say("SocketCAN " + scenario_.socketcan + ": up again");
            } else {
                std::cerr << "simnode: " << reason << "; waiting for it\n" << std::flush;
            }
        });
        Transport& port = add_port([this](const CanFrame& f) { can_->send(f); });
        can_->set_handler([&port](const CanFrame& f) { port.send(f); });
        return true;
    }

    bool open_serial() {
        if (scenario_.serial.empty()) return true;
        SerialOptions options;
        options.baud = scenario_.baud;
        options.rtscts = scenario_.rtscts;
        serial_ = std::make_unique<SerialPort>(io_, scenario_.serial, options);
        if (const auto failed = serial_->open()) {
            std::cerr << "simnode: " << *failed << "\n";
            return false;
        }
        // A lost adapter is reported and reopened; the nodes keep running meanwhile.
        serial_->set_connection_handler([this](bool up, const std::string& reason) {
            if (up) {
                say("serial " + serial_->device() + ": open again");
            } else {
                std::cerr << "simnode: " << reason << "; reopening\n" << std::flush;
            }
        });
        Transport& port = add_port([this](const CanFrame& f) { serial_->send(f); });
        serial_->set_handler([&port](const CanFrame& f) { port.send(f); });
        say("serial " + scenario_.serial + " open at " + std::to_string(scenario_.baud) + " baud");
        return true;
    }

    bool start_control() {
        if (!scenario_.control) return true;
        if (const auto ec = control_->listen(scenario_.control->host, scenario_.control->port)) {
            std::cerr << "simnode: cannot listen for control on " << scenario_.control->to_string()
                      << ": " << ec.message() << "\n";
            return false;
        }
        return true;
    }

    // Before the hub closes its clients: what they left open is judged as at the end of the run.
    void finish_audit() {
        if (!audit_) return;
        std::string failed = audit_->finish();  // "" also once it has finished
        if (failed.empty()) return;
        std::cerr << "simnode: audit: " << failed << '\n' << std::flush;
        audit_error_ = std::move(failed);
    }

    void stop() {
        control_->stop();
        finish_audit();
        if (hub_) hub_->stop();
        if (client_) client_->stop();
        if (can_) can_->close();
        if (serial_) serial_->close();
        io_.stop();
    }

    // SIGINT, SIGTERM and --run-for end the run.
    void arm_stop() {
        signals_.emplace(io_, SIGINT, SIGTERM);
        signals_->async_wait([this](const boost::system::error_code& ec, int) {
            if (!ec) stop();
        });
        if (!scenario_.run_for) return;
        run_timer_.expires_after(std::chrono::duration_cast<Clock::duration>(
            std::chrono::duration<double>(*scenario_.run_for)));
        run_timer_.async_wait([this](const boost::system::error_code& ec) {
            if (!ec) stop();
        });
    }

    void announce() {
        describe_nodes(nodes_);
        // The bit rate follows the address, without a colon: scripts take the port after the last.
        const std::string paced =
            scenario_.bitrate > 0
                ? " (bus paced at " + std::to_string(scenario_.bitrate) + " bit/s)"
                : "";
        if (hub_) {
            say("listening on " + HostPort{scenario_.listen->host, hub_->port()}.to_string() +
                paced);
        } else if (!paced.empty()) {
            say("in-process segment" + paced);
        }
        if (scenario_.control) {
            say("control on " + HostPort{scenario_.control->host, control_->port()}.to_string());
        }
    }

    bool start_nodes() {
        started_ = Clock::now();
        if (scenario_.start_on_connect && hub_) {
            // As a node that is itself a TCP server: a new client sees every node's login.
            hub_->set_connection_handler([this](const std::string& remote) {
                if (!nodes_started_) return;
                say("client " + remote + " connected: every node logs in again (start-on-connect)");
                const TimePoint now = Clock::now();
                for (auto& node : nodes_) node->relogin(now);
            });
        } else if (scenario_.start_on_connect) {
            std::cerr << "simnode: warning: start-on-connect does nothing without listen\n"
                      << std::flush;
        }
        if (!client_) {
            nodes_started_ = true;
            registry_->start_all();
            return true;
        }
        // The nodes start once the hub is reached, so the hub's nodes see their alias
        // reservation and can object to a collision.
        const std::string where = scenario_.connect->to_string();
        client_->set_connection_handler([this, where](bool up) {
            if (!up) {
                std::cerr << "simnode: lost the hub " << where << "; reconnecting\n" << std::flush;
                return;
            }
            say("connected to hub " + where);
            if (nodes_started_) return;
            nodes_started_ = true;
            started_ = Clock::now();
            registry_->start_all();
        });
        say("connecting to hub " + where);
        client_->start();
        // A hub that is not there at the start is a mistake to say at once (a wrong port), not
        // a silent wait; one that goes away later is reconnected to.
        const auto deadline = Clock::now() + kFirstConnectWait;
        while (!client_->connected() && !client_->gave_up() && client_->last_error().empty() &&
               Clock::now() < deadline)
            io_.run_one_for(std::chrono::milliseconds(50));
        if (client_->connected()) return true;
        const std::string why = client_->last_error();
        std::cerr << "simnode: cannot connect to hub " << where << ": "
                  << (why.empty()
                          ? "no answer within " + std::to_string(kFirstConnectWait.count()) + " s"
                          : why)
                  << "\n";
        return false;
    }

    // One line once every node holds an alias and sent Initialization Complete: start-up time
    // and memory for scripts and benchmarks.
    void watch_startup() {
        startup_timer_.expires_after(kStartupPoll);
        startup_timer_.async_wait([this](const boost::system::error_code& ec) {
            if (ec) return;
            std::size_t ready = 0;
            for (const auto& node : nodes_) {
                if (node->stack().initialized()) ++ready;
            }
            if (ready < nodes_.size()) {
                watch_startup();
                return;
            }
            const auto ms =
                std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - started_)
                    .count();
            say(std::to_string(nodes_.size()) + " node(s) initialized in " + std::to_string(ms) +
                " ms, RSS " + std::to_string(resident_kib() / 1024) + " MiB");
        });
    }

    const Scenario& scenario_;
    FdBudget fd_budget_;
    boost::asio::io_context io_;
    std::vector<std::unique_ptr<SimNode>> nodes_;
    std::unique_ptr<TcpHubServer> hub_;
    std::unique_ptr<InProcessBus> bus_;
    Transport* node_port_ = nullptr;
    std::string audit_error_;
    std::unique_ptr<audit::AuditTap> audit_;
    TrafficTap tap_;
    std::unique_ptr<TcpClient> client_;
    std::unique_ptr<socketcan::SocketCanPort> can_;
    std::unique_ptr<SerialPort> serial_;
    std::optional<StackDriver> driver_;
    std::optional<NodeRegistry> registry_;
    std::optional<ControlCommands> commands_;
    std::optional<ControlServer> control_;
    std::optional<boost::asio::signal_set> signals_;
    boost::asio::steady_timer run_timer_;
    TimePoint started_;
    bool nodes_started_ = false;
    boost::asio::steady_timer startup_timer_;
};

// --list-faults[=FORMAT]: docs/faults.md's table and the e2e oracle come from here.
int list_faults(const std::string& format) {
    if (format == "markdown") {
        std::cout << format_fault_markdown();
        return 0;
    }
    if (format == "json") {
        std::cout << format_fault_json();
        return 0;
    }
    if (!format.empty()) {
        std::cerr << "simnode: --list-faults=" << format << ": not markdown or json\n";
        return 2;
    }
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

// --list-scenarios: the name first, as --list-faults, so completion takes the first word.
int list_scenarios(std::span<const fs::path> dirs) {
    const auto scenarios = scenario_names(dirs);
    if (scenarios.empty()) {
        std::cerr << "simnode: no scenario found in";
        for (const auto& dir : dirs) std::cerr << " " << dir.string();
        std::cerr << "\n";
        return kExitRuntime;
    }
    for (const auto& [name, file] : scenarios) {
        std::string padded = name;
        padded.resize(std::max<std::size_t>(name.size() + 1, 32), ' ');
        std::cout << padded << file.string() << "\n";
    }
    return 0;
}

}  // namespace

static int main_checked(int argc, char** argv) {
    const std::vector<std::string> args(argv + 1, argv + argc);
    if (!args.empty() && args.front() == "ctl") {
        return run_ctl(std::span(args).subspan(1), std::cout, std::cerr);
    }
    const auto dirs = this_scenario_dirs();
    std::string error;
    const auto parsed = parse_arguments(args, dirs, error);
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
    if (parsed->list_faults) return list_faults(parsed->list_faults_format);
    if (parsed->list_scenarios) return list_scenarios(dirs);
    // A peer closing its socket must not kill the process.
    ::signal(SIGPIPE, SIG_IGN);
    // The soft limit (often 1,024) is a default, not a choice: the hard one is what may be used.
    if (!raise_fd_limit()) {
        std::cerr << "simnode: warning: cannot raise the file descriptor limit to the hard one: "
                  << std::strerror(errno) << "\n";
    }
    return Runner(parsed->scenario).run();
}

int main(int argc, char** argv) {
    try {
        return main_checked(argc, argv);
    } catch (const std::exception& e) {
        std::cerr << "simnode: internal error: " << e.what() << "\n";
        return kExitRuntime;
    }
}
