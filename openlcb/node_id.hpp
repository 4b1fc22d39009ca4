// NodeId and EventId live in base/ now (issue 29); this name stays for the code that includes it.
#pragma once

#include "base/node_id.hpp"
