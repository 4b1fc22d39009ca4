// Liveness of the node under test during a run: after a timeout, a final temporary reject or an
// Initialization Complete, the node is asked (Verify Node ID) whether it is still there and
// whether it restarted, so a report says "the node died after writing X to Y" instead of a string
// of unrelated timeouts, and the run stops writing at once.
#pragma once

#include <optional>
#include <string>

#include "conformance/link/session.hpp"
#include "conformance/report/check_result.hpp"
#include "conformance/run/encoding_checks.hpp"

namespace olcb::conform {

/// How the node left the run.
struct NodeIncident {
    enum class Kind : std::uint8_t { kStoppedAnswering, kRebooted };
    Kind kind = Kind::kStoppedAnswering;
    std::string step;    ///< what lcc-conform was doing, e.g. "writing Settings.Trim"
    std::string key;     ///< the variable's backup key ("" outside the encoding checks)
    std::string value;   ///< the value written last ("" when none)
    std::string bytes;   ///< its bytes in hex ("" when none)
    Duration elapsed{};  ///< since the node's run began
};

/// Watches one node through its run.
class NodeWatch {
public:
    /// Starts watching node (its counters now are the baseline; the clock starts).
    NodeWatch(Session& session, const NodeInfo& node);
    /// Takes the node's counters now as the baseline (after a deliberate Reset/Reboot).
    void rebase();
    /// Judges the node after one access of the encoding checks; nullopt while it is fine.
    std::optional<NodeIncident> after(const AccessStep& step);
    /// Judges the node outside the encoding checks (e.g. after the protocol checks).
    std::optional<NodeIncident> check_now(const std::string& step);
    /// Waits up to `wait` for the node to be back (it answers Verify Node ID); false when not.
    bool wait_for_return(Duration wait);

private:
    std::optional<NodeIncident> judge(const std::string& step, bool suspicious);

    Session& session_;
    NodeInfo node_;
    NodeTrack base_;
    TimePoint started_;
};

/// FAIL node.rebooted / node.stopped-answering naming the step, variable, value and time.
CheckResult incident_result(const NodeIncident& incident);

}  // namespace olcb::conform
