// A human-readable, indented tree of a laid-out CDI: names, descriptions, addresses, types, hints.
#pragma once

#include <ostream>

#include "cdi/layout.hpp"

namespace olcb::cdi {

/// Writes the tree of layout.document() to out; replicated groups are shown once, with their
/// count and stride, at the address of their first replica.
void render(const Layout& layout, std::ostream& out);

}  // namespace olcb::cdi
