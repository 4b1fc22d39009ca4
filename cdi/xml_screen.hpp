// Whether pugixml's acceptance of a text settles that it is well-formed XML. pugixml is not a
// conforming parser (it keeps unknown entity references, "--" in comments, text outside the root,
// any byte); libxml2 is, at four times pugixml's cost. The screen passes only texts made of what
// pugixml checks strictly: anything else goes to libxml2, so the verdict never gets weaker.
#pragma once

#include "cdi/loaded_xml.hpp"

namespace olcb::cdi {

/// What the screen found.
struct XmlScreen {
    /// The loaded text parsed and uses only: an optional `<?xml version="1.0"?>` declaration at
    /// the very start (UTF-8, standalone allowed), one root element with only whitespace,
    /// comments and processing instructions around it, comments free of "--", instructions whose
    /// targets libxml2 takes without a word, the five predefined entities and character
    /// references to legal characters, no "]]>", no DOCTYPE or CDATA section, and valid UTF-8
    /// with no character XML forbids. Names, namespaces and attribute values are the tree walk's
    /// to judge (schema_tree.hpp).
    bool passes = false;
    /// Every byte is ASCII (known only when passes).
    bool ascii = false;
};

/// Screens a loaded text.
XmlScreen screen(const LoadedXml& xml);

}  // namespace olcb::cdi
