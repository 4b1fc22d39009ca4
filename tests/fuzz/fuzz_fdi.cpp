// libFuzzer target: read arbitrary bytes as an FDI, render its function list, write the model
// back as FDI XML and read that again: the same functions must come back.
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>

#include "cdi/fdi_parser.hpp"
#include "cdi/fdi_render.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace olcb::cdi;
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    (void)is_fdi_text(bytes);
    const FdiParseResult parsed = parse_fdi(bytes);
    if (!parsed.document) return 0;
    const FdiDocument& doc = *parsed.document;
    std::ostringstream rendered;
    render_fdi(doc, rendered);
    const std::string text = write_fdi(doc);
    if (!is_fdi_text(text)) __builtin_trap();
    const FdiParseResult again = parse_fdi(text);
    if (!again.document || !again.diagnostics.empty()) __builtin_trap();
    const FdiDocument& back = *again.document;
    if (back.functions.size() != doc.functions.size() || back.groups.size() != doc.groups.size())
        __builtin_trap();
    for (std::size_t i = 0; i < doc.functions.size(); ++i) {
        const FdiFunction& a = doc.functions[i];
        const FdiFunction& b = back.functions[i];
        if (a.number != b.number || a.kind != b.kind || a.group != b.group || a.icon != b.icon ||
            a.min != b.min || a.max != b.max)
            __builtin_trap();
    }
    return 0;
}
