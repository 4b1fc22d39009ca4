// The standards' timings, each with the clause that sets it, so no library keeps its own copy of
// 750 ms or 3 s. Where a standard leaves a time open, the constant says whose choice it is.
// Plain std::chrono durations: they convert to any clock's duration (openlcb's Duration too).
#pragma once

#include <chrono>

namespace olcb::base {

/// A reply a protocol requires is sent within this, unless that protocol says otherwise
/// (MessageNetworkS §3.7).
inline constexpr std::chrono::milliseconds kReplyDue{750};

/// The shortest timeout a requester may give up on a lost reply after (MessageNetworkS §3.7); a
/// requester waiting at least this long never gives up on a node that keeps kReplyDue.
inline constexpr std::chrono::seconds kRequesterTimeout{3};

/// How long a datagram's sender waits for Datagram Received OK or Rejected after the last frame:
/// the requester timeout (MessageNetworkS §3.7, DatagramTransportS §6.1); OpenMRN and
/// OpenLCB_Java use exactly 3 s.
inline constexpr std::chrono::seconds kDatagramAckTimeout = kRequesterTimeout;

/// The least wait between the last CID frame and RID when reserving an alias
/// (CanFrameTransferS §6.2.1); OpenMRN and OpenLCB_Single_Thread wait exactly this.
inline constexpr std::chrono::milliseconds kAliasReservationWait{200};

/// How long a stream's source waits for the Stream Initiate Reply: the requester timeout
/// (MessageNetworkS §3.7); StreamTransportS gives no time of its own.
inline constexpr std::chrono::seconds kStreamInitiateTimeout = kRequesterTimeout;

/// How long a stream's source waits for Data Proceed after a full buffer. StreamTransportS gives
/// no time; this is OpenMRN's.
inline constexpr std::chrono::seconds kStreamProceedTimeout{20};

/// How long a stream's sink waits for the next data, Data Complete or Proceed before dropping the
/// stream. StreamTransportS gives no time; this is OpenMRN's source's 20 s.
inline constexpr std::chrono::seconds kStreamIdleTimeout{20};

}  // namespace olcb::base
