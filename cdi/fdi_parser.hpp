// Reads the FDI XML a train node serves (memory space 0xFA) into the model of fdi_document.hpp,
// and tells an FDI text from a CDI one by its root element.
#pragma once

#include <optional>
#include <string_view>

#include "cdi/diagnostic.hpp"
#include "cdi/fdi_document.hpp"
#include "cdi/loaded_xml.hpp"

namespace olcb::cdi {

/// The outcome of parse_fdi(): the model and what kept parts of the text out of it.
struct FdiParseResult {
    /// Present whenever the text is XML with an <fdi> root, even when some function could not be
    /// read (it is left out, with an error): a throttle uses what it can.
    std::optional<FdiDocument> document;
    /// Errors only: what the model cannot hold (no or a second <segment>, a function without a
    /// usable <number>, an unknown kind, a value that is no xs:int). Each is also a schema error
    /// (validate_fdi() reports the schema's words).
    Diagnostics diagnostics;
};

/// Parses FDI bytes as a node serves them (trailing NUL terminators ignored).
FdiParseResult parse_fdi(std::string_view bytes);

/// The same, from a text already loaded.
FdiParseResult parse_fdi(const LoadedXml& loaded);

/// True when the text's root element is <fdi> (after any BOM, XML declaration, processing
/// instructions, comments and DOCTYPE): how lcc-cdi tells an FDI file from a CDI. Reads only up
/// to the root's name, so it costs nothing on a large text.
bool is_fdi_text(std::string_view text);

}  // namespace olcb::cdi
