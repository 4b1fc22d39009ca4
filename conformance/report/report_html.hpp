// The HTML report of a conformance run (lcc-conform --html FILE): one self-contained page with
// the run summary, every node's checks (filterable by status) and its memory map with each
// variable's verdict. The page is cdi/html_page.hpp's, shared with lcc-cdi render --html.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "conformance/report/check_result.hpp"
#include "conformance/report/report.hpp"

namespace olcb::conform {

/// The data cdi/html/conform.js renders: the JSON report of to_json() (docs/report.schema.json).
nlohmann::json html_report_json(const std::vector<NodeReport>& reports, const RunInfo& run);

/// The whole page.
std::string to_html(const std::vector<NodeReport>& reports, const RunInfo& run = {});

}  // namespace olcb::conform
