#include "support/report_schema.hpp"

#include <libxml/xmlschemas.h>

#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validation_results.hpp>
#include <valijson/validator.hpp>

namespace olcb::test {
namespace {

std::string read_source_file(const std::string& relative) {
    const std::string path = std::string(OLCB_SOURCE_DIR) + "/" + relative;
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// Parsed once per test binary: the schema does not change while tests run.
const valijson::Schema& report_schema() {
    static const auto schema = [] {
        auto s = std::make_unique<valijson::Schema>();
        const nlohmann::json doc =
            nlohmann::json::parse(read_source_file("docs/report.schema.json"));
        valijson::SchemaParser parser(valijson::SchemaParser::kDraft7);
        valijson::adapters::NlohmannJsonAdapter adapter(doc);
        parser.populateSchema(adapter, *s);
        return s;
    }();
    return *schema;
}

void collect_xml_error(void* context, const char* format, ...) {
    auto* out = static_cast<std::string*>(context);
    char buf[1024];
    va_list args;
    va_start(args, format);
    std::vsnprintf(buf, sizeof buf, format, args);
    va_end(args);
    *out += buf;
}

}  // namespace

std::string json_report_errors(const std::string& json_text) {
    const nlohmann::json doc = nlohmann::json::parse(json_text, nullptr, false);
    if (doc.is_discarded()) return "not JSON\n";
    valijson::Validator validator;
    valijson::ValidationResults results;
    valijson::adapters::NlohmannJsonAdapter adapter(doc);
    if (validator.validate(report_schema(), adapter, &results)) return "";
    std::string errors;
    valijson::ValidationResults::Error e;
    while (results.popError(e)) {
        std::string where;
        for (const std::string& p : e.context) where += p;
        errors += where + ": " + e.description + "\n";
    }
    return errors;
}

std::string junit_report_errors(const std::string& xml_text) {
    static const std::string xsd = read_source_file("tests/support/junit.xsd");
    std::string errors;
    using ParserCtx = std::unique_ptr<xmlSchemaParserCtxt, decltype(&xmlSchemaFreeParserCtxt)>;
    ParserCtx pctx(xmlSchemaNewMemParserCtxt(xsd.data(), static_cast<int>(xsd.size())),
                   xmlSchemaFreeParserCtxt);
    xmlSchemaSetParserErrors(pctx.get(), collect_xml_error, collect_xml_error, &errors);
    std::unique_ptr<xmlSchema, decltype(&xmlSchemaFree)> schema(xmlSchemaParse(pctx.get()),
                                                                xmlSchemaFree);
    if (!schema) return "junit.xsd does not parse: " + errors;
    std::unique_ptr<xmlSchemaValidCtxt, decltype(&xmlSchemaFreeValidCtxt)> vctx(
        xmlSchemaNewValidCtxt(schema.get()), xmlSchemaFreeValidCtxt);
    xmlSchemaSetValidErrors(vctx.get(), collect_xml_error, collect_xml_error, &errors);
    std::unique_ptr<xmlDoc, decltype(&xmlFreeDoc)> doc(
        xmlReadMemory(xml_text.data(), static_cast<int>(xml_text.size()), "junit.xml", nullptr,
                      XML_PARSE_NONET),
        xmlFreeDoc);
    if (!doc) return "not well-formed XML\n";
    if (xmlSchemaValidateDoc(vctx.get(), doc.get()) != 0 && errors.empty()) errors = "invalid\n";
    return errors;
}

}  // namespace olcb::test
