#include "cdi/schema_validator.hpp"

#include <libxml/parser.h>
#include <libxml/tree.h>
#include <libxml/xmlerror.h>
#include <libxml/xmlschemas.h>
#include <libxml/xmlversion.h>

#include <array>
#include <charconv>
#include <memory>
#include <mutex>
#include <string>

namespace olcb::cdi {
namespace {

#if LIBXML_VERSION >= 21200
using XmlErrorArg = const xmlError*;
#else
using XmlErrorArg = xmlErrorPtr;
#endif

constexpr std::size_t kSchemaCount = 5;
// A CDI with thousands of bad elements would otherwise yield thousands of near-identical lines.
constexpr std::size_t kMaxDiagnostics = 1000;
constexpr const char* kXsiNamespace = "http://www.w3.org/2001/XMLSchema-instance";

/// Receives libxml2's structured errors for one phase of one call.
struct Collector {
    Diagnostics* out = nullptr;
    std::string prefix;
    std::size_t suppressed = 0;
};

void collect(void* user, XmlErrorArg error) {
    auto* collector = static_cast<Collector*>(user);
    if (collector == nullptr || error == nullptr) return;
    if (collector->out->size() >= kMaxDiagnostics) {
        ++collector->suppressed;
        return;
    }
    std::string message = error->message != nullptr ? error->message : "unknown libxml2 error";
    while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) {
        message.pop_back();
    }
    long line = error->line;
    if (line <= 0 && error->node != nullptr) {
        line = xmlGetLineNo(static_cast<const xmlNode*>(error->node));
    }
    Diagnostic diagnostic;
    diagnostic.severity = error->level == XML_ERR_WARNING ? Severity::kWarning : Severity::kError;
    diagnostic.line = line > 0 ? static_cast<std::uint32_t>(line) : 0;
    diagnostic.message = collector->prefix + message;
    collector->out->push_back(std::move(diagnostic));
}

void silent(void*, const char*, ...) {}

/// Routes this thread's libxml2 error reporting to a collector (never to stderr) while alive.
class ErrorRouting {
public:
    explicit ErrorRouting(Collector* collector)
        : saved_structured_(xmlStructuredError),
          saved_structured_context_(xmlStructuredErrorContext),
          saved_generic_(xmlGenericError),
          saved_generic_context_(xmlGenericErrorContext) {
        xmlSetStructuredErrorFunc(collector, collect);
        xmlSetGenericErrorFunc(nullptr, silent);
    }
    ~ErrorRouting() {
        xmlSetStructuredErrorFunc(saved_structured_context_, saved_structured_);
        xmlSetGenericErrorFunc(saved_generic_context_, saved_generic_);
    }
    ErrorRouting(const ErrorRouting&) = delete;
    ErrorRouting& operator=(const ErrorRouting&) = delete;

private:
    xmlStructuredErrorFunc saved_structured_;
    void* saved_structured_context_;
    xmlGenericErrorFunc saved_generic_;
    void* saved_generic_context_;
};

void finish(Collector& collector) {
    if (collector.suppressed == 0) return;
    collector.out->push_back(
        {Severity::kError, 0,
         std::to_string(collector.suppressed) + " further schema diagnostics suppressed"});
}

struct CompiledSchema {
    std::once_flag once;
    xmlSchemaPtr schema = nullptr;  // shared read-only by every thread; lives until exit
    Diagnostics errors;             // why it failed to compile (never expected)
};

const CompiledSchema& compiled_schema(SchemaVersion version) {
    static std::array<CompiledSchema, kSchemaCount> cache;
    CompiledSchema& entry = cache[static_cast<std::size_t>(version)];
    std::call_once(entry.once, [&entry, version] {
        xmlInitParser();
        const std::string_view xsd = embedded_schema(version);
        Collector collector{&entry.errors,
                            "CDI " + std::string(schema_version_name(version)) + " schema: "};
        ErrorRouting routing(&collector);
        xmlSchemaParserCtxtPtr parser =
            xmlSchemaNewMemParserCtxt(xsd.data(), static_cast<int>(xsd.size()));
        if (parser == nullptr) return;
        xmlSchemaSetParserStructuredErrors(parser, collect, &collector);
        entry.schema = xmlSchemaParse(parser);
        xmlSchemaFreeParserCtxt(parser);
    });
    return entry;
}

/// Per-parse state reachable from SAX callbacks through ctxt->_private.
struct ParseState {
    bool doctype_seen = false;
    int doctype_line = 0;
};

// A DOCTYPE is where entity declarations live; stopping as soon as it starts means no entity
// (billion laughs, external entities) is ever declared, let alone expanded.
void refuse_doctype(void* context, const xmlChar*, const xmlChar*, const xmlChar*) {
    auto* parser = static_cast<xmlParserCtxtPtr>(context);
    if (auto* state = static_cast<ParseState*>(parser->_private)) {
        state->doctype_seen = true;
        state->doctype_line = parser->input != nullptr ? parser->input->line : 0;
    }
    xmlStopParser(parser);
}

struct DocFree {
    void operator()(xmlDocPtr doc) const { xmlFreeDoc(doc); }
};
using DocPtr = std::unique_ptr<xmlDoc, DocFree>;

/// Parses without network, DTD loading or entity substitution; errors go to `out`.
DocPtr parse_document(std::string_view bytes, Diagnostics& out) {
    xmlInitParser();
    Collector collector{&out, "XML parse error: "};
    ErrorRouting routing(&collector);
    xmlParserCtxtPtr parser = xmlNewParserCtxt();
    if (parser == nullptr) {
        out.push_back({Severity::kError, 0, "XML parse error: out of memory"});
        return nullptr;
    }
    ParseState state;
    parser->_private = &state;
    parser->sax->internalSubset = refuse_doctype;
    // XML_PARSE_HUGE lifts libxml2's nesting limit (256 levels), which a valid CDI of deeply
    // nested groups passes; the input stays bounded by kMaxCdiBytes and entities are refused.
    const int options = XML_PARSE_NONET | XML_PARSE_BIG_LINES | XML_PARSE_HUGE;
    DocPtr doc(xmlCtxtReadMemory(parser, bytes.data(), static_cast<int>(bytes.size()), "cdi.xml",
                                 nullptr, options));
    const bool well_formed = parser->wellFormed != 0;
    // Only refuse_doctype stops the parser; this also covers a libxml2 that reset _private.
    if (parser->errNo == XML_ERR_USER_STOP) state.doctype_seen = true;
    xmlFreeParserCtxt(parser);
    finish(collector);
    if (state.doctype_seen) {
        out.push_back({Severity::kError, static_cast<std::uint32_t>(state.doctype_line),
                       "XML parse error: a DOCTYPE is not allowed in a CDI (refused; no entity "
                       "was expanded)"});
        return nullptr;
    }
    if (!well_formed || doc == nullptr) {
        if (out.empty()) out.push_back({Severity::kError, 0, "XML parse error: not well-formed"});
        return nullptr;
    }
    return doc;
}

std::string_view strip_trailing_nuls(std::string_view bytes) {
    while (!bytes.empty() && bytes.back() == '\0') bytes.remove_suffix(1);
    return bytes;
}

std::string declared_location(const xmlDoc& doc) {
    const xmlNode* root = xmlDocGetRootElement(&doc);
    if (root == nullptr) return {};
    xmlChar* value =
        xmlGetNsProp(root, reinterpret_cast<const xmlChar*>("noNamespaceSchemaLocation"),
                     reinterpret_cast<const xmlChar*>(kXsiNamespace));
    if (value == nullptr) return {};
    std::string location(reinterpret_cast<const char*>(value));
    xmlFree(value);
    return location;
}

std::uint32_t root_line(const xmlDoc& doc) {
    const xmlNode* root = xmlDocGetRootElement(&doc);
    const long line = root != nullptr ? xmlGetLineNo(root) : 0;
    return line > 0 ? static_cast<std::uint32_t>(line) : 0;
}

void validate_doc(xmlDoc& doc, SchemaVersion version, Diagnostics& out) {
    if (static_cast<std::size_t>(version) >= kSchemaCount) {
        out.push_back({Severity::kError, 0, "unknown CDI schema version requested"});
        return;
    }
    const CompiledSchema& compiled = compiled_schema(version);
    if (compiled.schema == nullptr) {
        out.push_back({Severity::kError, 0,
                       "internal error: the embedded CDI " +
                           std::string(schema_version_name(version)) + " schema did not compile"});
        out.insert(out.end(), compiled.errors.begin(), compiled.errors.end());
        return;
    }
    Collector collector{&out, "CDI " + std::string(schema_version_name(version)) + " schema: "};
    ErrorRouting routing(&collector);
    xmlSchemaValidCtxtPtr validator = xmlSchemaNewValidCtxt(compiled.schema);
    if (validator == nullptr) {
        out.push_back({Severity::kError, 0, "schema validation: out of memory"});
        return;
    }
    xmlSchemaSetValidStructuredErrors(validator, collect, &collector);
    const std::size_t before = out.size();
    const int result = xmlSchemaValidateDoc(validator, &doc);
    xmlSchemaFreeValidCtxt(validator);
    finish(collector);
    if (result != 0 && out.size() == before) {
        out.push_back({Severity::kError, 0,
                       "CDI " + std::string(schema_version_name(version)) +
                           " schema: validation failed (libxml2 code " + std::to_string(result) +
                           ")"});
    }
}

bool too_large(std::string_view bytes, Diagnostics& out) {
    if (bytes.size() <= kMaxCdiBytes) return false;
    out.push_back({Severity::kError, 0,
                   "CDI is " + std::to_string(bytes.size()) + " bytes; refusing more than " +
                       std::to_string(kMaxCdiBytes)});
    return true;
}

}  // namespace

