// The events check of the write phase (events.follow-write): a rewritten <eventid> variable is
// identified with its new value once Update Complete is sent. events.cpp also holds the read-only
// event checks of the registry (event_checks()).
#pragma once

#include <vector>

#include "conformance/checks/check_context.hpp"
#include "conformance/checks/protection.hpp"
#include "conformance/link/session.hpp"
#include "conformance/report/check_result.hpp"

namespace olcb::conform::checks {

/// Writes a new event ID into one unprotected eventid variable (original read first), sends Update
/// Complete, checks the node identifies the new ID (Identify Producer/Consumer per its role) and no
/// longer the old one, writes the original back, reads it back, sends Update Complete again.
///
/// The variable is the first one of the CDI whose value the node identified exactly in its answer
/// to Identify Events addressed (so its role is known), held by no other eventid variable, not
/// protected (protection_reason) and selected by rules (selection_reason). The new value is
/// 05.01.01.01.3F.FE.xx.yy, xx.yy the low 16 bits of its address. Results: one events.follow-write
/// (PASS, FAIL, or SKIP saying why nothing was written), plus encoding.original-restored (FAIL)
/// when the original did not read back. Run it under the safety backup and the node's lock.
std::vector<CheckResult> events_follow_write(Session& session, const NodeInfo& node,
                                             const CheckContext& ctx, const ProtectionRules& rules);

/// Sends events.pcer-payload-tolerated's PCERs with payload (4, 8, 12 and 2,044 bytes) of an event
/// in lcc-conform's own range (event_robustness.cpp); the shared event window sends them.
void inject_payload_pcers(Session& s);

}  // namespace olcb::conform::checks
