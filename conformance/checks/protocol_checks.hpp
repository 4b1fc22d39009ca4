// The frame, message, PIP, SNIP, ACDI, datagram, memory and CDI checks of docs/checks.md.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

#include "base/timings.hpp"
#include "conformance/checks/check_context.hpp"
#include "conformance/checks/check_registry.hpp"
#include "conformance/link/session.hpp"
#include "conformance/report/check_result.hpp"

namespace olcb::conform {

/// Knobs of run_protocol_checks().
struct ProtocolOptions {
    /// Window in which silence is awaited (a node that stays silent this long is silent).
    Duration window = std::chrono::milliseconds(250);
    /// Longest wait for an answer the node owes (checks end as soon as the answers are in).
    Duration answer_window = std::chrono::seconds(1);
    /// Shortest span over which the node must send nothing unsolicited (the run counts).
    Duration quiet_window = std::chrono::milliseconds(1200);
    /// Largest reply latency that passes.
    Duration max_reply_latency = base::kReplyDue;
    /// Skip the writes to read-only spaces (they rewrite the byte already there).
    bool read_only = false;
    /// Upper bound of the CDI download when Space Info gives none.
    std::uint32_t max_cdi_bytes = 1024 * 1024;
    /// --no-stream: stream checks SKIP and the CDI is read by datagrams only.
    bool no_stream = false;
    /// --reboot: checks that need a Reset/Reboot (the start-up sequence) may send one.
    bool reboot = false;
    /// The user named the node (--node): the checks that change a state no backup holds (a
    /// train's speed, functions, controller and listeners; a Broadcast Time clock's time, which
    /// they put back) may run; never on a node found by discovery.
    bool named = false;
    /// --command-station: the node creates train nodes on request (TrainSearchS §6.2), and the
    /// checks that make it create some may run (the trains stay, stopped and released).
    bool command_station = false;
    /// --train-address: the address of the train named with --node (a train's node ID need not
    /// tell it): search.address-match searches for it.
    std::optional<std::uint32_t> train_address;
    /// --only / --skip / --thorough: which registry entries run.
    CheckSelection selection;
    /// Called with the bytes read so far while the CDI downloads (run_protocol_checks() passes
    /// the CheckContext's).
    std::function<void(std::size_t)> cdi_progress;
};

/// Runs every protocol check against node, then hands what its probes learned to ctx for the
/// later phases (hand_over()).
std::vector<CheckResult> run_protocol_checks(Session& session, const NodeInfo& node,
                                             const ProtocolOptions& options, CheckContext& ctx);

/// One memory.short-read.<space> check per space this node was read from (two lower-case hex
/// digits, e.g. memory.short-read.fb): FAIL when a Read Reply OK was shorter than asked away from
/// the end of the space.
std::vector<CheckResult> short_read_checks(Session& session, const NodeInfo& node,
                                           CheckContext& ctx);

}  // namespace olcb::conform
