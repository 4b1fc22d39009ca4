#include "conformance/run/node_watch.hpp"

#include <algorithm>
#include <cstdio>

#include "base/error_codes.hpp"
#include "conformance/run/runner.hpp"

namespace olcb::conform {
namespace {

// How long the node is given to answer one Verify Node ID.
constexpr Duration kPingTimeout = std::chrono::seconds(2);

std::string seconds_text(Duration d) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f s",
                  std::chrono::duration_cast<std::chrono::duration<double>>(d).count());
    return buf;
}

}  // namespace

NodeWatch::NodeWatch(Session& session, const NodeInfo& node)
    : session_(session),
      node_(node),
      base_(session.track(node.id)),
      started_(session.link().now()) {}

void NodeWatch::rebase() {
    base_ = session_.track(node_.id);
}

std::optional<NodeIncident> NodeWatch::after(const AccessStep& step) {
    const AccessResult& r = *step.result;
    const bool failed = !r.ok && (r.error == base::to_u16(base::ErrorCode::kTimeout) ||
                                  base::is_temporary(r.error));
    auto incident = judge(step.what + " " + step.key, failed);
    if (incident) {
        incident->key = step.key;
        incident->value = step.value;
        incident->bytes = step.bytes.empty() ? "" : hex_bytes(step.bytes);
    }
    return incident;
}

std::optional<NodeIncident> NodeWatch::check_now(const std::string& step) {
    return judge(step, true);
}

std::optional<NodeIncident> NodeWatch::judge(const std::string& step, bool suspicious) {
    suspicious = suspicious || session_.track(node_.id).restarted_since(base_);
    if (!suspicious) return std::nullopt;
    const bool answers = session_.ping(node_, kPingTimeout);
    const NodeTrack seen = session_.track(node_.id);
    // A restart goes through alias reservation again (CID, RID, AMD); an Initialization Complete
    // without one is the node re-announcing itself (e.g. after its SNIP data changed).
    const bool rebooted = seen.reservations != base_.reservations;
    if (answers && !rebooted) {
        base_ = seen;
        return std::nullopt;
    }
    NodeIncident incident;
    incident.kind =
        rebooted ? NodeIncident::Kind::kRebooted : NodeIncident::Kind::kStoppedAnswering;
    incident.step = step;
    incident.elapsed = session_.link().now() - started_;
    return incident;
}

bool NodeWatch::wait_for_return(Duration wait) {
    const TimePoint deadline = session_.link().now() + wait;
    while (!stop_requested()) {
        const TimePoint now = session_.link().now();
        if (now >= deadline) return false;
        const NodeTrack before = session_.track(node_.id);
        // An Initialization Complete (or any answer) ends the wait early.
        session_.link().run_until(
            [&] {
                const NodeTrack t = session_.track(node_.id);
                return t.initializations != before.initializations;
            },
            std::min<Duration>(deadline - now, std::chrono::seconds(1)));
        if (session_.ping(node_,
                          std::min<Duration>(kPingTimeout, deadline - session_.link().now())))
            return true;
    }
    return false;
}

CheckResult incident_result(const NodeIncident& i) {
    const bool rebooted = i.kind == NodeIncident::Kind::kRebooted;
    std::string m = rebooted ? "the node restarted (new alias reservation) while lcc-conform was "
                             : "the node stopped answering while lcc-conform was ";
    m += i.step + ", " + seconds_text(i.elapsed) + " into its run";
    if (!i.value.empty()) m += "; last test value written: " + i.value + " (" + i.bytes + ")";
    m += "; nothing more was written to it";
    return {rebooted ? "node.rebooted" : "node.stopped-answering",
            Category::kNode,
            Status::kFail,
            m,
            "",
            "the node keeps running through the checks",
            rebooted ? "restart" : "no answer"};
}

}  // namespace olcb::conform