std::string_view schema_version_name(SchemaVersion version) {
    static constexpr std::array<std::string_view, kSchemaCount> kNames = {"1.0", "1.1", "1.2",
                                                                          "1.3", "1.4"};
    const auto index = static_cast<std::size_t>(version);
    return index < kNames.size() ? kNames[index] : std::string_view{"?"};
}

std::optional<SchemaVersion> schema_version_from_location(std::string_view location) {
    constexpr std::string_view kMarker = "/schema/cdi/1/";
    constexpr std::string_view kTail = "/cdi.xsd";
    while (!location.empty() && (location.back() == ' ' || location.back() == '\t' ||
                                 location.back() == '\n' || location.back() == '\r')) {
        location.remove_suffix(1);
    }
    const std::size_t marker = location.rfind(kMarker);
    if (marker == std::string_view::npos || !location.ends_with(kTail)) return std::nullopt;
    const std::size_t first = marker + kMarker.size();
    const std::size_t last = location.size() - kTail.size();
    if (last <= first) return std::nullopt;
    unsigned minor = 0;
    const char* begin = location.data() + first;
    const char* end = location.data() + last;
    const auto [ptr, ec] = std::from_chars(begin, end, minor);
    if (ec != std::errc{} || ptr != end || minor >= kSchemaCount) return std::nullopt;
    return static_cast<SchemaVersion>(minor);
}

