#include "cdi/schema_validator.hpp"

#include <libxml/parser.h>
#include <libxml/parserInternals.h>
#include <libxml/tree.h>
#include <libxml/xmlerror.h>
#include <libxml/xmlschemas.h>
#include <libxml/xmlversion.h>

#include <array>
#include <charconv>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "cdi/loaded_xml.hpp"

namespace olcb::cdi {
namespace {

#if LIBXML_VERSION >= 21200
using XmlErrorArg = const xmlError*;
#else
using XmlErrorArg = xmlErrorPtr;
#endif

constexpr std::size_t kSchemaCount = 5;
constexpr std::size_t kFdiSchemaCount = 2;
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

/// One family of schemas (CDI or FDI): its name in messages, where a schema URL names the
/// version, the versions' names, the embedded texts and their compiled forms (by index).
struct SchemaFamily {
    std::string_view name;           ///< "CDI"
    std::string_view with_article;   ///< "a CDI"
    std::string_view location_stem;  ///< "/schema/cdi/1/"
    std::string_view location_tail;  ///< "/cdi.xsd"
    std::span<const std::string_view> version_names;
    std::size_t newest = 0;
    std::string_view (*embedded)(std::size_t index) = nullptr;
    std::span<CompiledSchema> cache;  ///< one entry per version, compiled on first use

