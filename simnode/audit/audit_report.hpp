// The files of the client audit: JSON (every finding in full) and JUnit XML (one testcase per
// rule, a failure per rule with error findings); AuditTap replaces them whole on every write.
#pragma once

#include <string>

#include "simnode/audit/finding.hpp"

namespace olcb::simnode::audit {

/// What a report says about the run besides its findings.
struct ReportInfo {
    std::string started;    ///< when the audit started, ISO 8601 UTC
    bool complete = false;  ///< true once simnode stopped: no finding will be added
};

/// The audit as JSON (format: docs/audit.md).
std::string audit_json(const FindingLog& log, const ReportInfo& info);

/// The audit as JUnit XML: one testcase per rule; a rule with error findings fails, warnings
/// and notes are in its system-out.
std::string audit_junit(const FindingLog& log, const ReportInfo& info);

/// Now as ISO 8601 UTC ("2024-07-04T17:38:48Z").
std::string utc_now();

}  // namespace olcb::simnode::audit
