// The time limits and bounds the client audit judges by: the standards' own where they give one,
// the audit's choice (documented in docs/audit.md) where they do not.
#pragma once

#include <chrono>
#include <cstddef>

#include "base/timings.hpp"
#include "openlcb/clock.hpp"

namespace olcb::simnode::audit {

/// The shortest timeout a requester may use (MessageNetworkS §3.7, DatagramTransportS §6.1):
/// an exchange unanswered this long is over, and the client may go on.
inline constexpr Duration kRequesterTimeout = base::kRequesterTimeout;
/// Messages a protocol requires are due within this (MessageNetworkS §3.7).
inline constexpr Duration kAnswerDue = base::kReplyDue;
/// The least wait between the last CID frame and RID (CanFrameTransferS §6.2.1).
inline constexpr Duration kReservationWait = base::kAliasReservationWait;
/// How much shorter than it was a client's CID-to-RID wait may look: frames reach the audit when
/// the hub reads them, and under load a CID read late shortens a correct client's wait by as much
/// (a run at load 7-11 saw a 250 ms wait judged short). Only a wait shorter than the standard's by
/// more than this is reported, so a client that waits 100-200 ms goes unreported.
inline constexpr Duration kArrivalJitter = std::chrono::milliseconds(100);
/// A retry storm: more than kStormResends resends of one datagram within kStormWindow. The
/// standards set no bound; a client that pauses for a busy node never comes close (this
/// project's own sender resends at most 3 times, 100 ms apart).
inline constexpr std::size_t kStormResends = 5;
/// The window of kStormResends.
inline constexpr Duration kStormWindow = std::chrono::seconds(1);
/// Writes with no Update Complete are reported once the client sent the node no datagram for
/// this long (also at its disconnect and at the end of the run).
inline constexpr Duration kUpdateCompleteQuiet = std::chrono::seconds(10);
/// What a client left open is judged this long after its connection ended: with a paced bus
/// its last frames may still be on their way.
inline constexpr Duration kDisconnectGrace = std::chrono::seconds(2);
/// The first frames of a finding kept (a 72-byte datagram is 9 frames, its answer one more).
inline constexpr std::size_t kMaxFindingFrames = 16;
/// Findings kept; beyond, further ones are only counted (a flood must not grow the file).
inline constexpr std::size_t kMaxFindings = 10000;
/// Variables up to this size have their written value judged (bigger ones: coverage only).
inline constexpr std::size_t kMaxJudgedVariable = 4096;

}  // namespace olcb::simnode::audit
