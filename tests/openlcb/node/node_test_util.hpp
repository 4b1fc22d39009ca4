// Forwarding header: tests/simnode/faults still include the old path; drop this once they include
// openlcb/node_test_util.hpp.
#pragma once

#include "openlcb/node_test_util.hpp"  // IWYU pragma: export
