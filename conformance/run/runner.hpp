// The whole conformance run for one node, as phases (conformance/run/runner.cpp): protocol checks,
// then the encoding checks under the safety backup and the node's lock, one variable at a time,
// with the node watched for death or restart, then the restore; and the exit code of a run.
#pragma once

#include <chrono>
#include <functional>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "conformance/checks/check_context.hpp"
#include "conformance/checks/check_registry.hpp"
#include "conformance/checks/protection.hpp"
#include "conformance/link/session.hpp"
#include "conformance/link/session_memory.hpp"
#include "conformance/report/check_result.hpp"
#include "conformance/run/safety_backup.hpp"

namespace olcb::conform {

/// What the user asked for.
struct RunOptions {
    bool read_only = false;   ///< no write at all (encoding checks SKIP)
    std::size_t sample = 3;   ///< replicas per replicated group in the encoding checks
    bool blob = false;        ///< also write <blob> variables
    bool reboot = false;      ///< reset the node and check persistence
    std::string backup_path;  ///< safety backup file; empty: default_backup_path(node)
    bool progress = false;    ///< draw progress bars on the progress stream
    /// How long a link lost mid-run is waited for before the restore is left to the user.
    std::chrono::seconds link_wait{60};
    /// How long a node that stopped answering or restarted is waited for (--node-wait).
    std::chrono::seconds node_wait{30};
    /// Protected settings, --exclude / --only, --write-protected.
    ProtectionRules protection;
    /// Which checks are reported (--only / --skip with check IDs, --thorough); the encoding
    /// phase runs only when one of its checks is selected.
    CheckSelection selection;
    /// Multiplies every answer and silence window (--timeout-scale).
    double timeout_scale = 1.0;
    /// Why the node gets the protocol checks only ("" for a configurable node): e.g. its PIP
    /// has neither Memory Configuration nor CDI.
    std::string protocol_only;
    /// The command that restores a kept backup FILE later, e.g. "lcc-conform --serial DEV
    /// restore" (named in the message when the restore cannot happen now).
    std::string restore_command = "lcc-conform restore";
};

/// The protocol checks (run_protocol_checks, bound by the program); may be empty. What they
/// learn goes into the context (the encoding checks reuse its CDI layout).
using ProtocolChecks =
    std::function<std::vector<CheckResult>(Session&, const NodeInfo&, CheckContext&)>;

/// Runs every check against one node; `progress` receives progress bars when enabled.
NodeReport run_node(Session& session, const NodeInfo& node, const RunOptions& options,
                    const ProtocolChecks& protocol_checks, std::ostream& progress);

/// Restores a safety backup file onto its node (found on the session's link); the outcome, or
/// nullopt with `error` when the file or node is unusable.
std::optional<RestoreOutcome> restore_file(Session& session, const std::string& path,
                                           std::string& error);

/// 0 when every check passed (or warned/skipped) and restores were identical, 1 when a check
/// failed, 2 when a node's run could not finish (NodeReport::incomplete).
int exit_code(const std::vector<NodeReport>& reports);

/// Makes SIGINT and SIGTERM request a stop (the run restores, then exits) instead of killing.
void install_stop_handlers();
/// True once SIGINT/SIGTERM arrived (or request_stop() was called).
bool stop_requested();
/// Requests a stop as a signal would (tests).
void request_stop(bool on = true);

}  // namespace olcb::conform
