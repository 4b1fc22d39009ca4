// libFuzzer target: the schema check on pugixml's tree against libxml2's own parse of the same
// bytes. Both must agree that the text is XML or not, and whenever the tree was used, on every
// finding: severity, line and message.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "cdi/schema_validator.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace olcb::cdi;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    SchemaChoice tree;
    SchemaChoice parsed;
    const Diagnostics from_tree = validate_schema(bytes, &tree);
    const Diagnostics reference = validate_schema_parsed(bytes, &parsed);
    if (tree.well_formed != parsed.well_formed || tree.version != parsed.version) __builtin_trap();
    if (!tree.from_tree) return 0;  // both were libxml2's parse
    if (from_tree.size() != reference.size()) __builtin_trap();
    for (std::size_t i = 0; i < reference.size(); ++i) {
        const Diagnostic& a = from_tree[i];
        const Diagnostic& b = reference[i];
        if (a.severity != b.severity || a.line != b.line || a.message != b.message)
            __builtin_trap();
    }
    return 0;
}
