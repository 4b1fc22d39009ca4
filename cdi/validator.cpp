#include "cdi/validator.hpp"

#include <algorithm>
#include <tuple>
#include <utility>

#include "cdi/layout.hpp"
#include "cdi/parser.hpp"
#include "cdi/semantic_rules.hpp"

namespace olcb::cdi {

ValidationReport validate(std::string_view bytes) {
    return validate_model(bytes).report;
}

ValidatedCdi validate_model(std::string_view bytes) {
    ValidatedCdi out;
    ValidationReport& report = out.report;
    // libxml2 parses the text for the schema, pugixml for the model. Checking the schema on
    // pugixml's tree instead saved under 5 % of a whole `lcc-cdi validate` run and nothing of an
    // lcc-conform run: not worth a screen and a tree walk that must agree with libxml2
    // (docs/benchmarks.md, issue 29).
    append(report.diagnostics, validate_schema(bytes, &report.schema));

    ParseResult parsed = parse(bytes);
    if (!report.schema.well_formed && !parsed.document) {
        // libxml2 already reported why the text is not XML; the model parser's errors would
        // say the same thing a second time in other words.
        std::erase_if(parsed.diagnostics,
                      [](const Diagnostic& d) { return d.severity == Severity::kError; });
    }
    append(report.diagnostics, std::move(parsed.diagnostics));

    if (parsed.document) {
        report.parsed = true;
        out.document = std::make_unique<Document>(std::move(*parsed.document));
        append(report.diagnostics, check_semantics(*out.document));
        LayoutResult laid = build_layout(*out.document);
        append(report.diagnostics, std::move(laid.diagnostics));
        out.layout = std::move(laid.layout);
    }
    sort_and_dedupe(report.diagnostics);
    return out;
}

}  // namespace olcb::cdi