Diagnostics validate_schema(std::string_view bytes, SchemaChoice* chosen) {
    Diagnostics out;
    SchemaChoice choice;
    bytes = strip_trailing_nuls(bytes);
    if (!too_large(bytes, out)) {
        if (DocPtr doc = parse_document(bytes, out)) {
            choice.well_formed = true;
            const std::string location = declared_location(*doc);
            if (const auto version = schema_version_from_location(location)) {
                choice.version = *version;
                choice.declared = true;
            } else {
                const std::string newest(schema_version_name(kNewestSchema));
                const bool versioned = location.find("/schema/cdi/1/") != std::string::npos;
                out.push_back({Severity::kWarning, root_line(*doc),
                               (versioned ? "unknown schema version declared (" + location + ")"
                                          : std::string("no schema version declared")) +
                                   "; validated against CDI " + newest});
            }
            validate_doc(*doc, choice.version, out);
        }
    }
    if (chosen != nullptr) *chosen = choice;
    return out;
}

Diagnostics validate_schema_as(std::string_view bytes, SchemaVersion version) {
    Diagnostics out;
    bytes = strip_trailing_nuls(bytes);
    if (too_large(bytes, out)) return out;
    if (DocPtr doc = parse_document(bytes, out)) validate_doc(*doc, version, out);
    return out;
}

}  // namespace olcb::cdi