    std::string version_name(std::size_t index) const {
        return index < version_names.size() ? std::string(version_names[index]) : "?";
    }
    std::string prefix(std::size_t index) const {
        return std::string(name) + " " + version_name(index) + " schema: ";
    }
};

constexpr std::array<std::string_view, kSchemaCount> kCdiVersionNames = {"1.0", "1.1", "1.2", "1.3",
                                                                         "1.4"};
constexpr std::array<std::string_view, kFdiSchemaCount> kFdiVersionNames = {"1.0", "1.1"};

const SchemaFamily& cdi_family() {
    static std::array<CompiledSchema, kSchemaCount> cache;
    static const SchemaFamily family{
        "CDI",
        "a CDI",
        "/schema/cdi/1/",
        "/cdi.xsd",
        kCdiVersionNames,
        static_cast<std::size_t>(kNewestSchema),
        [](std::size_t index) { return embedded_schema(static_cast<SchemaVersion>(index)); },
        cache};
    return family;
}

const SchemaFamily& fdi_family() {
    static std::array<CompiledSchema, kFdiSchemaCount> cache;
    static const SchemaFamily family{
        "FDI",
        "an FDI",
        "/schema/fdi/1/",
        "/fdi.xsd",
        kFdiVersionNames,
        static_cast<std::size_t>(kNewestFdiSchema),
        [](std::size_t index) { return embedded_fdi_schema(static_cast<FdiSchemaVersion>(index)); },
        cache};
    return family;
}

const CompiledSchema& compiled_schema(const SchemaFamily& family, std::size_t version) {
    CompiledSchema& entry = family.cache[version];
    std::call_once(entry.once, [&entry, &family, version] {
        xmlInitParser();
        const std::string_view xsd = family.embedded(version);
        Collector collector{&entry.errors, family.prefix(version)};
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

// No network, no DTD loading, no entity substitution. XML_PARSE_HUGE lifts libxml2's nesting
// limit (256 levels), which a valid CDI of deeply nested groups passes; the input stays bounded
// by kMaxCdiBytes and entities are refused.
constexpr int kParseOptions = XML_PARSE_NONET | XML_PARSE_BIG_LINES | XML_PARSE_HUGE;

/// The compiled schema of `version`, or null with the reason in `out`.
xmlSchemaPtr schema_for(const SchemaFamily& family, std::size_t version, Diagnostics& out) {
    if (version >= family.cache.size()) {
        out.push_back({Severity::kError, 0,
                       "unknown " + std::string(family.name) + " schema version requested"});
        return nullptr;
    }
    const CompiledSchema& compiled = compiled_schema(family, version);
    if (compiled.schema == nullptr) {
        out.push_back({Severity::kError, 0,
                       "internal error: the embedded " + std::string(family.name) + " " +
                           family.version_name(version) + " schema did not compile"});
        out.insert(out.end(), compiled.errors.begin(), compiled.errors.end());
    }
    return compiled.schema;
}

/// Which schema of a family a pass used and why (SchemaChoice/FdiSchemaChoice by index).
struct Choice {
    std::size_t version = 0;
    bool declared = false;
    bool well_formed = false;
};

/// The version of `family` named by a schema location; nullopt when it names none it knows.
std::optional<std::size_t> version_from_location(const SchemaFamily& family,
                                                 std::string_view location) {
    while (!location.empty() && (location.back() == ' ' || location.back() == '\t' ||
                                 location.back() == '\n' || location.back() == '\r')) {
        location.remove_suffix(1);
    }
    const std::size_t marker = location.rfind(family.location_stem);
    if (marker == std::string_view::npos || !location.ends_with(family.location_tail))
        return std::nullopt;
    const std::size_t first = marker + family.location_stem.size();
    const std::size_t last = location.size() - family.location_tail.size();
    if (last <= first) return std::nullopt;
    unsigned minor = 0;
    const char* begin = location.data() + first;
    const char* end = location.data() + last;
    const auto [ptr, ec] = std::from_chars(begin, end, minor);
    if (ec != std::errc{} || ptr != end || minor >= family.cache.size()) return std::nullopt;
    return minor;
}

struct ValidatorFree {
    void operator()(xmlSchemaValidCtxtPtr validator) const { xmlSchemaFreeValidCtxt(validator); }
};
using ValidatorPtr = std::unique_ptr<xmlSchemaValidCtxt, ValidatorFree>;

/// What one validating parse found: parse errors, schema errors, whether the text is XML, and
/// the parse's own state (a refused DOCTYPE and its line, the schema chosen at the root).
struct PassResult {
    PassResult() = default;
    PassResult(const PassResult&) = delete;  // schema_collector points into it
    PassResult& operator=(const PassResult&) = delete;

    const SchemaFamily* family = nullptr;
    std::optional<std::size_t> fixed;  ///< validate_schema_as: the version, whatever is declared
    Choice choice;
    std::optional<Diagnostic> choice_warning;  ///< no or an unknown version declared
    Diagnostics setup_errors;                  ///< the schema could not be used
    bool doctype_seen = false;
    int doctype_line = 0;
    Diagnostics parse_errors;
    Diagnostics schema_errors;
    Collector schema_collector{&schema_errors, ""};
    ValidatorPtr validator;
    xmlSchemaSAXPlugPtr plug = nullptr;
    bool well_formed = false;
    bool valid = false;
};

PassResult& state_of(void* context) {
    return *static_cast<PassResult*>(static_cast<xmlParserCtxtPtr>(context)->_private);
}

// A DOCTYPE is where entity declarations live; stopping as soon as it starts means no entity
// (billion laughs, external entities) is ever declared, let alone expanded.
void refuse_doctype(void* context, const xmlChar*, const xmlChar*, const xmlChar*) {
    auto* parser = static_cast<xmlParserCtxtPtr>(context);
    PassResult& state = state_of(context);
    state.doctype_seen = true;
    state.doctype_line = parser->input != nullptr ? parser->input->line : 0;
    xmlStopParser(parser);
}

// The root's xsi:noNamespaceSchemaLocation ("" when absent).
std::string root_location(int attribute_count, const xmlChar** attributes) {
    const auto* xsi = reinterpret_cast<const xmlChar*>(kXsiNamespace);
    const auto* name = reinterpret_cast<const xmlChar*>("noNamespaceSchemaLocation");
    std::string location;
    for (int i = 0; i < attribute_count; ++i) {
        // Five pointers per attribute: local name, prefix, namespace URI, value, value end.
        const xmlChar* const* attribute = attributes + std::ptrdiff_t{5} * i;
        if (attribute[2] != nullptr && xmlStrEqual(attribute[2], xsi) != 0 &&
            xmlStrEqual(attribute[0], name) != 0) {
            location.assign(reinterpret_cast<const char*>(attribute[3]),
                            static_cast<std::size_t>(attribute[4] - attribute[3]));
        }
    }
    return location;
}

// The version to validate against: the one asked for, else the one the root declares, else the
// newest with a warning at the root's line.
void choose(PassResult& state, const std::string& location, std::uint32_t root_line) {
    const SchemaFamily& family = *state.family;
    if (state.fixed) {
        state.choice.version = *state.fixed;
        return;
    }
    if (const auto version = version_from_location(family, location)) {
        state.choice.version = *version;
        state.choice.declared = true;
        return;
    }
    state.choice.version = family.newest;
    const bool versioned = location.find(family.location_stem) != std::string::npos;
    state.choice_warning =
        Diagnostic{Severity::kWarning, root_line,
                   (versioned ? "unknown schema version declared (" + location + ")"
                              : std::string("no schema version declared")) +
                       "; validated against " + std::string(family.name) + " " +
                       family.version_name(family.newest)};
}

// Without a tree, the validator asks where the parser is for the line of what it reports: the
// end of a start tag for what the tag says, the end tag for content missing from an element.
int parser_position(void* context, const char** file, unsigned long* line) {
    const auto* parser = static_cast<const xmlParserCtxt*>(context);
    *file = nullptr;
    *line = parser->input != nullptr ? static_cast<unsigned long>(parser->input->line) : 0;
    return 0;
}

// Puts the validator of the chosen schema in front of the parser's handlers; false when the
// schema cannot be used (the reason is in setup_errors).
bool plug_validator(PassResult& state, xmlParserCtxtPtr parser) {
    const xmlSchemaPtr schema = schema_for(*state.family, state.choice.version, state.setup_errors);
    if (schema == nullptr) return false;
    state.schema_collector.prefix = state.family->prefix(state.choice.version);
    state.validator.reset(xmlSchemaNewValidCtxt(schema));
    if (state.validator == nullptr) {
        state.setup_errors.push_back({Severity::kError, 0, "schema validation: out of memory"});
        return false;
    }
    xmlSchemaSetValidStructuredErrors(state.validator.get(), collect, &state.schema_collector);
    xmlSchemaValidateSetLocator(state.validator.get(), parser_position, parser);
    state.plug = xmlSchemaSAXPlug(state.validator.get(), &parser->sax, &parser->userData);
    if (state.plug == nullptr) {
        state.setup_errors.push_back({Severity::kError, 0, "schema validation: out of memory"});
        return false;
    }
    return true;
}

// The root's start tag chooses the schema (so one parse both reads the declaration and
// validates): the validator is plugged in here and gets this tag as its first event.
void start_root(void* context, const xmlChar* local_name, const xmlChar* prefix, const xmlChar* uri,
                int namespace_count, const xmlChar** namespaces, int attribute_count,
                int defaulted_count, const xmlChar** attributes) {
    auto* parser = static_cast<xmlParserCtxtPtr>(context);
    PassResult& state = state_of(context);
    const auto root_line =
        parser->input != nullptr ? static_cast<std::uint32_t>(parser->input->line) : 0;
    choose(state, root_location(attribute_count, attributes), root_line);
    parser->sax->startElementNs = nullptr;  // every later start tag goes to the validator only
    // Still parsed when the schema cannot be used: well-formedness is reported.
    if (!plug_validator(state, parser)) return;
    parser->sax->startElementNs(parser->userData, local_name, prefix, uri, namespace_count,
                                namespaces, attribute_count, defaulted_count, attributes);
}

struct ParserFree {
    void operator()(xmlParserCtxtPtr parser) const { xmlFreeParserCtxt(parser); }
};
using ParserPtr = std::unique_ptr<xmlParserCtxt, ParserFree>;

/// A parser of `bytes` whose SAX handler builds no tree: it has only the root's start tag (where
/// the validator is plugged in) and the DOCTYPE refusal.
ParserPtr new_parser(std::string_view bytes, PassResult& state) {
    xmlInitParser();
    ParserPtr parser(xmlCreateMemoryParserCtxt(bytes.data(), static_cast<int>(bytes.size())));
    if (parser == nullptr) return nullptr;
    xmlSAXHandler* sax = parser->sax;
    *sax = xmlSAXHandler{};
    sax->initialized = XML_SAX2_MAGIC;
    sax->internalSubset = refuse_doctype;
    sax->startElementNs = start_root;
    parser->_private = &state;
    xmlCtxtUseOptions(parser.get(), kParseOptions);
    return parser;
}

/// Parses once, validating against the schema chosen at the root as the SAX events arrive; no
/// tree is built.
void validate_stream(std::string_view bytes, PassResult& result) {
    Collector parse_collector{&result.parse_errors, "XML parse error: "};
    ErrorRouting routing(&parse_collector);
    ParserPtr parser = new_parser(bytes, result);
    if (parser == nullptr) {
        result.parse_errors.push_back({Severity::kError, 0, "XML parse error: out of memory"});
        return;
    }
    xmlParseDocument(parser.get());
    if (result.plug != nullptr) xmlSchemaSAXUnplug(result.plug);
    // Only refuse_doctype stops the parser; this also covers a libxml2 that reset _private.
    if (parser->errNo == XML_ERR_USER_STOP) result.doctype_seen = true;
    result.well_formed = parser->wellFormed != 0 && !result.doctype_seen;
    result.valid = result.validator != nullptr && xmlSchemaIsValid(result.validator.get()) == 1;
    finish(parse_collector);
    finish(result.schema_collector);
}

/// Validates `bytes` against the declared schema (or `fixed`) while libxml2 parses them: libxml2
/// is the conforming parser, so its verdict on well-formedness is the one reported. Appends to
/// `out` what a reader needs (the choice's warning, if any, only for well-formed text). Returns
/// whether the text is XML; `choice` receives the schema used.
bool check_against(const SchemaFamily& family, std::string_view bytes,
                   std::optional<std::size_t> fixed, Diagnostics& out, Choice& choice) {
    PassResult pass;
    pass.family = &family;
    pass.fixed = fixed;
    validate_stream(bytes, pass);
    choice = pass.choice;
    const bool unusable = !pass.setup_errors.empty();
    const bool parse_failed = !pass.parse_errors.empty();
    append(out, std::move(pass.setup_errors));
    append(out, std::move(pass.parse_errors));
    if (pass.doctype_seen) {
        out.push_back({Severity::kError, static_cast<std::uint32_t>(pass.doctype_line),
                       "XML parse error: a DOCTYPE is not allowed in " +
                           std::string(family.with_article) +
                           " (refused; no entity was expanded)"});
        return false;
    }
    if (!pass.well_formed) {
        // Schema errors before the point where the text stopped being XML would only confuse.
        if (!parse_failed) out.push_back({Severity::kError, 0, "XML parse error: not well-formed"});
        return false;
    }
    if (unusable) return false;
    if (pass.choice_warning) out.push_back(std::move(*pass.choice_warning));
    if (!pass.valid && pass.schema_errors.empty()) {
        out.push_back({Severity::kError, 0, family.prefix(choice.version) + "validation failed"});
    }
    append(out, std::move(pass.schema_errors));
    return true;
}

bool too_large(const SchemaFamily& family, std::string_view bytes, Diagnostics& out) {
    if (bytes.size() <= kMaxCdiBytes) return false;
    out.push_back({Severity::kError, 0,
                   std::string(family.name) + " is " + std::to_string(bytes.size()) +
                       " bytes; refusing more than " + std::to_string(kMaxCdiBytes)});
    return true;
}

/// One validation of `bytes` against `fixed` or the declared schema of `family`.
Diagnostics validate_in(const SchemaFamily& family, std::string_view bytes,
                        std::optional<std::size_t> fixed, Choice& choice) {
    Diagnostics out;
    bytes = without_trailing_nuls(bytes);
    if (!too_large(family, bytes, out)) {
        choice.well_formed = check_against(family, bytes, fixed, out, choice);
    }
    return out;
}

}  // namespace

std::string_view schema_version_name(SchemaVersion version) {
    const auto index = static_cast<std::size_t>(version);
    return index < kCdiVersionNames.size() ? kCdiVersionNames[index] : std::string_view{"?"};
}

std::optional<SchemaVersion> schema_version_from_location(std::string_view location) {
    const auto index = version_from_location(cdi_family(), location);
    return index ? std::optional(static_cast<SchemaVersion>(*index)) : std::nullopt;
}

Diagnostics validate_schema(std::string_view bytes, SchemaChoice* chosen) {
    Choice choice{static_cast<std::size_t>(kNewestSchema)};
    Diagnostics out = validate_in(cdi_family(), bytes, std::nullopt, choice);
    if (chosen != nullptr) {
        *chosen = {static_cast<SchemaVersion>(choice.version), choice.declared, choice.well_formed};
    }
    return out;
}

Diagnostics validate_schema_as(std::string_view bytes, SchemaVersion version) {
    Choice choice;
    return validate_in(cdi_family(), bytes, static_cast<std::size_t>(version), choice);
}

std::string_view fdi_schema_version_name(FdiSchemaVersion version) {
    const auto index = static_cast<std::size_t>(version);
    return index < kFdiVersionNames.size() ? kFdiVersionNames[index] : std::string_view{"?"};
}

std::optional<FdiSchemaVersion> fdi_schema_version_from_location(std::string_view location) {
    const auto index = version_from_location(fdi_family(), location);
    return index ? std::optional(static_cast<FdiSchemaVersion>(*index)) : std::nullopt;
}

Diagnostics validate_fdi_schema(std::string_view bytes, FdiSchemaChoice* chosen) {
    Choice choice{static_cast<std::size_t>(kNewestFdiSchema)};
    Diagnostics out = validate_in(fdi_family(), bytes, std::nullopt, choice);
    if (chosen != nullptr) {
        *chosen = {static_cast<FdiSchemaVersion>(choice.version), choice.declared,
                   choice.well_formed};
    }
    return out;
}

Diagnostics validate_fdi_schema_as(std::string_view bytes, FdiSchemaVersion version) {
    Choice choice;
    return validate_in(fdi_family(), bytes, static_cast<std::size_t>(version), choice);
}

}  // namespace olcb::cdi
