// The registry entries of what happens to the node or the link during a run, reported by the node
// run's phases (run/node_watch.cpp, run/node_run.cpp).
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {

std::vector<CheckSpec> node_checks() {
    return {
        {"node.rebooted", 930, Category::kNode, "MessageNetworkS §3.4.1", Strength::kNone,
         "no clause forbids a restart; one not caused by lcc-conform (Update Complete, Reset, a "
         "staged "
         "collision) WARNs",
         "", "only as FAIL: the node reserved its alias again during the run"},
        {"node.stopped-answering", 940, Category::kNode, "MessageNetworkS §3.4.2", Strength::kShall,
         "a Verify Node ID addressed to the node is answered", "",
         "only as FAIL: the node no longer answers Verify Node ID"},
        {"link.lost", 950, Category::kLink, "", Strength::kRun,
         "the run itself: a lost link makes the results incomplete (exit 2)", "",
         "only as FAIL: the link went down during the node's run"},
    };
}

}  // namespace olcb::conform::checks
