// The general way to read a CDI's XML: pugixml, for every document read_simple_xml declines.
#pragma once

#include <pugixml.hpp>

#include "cdi/xml_tree.hpp"

namespace olcb::cdi {

/// How pugixml reads a CDI. parse_doctype keeps a DOCTYPE as a node so it can be refused;
/// pugixml never expands entities it does not know, so a billion-laughs DTD costs one linear
/// scan. parse_embed_pcdata stores an element's first text in the element: fewer nodes.
inline constexpr unsigned kPugixmlOptions =
    pugi::parse_default | pugi::parse_doctype | pugi::parse_embed_pcdata;

/// Copies root and every element below it into tree (empty, over the text pugixml parsed), in
/// document order, without recursion. The tree holds views of pugixml's text: the document
/// must outlive it.
void copy_pugixml_elements(pugi::xml_node root, XmlTree& tree);

}  // namespace olcb::cdi
