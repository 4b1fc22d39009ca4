// Validation of the reports tests produce against their published schemas: the JSON report
// against docs/report.schema.json (JSON Schema draft 7, valijson), JUnit XML against
// tests/support/junit.xsd (libxml2).
#pragma once

#include <string>

namespace olcb::test {

/// Every way `json_text` breaks docs/report.schema.json, one per line; "" when it validates.
std::string json_report_errors(const std::string& json_text);

/// Every way `xml_text` breaks tests/support/junit.xsd, one per line; "" when it validates.
std::string junit_report_errors(const std::string& xml_text);

}  // namespace olcb::test
