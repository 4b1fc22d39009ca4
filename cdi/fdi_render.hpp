// An FDI as text for a terminal: the function list a throttle would offer, in document order with
// the groups that organise it (`lcc-cdi render` of an FDI), and the FDI XML of a model
// (what a train node serves in space 0xFA).
#pragma once

#include <ostream>
#include <string>

#include "cdi/fdi_document.hpp"

namespace olcb::cdi {

/// Prints `doc` as an indented tree: the segment, each group ("group NAME" with its
/// description), each function as "F<number> <kind> NAME" with its range (analog) and icon.
/// Text from the FDI passes base::printable(): it is untrusted.
void render_fdi(const FdiDocument& doc, std::ostream& out);

/// The FDI XML of `doc` as a train node serves it (without the NUL terminator): the XML
/// declaration, the FDI 1.1 schema location, one <segment> with the groups and functions nested
/// and ordered as FdiDocument::walk() visits them (a hand-built model: set each function's
/// group; groups then come before the functions of their container), every text passed through
/// base::printable() and escaped. validate_fdi() accepts it without an error when the numbers
/// are in range (§5.1.4; an <icon> draws its warning).
std::string write_fdi(const FdiDocument& doc);

}  // namespace olcb::cdi
