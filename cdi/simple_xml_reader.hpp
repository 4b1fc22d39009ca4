// Reads the plain XML that CDIs are in practice straight into an XmlTree: several times faster
// than a general DOM parser and with a fraction of its memory.
//
// It accepts a strict subset only: elements, attributes, text with the five predefined
// entities, comments, and processing instructions (the XML declaration among them). Anything
// else (CDATA, a DTD, character references, a NUL byte, names outside ASCII, text outside the
// root, a second root, nesting deeper than max_depth, and every malformation) makes it decline;
// the caller then reads the document with pugixml, which gives the answer it always gave. On
// what it accepts it builds the same tree as reading with pugixml (kPugixmlOptions) would
// (tests/fuzz/fuzz_cdi_xml_reader.cpp checks exactly that).
#pragma once

#include <cstddef>
#include <string_view>

#include "cdi/xml_tree.hpp"

namespace olcb::cdi {

/// Fills tree (empty, over text) and returns true, or returns false and the tree is unusable.
bool read_simple_xml(std::string_view text, std::size_t max_depth, XmlTree& tree);

}  // namespace olcb::cdi
