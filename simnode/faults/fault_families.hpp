// One function per fault family, each returning its faults' declarations (fault_catalog.hpp).
// A new family is a new file here plus one line in fault_catalog.cpp's kFamilies.
#pragma once

#include <cstdint>
#include <vector>

#include "simnode/faults/fault_catalog.hpp"

namespace olcb::simnode {

// Bounds keep a typo from stalling a node for days or rejecting forever.
inline constexpr std::uint32_t kMaxDelayMs = 600'000;
inline constexpr std::uint32_t kMaxCount = 1'000'000;

std::vector<FaultDecl> snip_faults();      ///< SNIP strings
std::vector<FaultDecl> acdi_faults();      ///< ACDI space contents
std::vector<FaultDecl> pip_faults();       ///< Protocol Support Reply
std::vector<FaultDecl> cdi_faults();       ///< the CDI text in space 0xFF
std::vector<FaultDecl> encoding_faults();  ///< how variables are stored (byte order, width)
std::vector<FaultDecl> write_faults();     ///< what happens to writes
std::vector<FaultDecl> read_faults();      ///< reads, Space Info, reply forms and reject codes
std::vector<FaultDecl> datagram_faults();  ///< datagram acknowledgement
std::vector<FaultDecl> timing_faults();    ///< late answers
std::vector<FaultDecl> frame_faults();     ///< CAN frames and aliases
std::vector<FaultDecl> message_faults();   ///< unsolicited and missing messages
std::vector<FaultDecl> restart_faults();   ///< crashes, restarts and refused commands
std::vector<FaultDecl> event_faults();     ///< event identification
std::vector<FaultDecl> stream_faults();    ///< stream reads

}  // namespace olcb::simnode
