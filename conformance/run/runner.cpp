#include "conformance/run/runner.hpp"

#include <csignal>
#include <ostream>

#include "conformance/link/session_memory.hpp"
#include "conformance/run/node_run.hpp"

namespace olcb::conform {
namespace {

volatile std::sig_atomic_t g_stop = 0;

extern "C" void on_stop_signal(int) {
    g_stop = 1;
}

}  // namespace

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

NodeReport run_node(Session& session, const NodeInfo& node, const RunOptions& options,
                    const ProtocolChecks& protocol_checks, std::ostream& progress) {
    return NodeRun(session, node, options, protocol_checks, progress).run();
}

int exit_code(const std::vector<NodeReport>& reports) {
    for (const NodeReport& r : reports) {
        if (r.incomplete) return 2;
    }
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
