// The process's resident memory, for start-up reports and benchmarks.
#pragma once

namespace olcb::simnode {

/// VmRSS of this process in KiB (0 when /proc is unavailable).
long resident_kib();

}  // namespace olcb::simnode
