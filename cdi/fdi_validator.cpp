#include "cdi/fdi_validator.hpp"

#include <utility>

#include "cdi/fdi_parser.hpp"
#include "cdi/fdi_semantic_rules.hpp"

namespace olcb::cdi {

ValidatedFdi validate_fdi(std::string_view bytes) {
    ValidatedFdi out;
    append(out.diagnostics, validate_fdi_schema(bytes, &out.schema));
    FdiParseResult parsed = parse_fdi(bytes);
    // Every error of the model parser is a schema violation too (a missing or bad <number>, an
    // unknown kind, another root, no segment, text that is not XML): libxml2's findings already
    // say it. Only where the schema saw nothing wrong (groups nested past kMaxGroupDepth) are
    // they news.
    if (!has_errors(out.diagnostics)) append(out.diagnostics, std::move(parsed.diagnostics));
    if (parsed.document) {
        append(out.diagnostics, check_fdi_semantics(*parsed.document, out.schema.version));
        out.document = std::move(parsed.document);
    }
    sort_and_dedupe(out.diagnostics);
    return out;
}

}  // namespace olcb::cdi
