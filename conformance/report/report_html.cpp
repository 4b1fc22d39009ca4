#include "conformance/report/report_html.hpp"

#include <nlohmann/json.hpp>

#include "cdi/html_page.hpp"
#include "conformance/report/report.hpp"

namespace olcb::conform {

nlohmann::json html_report_json(const std::vector<NodeReport>& reports, const RunInfo& run) {
    // The page shows the JSON report itself (docs/report.schema.json), so the two never differ.
    return nlohmann::json::parse(to_json(reports, run));
}

std::string to_html(const std::vector<NodeReport>& reports, const RunInfo& run) {
    return cdi::html_page(cdi::PageKind::kConformance, html_report_json(reports, run));
}

}  // namespace olcb::conform
